// SPDX-License-Identifier: BSD-3-Clause
// vtkBrumeRendererScene's surfaces and lights: an actor's data as a Brume
// surface (world coordinates, material, colours, the side that shows) and
// point lights aimed at the scene.
#include "vtkBrumeRendererSceneParts.h"

#include "vtkActor.h"
#include "vtkAppendPolyData.h"
#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeFieldTuple.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCleanPolyData.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArray.h"
#include "vtkDataSetSurfaceFilter.h"
#include "vtkFeatureEdges.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkLookupTable.h"
#include "vtkMapper.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataNormals.h"
#include "vtkProperty.h"
#include "vtkScalarsToColors.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <string>

namespace
{
// The polygons of a prop's data in world coordinates, and where each of
// their cells and points comes from in that data (colours are mapped there).
struct WorldPolygons
{
  vtkSmartPointer<vtkPolyData> Surface;
  std::vector<vtkIdType> InputCells;  // per cell of Surface
  std::vector<vtkIdType> InputPoints; // per point of Surface
};

// The ids array `name` of a surface filter's output; identity without one.
std::vector<vtkIdType> OriginalIds(
  vtkDataSetAttributes* attributes, const char* name, vtkIdType count)
{
  std::vector<vtkIdType> ids(static_cast<std::size_t>(count));
  vtkDataArray* original = name ? attributes->GetArray(name) : nullptr;
  for (vtkIdType i = 0; i < count; ++i)
  {
    ids[i] = original ? static_cast<vtkIdType>(original->GetTuple1(i)) : i;
  }
  return ids;
}

// The surface of `data` in world coordinates (`matrix` applied): its points
// and polygons only (what a Brume surface is made of); no Surface when it
// has no polygon.
WorldPolygons WorldSurface(vtkDataSet* data, vtkMatrix4x4* matrix)
{
  WorldPolygons world;
  vtkSmartPointer<vtkPolyData> polygons = vtkPolyData::SafeDownCast(data);
  if (!polygons)
  {
    vtkNew<vtkDataSetSurfaceFilter> surface;
    surface->SetInputData(data);
    surface->PassThroughCellIdsOn();
    surface->PassThroughPointIdsOn();
    surface->Update();
    polygons = surface->GetOutput();
  }
  if (!polygons || !polygons->GetPoints() ||
    polygons->GetNumberOfPolys() + polygons->GetNumberOfStrips() == 0)
  {
    return world;
  }
  // The output holds polygons then strips: cells of `polygons` from the
  // first polygon on (vertices and lines come first there).
  const vtkIdType first = polygons->GetNumberOfVerts() + polygons->GetNumberOfLines();
  const vtkIdType cells = polygons->GetNumberOfPolys() + polygons->GetNumberOfStrips();
  const bool filtered = polygons.GetPointer() != data;
  const std::vector<vtkIdType> cellIds =
    OriginalIds(polygons->GetCellData(), filtered ? "vtkOriginalCellIds" : nullptr, first + cells);
  world.InputCells.assign(cellIds.begin() + first, cellIds.end());
  world.InputPoints = OriginalIds(polygons->GetPointData(),
    filtered ? "vtkOriginalPointIds" : nullptr, polygons->GetNumberOfPoints());
  auto out = vtkSmartPointer<vtkPolyData>::New();
  vtkPoints* in = polygons->GetPoints();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToFloat();
  points->SetNumberOfPoints(in->GetNumberOfPoints());
  for (vtkIdType i = 0; i < in->GetNumberOfPoints(); ++i)
  {
    double p[4] = { 0, 0, 0, 1 };
    in->GetPoint(i, p);
    matrix->MultiplyPoint(p, p);
    points->SetPoint(i, p[0] / p[3], p[1] / p[3], p[2] / p[3]);
  }
  out->SetPoints(points);
  out->SetPolys(polygons->GetPolys());
  out->SetStrips(polygons->GetStrips());
  world.Surface = out;
  return world;
}

// Brume lights and shows a surface's front side (its polygons' winding);
// VTK lights both. So a closed surface (once coincident points are merged)
// is turned outward, and an open one toward the camera (the side seen when
// the scene is built), each connected part's polygons made consistent
// first. Cell data follow.
vtkSmartPointer<vtkPolyData> FacingViewer(vtkPolyData* input, vtkCamera* camera)
{
  // Coincident points merged first: sources give each face of a closed
  // surface its own points (vtkCubeSource), which would leave it open.
  vtkNew<vtkCleanPolyData> merged;
  merged->SetInputData(input);
  merged->PointMergingOn();
  merged->SetTolerance(0.0);
  merged->ConvertLinesToPointsOff();
  merged->ConvertPolysToLinesOff();
  merged->ConvertStripsToPolysOff();
  merged->Update();
  vtkPolyData* surface = merged->GetOutput();
  vtkNew<vtkFeatureEdges> edges;
  edges->SetInputData(surface);
  edges->BoundaryEdgesOn();
  edges->NonManifoldEdgesOn();
  edges->FeatureEdgesOff();
  edges->ManifoldEdgesOff();
  edges->Update();
  const bool closed = edges->GetOutput()->GetNumberOfCells() == 0;
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputData(surface);
  // (Auto-orientation needs the point normals it computes; they are not kept.)
  normals->ComputePointNormalsOn();
  normals->ComputeCellNormalsOff();
  normals->SplittingOff();
  normals->ConsistencyOn();
  normals->SetAutoOrientNormals(closed);
  normals->Update();
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->ShallowCopy(normals->GetOutput());
  out->GetPointData()->RemoveArray("Normals");
  if (closed)
  {
    return out;
  }
  // The area-weighted normals against the directions to the eye.
  double eye[3];
  camera->GetPosition(eye);
  double facing = 0.0;
  vtkNew<vtkIdList> ids;
  vtkPoints* points = out->GetPoints();
  for (vtkIdType k = 0; k < out->GetNumberOfCells(); ++k)
  {
    out->GetCellPoints(k, ids);
    double p0[3], p1[3], p2[3];
    for (vtkIdType i = 2; i < ids->GetNumberOfIds(); ++i)
    {
      points->GetPoint(ids->GetId(0), p0);
      points->GetPoint(ids->GetId(i - 1), p1);
      points->GetPoint(ids->GetId(i), p2);
      double a[3], b[3], n[3], toEye[3];
      for (int c = 0; c < 3; ++c)
      {
        a[c] = p1[c] - p0[c];
        b[c] = p2[c] - p0[c];
        toEye[c] = eye[c] - p0[c];
      }
      vtkMath::Cross(a, b, n);
      facing += vtkMath::Dot(n, toEye) / std::max(1e-30, vtkMath::Norm(toEye));
    }
  }
  if (facing < 0.0)
  {
    vtkNew<vtkCellArray> polys;
    polys->DeepCopy(out->GetPolys());
    for (vtkIdType k = 0; k < polys->GetNumberOfCells(); ++k)
    {
      polys->ReverseCellAtId(k);
    }
    out->SetPolys(polys);
  }
  return out;
}

// Diffuse and specular reflectances scaled down together where their sum
// exceeds 1 in a channel (energy conservation, rho_d + rho_s <= 1).
void Conserve(double diffuse[3], double specular[3])
{
  double scale = 1.0;
  for (int c = 0; c < 3; ++c)
  {
    const double sum = diffuse[c] + specular[c];
    scale = sum > 1.0 ? std::min(scale, 1.0 / sum) : scale;
  }
  for (int c = 0; c < 3; ++c)
  {
    diffuse[c] *= scale;
    specular[c] *= scale;
  }
}

// The actor's vtkProperty as a Brume material, in the surface's field data.
// The property's diffuse and specular reflectances, conserving energy.
void PropertyReflectances(vtkProperty* property, double diffuse[3], double specular[3])
{
  property->GetDiffuseColor(diffuse);
  property->GetSpecularColor(specular);
  const double kd = property->GetDiffuse();
  const double ks = property->GetSpecular() > 0.0 ? property->GetSpecular() : 0.0;
  for (int c = 0; c < 3; ++c)
  {
    diffuse[c] = std::max(0.0, kd * diffuse[c]);
    specular[c] = std::max(0.0, ks * specular[c]);
  }
  Conserve(diffuse, specular);
}

void WriteMaterial(vtkProperty* property, vtkFieldData* fd)
{
  double diffuse[3], specular[3];
  PropertyReflectances(property, diffuse, specular);
  const double ks = property->GetSpecular() > 0.0 ? property->GetSpecular() : 0.0;
  vtkNew<vtkStringArray> material;
  material->SetName(vtkBrumeNames::Material);
  material->InsertNextValue(ks > 0.0 ? "phong" : "lambertian");
  fd->AddArray(material);
  vtkBrumeFieldTuple::Set(fd, vtkBrumeNames::Reflectance, diffuse, 3);
  if (ks > 0.0)
  {
    const double exponent = std::max(1.0, property->GetSpecularPower());
    vtkBrumeFieldTuple::Set(fd, vtkBrumeNames::Specular, specular, 3);
    vtkBrumeFieldTuple::Set(fd, vtkBrumeNames::Exponent, &exponent, 1);
  }
}

// The colours the mapper gives its input's points (cellFlag 0) or cells
// (1), mapped as VTK maps them for drawing; null where the actor has its
// property's colour (scalar visibility off, no scalars, colouring by a
// field-data tuple).
vtkSmartPointer<vtkUnsignedCharArray> MappedColours(
  vtkMapper* mapper, vtkDataSet* data, int& cellFlag)
{
  cellFlag = 0;
  if (!mapper || !mapper->GetScalarVisibility())
  {
    return nullptr;
  }
  vtkAbstractArray* scalars = vtkAbstractMapper::GetAbstractScalars(data, mapper->GetScalarMode(),
    mapper->GetArrayAccessMode(), mapper->GetArrayId(), mapper->GetArrayName(), cellFlag);
  if (!scalars || cellFlag > 1)
  {
    return nullptr;
  }
  vtkScalarsToColors* table = mapper->GetLookupTable();
  auto* values = vtkDataArray::SafeDownCast(scalars);
  if (values && values->GetLookupTable())
  {
    table = values->GetLookupTable();
  }
  table->Build();
  if (!mapper->GetUseLookupTableScalarRange())
  {
    table->SetRange(mapper->GetScalarRange());
  }
  return vtkSmartPointer<vtkUnsignedCharArray>::Take(
    table->MapScalars(scalars, mapper->GetColorMode(), mapper->GetArrayComponent()));
}

// Diffuse x the mapped colour as the surface's reflectance: point colours
// as the point array BrumeReflectance (interpolated over the triangles);
// cell colours as the cell array BrumeReflectance, with BrumeSpecular
// beside it where the property has a lobe, both scaled as WriteMaterial
// scales the property's.
void WriteColours(
  const WorldPolygons& world, vtkUnsignedCharArray* colours, int cellFlag, vtkProperty* property)
{
  vtkPolyData* surface = world.Surface;
  if (cellFlag == 0)
  {
    // Point colours: per vertex, interpolated over the triangles as VTK
    // interpolates them, under the property's specular lobe (below 1 with it).
    double diffuse[3], specular[3];
    PropertyReflectances(property, diffuse, specular);
    const double kd = std::max(0.0, property->GetDiffuse());
    vtkNew<vtkFloatArray> vertex;
    vertex->SetName(vtkBrumeNames::Reflectance);
    vertex->SetNumberOfComponents(3);
    vertex->SetNumberOfTuples(surface->GetNumberOfPoints());
    for (vtkIdType i = 0; i < surface->GetNumberOfPoints(); ++i)
    {
      float rho[3];
      for (int c = 0; c < 3; ++c)
      {
        const double most = specular[c] > 0.0 ? 1.0 - specular[c] - 1e-6 : 1.0;
        rho[c] = static_cast<float>(std::clamp(
          kd * colours->GetComponent(world.InputPoints[i], c) / 255.0, 0.0, std::max(0.0, most)));
      }
      vertex->SetTypedTuple(i, rho);
    }
    surface->GetPointData()->AddArray(vertex);
    return;
  }
  const vtkIdType cells = surface->GetNumberOfCells();
  vtkNew<vtkFloatArray> reflectance;
  reflectance->SetName(vtkBrumeNames::Reflectance);
  reflectance->SetNumberOfComponents(3);
  reflectance->SetNumberOfTuples(cells);
  vtkNew<vtkFloatArray> specularity;
  specularity->SetName(vtkBrumeNames::Specular);
  specularity->SetNumberOfComponents(3);
  specularity->SetNumberOfTuples(cells);
  double specularColour[3];
  property->GetSpecularColor(specularColour);
  const double kd = std::max(0.0, property->GetDiffuse());
  const double ks = property->GetSpecular() > 0.0 ? property->GetSpecular() : 0.0;
  for (vtkIdType k = 0; k < cells; ++k)
  {
    double colour[3];
    for (int c = 0; c < 3; ++c)
    {
      colour[c] = colours->GetComponent(world.InputCells[k], c);
    }
    double diffuse[3], specular[3];
    for (int c = 0; c < 3; ++c)
    {
      diffuse[c] = kd * colour[c] / 255.0;
      specular[c] = std::max(0.0, ks * specularColour[c]);
    }
    Conserve(diffuse, specular);
    reflectance->SetTuple(k, diffuse);
    specularity->SetTuple(k, specular);
  }
  surface->GetCellData()->AddArray(reflectance);
  if (ks > 0.0)
  {
    surface->GetCellData()->AddArray(specularity);
  }
}

}

