// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeReferencePathTracer
 * @brief   the unbiased reference image of a Brume scene
 *
 * An unbiased volumetric path tracer (brume/PathTracer.h) over the same
 * scene, media, phase functions, BRDFs and lights as vtkBrumeLightTracer:
 * delta tracking with spectral-tracking weights, next-event estimation with
 * multiple importance sampling, ratio-tracked shadow rays, Russian roulette.
 * It renders the scene's camera (or the one set here) into a float image:
 * point data `Radiance` (RGB, W m^-2 sr^-1, the pixel's mean) and `Variance`
 * (RGB, the variance of that mean), one point per pixel, row 0 at the
 * bottom, as vtkBrumeFloatImageCapture reads the fast pipeline's frames.
 *
 * Input: a scene collection, and optionally vtkLight objects (AddLight).
 * Each sample's random stream depends on (Seed, pixel, sample) only.
 *
 * @sa vtkBrumeLightTracer vtkBrumeRadianceReconstruction
 */
#ifndef vtkBrumeReferencePathTracer_h
#define vtkBrumeReferencePathTracer_h

#include "vtkBrumeTracingModule.h" // For export macro
#include "vtkImageAlgorithm.h"
#include "vtkSmartPointer.h" // For Lights

class vtkCamera;
class vtkLight;
class vtkLightCollection;

class VTKBRUMETRACING_EXPORT vtkBrumeReferencePathTracer : public vtkImageAlgorithm
{
public:
  static vtkBrumeReferencePathTracer* New();
  vtkTypeMacro(vtkBrumeReferencePathTracer, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Image size in pixels (default 256 x 256, each in [1, 16384]).
  vtkSetVector2Macro(Size, int);
  vtkGetVector2Macro(Size, int);
  ///@}

  ///@{
  /// Samples per pixel (default 16, in [1, 1000000]).
  vtkSetMacro(SamplesPerPixel, int);
  vtkGetMacro(SamplesPerPixel, int);
  ///@}

  ///@{
  /// Seed of the samples' random streams (default 0, non-negative).
  vtkSetMacro(Seed, vtkIdType);
  vtkGetMacro(Seed, vtkIdType);
  ///@}

  ///@{
  /**
   * Scattering and reflection vertices after which a path stops (default
   * 1024, in [1, 10^6]), each with its light sample: 1 gives the light
   * scattered or reflected once toward the eye (single scattering), 2 adds
   * the light scattered twice, and so on. vtkBrumeLightTracer's
   * MaximumDepth counts the same interactions from the light's side, so
   * the two images agree order by order.
   */
  vtkSetClampMacro(MaximumDepth, int, 1, 1000000);
  vtkGetMacro(MaximumDepth, int);
  ///@}

  ///@{
  /// The camera; without one, the scene's camera (or (0, 0, 4) looking at the origin).
  void SetCamera(vtkCamera* camera);
  vtkGetObjectMacro(Camera, vtkCamera);
  ///@}

  ///@{
  /// Point, spot and directional lights besides the emissive surfaces.
  void AddLight(vtkLight* light);
  void RemoveAllLights();
  ///@}

  vtkMTimeType GetMTime() override;

protected:
  vtkBrumeReferencePathTracer();
  ~vtkBrumeReferencePathTracer() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int Size[2] = { 256, 256 };
  int SamplesPerPixel = 16;
  vtkIdType Seed = 0;
  int MaximumDepth = 1024;
  vtkCamera* Camera = nullptr;
  vtkSmartPointer<vtkLightCollection> Lights;

private:
  vtkBrumeReferencePathTracer(const vtkBrumeReferencePathTracer&) = delete;
  void operator=(const vtkBrumeReferencePathTracer&) = delete;
};

#endif
