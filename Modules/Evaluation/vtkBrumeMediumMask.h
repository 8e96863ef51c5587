// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeMediumMask
 * @brief   the pixels whose camera ray crosses a medium of the scene
 *
 * For each pixel of a `Size` image seen by the camera, casts the ray
 * through the pixel's centre (brume::PinholeCamera, row 0 at the bottom, as
 * vtkBrumeReferencePathTracer's pixels) and marks it when the ray meets the
 * bounds of a medium: any vtkImageData object of the scene collection,
 * whatever lies in front of it. The output is a vtkImageData of `Size`
 * points with the unsigned char point scalars `MediumMask` (1 in a medium,
 * 0 elsewhere), the mask vtkBrumeImageError::Compare() takes.
 *
 * Input: a scene collection (see vtkBrumeSceneConversion).
 *
 * @sa vtkBrumeImageError vtkBrumeErrorChart
 */
#ifndef vtkBrumeMediumMask_h
#define vtkBrumeMediumMask_h

#include "vtkBrumeEvaluationModule.h" // For export macro
#include "vtkImageAlgorithm.h"

class vtkCamera;

class VTKBRUMEEVALUATION_EXPORT vtkBrumeMediumMask : public vtkImageAlgorithm
{
public:
  static vtkBrumeMediumMask* New();
  vtkTypeMacro(vtkBrumeMediumMask, vtkImageAlgorithm);
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
  vtkBrumeMediumMask();
  ~vtkBrumeMediumMask() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  int Size[2] = { 256, 256 };
  vtkCamera* Camera = nullptr;

private:
  vtkBrumeMediumMask(const vtkBrumeMediumMask&) = delete;
  void operator=(const vtkBrumeMediumMask&) = delete;
};

#endif