namespace vtkBrumeRendererSceneParts
{
vtkSmartPointer<vtkPolyData> ActorSurface(vtkActor* actor, vtkDataSet* data, vtkCamera* camera)
{
  const WorldPolygons world = WorldSurface(data, actor->GetMatrix());
  if (!world.Surface)
  {
    return nullptr;
  }
  int cellFlag = 0;
  if (vtkSmartPointer<vtkUnsignedCharArray> colours =
        MappedColours(actor->GetMapper(), data, cellFlag))
  {
    WriteColours(world, colours, cellFlag, actor->GetProperty());
  }
  vtkSmartPointer<vtkPolyData> surface =
    camera ? FacingViewer(world.Surface, camera) : world.Surface;
  WriteMaterial(actor->GetProperty(), surface->GetFieldData());
  return surface;
}

// A point light outside the sphere that bounds the scene emits into the
// cone that holds that sphere only: a spot of the same intensity (W/sr).
// Nothing lies outside the cone, so the particles it no longer emits are
// those that would have left the scene at once; the image is the same in
// expectation, and a light above an open VTK scene (a ground, a few
// objects) wastes several times fewer particles.
void AimPointLights(vtkPartitionedDataSetCollection* scene, std::vector<brume::Light>& lights)
{
  double box[6] = { VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX,
    VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
  for (unsigned int i = 0; i < scene->GetNumberOfPartitionedDataSets(); ++i)
  {
    vtkPartitionedDataSet* partitions = scene->GetPartitionedDataSet(i);
    for (unsigned int k = 0; partitions && k < partitions->GetNumberOfPartitions(); ++k)
    {
      double bounds[6];
      if (vtkDataSet* data = partitions->GetPartition(k))
      {
        data->GetBounds(bounds);
        for (int a = 0; a < 3; ++a)
        {
          box[2 * a] = std::min(box[2 * a], bounds[2 * a]);
          box[2 * a + 1] = std::max(box[2 * a + 1], bounds[2 * a + 1]);
        }
      }
    }
  }
  if (!(box[0] <= box[1]))
  {
    return;
  }
  const brume::Vec3 centre(static_cast<float>(0.5 * (box[0] + box[1])),
    static_cast<float>(0.5 * (box[2] + box[3])), static_cast<float>(0.5 * (box[4] + box[5])));
  // A little beyond the box's half diagonal, for float rounding.
  const double radius = 1.001 *
    std::sqrt((box[1] - box[0]) * (box[1] - box[0]) + (box[3] - box[2]) * (box[3] - box[2]) +
      (box[5] - box[4]) * (box[5] - box[4])) /
    2.0;
  for (brume::Light& light : lights)
  {
    const brume::Vec3 toScene = centre - light.Position;
    const double distance = Length(toScene);
    if (light.Type != brume::LightType::Point || !(distance > radius) || !(radius > 0.0))
    {
      continue;
    }
    light.Type = brume::LightType::Spot;
    light.Direction = Normalize(toScene);
    light.ConeAngle = static_cast<float>(vtkMath::DegreesFromRadians(std::asin(radius / distance)));
  }
}

}

namespace
{
// One volume's pieces (images on one lattice, each a box of its points) as
// one image: their union's box, each point's values from a piece holding
// it (pieces share their boundary's points, with equal values). Null when
// the pieces do not fit one lattice or hold different point arrays, or
// cell arrays: they are then kept as media of their own.
vtkSmartPointer<vtkImageData> MergedImage(const std::vector<vtkSmartPointer<vtkDataSet>>& pieces)
{
  std::vector<vtkImageData*> images;
  for (const auto& piece : pieces)
  {
    auto* image = vtkImageData::SafeDownCast(piece);
    if (!image || image->GetCellData()->GetNumberOfArrays() > 0 || image->GetNumberOfPoints() == 0)
    {
      return nullptr;
    }
    images.push_back(image);
  }
  double spacing[3], first[3];
  images[0]->GetSpacing(spacing);
  images[0]->GetPoint(0, first);
  std::vector<std::array<long long, 3>> starts;
  long long low[3] = { 0, 0, 0 }, high[3] = { 0, 0, 0 };
  for (std::size_t p = 0; p < images.size(); ++p)
  {
    double s[3], point[3];
    int dims[3];
    images[p]->GetSpacing(s);
    images[p]->GetPoint(0, point);
    images[p]->GetDimensions(dims);
    std::array<long long, 3> start{};
    for (int a = 0; a < 3; ++a)
    {
      const double steps = (point[a] - first[a]) / spacing[a];
      start[a] = std::llround(steps);
      if (!(spacing[a] > 0.0) || std::abs(s[a] - spacing[a]) > 1e-9 * spacing[a] ||
        std::abs(steps - static_cast<double>(start[a])) > 1e-6)
      {
        return nullptr;
      }
      low[a] = p == 0 ? start[a] : std::min(low[a], start[a]);
      high[a] = p == 0 ? start[a] + dims[a] - 1 : std::max(high[a], start[a] + dims[a] - 1);
    }
    starts.push_back(start);
  }
  const vtkIdType n[3] = { static_cast<vtkIdType>(high[0] - low[0] + 1),
    static_cast<vtkIdType>(high[1] - low[1] + 1), static_cast<vtkIdType>(high[2] - low[2] + 1) };
  auto merged = vtkSmartPointer<vtkImageData>::New();
  merged->SetSpacing(spacing);
  merged->SetOrigin(first[0] + static_cast<double>(low[0]) * spacing[0],
    first[1] + static_cast<double>(low[1]) * spacing[1],
    first[2] + static_cast<double>(low[2]) * spacing[2]);
  merged->SetDimensions(static_cast<int>(n[0]), static_cast<int>(n[1]), static_cast<int>(n[2]));
  vtkPointData* into = merged->GetPointData();
  vtkPointData* model = images[0]->GetPointData();
  for (int k = 0; k < model->GetNumberOfArrays(); ++k)
  {
    vtkAbstractArray* source = model->GetAbstractArray(k);
    for (vtkImageData* image : images)
    {
      vtkAbstractArray* other =
        source->GetName() ? image->GetPointData()->GetAbstractArray(source->GetName()) : nullptr;
      if (!other || other->GetDataType() != source->GetDataType() ||
        other->GetNumberOfComponents() != source->GetNumberOfComponents())
      {
        return nullptr;
      }
    }
    vtkSmartPointer<vtkAbstractArray> values;
    values.TakeReference(source->NewInstance());
    values->SetName(source->GetName());
    values->SetNumberOfComponents(source->GetNumberOfComponents());
    values->SetNumberOfTuples(n[0] * n[1] * n[2]);
    if (auto* numbers = vtkDataArray::SafeDownCast(values))
    {
      numbers->Fill(0.0); // a point no piece holds: no medium there
    }
    for (std::size_t p = 0; p < images.size(); ++p)
    {
      vtkAbstractArray* from = images[p]->GetPointData()->GetAbstractArray(source->GetName());
      int dims[3];
      images[p]->GetDimensions(dims);
      vtkIdType t = 0;
      for (int z = 0; z < dims[2]; ++z)
      {
        for (int y = 0; y < dims[1]; ++y)
        {
          const vtkIdType row =
            ((starts[p][2] - low[2] + z) * n[1] + (starts[p][1] - low[1] + y)) * n[0] +
            (starts[p][0] - low[0]);
          for (int x = 0; x < dims[0]; ++x, ++t)
          {
            values->SetTuple(row + x, t, from);
          }
        }
      }
    }
    into->AddArray(values);
  }
  if (vtkDataArray* scalars = model->GetScalars())
  {
    into->SetActiveScalars(scalars->GetName());
  }
  merged->GetFieldData()->ShallowCopy(images[0]->GetFieldData());
  return merged;
}
}

namespace vtkBrumeRendererSceneParts
{
vtkSmartPointer<vtkPartitionedDataSetCollection> Gathered(
  vtkMultiProcessController* controller, vtkPartitionedDataSetCollection* part, vtkCamera* camera)
{
  // What travels: each object's datasets, an image's field data beside it
  // in an empty polygonal carrier (VTK 9.2's legacy reader, which the
  // transfer goes through, warns on an image's field data).
  vtkNew<vtkPartitionedDataSetCollection> send;
  for (unsigned int i = 0; i < part->GetNumberOfPartitionedDataSets(); ++i)
  {
    vtkNew<vtkPartitionedDataSet> object;
    vtkPartitionedDataSet* partitions = part->GetPartitionedDataSet(i);
    for (unsigned int k = 0; partitions && k < partitions->GetNumberOfPartitions(); ++k)
    {
      vtkDataSet* data = partitions->GetPartition(k);
      if (auto* image = vtkImageData::SafeDownCast(data))
      {
        vtkNew<vtkImageData> bare;
        bare->ShallowCopy(image);
        bare->GetFieldData()->Initialize();
        vtkNew<vtkPolyData> carrier;
        carrier->GetFieldData()->ShallowCopy(image->GetFieldData());
        object->SetPartition(2 * k, bare);
        object->SetPartition(2 * k + 1, carrier);
      }
      else
      {
        object->SetPartition(2 * k, data);
      }
    }
    send->SetPartitionedDataSet(i, object);
    if (part->HasMetaData(i))
    {
      send->GetMetaData(i)->Copy(part->GetMetaData(i));
    }
  }
  std::vector<vtkSmartPointer<vtkDataObject>> parts;
  controller->AllGather(send, parts);

  // Each object's datasets, by name, in the processes' order.
  struct Object
  {
    std::string Name;
    std::vector<vtkSmartPointer<vtkDataSet>> Data;
    vtkSmartPointer<vtkInformation> Meta;
    bool Surface = false;
  };
  std::vector<Object> objects;
  std::map<std::string, std::size_t> named; // name -> index in objects
  for (std::size_t r = 0; r < parts.size(); ++r)
  {
    auto* received = vtkPartitionedDataSetCollection::SafeDownCast(parts[r]);
    for (unsigned int i = 0; received && i < received->GetNumberOfPartitionedDataSets(); ++i)
    {
      vtkPartitionedDataSet* sent = received->GetPartitionedDataSet(i);
      Object object;
      object.Meta = vtkSmartPointer<vtkInformation>::New();
      if (received->HasMetaData(i))
      {
        object.Meta->Copy(received->GetMetaData(i));
      }
      object.Name = object.Meta->Has(vtkCompositeDataSet::NAME())
        ? object.Meta->Get(vtkCompositeDataSet::NAME())
        : "object " + std::to_string(objects.size());
      bool surface = true;
      for (unsigned int k = 0; sent && 2 * k < sent->GetNumberOfPartitions(); ++k)
      {
        vtkDataSet* data = sent->GetPartition(2 * k);
        if (auto* image = vtkImageData::SafeDownCast(data))
        {
          // A plain image (the transfer gives vtkStructuredPoints).
          auto plain = vtkSmartPointer<vtkImageData>::New();
          plain->ShallowCopy(image);
          if (vtkDataSet* carrier =
                2 * k + 1 < sent->GetNumberOfPartitions() ? sent->GetPartition(2 * k + 1) : nullptr)
          {
            plain->GetFieldData()->ShallowCopy(carrier->GetFieldData());
          }
          object.Data.emplace_back(plain);
          surface = false;
        }
        else if (data)
        {
          object.Data.emplace_back(data);
          surface = surface && vtkPolyData::SafeDownCast(data) != nullptr;
        }
      }
      // A prop's pieces: one object (a surface of polygons, or a volume of
      // one image per process).
      const bool volume = !surface && object.Data.size() == 1;
      auto found = surface || volume ? named.find(object.Name) : named.end();
      if (found != named.end() && objects[found->second].Surface == surface)
      {
        Object& whole = objects[found->second];
        whole.Data.insert(whole.Data.end(), object.Data.begin(), object.Data.end());
        continue;
      }
      object.Surface = surface;
      if (found == named.end())
      {
        named[object.Name] = objects.size();
      }
      objects.push_back(std::move(object));
    }
  }

  auto whole = vtkSmartPointer<vtkPartitionedDataSetCollection>::New();
  whole->GetFieldData()->ShallowCopy(part->GetFieldData());
  for (Object& object : objects)
  {
    vtkNew<vtkPartitionedDataSet> partitions;
    if (!object.Data.empty() && vtkPolyData::SafeDownCast(object.Data[0]))
    {
      // One prop's pieces: one surface, turned as a whole (the pieces come
      // unturned: turned alone, each would be open, and its winding would
      // depend on the camera).
      vtkSmartPointer<vtkPolyData> surface = vtkPolyData::SafeDownCast(object.Data[0]);
      if (object.Data.size() > 1)
      {
        vtkNew<vtkAppendPolyData> append;
        for (const auto& data : object.Data)
        {
          append->AddInputData(vtkPolyData::SafeDownCast(data));
        }
        append->Update();
        // The pieces' shared edges: their points computed on each process,
        // equal but for rounding (an edge interpolated from either end), so
        // merged within a millionth of the surface's size. Unmerged, a
        // closed surface would stay open, and part of it turned inward.
        vtkNew<vtkCleanPolyData> seams;
        seams->SetInputConnection(append->GetOutputPort());
        seams->PointMergingOn();
        seams->ToleranceIsAbsoluteOn();
        seams->SetAbsoluteTolerance(1e-6 * append->GetOutput()->GetLength());
        seams->ConvertLinesToPointsOff();
        seams->ConvertPolysToLinesOff();
        seams->ConvertStripsToPolysOff();
        seams->Update();
        surface = seams->GetOutput();
      }
      vtkSmartPointer<vtkPolyData> turned = FacingViewer(surface, camera);
      turned->GetFieldData()->ShallowCopy(object.Data[0]->GetFieldData());
      partitions->SetPartition(0, turned);
    }
    else if (vtkSmartPointer<vtkImageData> merged =
               object.Data.size() > 1 ? MergedImage(object.Data) : nullptr)
    {
      partitions->SetPartition(0, merged); // one volume's pieces: one medium
    }
    else if (object.Data.size() > 1 && !object.Surface)
    {
      // Pieces that do not make one image: a medium each.
      for (std::size_t p = 0; p < object.Data.size(); ++p)
      {
        vtkNew<vtkPartitionedDataSet> piece;
        piece->SetPartition(0, object.Data[p]);
        const unsigned int index = whole->GetNumberOfPartitionedDataSets();
        whole->SetPartitionedDataSet(index, piece);
        whole->GetMetaData(index)->Copy(object.Meta);
        whole->GetMetaData(index)->Set(vtkCompositeDataSet::NAME(),
          (object.Name + (p > 0 ? " (piece " + std::to_string(p) + ")" : "")).c_str());
      }
      continue;
    }
    else
    {
      for (unsigned int k = 0; k < object.Data.size(); ++k)
      {
        partitions->SetPartition(k, object.Data[k]);
      }
    }
    const unsigned int index = whole->GetNumberOfPartitionedDataSets();
    whole->SetPartitionedDataSet(index, partitions);
    whole->GetMetaData(index)->Copy(object.Meta);
  }
  return whole;
}
}
