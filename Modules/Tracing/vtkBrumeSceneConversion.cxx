// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeSceneConversion.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnsignedShortArray.h"

#include <cmath>
#include <sstream>

namespace
{
// Reads a field-data tuple of `n` components; false when absent.
bool ReadField(vtkFieldData* fd, const char* name, int n, double* values, std::string& error)
{
  vtkDataArray* a = fd ? vtkDataArray::SafeDownCast(fd->GetAbstractArray(name)) : nullptr;
  if (!a)
  {
    return false;
  }
  if (a->GetNumberOfTuples() < 1 || a->GetNumberOfComponents() != n)
  {
    std::ostringstream os;
    os << "field array '" << name << "' must have one tuple of " << n << " components";
    error = os.str();
    return false;
  }
  a->GetTuple(0, values);
  return true;
}

bool ReadVec3(vtkFieldData* fd, const char* name, brume::Vec3& v, std::string& error)
{
  double d[3];
  if (!ReadField(fd, name, 3, d, error))
  {
    return false;
  }
  v = { static_cast<float>(d[0]), static_cast<float>(d[1]), static_cast<float>(d[2]) };
  return true;
}

std::string ConvertSurface(vtkPolyData* pd, brume::Surface& s)
{
  std::string error;
  vtkPoints* points = pd->GetPoints();
  if (!points || points->GetNumberOfPoints() == 0)
  {
    return "has no points";
  }
  s.Vertices.resize(points->GetNumberOfPoints());
  for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
  {
    double p[3];
    points->GetPoint(i, p);
    s.Vertices[i] = { static_cast<float>(p[0]), static_cast<float>(p[1]),
      static_cast<float>(p[2]) };
  }
  // Polygons as triangle fans, strips with alternating winding.
  vtkIdType npts = 0;
  const vtkIdType* ids = nullptr;
  vtkCellArray* polys = pd->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(npts, ids);)
  {
    for (vtkIdType k = 2; k < npts; ++k)
    {
      s.Triangles.push_back({ static_cast<std::uint32_t>(ids[0]),
        static_cast<std::uint32_t>(ids[k - 1]), static_cast<std::uint32_t>(ids[k]) });
    }
  }
  vtkCellArray* strips = pd->GetStrips();
  for (strips->InitTraversal(); strips->GetNextCell(npts, ids);)
  {
    for (vtkIdType k = 2; k < npts; ++k)
    {
      const bool even = (k % 2) == 0;
      s.Triangles.push_back({ static_cast<std::uint32_t>(ids[k - 2]),
        static_cast<std::uint32_t>(even ? ids[k - 1] : ids[k]),
        static_cast<std::uint32_t>(even ? ids[k] : ids[k - 1]) });
    }
  }
  if (s.Triangles.empty())
  {
    return "has no polygons";
  }
  vtkFieldData* fd = pd->GetFieldData();
  ReadVec3(fd, "BrumeReflectance", s.Reflectance, error);
  if (error.empty())
  {
    ReadVec3(fd, "BrumeEmission", s.Emission, error);
  }
  return error;
}

std::string ConvertMedium(vtkImageData* image, brume::Medium& m)
{
  std::string error;
  vtkFieldData* fd = image->GetFieldData();
  if (!ReadVec3(fd, "BrumeSigmaA", m.SigmaA, error) ||
    !ReadVec3(fd, "BrumeSigmaS", m.SigmaS, error))
  {
    return error.empty() ? "lacks the BrumeSigmaA or BrumeSigmaS field array" : error;
  }
  double g = 0.0;
  if (ReadField(fd, "BrumeG", 1, &g, error))
  {
    m.G = static_cast<float>(g);
  }
  if (!error.empty())
  {
    return error;
  }
  if (image->GetPointData()->GetNumberOfArrays() > 0 ||
    image->GetCellData()->GetNumberOfArrays() > 0)
  {
    return "carries density arrays: heterogeneous media are not supported yet (the medium "
           "must be homogeneous, given by its bounds and field data)";
  }
  double b[6];
  image->GetBounds(b);
  m.Bounds = { { static_cast<float>(b[0]), static_cast<float>(b[2]), static_cast<float>(b[4]) },
    { static_cast<float>(b[1]), static_cast<float>(b[3]), static_cast<float>(b[5]) } };
  return {};
}
}

std::string vtkBrumeSceneConversion::ToScene(
  vtkDataObject* input, brume::Scene& scene, std::vector<ObjectSource>* sources)
{
  scene = brume::Scene();
  auto* collection = vtkPartitionedDataSetCollection::SafeDownCast(input);
  if (!collection)
  {
    return "the scene must be a vtkPartitionedDataSetCollection";
  }
  std::vector<ObjectSource> surfaceSources, mediumSources;
  for (unsigned int i = 0; i < collection->GetNumberOfPartitionedDataSets(); ++i)
  {
    vtkPartitionedDataSet* pds = collection->GetPartitionedDataSet(i);
    std::string name = "object" + std::to_string(i);
    if (collection->HasMetaData(i) && collection->GetMetaData(i)->Has(vtkCompositeDataSet::NAME()))
    {
      name = collection->GetMetaData(i)->Get(vtkCompositeDataSet::NAME());
    }
    if (!pds || pds->GetNumberOfPartitions() == 0 || !pds->GetPartition(0))
    {
      return "scene object '" + name + "' is empty";
    }
    vtkDataObject* part = pds->GetPartition(0);
    if (auto* pd = vtkPolyData::SafeDownCast(part))
    {
      brume::Surface s;
      s.Name = name;
      const std::string error = ConvertSurface(pd, s);
      if (!error.empty())
      {
        return "surface '" + name + "' " + error;
      }
      scene.Surfaces.push_back(std::move(s));
      surfaceSources.push_back({ i, name });
    }
    else if (auto* image = vtkImageData::SafeDownCast(part))
    {
      brume::Medium m;
      m.Name = name;
      const std::string error = ConvertMedium(image, m);
      if (!error.empty())
      {
        return "medium '" + name + "' " + error;
      }
      scene.Media.push_back(m);
      mediumSources.push_back({ i, name });
    }
    else
    {
      return "scene object '" + name + "' is a " + part->GetClassName() +
        ", not a vtkPolyData surface or a vtkImageData medium";
    }
  }
  if (sources)
  {
    *sources = surfaceSources;
    sources->insert(sources->end(), mediumSources.begin(), mediumSources.end());
  }
  return scene.Validate();
}

