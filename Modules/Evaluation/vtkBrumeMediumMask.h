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
#include "vtkBrumeViewImageAlgorithm.h"

class VTKBRUMEEVALUATION_EXPORT vtkBrumeMediumMask : public vtkBrumeViewImageAlgorithm
{
public:
  static vtkBrumeMediumMask* New();
  vtkTypeMacro(vtkBrumeMediumMask, vtkBrumeViewImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

protected:
  vtkBrumeMediumMask();
  ~vtkBrumeMediumMask() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkBrumeMediumMask(const vtkBrumeMediumMask&) = delete;
  void operator=(const vtkBrumeMediumMask&) = delete;
};

#endif
