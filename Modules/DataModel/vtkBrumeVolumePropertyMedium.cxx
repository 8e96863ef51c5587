// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeVolumePropertyMedium.h"

#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkObjectFactory.h"
#include "vtkPiecewiseFunction.h"
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
void SetField(vtkFieldData* fd, const char* name, const double* values, int n)
{
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->SetNumberOfComponents(n);
  a->InsertNextTuple(values);
  fd->RemoveArray(name);
  fd->AddArray(a);
}

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
  points.clear();
  for (int i = 0; i < samples; ++i)
  {
    const double s = lo + (hi - lo) * i / (samples - 1);
    points.push_back({ s, f->GetValue(s) });
  }
  return points;
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

vtkMTimeType vtkBrumeVolumePropertyMedium::GetMTime()
{
  vtkMTimeType t = this->Superclass::GetMTime();
  if (this->VolumeProperty)
  {
    t = std::max(t, this->VolumeProperty->GetMTime());
    if (vtkPiecewiseFunction* f = this->VolumeProperty->GetScalarOpacity(this->Component))
    {
      t = std::max(t, f->GetMTime());
    }
  }
  return t;
}

int vtkBrumeVolumePropertyMedium::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkImageData* output = vtkImageData::GetData(outputVector);
  if (!input || !output)
  {
    vtkErrorMacro("needs a vtkImageData input");
    return 0;
  }
  if (!this->VolumeProperty)
  {
    vtkErrorMacro("has no VolumeProperty");
    return 0;
  }
  int association = 0;
  vtkDataArray* scalars = this->GetInputArrayToProcess(0, inputVector, association);
  if (!scalars)
  {
    vtkErrorMacro("finds no array to process (point or cell scalars, or the one named by "
                  "SetInputArrayToProcess) in its input");
    return 0;
  }
  if (!scalars->GetName() || !*scalars->GetName())
  {
    vtkErrorMacro("needs the array to process to have a name");
    return 0;
  }
  if (this->Component >= scalars->GetNumberOfComponents())
  {
    vtkErrorMacro("has Component " << this->Component << " but the array '" << scalars->GetName()
                                   << "' has " << scalars->GetNumberOfComponents()
                                   << " components");
    return 0;
  }
  for (int c = 0; c < 3; ++c)
  {
    if (!(this->Albedo[c] >= 0.0 && this->Albedo[c] <= 1.0))
    {
      vtkErrorMacro("has an Albedo outside [0, 1]: " << this->Albedo[0] << ", " << this->Albedo[1]
                                                     << ", " << this->Albedo[2]);
      return 0;
    }
  }
  vtkPiecewiseFunction* opacity = this->VolumeProperty->GetScalarOpacity(this->Component);
  const std::vector<std::array<double, 2>> points = Points(opacity, this->SampledFunctionPoints);
  std::vector<brume::OpacityTransferFunction::Node> nodes;
  for (const auto& p : points)
  {
    nodes.push_back({ static_cast<float>(p[0]), static_cast<float>(p[1]) });
  }
  const double unit = this->VolumeProperty->GetScalarOpacityUnitDistance(this->Component);
  const std::string error = brume::OpacityTransferFunction::Validate(nodes, unit);
  if (!error.empty())
  {
    vtkErrorMacro(
      "has a volume property whose scalar opacity (component " << this->Component << ") " << error);
    return 0;
  }

  output->ShallowCopy(input);
  vtkNew<vtkFieldData> fd;
  fd->DeepCopy(input->GetFieldData());
  const double sigmaA[3] = { 1.0 - this->Albedo[0], 1.0 - this->Albedo[1], 1.0 - this->Albedo[2] };
  SetField(fd, "BrumeSigmaA", sigmaA, 3);
  SetField(fd, "BrumeSigmaS", this->Albedo, 3);
  const double g =
    std::clamp(static_cast<double>(this->VolumeProperty->GetScatteringAnisotropy()), -0.999, 0.999);
  SetField(fd, "BrumeG", &g, 1);
  const double component = this->Component;
  SetField(fd, "BrumeScalarComponent", &component, 1);
  SetField(fd, "BrumeScalarOpacityUnitDistance", &unit, 1);
  SetString(fd, "BrumeDensityArray", scalars->GetName());
  SetString(fd, "BrumeInterpolation",
    this->VolumeProperty->GetInterpolationType() == VTK_NEAREST_INTERPOLATION ? "nearest"
                                                                              : "linear");
  vtkNew<vtkDoubleArray> function;
  function->SetName("BrumeScalarOpacity");
  function->SetNumberOfComponents(2);
  for (const auto& p : points)
  {
    function->InsertNextTuple(p.data());
  }
  fd->RemoveArray("BrumeScalarOpacity");
  fd->AddArray(function);
  fd->RemoveArray("BrumeDensityScale");
  fd->RemoveArray("BrumeVDBFile");
  output->SetFieldData(fd);
  return 1;
}

void vtkBrumeVolumePropertyMedium::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "VolumeProperty: " << this->VolumeProperty << "\n";
  os << indent << "Component: " << this->Component << "\n";
  os << indent << "Albedo: " << this->Albedo[0] << ", " << this->Albedo[1] << ", "
     << this->Albedo[2] << "\n";
  os << indent << "SampledFunctionPoints: " << this->SampledFunctionPoints << "\n";
}
