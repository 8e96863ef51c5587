// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeTimedPipeline
 * @brief   the three phases at one particle budget: their image and their times
 *
 * Runs the fast pipeline on the input scene as `brume render` does, and
 * times it:
 *
 * 1. the pipeline (vtkBrumePipeline: light tracing, radiance reconstruction
 *    for the camera and the scene's props) and the off-screen frame
 *    (Supersampling^2 renders read back and averaged by
 *    vtkBrumeFloatImageCapture): the full time, `FullSeconds`;
 * 2. when MeasureNewView is on, a new viewpoint: the camera turns 2 degrees
 *    in azimuth and a frame is drawn there (untimed, so that every per-view
 *    step runs again), then it turns back and the reconstruction's
 *    incremental update and the frame (supersampled as above) are timed:
 *    `NewViewSeconds`.
 *
 * The frame is the mean of `Supersampling`^2 frames at `Size`, shifted by
 * sub-pixel offsets on a rotated grid
 * (vtkBrumeFloatImageCapture::CaptureSupersampled), so that, like the
 * reference path tracer's pixels, each pixel estimates the radiance
 * averaged over its area. The output is that image: point data `Radiance`
 * (float RGB, row 0 at the bottom).
 *
 * Needs an OpenGL context (an X display; `xvfb-run -a` without one). A
 * first run in a process also pays OpenGL's start-up and shader
 * compilation: run one untimed first when the times matter.
 *
 * @sa vtkBrumeErrorChart vtkBrumeImageError
 */
#ifndef vtkBrumeTimedPipeline_h
#define vtkBrumeTimedPipeline_h

#include "vtkBrumeEvaluationModule.h" // For export macro
#include "vtkBrumeViewImageAlgorithm.h"
#include "vtkSmartPointer.h" // For Pipeline

class vtkBrumePipeline;

class VTKBRUMEEVALUATION_EXPORT vtkBrumeTimedPipeline : public vtkBrumeViewImageAlgorithm
{
public:
  static vtkBrumeTimedPipeline* New();
  vtkTypeMacro(vtkBrumeTimedPipeline, vtkBrumeViewImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Samples per pixel along each axis: Supersampling^2 frames (default 4, in [1, 16]).
  vtkSetClampMacro(Supersampling, int, 1, 16);
  vtkGetMacro(Supersampling, int);
  ///@}

  /**
   * The pipeline it runs (vtkBrumePipeline): every setting of the phases is
   * set there, on the filter that owns it, and defaulted there. The
   * setters below are shortcuts to the same settings.
   */
  vtkBrumePipeline* GetPipeline();

  ///@{
  /// The light tracer's NumberOfParticles, Seed, MaximumDepth (1 keeps the
  /// light scattered or reflected once: vtkBrumeReferencePathTracer's
  /// MaximumDepth of the same value renders the same light),
  /// MediumAimFraction and SplitHeavyParticles.
  void SetNumberOfParticles(vtkTypeInt64 particles);
  vtkTypeInt64 GetNumberOfParticles();
  void SetSeed(vtkIdType seed);
  vtkIdType GetSeed();
  void SetMaximumDepth(int depth);
  int GetMaximumDepth();
  void SetMediumAimFraction(double fraction);
  double GetMediumAimFraction();
  void SetSplitHeavyParticles(bool split);
  bool GetSplitHeavyParticles();
  vtkBooleanMacro(SplitHeavyParticles, bool);
  ///@}

  ///@{
  /// The reconstruction's RadiosityThreshold, CentroidMatching,
  /// DirectionalRadiance (spherical-harmonics media) and DirectionalOrder.
  void SetRadiosityThreshold(double threshold);
  double GetRadiosityThreshold();
  void SetCentroidMatching(bool matching);
  bool GetCentroidMatching();
  vtkBooleanMacro(CentroidMatching, bool);
  void SetDirectionalRadiance(bool directional);
  bool GetDirectionalRadiance();
  vtkBooleanMacro(DirectionalRadiance, bool);
  void SetDirectionalOrder(int order);
  int GetDirectionalOrder();
  ///@}

  ///@{
  /// Time a new viewpoint after the full run (default on).
  vtkSetMacro(MeasureNewView, bool);
  vtkGetMacro(MeasureNewView, bool);
  vtkBooleanMacro(MeasureNewView, bool);
  ///@}

  ///@{
  /// Seconds of the last update's full run and of its new viewpoint (0 when not measured).
  vtkGetMacro(FullSeconds, double);
  vtkGetMacro(NewViewSeconds, double);
  ///@}

protected:
  vtkBrumeTimedPipeline();
  ~vtkBrumeTimedPipeline() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  vtkMTimeType GetMTime() override;

  int Supersampling = 4;
  bool MeasureNewView = true;
  double FullSeconds = 0;
  double NewViewSeconds = 0;

private:
  vtkSmartPointer<vtkBrumePipeline> Pipeline;

  vtkBrumeTimedPipeline(const vtkBrumeTimedPipeline&) = delete;
  void operator=(const vtkBrumeTimedPipeline&) = delete;
};

#endif
