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
 * - **Albedo** (the single-scattering albedo) from the property's colour
 *   transfer function of that component, classified after interpolation
 *   like the opacity: the albedo at x is Albedo * colour(s(x)) per
 *   channel, so a white point scatters the fraction Albedo (default 0.8,
 *   0.8, 0.8) of the light it stops and a black point absorbs it all
 *   (brume::ClassifiedAlbedo). This is read when ColorAsAlbedo is on (the
 *   default) and the property's colour for the component is an RGB
 *   function (GetColorChannels() is 3, as after SetColor() with a
 *   vtkColorTransferFunction); an RGB-space function with default
 *   midpoints and sharpness is taken node for node, any other (ParaView's
 *   diverging and Lab colour maps) sampled at SampledFunctionPoints
 *   points (as are log-scale functions). Otherwise (ColorAsAlbedo off, or
 *   a grey function) the albedo is Albedo everywhere. Either way sigma_t
 *   is the opacity's alone. Beyond their points both functions keep their
 *   end values, as with VTK's Clamping on (a function with Clamping off,
 *   or above- and below-range colours, is read clamped all the same).
 *
 * The array is the first input array to process (default: the point
 * scalars, else the cell scalars), and it must have a name. The output's
 * field data gains BrumeSigmaA, BrumeSigmaS, BrumeG, BrumeDensityArray,
 * BrumeScalarComponent, BrumeScalarOpacity, BrumeScalarOpacityUnitDistance,
 * BrumeInterpolation and, with a colour, BrumeScalarColor (scalar, red,
 * green, blue), replacing any of those the input had.
 *
 * Any other dataset (an unstructured or curvilinear grid) is resampled to
 * an image first (vtkResampleToImage) over its bounds, at
 * SamplingDimensions or, by default, at one point per cell: a spacing of
 * the cube root of (bounds' volume / cells) along every axis, at least 2
 * points an axis, grown evenly until the image holds at most
 * MaximumSampledPoints. Points outside the dataset take a scalar the
 * function takes to 0 (its first point of opacity 0). An OpenVDB grid is
 * classified in place by the same field arrays on its medium image
 * (BrumeVDBFile beside BrumeScalarOpacity; scene files:
 * density.transfer_function).
 *
 * @sa vtkBrumeSceneConversion vtkVolumeProperty vtkPiecewiseFunction
 */
#ifndef vtkBrumeVolumePropertyMedium_h
#define vtkBrumeVolumePropertyMedium_h

#include "vtkBrumeDataModelModule.h" // For export macro
#include "vtkImageAlgorithm.h"
#include "vtkSmartPointer.h" // For the functions set one by one

class vtkColorTransferFunction;
class vtkDataArray;
class vtkDataSet;
class vtkImageData;
class vtkPiecewiseFunction;
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
  /**
   * Without a VolumeProperty, the functions and settings it would hold,
   * one by one, as ParaView's "Brume Medium From Field" filter sets them
   * from the colour map and opacity editor of the array: the scalar
   * opacity (required then), the colour (none: one albedo), the unit
   * distance (default 1), the interpolation (VTK_LINEAR_INTERPOLATION,
   * the default, or VTK_NEAREST_INTERPOLATION) and g (default 0). A
   * VolumeProperty, when set, is used instead.
   */
  void SetScalarOpacity(vtkPiecewiseFunction* function);
  vtkPiecewiseFunction* GetScalarOpacity();
  void SetColor(vtkColorTransferFunction* function);
  vtkColorTransferFunction* GetColor();
  vtkSetMacro(ScalarOpacityUnitDistance, double);
  vtkGetMacro(ScalarOpacityUnitDistance, double);
  vtkSetClampMacro(InterpolationType, int, VTK_NEAREST_INTERPOLATION, VTK_LINEAR_INTERPOLATION);
  vtkGetMacro(InterpolationType, int);
  vtkSetMacro(ScatteringAnisotropy, double);
  vtkGetMacro(ScatteringAnisotropy, double);
  ///@}

  ///@{
  /// The component of the array, and of the property's functions (default 0).
  vtkSetClampMacro(Component, int, 0, 3);
  vtkGetMacro(Component, int);
  ///@}

  ///@{
  /**
   * Single-scattering albedo per channel, each in [0, 1] (default 0.8,
   * 0.8, 0.8): the medium's, or with a colour function its factor.
   */
  vtkSetVector3Macro(Albedo, double);
  vtkGetVector3Macro(Albedo, double);
  ///@}

  ///@{
  /// Whether the property's RGB colour function colours the albedo (default on).
  vtkSetMacro(ColorAsAlbedo, bool);
  vtkGetMacro(ColorAsAlbedo, bool);
  vtkBooleanMacro(ColorAsAlbedo, bool);
  ///@}

  ///@{
  /// Points at which a function that is not piecewise linear is sampled (default 1024).
  vtkSetClampMacro(SampledFunctionPoints, int, 2, 65536);
  vtkGetMacro(SampledFunctionPoints, int);
  ///@}

  ///@{
  /**
   * The image a dataset other than vtkImageData is resampled to: its
   * points along each axis (default 0, 0, 0: chosen from the cells' size,
   * above), and the most points a chosen image may hold (default 2^24).
   */
  vtkSetVector3Macro(SamplingDimensions, int);
  vtkGetVector3Macro(SamplingDimensions, int);
  vtkSetClampMacro(MaximumSampledPoints, vtkIdType, 8, VTK_ID_MAX);
  vtkGetMacro(MaximumSampledPoints, vtkIdType);
  ///@}

  /**
   * The points along each axis the default rule gives `dataset` (above);
   * false when it has no cells, its bounds are empty or flat along an
   * axis, or `maximumPoints` is below 8.
   */
  static bool ChooseSamplingDimensions(vtkDataSet* dataset, vtkIdType maximumPoints, int dims[3]);

  /// Also the property's and its functions' modification times.
  vtkMTimeType GetMTime() override;

protected:
  vtkBrumeVolumePropertyMedium();
  ~vtkBrumeVolumePropertyMedium() override;

  // An image's extent and spacing are the input's (the executive's copy);
  // a resampled dataset's are known once it is resampled.
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override
  {
    return 1;
  }
  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  // RequestData's steps. The property to apply: VolumeProperty, or one made
  // of the functions set one by one (null, after an error, without either).
  vtkSmartPointer<vtkVolumeProperty> EffectiveProperty();
  // Whether the array to process and the settings can make a medium (an
  // error says why not).
  bool CheckInputArray(vtkDataArray* scalars);
  // A dataset other than an image resampled to one, with `scalars` probed
  // (null after an error): points outside the dataset take *outsideScalar,
  // or 0 with a warning when it is null. Sets the output's whole extent.
  vtkSmartPointer<vtkImageData> ResampleToImage(vtkDataSet* dataset, vtkDataArray* scalars,
    const float* outsideScalar, vtkInformationVector* outputVector);

  vtkVolumeProperty* VolumeProperty = nullptr;
  vtkSmartPointer<vtkPiecewiseFunction> ScalarOpacity;
  vtkSmartPointer<vtkColorTransferFunction> Color;
  double ScalarOpacityUnitDistance = 1.0;
  int InterpolationType = VTK_LINEAR_INTERPOLATION;
  double ScatteringAnisotropy = 0.0;
  int Component = 0;
  double Albedo[3] = { 0.8, 0.8, 0.8 };
  bool ColorAsAlbedo = true;
  int SampledFunctionPoints = 1024;
  int SamplingDimensions[3] = { 0, 0, 0 };
  vtkIdType MaximumSampledPoints = vtkIdType(1) << 24;

private:
  vtkBrumeVolumePropertyMedium(const vtkBrumeVolumePropertyMedium&) = delete;
  void operator=(const vtkBrumeVolumePropertyMedium&) = delete;
};

#endif
