// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeEvaluationAlgorithm
 * @brief   what the error chart and the stability sweep share
 *
 * A study of a scene (the input: any data object the scene conversion
 * accepts) seen from one view, whose measurements are rows of a vtkTable:
 * the image size, the particle budgets of the pipeline, the samples of the
 * converged reference and where it is cached, the reconstruction's
 * threshold, the seed, the order of directional media and the camera (or
 * else the scene's camera, or else Brume's default view). WriteCsv() saves
 * the last output; subclasses draw it (WriteImage()).
 *
 * @sa vtkBrumeErrorChart vtkBrumeStabilitySweep
 */
#ifndef vtkBrumeEvaluationAlgorithm_h
#define vtkBrumeEvaluationAlgorithm_h

#include "vtkBrumeEvaluationModule.h" // For export macro
#include "vtkTableAlgorithm.h"

class vtkCamera;

class VTKBRUMEEVALUATION_EXPORT vtkBrumeEvaluationAlgorithm : public vtkTableAlgorithm
{
public:
  vtkTypeMacro(vtkBrumeEvaluationAlgorithm, vtkTableAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Image size in pixels (each in [1, 16384]; the default is the subclass's).
  vtkSetVector2Macro(Size, int);
  vtkGetVector2Macro(Size, int);
  ///@}

  ///@{
  /// The pipeline's particle budgets (how they are used: the subclass's).
  vtkSetMacro(MinParticles, vtkTypeInt64);
  vtkGetMacro(MinParticles, vtkTypeInt64);
  vtkSetMacro(MaxParticles, vtkTypeInt64);
  vtkGetMacro(MaxParticles, vtkTypeInt64);
  ///@}

  ///@{
  /// Samples per pixel of the converged reference.
  vtkSetMacro(ReferenceSamples, int);
  vtkGetMacro(ReferenceSamples, int);
  ///@}

  ///@{
  /// The reconstruction's radiosity threshold (default: the reconstruction's).
  vtkSetMacro(RadiosityThreshold, double);
  vtkGetMacro(RadiosityThreshold, double);
  ///@}

  ///@{
  /// Seed of the light tracer and the path tracer (default 0, non-negative).
  vtkSetMacro(Seed, vtkIdType);
  vtkGetMacro(Seed, vtkIdType);
  ///@}

  ///@{
  /// Spherical-harmonics order of the directional media (default 3, in [1, 3]).
  vtkSetMacro(DirectionalOrder, int);
  vtkGetMacro(DirectionalOrder, int);
  ///@}

  ///@{
  /**
   * The pipeline's samples per pixel along each axis: Supersampling^2
   * frames on a rotated grid (vtkBrumeTimedPipeline; default 4, in
   * [1, 16]), each pixel's area as the path tracer integrates it. A k x k
   * grid places a straight edge to 1/k^2 of a pixel, and along an edge
   * where the image steps by orders of magnitude (an emitter's) that
   * error adds up and stays whatever the particles: the default scene at
   * 10^7 particles has 0.60 % block error at 4 x 4 and 0.28 % at 8 x 8,
   * 64 frames of 3-4 ms at 128 x 128 on llvmpipe.
   */
  vtkSetClampMacro(Supersampling, int, 1, 16);
  vtkGetMacro(Supersampling, int);
  ///@}

  ///@{
  /// The camera; without one, the scene's camera or Brume's default view.
  void SetCamera(vtkCamera* camera);
  vtkGetObjectMacro(Camera, vtkCamera);
  ///@}

  ///@{
  /// Where converged references are kept (default empty: rendered every time).
  vtkSetStringMacro(CacheDirectory);
  vtkGetStringMacro(CacheDirectory);
  ///@}

  ///@{
  /**
   * The scene's name (default "scene": titles and cache files), and what
   * names it in the cached references' file names instead when set
   * (default empty). The key must change whenever the scene or the camera
   * does (see vtkBrumeReferenceCache).
   */
  vtkSetStringMacro(SceneName);
  vtkGetStringMacro(SceneName);
  vtkSetStringMacro(CacheKey);
  vtkGetStringMacro(CacheKey);
  ///@}

  /// Writes the last output as CSV (the subclass's columns); false if it could not.
  bool WriteCsv(const char* fileName);

  vtkMTimeType GetMTime() override;

protected:
  vtkBrumeEvaluationAlgorithm();
  ~vtkBrumeEvaluationAlgorithm() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;

  /// The settings every study needs (reported as errors): the size and the seed.
  bool CheckCommonSettings();

  int Size[2] = { 64, 64 };
  vtkTypeInt64 MinParticles = 100;
  vtkTypeInt64 MaxParticles = 1000000;
  int ReferenceSamples = 4096;
  double RadiosityThreshold; // vtkBrumeRadianceReconstruction's default
  vtkIdType Seed = 0;
  int DirectionalOrder = 3;
  int Supersampling = 4;
  vtkCamera* Camera = nullptr;
  char* CacheDirectory = nullptr;
  char* SceneName = nullptr;
  char* CacheKey = nullptr;

private:
  vtkBrumeEvaluationAlgorithm(const vtkBrumeEvaluationAlgorithm&) = delete;
  void operator=(const vtkBrumeEvaluationAlgorithm&) = delete;
};

#endif
