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
 * - the pipeline (vtkBrumeTimedPipeline, Supersampling x Supersampling
 *   frames a pixel) at
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

#include "vtkBrumeEvaluationAlgorithm.h"
#include "vtkBrumeEvaluationModule.h" // For export macro
#include "vtkSmartPointer.h"          // For ReferenceCache

class vtkBrumeReferenceCache;

class VTKBRUMEEVALUATION_EXPORT vtkBrumeErrorChart : public vtkBrumeEvaluationAlgorithm
{
public:
  static vtkBrumeErrorChart* New();
  vtkTypeMacro(vtkBrumeErrorChart, vtkBrumeEvaluationAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The path tracer's largest budget, in powers of 4 from 1 (default 1024 samples per pixel).
  vtkSetMacro(MaxSamples, int);
  vtkGetMacro(MaxSamples, int);
  ///@}

  /// The converged reference's source: after an update, says whether it was read or rendered.
  vtkBrumeReferenceCache* GetReferenceCache();

  /// Draws the last output (rel_mae against seconds per method) into a PNG file.
  bool WriteImage(const char* fileName);

protected:
  vtkBrumeErrorChart();
  ~vtkBrumeErrorChart() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int MaxSamples = 1024;
  vtkSmartPointer<vtkBrumeReferenceCache> ReferenceCache;

private:
  vtkBrumeErrorChart(const vtkBrumeErrorChart&) = delete;
  void operator=(const vtkBrumeErrorChart&) = delete;

  bool CheckSettings();
};

#endif
