// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeErrorChart
 * @brief   error against time: the pipeline against the reference path tracer
 *
 * Measures, on the input scene and for one view, every image against a
 * converged reference (vtkBrumeReferenceCache: ReferenceSamples samples per
 * pixel, seed Seed + 1000003 so that its noise is not correlated with the
 * images', kept in CacheDirectory under CacheKey):
 *
 * - the pipeline (vtkBrumeTimedPipeline, 4x4 supersampled) at
 *   MinParticles, 10 x MinParticles, ... up to MaxParticles, with per-view
 *   media (rows `pipeline`, and `pipeline-new-view` for the time of a new
 *   viewpoint) and with spherical-harmonics media of order
 *   DirectionalOrder (`pipeline-sh`, `pipeline-sh-new-view`), after one
 *   untimed run at 1,000 particles (OpenGL's start-up is not the
 *   pipeline's cost);
 * - the path tracer at 1, 4, 16, ... up to MaxSamples samples per pixel
 *   (`path-tracer`, seed Seed).
 *
 * The output is a vtkTable, one row per image, in that order: `method`
 * (string), `budget` (particles or samples per pixel), `seconds`,
 * `rel_mae`, `rel_rmse`, `rel_mae_medium`, `rel_rmse_medium` (over the
 * pixels whose ray crosses a medium, vtkBrumeMediumMask; 0 without a
 * medium) and `block_error` (vtkBrumeImageError). Rows are appended as
 * they are measured, each followed by a progress event, so that an
 * observer can show them while the chart runs.
 *
 * The view is the Camera, or else the scene's camera, or else Brume's
 * default view. WriteCsv() and WriteImage() save the last output as CSV and
 * as a chart (error against wall time, log-log, one curve per method).
 * Needs an OpenGL context (an X display; `xvfb-run -a` without one).
 *
 * @code
 * vtkNew<vtkBrumeErrorChart> chart;
 * chart->SetInputConnection(scene->GetOutputPort());   // any scene collection
 * chart->SetSize(64, 64);
 * chart->SetMaxParticles(1000000);
 * chart->SetCacheDirectory("/tmp/brume-cache");
 * chart->SetSceneName("my scene");
 * chart->Update();
 * chart->WriteCsv("chart.csv");
 * chart->WriteImage("chart.png");
 * @endcode
 *
 * @sa vtkBrumeStabilitySweep vtkBrumeTimedPipeline vtkBrumeReferenceCache
 */
#ifndef vtkBrumeErrorChart_h
#define vtkBrumeErrorChart_h

#include "vtkBrumeEvaluationModule.h" // For export macro
#include "vtkSmartPointer.h"          // For ReferenceCache
#include "vtkTableAlgorithm.h"

class vtkBrumeReferenceCache;
class vtkCamera;

class VTKBRUMEEVALUATION_EXPORT vtkBrumeErrorChart : public vtkTableAlgorithm
{
public:
  static vtkBrumeErrorChart* New();
  vtkTypeMacro(vtkBrumeErrorChart, vtkTableAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Image size in pixels (default 128 x 128, each in [1, 16384]).
  vtkSetVector2Macro(Size, int);
  vtkGetVector2Macro(Size, int);
  ///@}

  ///@{
  /// The pipeline's particle budgets, in powers of 10 (default 10^4 to 10^7; at least 1).
  vtkSetMacro(MinParticles, vtkTypeInt64);
  vtkGetMacro(MinParticles, vtkTypeInt64);
  vtkSetMacro(MaxParticles, vtkTypeInt64);
  vtkGetMacro(MaxParticles, vtkTypeInt64);
  ///@}

  ///@{
  /// The path tracer's largest budget, in powers of 4 from 1 (default 1024 samples per pixel).
  vtkSetMacro(MaxSamples, int);
  vtkGetMacro(MaxSamples, int);
  ///@}

  ///@{
  /// Samples per pixel of the converged reference (default 16384).
  vtkSetMacro(ReferenceSamples, int);
  vtkGetMacro(ReferenceSamples, int);
  ///@}

  ///@{
  /// The reconstruction's radiosity threshold (default 128 hits).
  vtkSetMacro(RadiosityThreshold, double);
  vtkGetMacro(RadiosityThreshold, double);
  ///@}

  ///@{
  /// Seed of the light tracer and the path tracer (default 0, non-negative).
  vtkSetMacro(Seed, vtkIdType);
  vtkGetMacro(Seed, vtkIdType);
  ///@}

  ///@{
  /// Spherical-harmonics order of the `pipeline-sh` rows (default 3, in [1, 3]).
  vtkSetMacro(DirectionalOrder, int);
  vtkGetMacro(DirectionalOrder, int);
  ///@}

  ///@{
  /// The camera; without one, the scene's camera or Brume's default view.
  void SetCamera(vtkCamera* camera);
  vtkGetObjectMacro(Camera, vtkCamera);
  ///@}

  ///@{
  /// Where converged references are kept (default empty: render it every time).
  vtkSetStringMacro(CacheDirectory);
  vtkGetStringMacro(CacheDirectory);
  ///@}

  ///@{
  /// The scene's name, in the chart's title (default "scene").
  vtkSetStringMacro(SceneName);
  vtkGetStringMacro(SceneName);
  ///@}

  ///@{
  /**
   * What names the scene in the cached references' file names (default
   * empty: the SceneName). It must change whenever the scene or the
   * camera does (see vtkBrumeReferenceCache).
   */
  vtkSetStringMacro(CacheKey);
  vtkGetStringMacro(CacheKey);
  ///@}

  /// The converged reference's source: after an update, says whether it was read or rendered.
  vtkBrumeReferenceCache* GetReferenceCache();

  /// Writes the last output as CSV (the columns above); false if it could not.
  bool WriteCsv(const char* fileName);

  /// Draws the last output (rel_mae against seconds per method) into a PNG file.
  bool WriteImage(const char* fileName);

  vtkMTimeType GetMTime() override;

protected:
  vtkBrumeErrorChart();
  ~vtkBrumeErrorChart() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int Size[2] = { 128, 128 };
  vtkTypeInt64 MinParticles = 10000;
  vtkTypeInt64 MaxParticles = 10000000;
  int MaxSamples = 1024;
  int ReferenceSamples = 16384;
  double RadiosityThreshold = 128.0;
  vtkIdType Seed = 0;
  int DirectionalOrder = 3;
  vtkCamera* Camera = nullptr;
  char* CacheDirectory = nullptr;
  char* SceneName = nullptr;
  char* CacheKey = nullptr;
  vtkSmartPointer<vtkBrumeReferenceCache> ReferenceCache;

private:
  vtkBrumeErrorChart(const vtkBrumeErrorChart&) = delete;
  void operator=(const vtkBrumeErrorChart&) = delete;

  bool CheckSettings();
};

#endif