vtkSmartPointer<vtkPolyData> vtkBrumeSceneConversion::HitsToPolyData(
  const std::vector<brume::Hit>& hits, const brume::Vec3& totalPower, long long particles)
{
  const auto n = static_cast<vtkIdType>(hits.size());
  vtkNew<vtkPoints> points;
  points->SetDataTypeToFloat();
  points->SetNumberOfPoints(n);
  vtkNew<vtkFloatArray> direction;
  direction->SetName("Direction");
  direction->SetNumberOfComponents(3);
  direction->SetNumberOfTuples(n);
  vtkNew<vtkFloatArray> flux;
  flux->SetName("Flux");
  flux->SetNumberOfComponents(3);
  flux->SetNumberOfTuples(n);
  vtkNew<vtkUnsignedShortArray> object;
  object->SetName("ObjectId");
  object->SetNumberOfTuples(n);
  vtkNew<vtkUnsignedShortArray> emitter;
  emitter->SetName("EmitterId");
  emitter->SetNumberOfTuples(n);
  vtkNew<vtkUnsignedCharArray> depth;
  depth->SetName("Depth");
  depth->SetNumberOfTuples(n);
  auto* p = static_cast<float*>(points->GetVoidPointer(0));
  float* d = direction->GetPointer(0);
  float* f = flux->GetPointer(0);
  for (vtkIdType i = 0; i < n; ++i)
  {
    const brume::Hit& h = hits[i];
    for (int c = 0; c < 3; ++c)
    {
      p[3 * i + c] = h.Position[c];
      d[3 * i + c] = h.Direction[c];
      f[3 * i + c] = h.Flux[c];
    }
    object->SetValue(i, h.Object);
    emitter->SetValue(i, h.Emitter);
    depth->SetValue(i, h.Depth);
  }
  auto output = vtkSmartPointer<vtkPolyData>::New();
  output->SetPoints(points);
  output->GetPointData()->AddArray(direction);
  output->GetPointData()->AddArray(flux);
  output->GetPointData()->AddArray(object);
  output->GetPointData()->AddArray(emitter);
  output->GetPointData()->AddArray(depth);
  vtkNew<vtkDoubleArray> power;
  power->SetName("TotalPower");
  power->SetNumberOfComponents(3);
  power->InsertNextTuple3(totalPower.x, totalPower.y, totalPower.z);
  output->GetFieldData()->AddArray(power);
  vtkNew<vtkDoubleArray> count;
  count->SetName("NumberOfParticles");
  count->InsertNextValue(static_cast<double>(particles));
  output->GetFieldData()->AddArray(count);
  return output;
}

std::string vtkBrumeSceneConversion::HitsFromPolyData(
  vtkPolyData* data, std::vector<brume::Hit>& hits)
{
  hits.clear();
  if (!data)
  {
    return "no particle hits were given";
  }
  const vtkIdType n = data->GetNumberOfPoints();
  vtkPointData* pd = data->GetPointData();
  auto* direction = vtkFloatArray::SafeDownCast(pd->GetArray("Direction"));
  auto* flux = vtkFloatArray::SafeDownCast(pd->GetArray("Flux"));
  auto* object = vtkUnsignedShortArray::SafeDownCast(pd->GetArray("ObjectId"));
  auto* emitter = vtkUnsignedShortArray::SafeDownCast(pd->GetArray("EmitterId"));
  auto* depth = vtkUnsignedCharArray::SafeDownCast(pd->GetArray("Depth"));
  if (n > 0 &&
    (!direction || !flux || !object || direction->GetNumberOfComponents() != 3 ||
      flux->GetNumberOfComponents() != 3))
  {
    return "the particle hits lack the float[3] 'Direction' and 'Flux' or the unsigned short "
           "'ObjectId' point arrays";
  }
  hits.resize(n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    brume::Hit& h = hits[i];
    double p[3];
    data->GetPoint(i, p);
    for (int c = 0; c < 3; ++c)
    {
      h.Position[c] = static_cast<float>(p[c]);
      h.Direction[c] = direction->GetValue(3 * i + c);
      h.Flux[c] = flux->GetValue(3 * i + c);
    }
    h.Object = object->GetValue(i);
    h.Emitter = emitter ? emitter->GetValue(i) : 0;
    h.Depth = depth ? depth->GetValue(i) : 0;
    h.Padding[0] = h.Padding[1] = h.Padding[2] = 0;
  }
  return {};
}

bool vtkBrumeSceneConversion::GetCamera(vtkDataObject* input, double position[3],
  double focalPoint[3], double viewUp[3], double& viewAngle)
{
  vtkFieldData* fd = input ? input->GetFieldData() : nullptr;
  std::string error;
  return ReadField(fd, "BrumeCameraPosition", 3, position, error) &&
    ReadField(fd, "BrumeCameraFocalPoint", 3, focalPoint, error) &&
    ReadField(fd, "BrumeCameraViewUp", 3, viewUp, error) &&
    ReadField(fd, "BrumeCameraViewAngle", 1, &viewAngle, error);
}
