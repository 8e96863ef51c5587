// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeSceneConversion.h"

#include "vtkAlgorithm.h"
#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeFieldCache.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCompositeDataSet.h"
#include "vtkConvertToPartitionedDataSetCollection.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMatrix3x3.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"

#include "brume/TransferFunction.h"
#include "brume/VdbDensity.h"

#include "vtkBrumeSceneConversionInternals.h"
#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

using namespace vtkBrumeSceneConversionInternals;

namespace
{
bool ReadMaterialType(const std::string& name, brume::MaterialType& type)
{
  if (name == "lambertian")
  {
    type = brume::MaterialType::Lambertian;
  }
  else if (name == "phong")
  {
    type = brume::MaterialType::Phong;
  }
  else if (name == "mirror")
  {
    type = brume::MaterialType::Mirror;
  }
  else
  {
    return false;
  }
  return true;
}

// The object's material from its field data.
std::string ReadMaterial(vtkFieldData* fd, brume::Material& m)
{
  std::string error;
  if (auto* type =
        fd ? vtkStringArray::SafeDownCast(fd->GetAbstractArray(vtkBrumeNames::Material)) : nullptr)
  {
    if (type->GetNumberOfValues() < 1 || !ReadMaterialType(type->GetValue(0), m.Type))
    {
      return "has a BrumeMaterial that is not 'lambertian', 'phong' or 'mirror'";
    }
  }
  ReadVec3(fd, vtkBrumeNames::Reflectance, m.Reflectance, error);
  if (error.empty())
  {
    ReadVec3(fd, vtkBrumeNames::Specular, m.Specular, error);
  }
  if (error.empty())
  {
    double e = 0.0;
    if (ReadField(fd, vtkBrumeNames::Exponent, 1, &e, error))
    {
      m.Exponent = static_cast<float>(e);
    }
  }
  if (error.empty())
  {
    ReadVec3(fd, vtkBrumeNames::Emission, m.Emission, error);
  }
  return error;
}

// Per-cell overrides: cell arrays with the field arrays' names (BrumeMaterial
// as an integer: 0 lambertian, 1 phong, 2 mirror).
std::string ReadCellMaterials(vtkPolyData* pd, const brume::Material& base,
  const std::vector<vtkIdType>& triangleCells, std::vector<brume::Material>& materials)
{
  vtkCellData* cd = pd->GetCellData();
  const char* names[] = { vtkBrumeNames::Material, vtkBrumeNames::Reflectance,
    vtkBrumeNames::Specular, vtkBrumeNames::Exponent, vtkBrumeNames::Emission };
  const int components[] = { 1, 3, 3, 1, 3 };
  vtkDataArray* arrays[5];
  bool any = false;
  for (int i = 0; i < 5; ++i)
  {
    arrays[i] = cd->GetArray(names[i]);
    if (arrays[i] && arrays[i]->GetNumberOfComponents() != components[i])
    {
      return std::string("has a cell array '") + names[i] + "' with " +
        std::to_string(arrays[i]->GetNumberOfComponents()) + " components instead of " +
        std::to_string(components[i]);
    }
    any = any || arrays[i];
  }
  if (!any)
  {
    return {};
  }
  materials.assign(triangleCells.size(), base);
  for (std::size_t t = 0; t < triangleCells.size(); ++t)
  {
    brume::Material& m = materials[t];
    const vtkIdType cell = triangleCells[t];
    double v[3];
    if (arrays[0])
    {
      const double type = arrays[0]->GetTuple1(cell);
      if (type != 0.0 && type != 1.0 && type != 2.0)
      {
        return "has a BrumeMaterial cell value that is not 0, 1 or 2";
      }
      m.Type = static_cast<brume::MaterialType>(static_cast<int>(type));
    }
    if (arrays[1])
    {
      arrays[1]->GetTuple(cell, v);
      m.Reflectance = { static_cast<float>(v[0]), static_cast<float>(v[1]),
        static_cast<float>(v[2]) };
    }
    if (arrays[2])
    {
      arrays[2]->GetTuple(cell, v);
      m.Specular = { static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2]) };
    }
    if (arrays[3])
    {
      m.Exponent = static_cast<float>(arrays[3]->GetTuple1(cell));
    }
    if (arrays[4])
    {
      arrays[4]->GetTuple(cell, v);
      m.Emission = { static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2]) };
    }
  }
  return {};
}

