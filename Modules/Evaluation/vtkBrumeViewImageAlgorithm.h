// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeViewImageAlgorithm
 * @brief   an image of a scene seen by a camera: the base of the evaluation's images
 *
 * A vtkImageAlgorithm whose input is a scene (any data object the scene
 * conversion accepts) and whose output is a `Size` image seen by `Camera`:
 * without a camera, the scene's own (its field data) or Brume's default view
 * (vtkBrumeSceneCamera). Changing the camera re-executes the algorithm.
 *
 * @sa vtkBrumeMediumMask vtkBrumeReferenceCache vtkBrumeTimedPipeline
 */
#ifndef vtkBrumeViewImageAlgorithm_h
#define vtkBrumeViewImageAlgorithm_h

#include "vtkBrumeEvaluationModule.h" // For export macro
#include "vtkImageAlgorithm.h"

class vtkCamera;

class VTKBRUMEEVALUATION_EXPORT vtkBrumeViewImageAlgorithm : public vtkImageAlgorithm
{
public:
  vtkTypeMacro(vtkBrumeViewImageAlgorithm, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Image size in pixels (default 256 x 256, each in [1, 16384]).
  vtkSetVector2Macro(Size, int);
  vtkGetVector2Macro(Size, int);
  ///@}

  ///@{
  /**
   * The camera; without one, the scene's camera (its field data), or
   * Brume's default view from (0, 0, 4) toward the origin, 40 degrees.
   */
  void SetCamera(vtkCamera* camera);
  vtkGetObjectMacro(Camera, vtkCamera);
  ///@}

  vtkMTimeType GetMTime() override;

protected:
  vtkBrumeViewImageAlgorithm();
  ~vtkBrumeViewImageAlgorithm() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  /// The whole extent of a `Size` image, unit spacing, origin at 0.
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int Size[2] = { 256, 256 };
  vtkCamera* Camera = nullptr;

private:
  vtkBrumeViewImageAlgorithm(const vtkBrumeViewImageAlgorithm&) = delete;
  void operator=(const vtkBrumeViewImageAlgorithm&) = delete;
};

#endif
