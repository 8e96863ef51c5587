// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeSliceVolumeMapper.h"

#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkObjectFactory.h"

#include <algorithm>
#include <cmath>

vtkAbstractObjectFactoryNewMacro(vtkBrumeSliceVolumeMapper);

vtkBrumeSliceVolumeMapper::vtkBrumeSliceVolumeMapper() = default;
vtkBrumeSliceVolumeMapper::~vtkBrumeSliceVolumeMapper() = default;

int vtkBrumeSliceVolumeMapper::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

std::string vtkBrumeSliceVolumeMapper::ValidateInput(vtkImageData* image)
{
  if (!image)
  {
    return "no input image";
  }
  int pointDims[3];
  image->GetDimensions(pointDims);
  const double* spacing = image->GetSpacing();
  for (int a = 0; a < 3; ++a)
  {
    if (pointDims[a] < 2)
    {
      return "the medium image needs at least one cell along each axis (empty extent)";
    }
    if (!(spacing[a] > 0.0) || !std::isfinite(spacing[a]))
    {
      return "the medium image needs a positive spacing";
    }
  }
  const vtkIdType cells =
    static_cast<vtkIdType>(pointDims[0] - 1) * (pointDims[1] - 1) * (pointDims[2] - 1);
  vtkDataArray* source = image->GetCellData()->GetArray("SourceRadiance");
  vtkDataArray* extinction = image->GetCellData()->GetArray("Extinction");
  if (!source || !extinction || source->GetNumberOfComponents() != 3 ||
    (extinction->GetNumberOfComponents() != 1 && extinction->GetNumberOfComponents() != 3) ||
    source->GetNumberOfTuples() != cells || extinction->GetNumberOfTuples() != cells)
  {
    return "the medium image needs the cell arrays 'SourceRadiance' (3 components) and "
           "'Extinction' (1 or 3 components), one tuple per cell";
  }
  if (vtkDataArray* sh = image->GetCellData()->GetArray("SourceRadianceSH"))
  {
    const int order = DirectionalOrder(sh->GetNumberOfComponents());
    vtkDataArray* g = image->GetFieldData()->GetArray("BrumePhaseAsymmetry");
    if (order < 1 || sh->GetNumberOfTuples() != cells)
    {
      return "the cell array 'SourceRadianceSH' needs 3 (order + 1)^2 components (order 1 to 3), "
             "one tuple per cell";
    }
    if (!g || g->GetNumberOfTuples() < 1 || !(std::abs(g->GetTuple1(0)) < 1.0))
    {
      return "directional radiance ('SourceRadianceSH') needs the field array "
             "'BrumePhaseAsymmetry' with the phase function's g in (-1, 1)";
    }
  }
  return {};
}

void vtkBrumeSliceVolumeMapper::SetExtinctionData(vtkImageData* extinction)
{
  if (this->ExtinctionData != extinction)
  {
    this->ExtinctionData = extinction;
    this->Modified();
  }
}

vtkImageData* vtkBrumeSliceVolumeMapper::GetExtinctionData()
{
  return this->ExtinctionData;
}

vtkMTimeType vtkBrumeSliceVolumeMapper::GetMTime()
{
  const vtkMTimeType t = this->Superclass::GetMTime();
  return this->ExtinctionData ? std::max(t, this->ExtinctionData->GetMTime()) : t;
}

