// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeSliceVolumeMapper.h"

#include "vtkBrumeDataModelNames.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkIntArray.h"
#include "vtkObjectFactory.h"
#include "vtkRenderer.h"
#include "vtkVolumeCollection.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

vtkAbstractObjectFactoryNewMacro(vtkBrumeSliceVolumeMapper);

namespace
{
// Directional radiance (the array `coefficients`) needs the phase
// function's g.
std::string CheckAsymmetry(vtkFieldData* fd, const char* coefficients)
{
  vtkDataArray* g = fd->GetArray(vtkBrumeNames::PhaseAsymmetry);
  if (!g || g->GetNumberOfTuples() < 1 || !(std::abs(g->GetTuple1(0)) < 1.0))
  {
    return std::string("directional radiance ('") + coefficients +
      "') needs the field array 'BrumePhaseAsymmetry' with the phase function's g in (-1, 1)";
  }
  return {};
}
}

vtkBrumeSliceVolumeMapper::vtkBrumeSliceVolumeMapper() = default;
vtkBrumeSliceVolumeMapper::~vtkBrumeSliceVolumeMapper() = default;

void vtkBrumeSliceVolumeMapper::SetVolumeGroup(vtkVolumeCollection* volumes)
{
  if (this->VolumeGroup != volumes)
  {
    this->VolumeGroup = volumes;
    this->Modified();
  }
}

vtkVolumeCollection* vtkBrumeSliceVolumeMapper::GetVolumeGroup()
{
  return this->VolumeGroup;
}

vtkVolumeCollection* vtkBrumeSliceVolumeMapper::GetDrawnVolumes(vtkRenderer* ren)
{
  return this->VolumeGroup ? this->VolumeGroup.GetPointer() : ren->GetVolumes();
}

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
  if (vtkDataArray* forward = image->GetFieldData()->GetArray(vtkBrumeNames::ForwardFraction))
  {
    const double f = forward->GetNumberOfTuples() > 0 ? forward->GetTuple1(0) : -1.0;
    if (!(f >= 0.0 && f < 1.0))
    {
      return "the field array 'BrumeForwardFraction' needs one value in [0, 1)";
    }
  }
  const vtkIdType cells =
    static_cast<vtkIdType>(pointDims[0] - 1) * (pointDims[1] - 1) * (pointDims[2] - 1);
  if (IsSparseSource(image))
  {
    const int dims[3] = { pointDims[0] - 1, pointDims[1] - 1, pointDims[2] - 1 };
    return ValidateSourceBricks(image, dims);
  }
  vtkDataArray* source = image->GetCellData()->GetArray(vtkBrumeNames::SourceRadiance);
  vtkDataArray* extinction = image->GetCellData()->GetArray(vtkBrumeNames::Extinction);
  if (!source || !extinction || source->GetNumberOfComponents() != 3 ||
    (extinction->GetNumberOfComponents() != 1 && extinction->GetNumberOfComponents() != 3) ||
    source->GetNumberOfTuples() != cells || extinction->GetNumberOfTuples() != cells)
  {
    return "the medium image needs the cell arrays 'SourceRadiance' (3 components) and "
           "'Extinction' (1 or 3 components), one tuple per cell";
  }
  if (vtkDataArray* sh = image->GetCellData()->GetArray(vtkBrumeNames::SourceRadianceSH))
  {
    const int order = DirectionalOrder(sh->GetNumberOfComponents());
    if (order < 1 || sh->GetNumberOfTuples() != cells)
    {
      return "the cell array 'SourceRadianceSH' needs 3 (order + 1)^2 components (order 1 to 3), "
             "one tuple per cell";
    }
    return CheckAsymmetry(image->GetFieldData(), vtkBrumeNames::SourceRadianceSH);
  }
  return {};
}

bool vtkBrumeSliceVolumeMapper::IsSparseSource(vtkImageData* image)
{
  return image && image->GetFieldData()->GetArray(vtkBrumeNames::SourceBrickSlots) != nullptr;
}

