// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeVolumePropertyMedium.h"

#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeFieldTuple.h"
#include "vtkCharArray.h"
#include "vtkColorTransferFunction.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkDataSet.h"
#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkObjectFactory.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkResampleToImage.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtkVolumeProperty.h"

#include "brume/TransferFunction.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

vtkStandardNewMacro(vtkBrumeVolumePropertyMedium);
vtkCxxSetObjectMacro(vtkBrumeVolumePropertyMedium, VolumeProperty, vtkVolumeProperty);

namespace
{
void SetString(vtkFieldData* fd, const char* name, const std::string& value)
{
  vtkNew<vtkStringArray> a;
  a->SetName(name);
  a->InsertNextValue(value);
  fd->RemoveArray(name);
  fd->AddArray(a);
}

// The function's (scalar, opacity) points: its nodes when it is piecewise
// linear (midpoints 0.5, sharpness 0), else `samples` samples over its range.
std::vector<std::array<double, 2>> Points(vtkPiecewiseFunction* f, int samples)
{
  std::vector<std::array<double, 2>> points;
  bool linear = true;
  double node[4];
  for (int i = 0; i < f->GetSize(); ++i)
  {
    f->GetNodeValue(i, node);
    linear = linear && node[2] == 0.5 && node[3] == 0.0;
    points.push_back({ node[0], node[1] });
  }
  if (linear || points.size() < 2)
  {
    return points;
  }
  const double lo = points.front()[0], hi = points.back()[0];
  std::vector<double> values(static_cast<std::size_t>(samples));
  f->GetTable(lo, hi, samples, values.data());
  points.clear();
  for (int i = 0; i < samples; ++i)
  {
    points.push_back({ lo + (hi - lo) * i / (samples - 1), values[i] });
  }
  return points;
}

// The function's (scalar, red, green, blue) points: its nodes when it is
// piecewise linear in RGB over a linear scale (midpoints 0.5, sharpness 0),
// else `samples` samples over its range (GetTable follows a log scale).
std::vector<std::array<double, 4>> Points(vtkColorTransferFunction* f, int samples)
{
  std::vector<std::array<double, 4>> points;
  bool linear = f->GetColorSpace() == VTK_CTF_RGB && f->GetScale() == VTK_CTF_LINEAR;
  double node[6];
  for (int i = 0; i < f->GetSize(); ++i)
  {
    f->GetNodeValue(i, node);
    linear = linear && node[4] == 0.5 && node[5] == 0.0;
    points.push_back({ node[0], node[1], node[2], node[3] });
  }
  if (linear || points.size() < 2)
  {
    return points;
  }
  const double lo = points.front()[0], hi = points.back()[0];
  std::vector<double> rgb(3 * static_cast<std::size_t>(samples));
  f->GetTable(lo, hi, samples, rgb.data());
  points.clear();
  for (int i = 0; i < samples; ++i)
  {
    points.push_back(
      { lo + (hi - lo) * i / (samples - 1), rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2] });
  }
  return points;
}

// Replaces the transfer functions' field arrays: BrumeScalarOpacity, and
// BrumeScalarColor only with `colors`.
void SetFunctionFields(vtkFieldData* fd, const std::vector<std::array<double, 2>>& points,
  const std::vector<std::array<double, 4>>& colors)
{
  vtkNew<vtkDoubleArray> function;
  function->SetName(vtkBrumeNames::ScalarOpacity);
  function->SetNumberOfComponents(2);
  for (const auto& p : points)
  {
    function->InsertNextTuple(p.data());
  }
  fd->RemoveArray(vtkBrumeNames::ScalarOpacity);
  fd->AddArray(function);
  fd->RemoveArray(vtkBrumeNames::ScalarColor);
  if (!colors.empty())
  {
    vtkNew<vtkDoubleArray> color;
    color->SetName(vtkBrumeNames::ScalarColor);
    color->SetNumberOfComponents(4);
    for (const auto& p : colors)
    {
      color->InsertNextTuple(p.data());
    }
    fd->AddArray(color);
  }
}
}

vtkBrumeVolumePropertyMedium::vtkBrumeVolumePropertyMedium()
{
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS_THEN_CELLS, vtkDataSetAttributes::SCALARS);
}

vtkBrumeVolumePropertyMedium::~vtkBrumeVolumePropertyMedium()
{
  this->SetVolumeProperty(nullptr);
}