std::string vtkBrumeSliceVolumeMapper::ValidateBricks(
  const int pointDims[3], vtkFieldData* fd, vtkDataArray* samples)
{
  vtkDataArray* slots = fd->GetArray("ExtinctionBrickSlots");
  vtkDataArray* values = fd->GetArray("ExtinctionBrickValues");
  vtkDataArray* scale = fd->GetArray("ExtinctionScale");
  vtkIdType bricks = 1;
  for (int a = 0; a < 3; ++a)
  {
    bricks *= ExtinctionBricksAlong(pointDims[a] - 1);
  }
  const vtkIdType brickCells =
    static_cast<vtkIdType>(ExtinctionBrickSize) * ExtinctionBrickSize * ExtinctionBrickSize;
  if (!slots || !values || !scale || slots->GetNumberOfComponents() != 1 ||
    values->GetNumberOfComponents() != 1 || samples->GetNumberOfComponents() != 1 ||
    scale->GetNumberOfComponents() != 3 || scale->GetNumberOfTuples() < 1 ||
    slots->GetNumberOfTuples() != bricks || values->GetNumberOfTuples() != bricks ||
    samples->GetNumberOfTuples() % brickCells != 0)
  {
    return "the sparse extinction needs the field arrays 'ExtinctionBrickSlots' and "
           "'ExtinctionBrickValues' (one value per brick), 'ExtinctionBrickSamples' (" +
      std::to_string(brickCells) + " values per slot) and 'ExtinctionScale' (3 components)";
  }
  const vtkIdType slotCount = samples->GetNumberOfTuples() / brickCells;
  for (vtkIdType b = 0; b < bricks; ++b)
  {
    const double slot = slots->GetTuple1(b);
    if (!(slot >= -1.0 && slot < static_cast<double>(slotCount)) || slot != std::floor(slot))
    {
      return "the sparse extinction's brick " + std::to_string(b) +
        " names a slot that 'ExtinctionBrickSamples' does not hold";
    }
  }
  return {};
}

std::string vtkBrumeSliceVolumeMapper::ValidateExtinction(
  vtkImageData* image, vtkImageData* extinction)
{
  int pointDims[3];
  extinction->GetDimensions(pointDims);
  const double* spacing = extinction->GetSpacing();
  for (int a = 0; a < 3; ++a)
  {
    if (pointDims[a] < 2 || !(spacing[a] > 0.0) || !std::isfinite(spacing[a]))
    {
      return "the extinction image needs at least one cell and a positive spacing along each axis";
    }
  }
  const vtkIdType cells =
    static_cast<vtkIdType>(pointDims[0] - 1) * (pointDims[1] - 1) * (pointDims[2] - 1);
  vtkFieldData* fd = extinction->GetFieldData();
  if (vtkDataArray* samples = fd->GetArray("ExtinctionBrickSamples"))
  {
    const std::string problem = ValidateBricks(pointDims, fd, samples);
    if (!problem.empty())
    {
      return problem;
    }
  }
  else
  {
    vtkDataArray* e = extinction->GetCellData()->GetArray("Extinction");
    if (!e || (e->GetNumberOfComponents() != 1 && e->GetNumberOfComponents() != 3) ||
      e->GetNumberOfTuples() != cells)
    {
      return "the extinction image needs the cell array 'Extinction' (1 or 3 components), one "
             "tuple per cell, or the sparse form's field arrays";
    }
  }
  double a[6], b[6];
  image->GetBounds(a);
  extinction->GetBounds(b);
  for (int k = 0; k < 3; ++k)
  {
    const double size = a[2 * k + 1] - a[2 * k];
    if (b[2 * k] > a[2 * k] + 1e-6 * size || b[2 * k + 1] < a[2 * k + 1] - 1e-6 * size)
    {
      return "the extinction image must cover the medium image's box";
    }
  }
  return {};
}

int vtkBrumeSliceVolumeMapper::DirectionalOrder(int components)
{
  for (int order = 1; order <= 3; ++order)
  {
    if (components == 3 * (order + 1) * (order + 1))
    {
      return order;
    }
  }
  return -1;
}

void vtkBrumeSliceVolumeMapper::SetImageSampleDistance(double distance)
{
  this->ImageSampleDistance = std::isnan(distance) ? 1.0 : std::min(16.0, std::max(1.0, distance));
}

void vtkBrumeSliceVolumeMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SliceSpacing: " << this->SliceSpacing << "\n";
  os << indent << "WriteDepth: " << this->WriteDepth << "\n";
  os << indent << "RadianceScale: " << this->RadianceScale << "\n";
  os << indent << "DirectionalEvaluation: "
     << (this->DirectionalEvaluation == PerVoxel ? "PerVoxel" : "PerFragment") << "\n";
  os << indent << "ImageSampleDistance: " << this->ImageSampleDistance << "\n";
  os << indent << "LastImageSampleDistance: " << this->LastImageSampleDistance << "\n";
  os << indent << "LastNumberOfSlices: " << this->LastNumberOfSlices << "\n";
  os << indent << "ExtinctionData: " << this->ExtinctionData.GetPointer() << "\n";
}