// A point array BrumeReflectance (3 components): the diffuse reflectance
// at each vertex, interpolated over the triangles (a surface coloured by
// point scalars).
std::string ReadVertexReflectance(vtkPolyData* pd, brume::Surface& s)
{
  vtkDataArray* rho = pd->GetPointData()->GetArray(vtkBrumeNames::Reflectance);
  if (!rho)
  {
    return {};
  }
  if (rho->GetNumberOfComponents() != 3)
  {
    return std::string("has a point array '") + vtkBrumeNames::Reflectance + "' with " +
      std::to_string(rho->GetNumberOfComponents()) + " components instead of 3";
  }
  s.VertexReflectance.resize(static_cast<std::size_t>(rho->GetNumberOfTuples()));
  for (vtkIdType i = 0; i < rho->GetNumberOfTuples(); ++i)
  {
    double v[3];
    rho->GetTuple(i, v);
    s.VertexReflectance[i] = { static_cast<float>(v[0]), static_cast<float>(v[1]),
      static_cast<float>(v[2]) };
  }
  return {};
}

std::string ConvertSurface(vtkPolyData* pd, brume::Surface& s)
{
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
  // Polygons as triangle fans, strips with alternating winding; cell ids
  // follow vtkPolyData's order (verts, lines, polys, strips).
  std::vector<vtkIdType> triangleCells;
  vtkIdType cellId = pd->GetNumberOfVerts() + pd->GetNumberOfLines();
  vtkIdType npts = 0;
  const vtkIdType* ids = nullptr;
  vtkCellArray* polys = pd->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(npts, ids); ++cellId)
  {
    for (vtkIdType k = 2; k < npts; ++k)
    {
      s.Triangles.push_back({ static_cast<std::uint32_t>(ids[0]),
        static_cast<std::uint32_t>(ids[k - 1]), static_cast<std::uint32_t>(ids[k]) });
      triangleCells.push_back(cellId);
    }
  }
  vtkCellArray* strips = pd->GetStrips();
  for (strips->InitTraversal(); strips->GetNextCell(npts, ids); ++cellId)
  {
    for (vtkIdType k = 2; k < npts; ++k)
    {
      const bool even = (k % 2) == 0;
      s.Triangles.push_back({ static_cast<std::uint32_t>(ids[k - 2]),
        static_cast<std::uint32_t>(even ? ids[k - 1] : ids[k]),
        static_cast<std::uint32_t>(even ? ids[k] : ids[k - 1]) });
      triangleCells.push_back(cellId);
    }
  }
  if (s.Triangles.empty())
  {
    return "has no polygons";
  }
  std::string error = ReadMaterial(pd->GetFieldData(), s.Mat);
  if (error.empty())
  {
    error = ReadCellMaterials(pd, s.Mat, triangleCells, s.TriangleMaterials);
  }
  if (error.empty())
  {
    error = ReadVertexReflectance(pd, s);
  }
  return error;
}
}

namespace
{
// Bounds of everything in the scene (for directional beams).
brume::Box SceneBounds(const brume::Scene& scene)
{
  brume::Box box{ brume::Vec3(1e30f), brume::Vec3(-1e30f) };
  auto grow = [&](const brume::Vec3& p)
  {
    for (int a = 0; a < 3; ++a)
    {
      box.lower[a] = std::min(box.lower[a], p[a]);
      box.upper[a] = std::max(box.upper[a], p[a]);
    }
  };
  for (const auto& s : scene.Surfaces)
  {
    for (const auto& v : s.Vertices)
    {
      grow(v);
    }
  }
  for (const auto& m : scene.Media)
  {
    grow(m.Bounds.lower);
    grow(m.Bounds.upper);
  }
  return box;
}
}

namespace
{
// A collimated beam along `direction` that covers the whole scene.
void CoverWithBeam(brume::Light& l, const brume::Scene& scene)
{
  const brume::Box bounds = SceneBounds(scene);
  const brume::Vec3 centre = (bounds.lower + bounds.upper) * 0.5f;
  const float radius = 0.5f * Length(bounds.Extent()) * 1.01f;
  l.BeamRadius = radius;
  l.BeamCenter = centre - l.Direction * radius;
}
}

