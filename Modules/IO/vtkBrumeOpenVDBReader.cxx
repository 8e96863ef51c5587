// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeOpenVDBReader.h"

#include "brume/VdbDensity.h"
#include "brume/VdbGrid.h"

#include "vtkBrumeDataModelNames.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"

#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>

#include <filesystem>
#include <mutex>

vtkStandardNewMacro(vtkBrumeOpenVDBReader);

namespace
{
void InitializeOpenVDB()
{
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}
}

vtkBrumeOpenVDBReader::vtkBrumeOpenVDBReader()
{
  this->SetNumberOfInputPorts(0);
  this->GridNames->SetName("GridNames");
}

vtkBrumeOpenVDBReader::~vtkBrumeOpenVDBReader() = default;

vtkStringArray* vtkBrumeOpenVDBReader::GetGridNames()
{
  return this->GridNames;
}

int vtkBrumeOpenVDBReader::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector*)
{
  this->GridNames->Reset();
  InitializeOpenVDB();
  const std::string invalid = brume::CheckVdbFile(this->FileName);
  if (!invalid.empty())
  {
    vtkErrorMacro("Cannot read OpenVDB file: " << invalid << ".");
    return 0;
  }
  try
  {
    openvdb::io::File file(this->FileName);
    file.open(false);
    for (auto it = file.beginName(); it != file.endName(); ++it)
    {
      if (file.readGridMetadata(it.gridName())->isType<openvdb::FloatGrid>())
      {
        this->GridNames->InsertNextValue(it.gridName());
      }
    }
    file.close();
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(
      "Cannot read OpenVDB file '" << this->FileName << "': " << brume::ShortMessage(e.what()));
    return 0;
  }
  return 1;
}

int vtkBrumeOpenVDBReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  auto* output = vtkImageData::GetData(outputVector, 0);
  InitializeOpenVDB();
  std::string error;
  const openvdb::FloatGrid::Ptr grid = brume::ReadVdbFloatGrid(this->FileName, this->GridName, error);
  if (!grid)
  {
    vtkErrorMacro("" << error << ".");
    return 0;
  }
  const std::string name = grid->getName();
  const openvdb::math::Transform& transform = grid->transform();
  const openvdb::CoordBBox bbox = grid->evalActiveVoxelBoundingBox();
  if (bbox.empty())
  {
    vtkErrorMacro("Grid '" << name << "' has no active voxels.");
    return 0;
  }
  const openvdb::Vec3d origin = transform.indexToWorld(openvdb::Vec3d(0.0));
  const openvdb::Vec3d voxel = transform.indexToWorld(openvdb::Vec3d(1.0)) - origin;
  const int k = this->Downsample;
  const openvdb::Coord lo = bbox.min(), dim = bbox.dim();
  int dims[3];
  for (int a = 0; a < 3; ++a)
  {
    if (!(voxel[a] > 0.0))
    {
      vtkErrorMacro("Grid '" << name << "' has a non-positive voxel size.");
      return 0;
    }
    dims[a] = std::max(2, (dim[a] + k - 1) / k);
  }
  output->SetOrigin(
    origin[0] + lo[0] * voxel[0], origin[1] + lo[1] * voxel[1], origin[2] + lo[2] * voxel[2]);
  if (this->SparseReference)
  {
    // Only the box: the tracer reads the grid in place.
    output->SetDimensions(2, 2, 2);
    output->SetSpacing((dim[0] - 1) * voxel[0], (dim[1] - 1) * voxel[1], (dim[2] - 1) * voxel[2]);
    vtkNew<vtkStringArray> file, gridName;
    file->SetName(vtkBrumeNames::VDBFile);
    file->InsertNextValue(std::filesystem::absolute(this->FileName).string());
    gridName->SetName(vtkBrumeNames::VDBGrid);
    gridName->InsertNextValue(name);
    output->GetFieldData()->AddArray(file);
    output->GetFieldData()->AddArray(gridName);
    return 1;
  }
  const double bytes = 4.0 * dims[0] * static_cast<double>(dims[1]) * dims[2];
  if (bytes > static_cast<double>(this->MemoryLimit))
  {
    vtkErrorMacro("A dense copy of grid '"
      << name << "' would take " << bytes / (1 << 20) << " MiB, more than MemoryLimit ("
      << this->MemoryLimit / (1 << 20) << " MiB): raise Downsample or use SparseReference.");
    return 0;
  }
  output->SetDimensions(dims);
  output->SetSpacing(k * voxel[0], k * voxel[1], k * voxel[2]);
  vtkNew<vtkFloatArray> values;
  values->SetName(name.c_str());
  values->SetNumberOfTuples(static_cast<vtkIdType>(dims[0]) * dims[1] * dims[2]);
  auto accessor = grid->getConstAccessor();
  vtkIdType n = 0;
  for (int z = 0; z < dims[2]; ++z)
  {
    for (int y = 0; y < dims[1]; ++y)
    {
      for (int x = 0; x < dims[0]; ++x)
      {
        const openvdb::Coord ijk(lo[0] + x * k, lo[1] + y * k, lo[2] + z * k);
        values->SetValue(n++, accessor.getValue(ijk));
      }
    }
    this->UpdateProgress(static_cast<double>(z + 1) / dims[2]);
  }
  output->GetPointData()->SetScalars(values);
  return 1;
}

void vtkBrumeOpenVDBReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "GridName: " << this->GridName << "\n";
  os << indent << "Downsample: " << this->Downsample << "\n";
  os << indent << "MemoryLimit: " << this->MemoryLimit << "\n";
  os << indent << "SparseReference: " << this->SparseReference << "\n";
}
