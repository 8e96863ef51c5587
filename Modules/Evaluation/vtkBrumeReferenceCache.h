// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeReferenceCache
 * @brief   a converged reference image, read from disk when it was rendered before
 *
 * Converged references (vtkBrumeReferencePathTracer at thousands of samples
 * per pixel) take minutes to hours: they are kept in `CacheDirectory` as
 * binary VTK XML images (binary: readable despite expat's reparse deferral),
 * one file per
 *
 *   brume-reference-SCENEKEY-WxH-sppN-seedS-v1.vti
 *
 * where SCENEKEY is `SceneKey` with every character other than letters,
 * digits, '.', '_' and '-' replaced by '-'. The key does not see the scene's
 * contents nor the camera: give every scene (and camera) its own SceneKey,
 * and change it when the scene changes. A present file with a `Radiance`
 * point array is read; otherwise the path tracer renders the image and it is
 * written there (the directory is created). With an empty CacheDirectory
 * the image is rendered and nothing is written.
 *
 * Input: a scene collection. Output: the reference image (point data
 * `Radiance` and, when rendered or cached with it, `Variance`).
 *
 * @sa vtkBrumeReferencePathTracer vtkBrumeErrorChart
 */
#ifndef vtkBrumeReferenceCache_h
#define vtkBrumeReferenceCache_h

#include "vtkBrumeEvaluationModule.h" // For export macro
#include "vtkBrumeViewImageAlgorithm.h"

#include <string> // For FileName

class VTKBRUMEEVALUATION_EXPORT vtkBrumeReferenceCache : public vtkBrumeViewImageAlgorithm
{
public:
  static vtkBrumeReferenceCache* New();
  vtkTypeMacro(vtkBrumeReferenceCache, vtkBrumeViewImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Samples per pixel of the reference (default 16384, in [1, 1000000]).
  vtkSetMacro(SamplesPerPixel, int);
  vtkGetMacro(SamplesPerPixel, int);
  ///@}

  ///@{
  /// Seed of the path tracer (default 0, non-negative).
  vtkSetMacro(Seed, vtkIdType);
  vtkGetMacro(Seed, vtkIdType);
  ///@}

  ///@{
  /// Where references are kept (default empty: render, keep nothing).
  vtkSetStringMacro(CacheDirectory);
  vtkGetStringMacro(CacheDirectory);
  ///@}

  ///@{
  /// What names the scene in the file names (default "scene").
  vtkSetStringMacro(SceneKey);
  vtkGetStringMacro(SceneKey);
  ///@}

  /// The cache file of the last update (empty without a CacheDirectory).
  const char* GetFileName() { return this->FileName.c_str(); }

  /// True when the last update read the image from the cache.
  vtkGetMacro(ReadFromCache, bool);

  /// Seconds the last update spent path tracing (0 when it read the cache).
  vtkGetMacro(RenderSeconds, double);

protected:
  vtkBrumeReferenceCache();
  ~vtkBrumeReferenceCache() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int SamplesPerPixel = 16384;
  vtkIdType Seed = 0;
  char* CacheDirectory = nullptr;
  char* SceneKey = nullptr;
  std::string FileName;
  bool ReadFromCache = false;
  double RenderSeconds = 0;

private:
  vtkBrumeReferenceCache(const vtkBrumeReferenceCache&) = delete;
  void operator=(const vtkBrumeReferenceCache&) = delete;
};

#endif