void vtkBrumeVolumePropertyMedium::SetScalarOpacity(vtkPiecewiseFunction* function)
{
  if (this->ScalarOpacity != function)
  {
    this->ScalarOpacity = function;
    this->Modified();
  }
}

void vtkBrumeVolumePropertyMedium::SetColor(vtkColorTransferFunction* function)
{
  if (this->Color != function)
  {
    this->Color = function;
    this->Modified();
  }
}

vtkPiecewiseFunction* vtkBrumeVolumePropertyMedium::GetScalarOpacity()
{
  return this->ScalarOpacity;
}

vtkColorTransferFunction* vtkBrumeVolumePropertyMedium::GetColor()
{
  return this->Color;
}

vtkMTimeType vtkBrumeVolumePropertyMedium::GetMTime()
{
  vtkMTimeType t = this->Superclass::GetMTime();
  if (this->ScalarOpacity)
  {
    t = std::max(t, this->ScalarOpacity->GetMTime());
  }
  if (this->Color)
  {
    t = std::max(t, this->Color->GetMTime());
  }
  if (this->VolumeProperty)
  {
    t = std::max(t, this->VolumeProperty->GetMTime());
    if (vtkPiecewiseFunction* f = this->VolumeProperty->GetScalarOpacity(this->Component))
    {
      t = std::max(t, f->GetMTime());
    }
    if (this->VolumeProperty->GetColorChannels(this->Component) == 3)
    {
      t = std::max(t, this->VolumeProperty->GetRGBTransferFunction(this->Component)->GetMTime());
    }
  }
  return t;
}

int vtkBrumeVolumePropertyMedium::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
  return 1;
}

bool vtkBrumeVolumePropertyMedium::ChooseSamplingDimensions(
  vtkDataSet* dataset, vtkIdType maximumPoints, int dims[3])
{
  double b[6];
  dataset->GetBounds(b);
  const double extent[3] = { b[1] - b[0], b[3] - b[2], b[5] - b[4] };
  const vtkIdType cells = dataset->GetNumberOfCells();
  if (maximumPoints < 8 || cells < 1 || !(extent[0] > 0.0 && extent[1] > 0.0 && extent[2] > 0.0) ||
    !std::isfinite(extent[0] * extent[1] * extent[2]))
  {
    return false;
  }
  // One point per cell: the spacing of `cells` cubes filling the bounds.
  double spacing = std::cbrt(extent[0] * extent[1] * extent[2] / static_cast<double>(cells));
  for (;;)
  {
    double points = 1.0;
    for (int a = 0; a < 3; ++a)
    {
      dims[a] = static_cast<int>(std::min(
        std::max(2.0, std::round(extent[a] / spacing) + 1.0), static_cast<double>(VTK_INT_MAX)));
      points *= dims[a];
    }
    if (points <= static_cast<double>(maximumPoints))
    {
      return true;
    }
    spacing *= 1.05;
  }
}

vtkSmartPointer<vtkVolumeProperty> vtkBrumeVolumePropertyMedium::EffectiveProperty()
{
  vtkSmartPointer<vtkVolumeProperty> property = this->VolumeProperty;
  if (!property)
  {
    if (!this->ScalarOpacity)
    {
      vtkErrorMacro("has no opacity transfer function to make a medium of its scalars: set "
                    "ScalarOpacity (in ParaView, Scalar Opacity Function: the array's opacity "
                    "function, which the Color Map Editor edits) or a VolumeProperty");
      return nullptr;
    }
    property = vtkSmartPointer<vtkVolumeProperty>::New();
    property->SetScalarOpacity(this->Component, this->ScalarOpacity);
    property->SetScalarOpacityUnitDistance(this->Component, this->ScalarOpacityUnitDistance);
    if (this->Color)
    {
      property->SetColor(this->Component, this->Color);
    }
    property->SetInterpolationType(this->InterpolationType);
    property->SetScatteringAnisotropy(static_cast<float>(this->ScatteringAnisotropy));
  }
  return property;
}

