// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeVolumePropertyMedium
 * @brief   makes a participating medium of any scalar field and a vtkVolumeProperty
 *
 * Takes a vtkImageData and the vtkVolumeProperty a VTK volume pipeline
 * renders it with, and outputs the same image marked as a Brume medium
 * (see vtkBrumeSceneConversion), ready for vtkBrumeSceneConversion::AddObject
 * or a scene collection:
 *
 * - **Extinction** from the property's scalar opacity of the chosen
 *   component, classified after interpolation as VTK's ray caster does:
 *   the opacity alpha per ScalarOpacityUnitDistance stands for
 *   sigma_t = -ln(1 - alpha) / unit (brume::OpacityTransferFunction), so a
 *   step dt of the medium lets (1 - alpha)^(dt / unit) through, as VTK
 *   composites it. A piecewise function with midpoints at 0.5 and
 *   sharpness 0 is taken node for node; any other is sampled at
 *   SampledFunctionPoints points over its range, linear in between.
 * - **Interpolation** from the property: linear (trilinear between point
 *   scalars) or nearest. Cell scalars are constant per cell.
 * - **g** (Henyey-Greenstein) from the property's ScatteringAnisotropy
 *   (VTK >= 9.2), held inside (-1, 1).
 * - **Albedo**: one single-scattering albedo colour for the whole medium
 *   (default 0.8, 0.8, 0.8): sigma_s = Albedo sigma_t and sigma_a =
 *   (1 - Albedo) sigma_t. The property's colour transfer function is not
 *   read yet.
 *
 * The array is the first input array to process (default: the point
 * scalars, else the cell scalars), and it must have a name. The output's
 * field data gains BrumeSigmaA, BrumeSigmaS, BrumeG, BrumeDensityArray,
 * BrumeScalarComponent, BrumeScalarOpacity, BrumeScalarOpacityUnitDistance
 * and BrumeInterpolation, replacing any of those the input had.
 *
 * An OpenVDB grid must be resampled to a vtkImageData first; unstructured
 * grids through vtkResampleToImage.
 *
 * @sa vtkBrumeSceneConversion vtkVolumeProperty vtkPiecewiseFunction
 */
#ifndef vtkBrumeVolumePropertyMedium_h
#define vtkBrumeVolumePropertyMedium_h

#include "vtkBrumeDataModelModule.h" // For export macro
#include "vtkImageAlgorithm.h"

class vtkVolumeProperty;

class VTKBRUMEDATAMODEL_EXPORT vtkBrumeVolumePropertyMedium : public vtkImageAlgorithm
{
public:
  static vtkBrumeVolumePropertyMedium* New();
  vtkTypeMacro(vtkBrumeVolumePropertyMedium, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The volume property that defines the medium (required).
  void SetVolumeProperty(vtkVolumeProperty* property);
  vtkGetObjectMacro(VolumeProperty, vtkVolumeProperty);
  ///@}

  ///@{
  /// The component of the array, and of the property's functions (default 0).
  vtkSetClampMacro(Component, int, 0, 3);
  vtkGetMacro(Component, int);
  ///@}

  ///@{
  /// Single-scattering albedo per channel, each in [0, 1] (default 0.8, 0.8, 0.8).
  vtkSetVector3Macro(Albedo, double);
  vtkGetVector3Macro(Albedo, double);
  ///@}

  ///@{
  /// Points at which a function that is not piecewise linear is sampled (default 1024).
  vtkSetClampMacro(SampledFunctionPoints, int, 2, 65536);
  vtkGetMacro(SampledFunctionPoints, int);
  ///@}

  /// Also the property's and its functions' modification times.
  vtkMTimeType GetMTime() override;

protected:
  vtkBrumeVolumePropertyMedium();
  ~vtkBrumeVolumePropertyMedium() override;

  // The output's extent and spacing are the input's (the executive's copy).
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override
  {
    return 1;
  }
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  vtkVolumeProperty* VolumeProperty = nullptr;
  int Component = 0;
  double Albedo[3] = { 0.8, 0.8, 0.8 };
  int SampledFunctionPoints = 1024;

private:
  vtkBrumeVolumePropertyMedium(const vtkBrumeVolumePropertyMedium&) = delete;
  void operator=(const vtkBrumeVolumePropertyMedium&) = delete;
};

#endif