std::string vtkBrumeSceneConversion::ConvertFieldLights(vtkFieldData* fd, brume::Scene& scene)
{
  auto* types =
    fd ? vtkStringArray::SafeDownCast(fd->GetAbstractArray(vtkBrumeNames::LightType)) : nullptr;
  if (!types)
  {
    return {};
  }
  const vtkIdType n = types->GetNumberOfValues();
  auto array = [&](const char* name, int components) -> vtkDataArray*
  {
    vtkDataArray* a = fd->GetArray(name);
    return a && a->GetNumberOfComponents() == components && a->GetNumberOfTuples() == n ? a
                                                                                        : nullptr;
  };
  vtkDataArray* position = array(vtkBrumeNames::LightPosition, 3);
  vtkDataArray* direction = array(vtkBrumeNames::LightDirection, 3);
  vtkDataArray* intensity = array(vtkBrumeNames::LightIntensity, 3);
  vtkDataArray* cone = array(vtkBrumeNames::LightConeAngle, 1);
  if (!position || !direction || !intensity || !cone)
  {
    return "the scene's lights need BrumeLightPosition, BrumeLightDirection, BrumeLightIntensity "
           "(3 components) and BrumeLightConeAngle (1), one tuple per BrumeLightType";
  }
  for (vtkIdType i = 0; i < n; ++i)
  {
    brume::Light l;
    l.Name = "light " + std::to_string(i);
    double v[3];
    position->GetTuple(i, v);
    l.Position = { static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2]) };
    direction->GetTuple(i, v);
    const brume::Vec3 d(
      static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2]));
    l.Direction = Length(d) > 0.f ? Normalize(d) : d;
    intensity->GetTuple(i, v);
    l.Intensity = { static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2]) };
    l.ConeAngle = static_cast<float>(cone->GetTuple1(i));
    const std::string type = types->GetValue(i);
    if (type == "point")
    {
      l.Type = brume::LightType::Point;
    }
    else if (type == "spot")
    {
      l.Type = brume::LightType::Spot;
    }
    else if (type == "directional")
    {
      l.Type = brume::LightType::Directional;
      CoverWithBeam(l, scene);
    }
    else
    {
      return "light " + std::to_string(i) + " has the unknown type '" + type + "'";
    }
    scene.Lights.push_back(l);
  }
  return {};
}

void vtkBrumeSceneConversion::AppendFieldLights(
  const std::vector<brume::Light>& lights, vtkFieldData* fd)
{
  if (lights.empty())
  {
    return;
  }
  auto* types = vtkStringArray::SafeDownCast(fd->GetAbstractArray(vtkBrumeNames::LightType));
  if (!types)
  {
    vtkNew<vtkStringArray> created;
    created->SetName(vtkBrumeNames::LightType);
    fd->AddArray(created);
    types = created;
  }
  for (const brume::Light& l : lights)
  {
    types->InsertNextValue(l.Type == brume::LightType::Point ? "point"
        : l.Type == brume::LightType::Spot                   ? "spot"
                                                             : "directional");
    const double position[3] = { l.Position.x, l.Position.y, l.Position.z };
    const double direction[3] = { l.Direction.x, l.Direction.y, l.Direction.z };
    const double intensity[3] = { l.Intensity.x, l.Intensity.y, l.Intensity.z };
    const double cone = l.ConeAngle;
    AppendTuple(fd, vtkBrumeNames::LightPosition, position, 3);
    AppendTuple(fd, vtkBrumeNames::LightDirection, direction, 3);
    AppendTuple(fd, vtkBrumeNames::LightIntensity, intensity, 3);
    AppendTuple(fd, vtkBrumeNames::LightConeAngle, &cone, 1);
  }
}

std::string vtkBrumeSceneConversion::ConvertLights(vtkLightCollection* lights, brume::Scene& scene)
{
  lights->InitTraversal();
  int index = 0;
  while (vtkLight* light = lights->GetNextItem())
  {
    ++index;
    if (!light->GetSwitch())
    {
      continue;
    }
    brume::Light l;
    l.Name = "vtkLight " + std::to_string(index - 1);
    double color[3], position[3], focal[3];
    light->GetDiffuseColor(color);
    light->GetTransformedPosition(position);
    light->GetTransformedFocalPoint(focal);
    const double intensity = light->GetIntensity();
    l.Intensity = { static_cast<float>(intensity * color[0]),
      static_cast<float>(intensity * color[1]), static_cast<float>(intensity * color[2]) };
    l.Position = { static_cast<float>(position[0]), static_cast<float>(position[1]),
      static_cast<float>(position[2]) };
    const brume::Vec3 axis(static_cast<float>(focal[0] - position[0]),
      static_cast<float>(focal[1] - position[1]), static_cast<float>(focal[2] - position[2]));
    if (!(Length(axis) > 0.f) && (!light->GetPositional() || light->GetConeAngle() < 90.0))
    {
      return "light '" + l.Name + "' has its focal point at its position: it has no direction";
    }
    if (Length(axis) > 0.f)
    {
      l.Direction = Normalize(axis);
    }
    if (!light->GetPositional())
    {
      // A collimated beam covering the whole scene.
      l.Type = brume::LightType::Directional;
      CoverWithBeam(l, scene);
    }
    else if (light->GetConeAngle() >= 90.0)
    {
      l.Type = brume::LightType::Point;
    }
    else
    {
      l.Type = brume::LightType::Spot;
      l.ConeAngle = static_cast<float>(light->GetConeAngle());
    }
    scene.Lights.push_back(l);
  }
  return {};
}