bool vtkBrumeVolumePropertyMedium::CheckInputArray(vtkDataArray* scalars)
{
  if (!scalars)
  {
    vtkErrorMacro("finds no array to process (point or cell scalars, or the one named by "
                  "SetInputArrayToProcess; in ParaView, Scalars) in its input");
    return false;
  }
  if (!scalars->GetName() || !*scalars->GetName())
  {
    vtkErrorMacro("needs the array to process to have a name");
    return false;
  }
  if (this->Component >= scalars->GetNumberOfComponents())
  {
    vtkErrorMacro("has Component " << this->Component << " but the array '" << scalars->GetName()
                                   << "' has " << scalars->GetNumberOfComponents()
                                   << " components");
    return false;
  }
  for (int c = 0; c < 3; ++c)
  {
    if (!(this->Albedo[c] >= 0.0 && this->Albedo[c] <= 1.0))
    {
      vtkErrorMacro("has an Albedo outside [0, 1]: " << this->Albedo[0] << ", " << this->Albedo[1]
                                                     << ", " << this->Albedo[2]);
      return false;
    }
  }
  return true;
}

vtkSmartPointer<vtkImageData> vtkBrumeVolumePropertyMedium::ResampleToImage(vtkDataSet* dataset,
  vtkDataArray* scalars, const float* outsideScalar, vtkInformationVector* outputVector)
{
  int dims[3] = { this->SamplingDimensions[0], this->SamplingDimensions[1],
    this->SamplingDimensions[2] };
  if ((dims[0] < 2 || dims[1] < 2 || dims[2] < 2) &&
    !ChooseSamplingDimensions(dataset, this->MaximumSampledPoints, dims))
  {
    vtkErrorMacro("cannot resample a " << dataset->GetClassName()
                                       << " without cells or with flat bounds to an image");
    return nullptr;
  }
  vtkNew<vtkResampleToImage> resample;
  resample->SetInputDataObject(dataset);
  resample->SetSamplingDimensions(dims);
  resample->Update();
  vtkSmartPointer<vtkImageData> input = resample->GetOutput();
  vtkDataArray* probed = input->GetPointData()->GetArray(scalars->GetName());
  auto* valid =
    vtkCharArray::SafeDownCast(input->GetPointData()->GetArray(resample->GetMaskArrayName()));
  if (!probed || !valid)
  {
    vtkErrorMacro(
      "lost the array '" << scalars->GetName() << "' resampling the " << dataset->GetClassName());
    return nullptr;
  }
  // Points outside the dataset: a scalar the function takes to 0.
  for (vtkIdType i = 0; i < probed->GetNumberOfTuples(); ++i)
  {
    if (!valid->GetValue(i))
    {
      for (int c = 0; c < probed->GetNumberOfComponents(); ++c)
      {
        probed->SetComponent(i, c, outsideScalar ? *outsideScalar : 0.0);
      }
    }
  }
  if (!outsideScalar)
  {
    vtkWarningMacro("resampled points outside the "
      << dataset->GetClassName() << " take the scalar 0, and the function has no opacity 0");
  }
  input->GetPointData()->RemoveArray(resample->GetMaskArrayName());
  int extent[6];
  input->GetExtent(extent);
  outputVector->GetInformationObject(0)->Set(
    vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  return input;
}

int vtkBrumeVolumePropertyMedium::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkDataSet* dataset = vtkDataSet::GetData(inputVector[0]);
  vtkImageData* output = vtkImageData::GetData(outputVector);
  if (!dataset || !output)
  {
    vtkErrorMacro("needs a vtkDataSet input");
    return 0;
  }
  // The scalars first (without them no function helps), then the
  // property, or one made of the functions set one by one.
  int association = 0;
  vtkDataArray* scalars = this->GetInputArrayToProcess(0, inputVector, association);
  if (!this->CheckInputArray(scalars))
  {
    return 0;
  }
  vtkSmartPointer<vtkVolumeProperty> property = this->EffectiveProperty();
  if (!property)
  {
    return 0;
  }
  vtkPiecewiseFunction* opacity = property->GetScalarOpacity(this->Component);
  const std::vector<std::array<double, 2>> points = Points(opacity, this->SampledFunctionPoints);
  std::vector<brume::OpacityTransferFunction::Node> nodes;
  for (const auto& p : points)
  {
    nodes.push_back({ static_cast<float>(p[0]), static_cast<float>(p[1]) });
  }
  const double unit = property->GetScalarOpacityUnitDistance(this->Component);
  std::string error = brume::OpacityTransferFunction::Validate(nodes, unit);
  if (!error.empty())
  {
    vtkErrorMacro(
      "has a volume property whose scalar opacity (component " << this->Component << ") " << error);
    return 0;
  }
  std::vector<std::array<double, 4>> colors;
  if (this->ColorAsAlbedo && property->GetColorChannels(this->Component) == 3)
  {
    colors = Points(property->GetRGBTransferFunction(this->Component), this->SampledFunctionPoints);
    std::vector<brume::ColorTransferFunction::Node> colorNodes;
    for (const auto& p : colors)
    {
      colorNodes.push_back({ static_cast<float>(p[0]),
        brume::Vec3(
          static_cast<float>(p[1]), static_cast<float>(p[2]), static_cast<float>(p[3])) });
    }
    error = brume::ColorTransferFunction::Validate(colorNodes);
    if (!error.empty())
    {
      vtkErrorMacro(
        "has a volume property whose colour (component " << this->Component << ") " << error);
      return 0;
    }
  }

  // Another dataset is resampled to an image, its arrays probed at the points.
  vtkSmartPointer<vtkImageData> input = vtkImageData::SafeDownCast(dataset);
  if (!input)
  {
    // Points outside the dataset take a scalar the function takes to 0.
    auto none = std::find_if(nodes.begin(), nodes.end(),
      [](const brume::OpacityTransferFunction::Node& n) { return n.Opacity == 0.f; });
    input = this->ResampleToImage(
      dataset, scalars, none != nodes.end() ? &none->Scalar : nullptr, outputVector);
    if (!input)
    {
      return 0;
    }
  }

  output->ShallowCopy(input);
  vtkNew<vtkFieldData> fd;
  fd->DeepCopy(dataset->GetFieldData());
  const double sigmaA[3] = { 1.0 - this->Albedo[0], 1.0 - this->Albedo[1], 1.0 - this->Albedo[2] };
  vtkBrumeFieldTuple::Set(fd, vtkBrumeNames::SigmaA, sigmaA, 3);
  vtkBrumeFieldTuple::Set(fd, vtkBrumeNames::SigmaS, this->Albedo, 3);
  const double g =
    std::clamp(static_cast<double>(property->GetScatteringAnisotropy()), -0.999, 0.999);
  vtkBrumeFieldTuple::Set(fd, vtkBrumeNames::G, &g, 1);
  const double component = this->Component;
  vtkBrumeFieldTuple::Set(fd, vtkBrumeNames::ScalarComponent, &component, 1);
  vtkBrumeFieldTuple::Set(fd, vtkBrumeNames::ScalarOpacityUnitDistance, &unit, 1);
  SetString(fd, vtkBrumeNames::DensityArray, scalars->GetName());
  SetString(fd, vtkBrumeNames::Interpolation,
    property->GetInterpolationType() == VTK_NEAREST_INTERPOLATION ? "nearest" : "linear");
  SetFunctionFields(fd, points, colors);
  fd->RemoveArray(vtkBrumeNames::DensityScale);
  fd->RemoveArray(vtkBrumeNames::VDBFile);
  output->SetFieldData(fd);
  return 1;
}

void vtkBrumeVolumePropertyMedium::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "VolumeProperty: " << this->VolumeProperty << "\n";
  os << indent << "ScalarOpacity: " << this->ScalarOpacity.Get() << "\n";
  os << indent << "Color: " << this->Color.Get() << "\n";
  os << indent << "ScalarOpacityUnitDistance: " << this->ScalarOpacityUnitDistance << "\n";
  os << indent << "InterpolationType: " << this->InterpolationType << "\n";
  os << indent << "ScatteringAnisotropy: " << this->ScatteringAnisotropy << "\n";
  os << indent << "Component: " << this->Component << "\n";
  os << indent << "Albedo: " << this->Albedo[0] << ", " << this->Albedo[1] << ", "
     << this->Albedo[2] << "\n";
  os << indent << "ColorAsAlbedo: " << this->ColorAsAlbedo << "\n";
  os << indent << "SampledFunctionPoints: " << this->SampledFunctionPoints << "\n";
  os << indent << "SamplingDimensions: " << this->SamplingDimensions[0] << ", "
     << this->SamplingDimensions[1] << ", " << this->SamplingDimensions[2] << "\n";
  os << indent << "MaximumSampledPoints: " << this->MaximumSampledPoints << "\n";
}