std::string vtkBrumeSliceVolumeMapper::ValidateSourceBricks(vtkImageData* image, const int cells[3])
{
  vtkFieldData* fd = image->GetFieldData();
  vtkDataArray* slots = fd->GetArray(vtkBrumeNames::SourceBrickSlots);
  vtkDataArray* source = fd->GetArray(vtkBrumeNames::SourceRadianceBrickSamples);
  vtkDataArray* sh = fd->GetArray(vtkBrumeNames::SourceRadianceSHBrickSamples);
  vtkIdType bricks = 1;
  for (int a = 0; a < 3; ++a)
  {
    bricks *= SourceBricksAlong(cells[a]);
  }
  const vtkIdType brickCells = static_cast<vtkIdType>(SourceBrickEdge(cells[0])) *
    SourceBrickEdge(cells[1]) * SourceBrickEdge(cells[2]);
  if (slots->GetNumberOfComponents() != 1 || slots->GetNumberOfTuples() != bricks || !source ||
    source->GetNumberOfComponents() != 3 || source->GetNumberOfTuples() % brickCells != 0)
  {
    return "the sparse source radiance needs the field arrays 'SourceBrickSlots' (one integer "
           "per brick, " +
      std::to_string(bricks) + " here) and 'SourceRadianceBrickSamples' (3 components, " +
      std::to_string(brickCells) + " tuples per slot)";
  }
  const vtkIdType slotCount = source->GetNumberOfTuples() / brickCells;
  if (sh &&
    (DirectionalOrder(sh->GetNumberOfComponents()) < 1 ||
      sh->GetNumberOfTuples() != source->GetNumberOfTuples()))
  {
    return "the field array 'SourceRadianceSHBrickSamples' needs 3 (order + 1)^2 components "
           "(order 1 to 3) and as many tuples as 'SourceRadianceBrickSamples'";
  }
  for (vtkIdType b = 0; b < bricks; ++b)
  {
    const double slot = slots->GetTuple1(b);
    if (!(slot >= -1.0 && slot < static_cast<double>(slotCount)) || slot != std::floor(slot))
    {
      return "the sparse source radiance's brick " + std::to_string(b) +
        " names a slot that 'SourceRadianceBrickSamples' does not hold";
    }
  }
  return sh ? CheckAsymmetry(fd, vtkBrumeNames::SourceRadianceSHBrickSamples) : std::string();
}

