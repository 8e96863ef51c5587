// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeTimedPipeline
 * @brief   the three phases at one particle budget: their image and their times
 *
 * Runs the fast pipeline on the input scene as `brume render` does, and
 * times it:
 *
 * 1. light tracing (vtkBrumeLightTracer, NumberOfParticles, Seed), radiance
 *    reconstruction (vtkBrumeRadianceReconstruction for the camera, with
 *    RadiosityThreshold and, when DirectionalRadiance is on, the media's
 *    spherical harmonics up to DirectionalOrder) and the off-screen frame
 *    (vtkBrumeSceneActors; Supersampling^2 renders read back and averaged
 *    by vtkBrumeFloatImageCapture): the full time, `FullSeconds`;
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

  ///@{
  /// Particles traced (default 1,000,000).
  vtkSetMacro(NumberOfParticles, vtkTypeInt64);
  vtkGetMacro(NumberOfParticles, vtkTypeInt64);
  ///@}

  ///@{
  /// Seed of the light tracer (default 0).
  vtkSetMacro(Seed, vtkIdType);
  vtkGetMacro(Seed, vtkIdType);
  ///@}

  ///@{
  /// The light tracer's MaximumDepth (default 1024): 1 keeps the light
  /// scattered or reflected once (vtkBrumeReferencePathTracer's MaximumDepth
  /// of the same value renders the same light).
  vtkSetClampMacro(MaximumDepth, int, 1, 1000000);
  vtkGetMacro(MaximumDepth, int);
  ///@}

  ///@{
  /// The reconstruction's radiosity threshold (default 128 hits).
  vtkSetMacro(RadiosityThreshold, double);
  vtkGetMacro(RadiosityThreshold, double);
  ///@}

  ///@{
  /// The light tracer's MediumAimFraction (default 0.2).
  vtkSetClampMacro(MediumAimFraction, double, 0.0, 0.99);
  vtkGetMacro(MediumAimFraction, double);
  /// The light tracer's SplitHeavyParticles (default on).
  vtkSetMacro(SplitHeavyParticles, bool);
  vtkGetMacro(SplitHeavyParticles, bool);
  vtkBooleanMacro(SplitHeavyParticles, bool);

  /// The reconstruction's CentroidMatching (default on).
  vtkSetMacro(CentroidMatching, bool);
  vtkGetMacro(CentroidMatching, bool);
  vtkBooleanMacro(CentroidMatching, bool);
  ///@}

  ///@{
  /// Directional (spherical-harmonics) media, and their order (default off, 3).
  vtkSetMacro(DirectionalRadiance, bool);
  vtkGetMacro(DirectionalRadiance, bool);
  vtkBooleanMacro(DirectionalRadiance, bool);
  vtkSetMacro(DirectionalOrder, int);
  vtkGetMacro(DirectionalOrder, int);
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

  int Supersampling = 4;
  vtkTypeInt64 NumberOfParticles = 1000000;
  vtkIdType Seed = 0;
  int MaximumDepth = 1024;
  double RadiosityThreshold = 128.0;
  bool CentroidMatching = true;
  double MediumAimFraction = 0.2;
  bool SplitHeavyParticles = true;
  bool DirectionalRadiance = false;
  int DirectionalOrder = 3;
  bool MeasureNewView = true;
  double FullSeconds = 0;
  double NewViewSeconds = 0;

private:
  vtkBrumeTimedPipeline(const vtkBrumeTimedPipeline&) = delete;
  void operator=(const vtkBrumeTimedPipeline&) = delete;
};

#endif