void vtkBrumeSceneConversion::AddObject(
  vtkPartitionedDataSetCollection* scene, vtkDataObject* data, const std::string& name)
{
  const unsigned int index = scene->GetNumberOfPartitionedDataSets();
  scene->SetNumberOfPartitionedDataSets(index + 1);
  vtkNew<vtkPartitionedDataSet> pds;
  pds->SetNumberOfPartitions(1);
  pds->SetPartition(0, data);
  scene->SetPartitionedDataSet(index, pds);
  scene->GetMetaData(index)->Set(vtkCompositeDataSet::NAME(), name.c_str());
}

void vtkBrumeSceneConversion::AppendTuple(
  vtkFieldData* fieldData, const char* name, const double* values, int n)
{
  vtkSmartPointer<vtkDoubleArray> a = vtkDoubleArray::SafeDownCast(fieldData->GetArray(name));
  if (!a)
  {
    a = vtkSmartPointer<vtkDoubleArray>::New();
    a->SetName(name);
    a->SetNumberOfComponents(n);
    fieldData->AddArray(a);
  }
  a->InsertNextTuple(values);
}

vtkSmartPointer<vtkPartitionedDataSetCollection> vtkBrumeSceneConversion::AsCollection(
  vtkDataObject* input)
{
  if (auto* collection = vtkPartitionedDataSetCollection::SafeDownCast(input))
  {
    return collection;
  }
  if (vtkMultiBlockDataSet::SafeDownCast(input))
  {
    vtkNew<vtkConvertToPartitionedDataSetCollection> convert;
    convert->SetInputDataObject(input);
    convert->Update();
    auto result = vtkSmartPointer<vtkPartitionedDataSetCollection>::New();
    result->ShallowCopy(convert->GetOutput());
    result->GetFieldData()->ShallowCopy(input->GetFieldData());
    return result;
  }
  if (vtkPolyData::SafeDownCast(input) || vtkImageData::SafeDownCast(input))
  {
    auto result = vtkSmartPointer<vtkPartitionedDataSetCollection>::New();
    vtkNew<vtkPartitionedDataSet> pds;
    pds->SetNumberOfPartitions(1);
    pds->SetPartition(0, input);
    result->SetPartitionedDataSet(0, pds);
    result->GetMetaData(0u)->Set(vtkCompositeDataSet::NAME(), "object0");
    return result;
  }
  return nullptr;
}

bool vtkBrumeSceneConversion::ToTracedScene(vtkAlgorithm* algorithm, vtkDataObject* input,
  vtkIdType seed, vtkLightCollection* lights, brume::Scene& scene)
{
  if (seed < 0)
  {
    vtkErrorWithObjectMacro(algorithm, "Seed must be non-negative, not " << seed << ".");
    return false;
  }
  const std::string error = ToScene(input, scene, nullptr, lights);
  if (!error.empty())
  {
    vtkErrorWithObjectMacro(algorithm, "Invalid scene: " << error << ".");
    return false;
  }
  return true;
}

std::string vtkBrumeSceneConversion::ToScene(vtkDataObject* input, brume::Scene& scene,
  std::vector<ObjectSource>* sources, vtkLightCollection* lights, vtkFieldData* tracedLights)
{
  scene = brume::Scene();
  auto* collection = vtkPartitionedDataSetCollection::SafeDownCast(input);
  if (!collection)
  {
    return std::string("the scene must be a vtkPartitionedDataSetCollection (or a ") +
      "vtkMultiBlockDataSet, a vtkPolyData or a vtkImageData), not " +
      (input ? input->GetClassName() : "nothing");
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
  std::string lightError = ConvertFieldLights(collection->GetFieldData(), scene);
  if (lightError.empty() && tracedLights)
  {
    lightError = ConvertFieldLights(tracedLights, scene);
  }
  if (lightError.empty() && lights)
  {
    lightError = ConvertLights(lights, scene);
  }
  if (!lightError.empty())
  {
    return lightError;
  }
  return scene.Validate();
}

std::size_t vtkBrumeSceneConversion::GetNumberOfCachedArrays()
{
  return vtkBrumeSceneConversionInternals::FieldCache::Instance().NumberOfKeptArrays();
}