vtkSmartPointer<vtkDataArray> vtkBrumeSliceVolumeMapper::DenseSourceArray(
  vtkImageData* image, const char* name)
{
  if (!image)
  {
    return nullptr;
  }
  if (!IsSparseSource(image))
  {
    return image->GetCellData()->GetArray(name);
  }
  int pointDims[3];
  image->GetDimensions(pointDims);
  const int cells[3] = { pointDims[0] - 1, pointDims[1] - 1, pointDims[2] - 1 };
  vtkFieldData* fd = image->GetFieldData();
  vtkDataArray* slots = fd->GetArray(vtkBrumeNames::SourceBrickSlots);
  vtkDataArray* samples = fd->GetArray(vtkBrumeNames::BrickSamplesName(name).c_str());
  if (cells[0] < 1 || cells[1] < 1 || cells[2] < 1 || !samples ||
    !ValidateSourceBricks(image, cells).empty())
  {
    return nullptr;
  }
  const int n = samples->GetNumberOfComponents();
  const int bricks[3] = { SourceBricksAlong(cells[0]), SourceBricksAlong(cells[1]),
    SourceBricksAlong(cells[2]) };
  const int edge[3] = { SourceBrickEdge(cells[0]), SourceBrickEdge(cells[1]),
    SourceBrickEdge(cells[2]) };
  auto dense = vtkSmartPointer<vtkFloatArray>::New();
  dense->SetName(name);
  dense->SetNumberOfComponents(n);
  dense->SetNumberOfTuples(static_cast<vtkIdType>(cells[0]) * cells[1] * cells[2]);
  float* out = dense->GetPointer(0);
  auto* typed = vtkFloatArray::FastDownCast(samples);
  vtkIdType cell = 0;
  for (int k = 0; k < cells[2]; ++k)
    for (int j = 0; j < cells[1]; ++j)
      for (int i = 0; i < cells[0]; ++i, ++cell)
      {
        const vtkIdType brick =
          (static_cast<vtkIdType>(k / edge[2]) * bricks[1] + j / edge[1]) * bricks[0] + i / edge[0];
        const vtkIdType slot = static_cast<vtkIdType>(slots->GetTuple1(brick));
        float* to = out + cell * n;
        if (slot < 0)
        {
          std::fill_n(to, n, 0.f);
          continue;
        }
        const vtkIdType from = slot * edge[0] * edge[1] * edge[2] +
          (static_cast<vtkIdType>(k % edge[2]) * edge[1] + j % edge[1]) * edge[0] + i % edge[0];
        for (int c = 0; c < n; ++c)
        {
          to[c] = typed ? typed->GetTypedComponent(from, c)
                        : static_cast<float>(samples->GetComponent(from, c));
        }
      }
  return dense;
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
  vtkDataArray* slots = fd->GetArray(vtkBrumeNames::ExtinctionBrickSlots);
  vtkDataArray* values = fd->GetArray(vtkBrumeNames::ExtinctionBrickValues);
  vtkDataArray* scale = fd->GetArray(vtkBrumeNames::ExtinctionScale);
  vtkIdType bricks = 1;
  for (int a = 0; a < 3; ++a)
  {
    bricks *= ExtinctionBricksAlong(pointDims[a] - 1);
  }
  const vtkIdType brickCells =
    static_cast<vtkIdType>(ExtinctionBrickSize) * ExtinctionBrickSize * ExtinctionBrickSize;
  // The samples in slots, or the cells' own values (one per cell).
  const bool cellValues = fd->GetArray(vtkBrumeNames::ExtinctionBrickSamples) != samples;
  const vtkIdType cells =
    static_cast<vtkIdType>(pointDims[0] - 1) * (pointDims[1] - 1) * (pointDims[2] - 1);
  if (!slots || !values || !scale || slots->GetNumberOfComponents() != 1 ||
    values->GetNumberOfComponents() != 1 || samples->GetNumberOfComponents() != 1 ||
    scale->GetNumberOfComponents() != 3 || scale->GetNumberOfTuples() < 1 ||
    slots->GetNumberOfTuples() != bricks || values->GetNumberOfTuples() != bricks ||
    (cellValues ? samples->GetNumberOfTuples() != cells
                : samples->GetNumberOfTuples() % brickCells != 0))
  {
    return "the sparse extinction needs the field arrays 'ExtinctionBrickSlots' and "
           "'ExtinctionBrickValues' (one value per brick), 'ExtinctionBrickSamples' (" +
      std::to_string(brickCells) +
      " values per slot) or 'ExtinctionCellValues' (one value per cell), and "
      "'ExtinctionScale' (3 components)";
  }
  vtkDataArray* table = fd->GetArray(vtkBrumeNames::ExtinctionTransferFunction);
  vtkDataArray* range = fd->GetArray(vtkBrumeNames::ExtinctionTransferRange);
  if (table || range)
  {
    if (!table || !range || table->GetNumberOfComponents() != 1 || table->GetNumberOfTuples() < 2 ||
      range->GetNumberOfComponents() != 2 || range->GetNumberOfTuples() < 1)
    {
      return "classified scalars need 'ExtinctionTransferFunction' (at least two values) and "
             "'ExtinctionTransferRange' (2 components)";
    }
    const double lo = range->GetComponent(0, 0), hi = range->GetComponent(0, 1);
    if (!std::isfinite(lo) || !std::isfinite(hi) || !(hi > lo))
    {
      return "'ExtinctionTransferRange' must be two finite scalars, the first below the second";
    }
    for (vtkIdType i = 0; i < table->GetNumberOfTuples(); ++i)
    {
      const double v = table->GetTuple1(i);
      if (!(v >= 0.0) || !std::isfinite(v))
      {
        return "'ExtinctionTransferFunction' value " + std::to_string(i) +
          " is negative or not finite";
      }
    }
    if (vtkDataArray* albedo = fd->GetArray(vtkBrumeNames::AlbedoTransferFunction))
    {
      if (albedo->GetNumberOfComponents() != 3 ||
        albedo->GetNumberOfTuples() != table->GetNumberOfTuples())
      {
        return "'AlbedoTransferFunction' needs 3 components and as many tuples as "
               "'ExtinctionTransferFunction'";
      }
      for (vtkIdType i = 0; i < albedo->GetNumberOfValues(); ++i)
      {
        const double v = albedo->GetComponent(i / 3, static_cast<int>(i % 3));
        if (!(v >= 0.0 && v <= 1.0))
        {
          return "'AlbedoTransferFunction' value " + std::to_string(i) + " is not in [0, 1]";
        }
      }
    }
  }
  else if (fd->GetArray(vtkBrumeNames::AlbedoTransferFunction))
  {
    return "'AlbedoTransferFunction' needs classified scalars ('ExtinctionTransferFunction')";
  }
  // Slots in samples must be held there; slots of cells' values are where
  // the bricks go, each brick its own (fewer than the bricks).
  const vtkIdType slotCount = cellValues ? bricks : samples->GetNumberOfTuples() / brickCells;
  std::vector<char> taken(cellValues ? static_cast<std::size_t>(bricks) : 0, 0);
  vtkIntArray* ints = vtkIntArray::FastDownCast(slots); // the reconstruction's
  for (vtkIdType b = 0; b < bricks; ++b)
  {
    const double slot = ints ? ints->GetValue(b) : slots->GetTuple1(b);
    if (!(slot >= -1.0 && slot < static_cast<double>(slotCount)) || slot != std::floor(slot))
    {
      return "the sparse extinction's brick " + std::to_string(b) + " names a slot that " +
        (cellValues ? "is not below the number of bricks"
                    : "'ExtinctionBrickSamples' does not hold");
    }
    if (cellValues && slot >= 0.0 && taken[static_cast<std::size_t>(slot)]++)
    {
      return "the sparse extinction's brick " + std::to_string(b) +
        " names the slot of another brick ('ExtinctionCellValues' gives each its own)";
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
  vtkDataArray* samples = fd->GetArray(vtkBrumeNames::ExtinctionBrickSamples);
  if (!samples)
  {
    samples = fd->GetArray(vtkBrumeNames::ExtinctionCellValues);
  }
  if (samples)
  {
    const std::string problem = ValidateBricks(pointDims, fd, samples);
    if (!problem.empty())
    {
      return problem;
    }
  }
  else
  {
    vtkDataArray* e = extinction->GetCellData()->GetArray(vtkBrumeNames::Extinction);
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

void vtkBrumeSliceVolumeMapper::SetSliceSpacingScale(double scale)
{
  this->SliceSpacingScale = std::isnan(scale) ? 1.0 : std::min(16.0, std::max(1.0, scale));
}

void vtkBrumeSliceVolumeMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "VolumeGroup: " << this->VolumeGroup.GetPointer() << "\n";
  os << indent << "SliceSpacing: " << this->SliceSpacing << "\n";
  os << indent << "SliceSpacingScale: " << this->SliceSpacingScale << "\n";
  os << indent << "SlabSampling: " << this->SlabSampling << "\n";
  os << indent << "WriteDepth: " << this->WriteDepth << "\n";
  os << indent << "RadianceScale: " << this->RadianceScale << "\n";
  os << indent << "DirectionalEvaluation: "
     << (this->DirectionalEvaluation == PerVoxel ? "PerVoxel" : "PerFragment") << "\n";
  os << indent << "ImageSampleDistance: " << this->ImageSampleDistance << "\n";
  os << indent << "LastImageSampleDistance: " << this->LastImageSampleDistance << "\n";
  os << indent << "LastNumberOfSlices: " << this->LastNumberOfSlices << "\n";
  os << indent << "LastSlabSamples: " << this->LastSlabSamples << "\n";
  os << indent << "ExtinctionData: " << this->ExtinctionData.GetPointer() << "\n";
}
