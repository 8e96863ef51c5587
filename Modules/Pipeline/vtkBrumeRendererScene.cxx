// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeRendererScene.h"

#include "vtkAbstractVolumeMapper.h"
#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkAlgorithm.h"
#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeFieldTuple.h"
#include "vtkBrumeSceneActors.h"
#include "vtkBrumeSceneConversion.h"
#include "vtkBrumeVolumePropertyMedium.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCleanPolyData.h"
#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArray.h"
#include "vtkDataSetSurfaceFilter.h"
#include "vtkExecutive.h"
#include "vtkFeatureEdges.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkLookupTable.h"
#include "vtkMapper.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataNormals.h"
#include "vtkPropCollection.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkScalarsToColors.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"
#include "vtkTimeStamp.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVolume.h"
#include "vtkVolumeCollection.h"
#include "vtkVolumeProperty.h"
#include "vtkWeakPointer.h"

#include "brume/Scene.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkBrumeRendererScene);

struct vtkBrumeRendererScene::vtkInternals
{
  vtkWeakPointer<vtkRenderer> Renderer;
  // The props last seen, and when they last changed: vtkRenderer gathers
  // its actors and volumes anew at every GetActors(), GetVolumes(), which
  // modifies those collections each time.
  std::vector<vtkProp*> Props;
  vtkTimeStamp PropsChanged;
  // The props the last RequestData made part of the scene.
  std::set<vtkProp*> Translated;
  // Per light of the last scene: whether it follows the camera.
  std::vector<bool> CameraLights;
};

namespace
{
// Brings a mapper's input up to date; its data object, or null.
vtkDataObject* MapperData(vtkAbstractMapper* mapper, int port = 0)
{
  if (!mapper || mapper->GetNumberOfInputConnections(port) < 1)
  {
    return nullptr;
  }
  vtkAlgorithm* producer = mapper->GetInputAlgorithm(port, 0);
  if (producer)
  {
    producer->Update();
  }
  return mapper->GetInputDataObject(port, 0);
}

vtkDataSet* MapperInput(vtkAbstractMapper* mapper, int port = 0)
{
  return vtkDataSet::SafeDownCast(MapperData(mapper, port));
}

// The datasets a mapper draws: its input, or the leaves of a composite
// input (ParaView's representations give their mappers composite data).
std::vector<vtkDataSet*> MapperDatasets(vtkAbstractMapper* mapper)
{
  std::vector<vtkDataSet*> datasets;
  vtkDataObject* data = MapperData(mapper);
  if (auto* composite = vtkCompositeDataSet::SafeDownCast(data))
  {
    vtkSmartPointer<vtkCompositeDataIterator> leaves;
    leaves.TakeReference(composite->NewIterator());
    for (leaves->InitTraversal(); !leaves->IsDoneWithTraversal(); leaves->GoToNextItem())
    {
      if (auto* leaf = vtkDataSet::SafeDownCast(leaves->GetCurrentDataObject()))
      {
        datasets.push_back(leaf);
      }
    }
  }
  else if (auto* dataset = vtkDataSet::SafeDownCast(data))
  {
    datasets.push_back(dataset);
  }
  return datasets;
}

// Whether a prop shows radiance Brume computed (vtkBrumeSceneActors' props,
// ParaView's "Brume Radiance" representation): drawn as it is, not lit.
bool ShowsRadiance(vtkProp* prop)
{
  vtkInformation* keys = prop->GetPropertyKeys();
  return keys && keys->Has(vtkBrumeSceneActors::RADIANCE_PROP());
}

// The renderer's own actors and volumes: its view props that are vtkActors
// (not vtkFollowers, which turn with the camera) or vtkVolumes. The parts
// of other props (an interactive widget's handles and labels, an
// assembly's parts) are left to VTK.
std::vector<vtkActor*> OwnActors(vtkRenderer* renderer)
{
  std::vector<vtkActor*> actors;
  vtkPropCollection* props = renderer->GetViewProps();
  vtkCollectionSimpleIterator it;
  props->InitTraversal(it);
  while (vtkProp* prop = props->GetNextProp(it))
  {
    auto* actor = vtkActor::SafeDownCast(prop);
    if (actor && !actor->IsA("vtkFollower") && !ShowsRadiance(actor))
    {
      actors.push_back(actor);
    }
  }
  return actors;
}

std::vector<vtkVolume*> OwnVolumes(vtkRenderer* renderer)
{
  std::vector<vtkVolume*> volumes;
  vtkPropCollection* props = renderer->GetViewProps();
  vtkCollectionSimpleIterator it;
  props->InitTraversal(it);
  while (vtkProp* prop = props->GetNextProp(it))
  {
    auto* volume = vtkVolume::SafeDownCast(prop);
    if (volume && !ShowsRadiance(volume))
    {
      volumes.push_back(volume);
    }
  }
  return volumes;
}

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

// The light as vtkBrumeLightTracer reads it, where it stands now (camera
// lights and headlights included), its intensity scaled; with `vtkUnits`,
// Intensity 1 an irradiance of pi at the focal point.
vtkSmartPointer<vtkLight> SceneLight(vtkLight* light, double scale, bool vtkUnits)
{
  auto copy = vtkSmartPointer<vtkLight>::New();
  double position[3], focal[3];
  light->GetTransformedPosition(position);
  light->GetTransformedFocalPoint(focal);
  copy->SetLightTypeToSceneLight();
  copy->SetPosition(position);
  copy->SetFocalPoint(focal);
  copy->SetPositional(light->GetPositional());
  copy->SetConeAngle(light->GetConeAngle());
  copy->SetDiffuseColor(light->GetDiffuseColor());
  double factor = scale;
  if (vtkUnits)
  {
    const double d2 = vtkMath::Distance2BetweenPoints(position, focal);
    factor *= vtkMath::Pi() * (light->GetPositional() ? d2 : 1.0);
  }
  copy->SetIntensity(light->GetIntensity() * factor);
  return copy;
}
}

vtkBrumeRendererScene::vtkBrumeRendererScene()
  : Internals(new vtkInternals)
{
  this->SetNumberOfInputPorts(0);
}

vtkBrumeRendererScene::~vtkBrumeRendererScene()
{
  delete this->Internals;
}

void vtkBrumeRendererScene::SetRenderer(vtkRenderer* renderer)
{
  if (this->Internals->Renderer != renderer)
  {
    this->Internals->Renderer = renderer;
    this->Modified();
  }
}

vtkRenderer* vtkBrumeRendererScene::GetRenderer()
{
  return this->Internals->Renderer;
}

vtkMTimeType vtkBrumeRendererScene::GetMTime()
{
  vtkMTimeType t = this->Superclass::GetMTime();
  vtkRenderer* renderer = this->Internals->Renderer;
  if (!renderer)
  {
    return t;
  }
  auto input = [&t](vtkAbstractMapper* mapper)
  {
    if (!mapper)
    {
      return;
    }
    t = std::max(t, mapper->GetMTime());
    if (mapper->GetNumberOfInputConnections(0) > 0)
    {
      if (vtkAlgorithm* producer = mapper->GetInputAlgorithm(0, 0))
      {
        t = std::max(t, producer->GetMTime());
      }
    }
  };
  // The visible props: those in the scene with everything that places and
  // colours them; the others (translucent, without polygons) with what
  // could make them part of it, not their matrices (ParaView's centre axes
  // follow the camera).
  std::vector<vtkProp*> props;
  const std::set<vtkProp*>& translated = this->Internals->Translated;
  for (vtkActor* actor : OwnActors(renderer))
  {
    if (!actor->GetVisibility())
    {
      continue;
    }
    t = std::max(t, translated.count(actor) ? actor->GetMTime() : actor->GetProperty()->GetMTime());
    input(actor->GetMapper());
    props.push_back(actor);
  }
  for (vtkVolume* volume : OwnVolumes(renderer))
  {
    if (!volume->GetVisibility())
    {
      continue;
    }
    t = std::max(t, volume->GetMTime()); // its property and transfer functions
    input(volume->GetMapper());
    props.push_back(volume);
  }
  if (props != this->Internals->Props)
  {
    this->Internals->Props = props;
    this->Internals->PropsChanged.Modified();
  }
  t = std::max(t, this->Internals->PropsChanged.GetMTime());
  // Scene lights only: the renderer moves headlights and camera lights with
  // the camera, which rebuilds nothing.
  vtkLightCollection* lights = renderer->GetLights();
  t = std::max(t, lights->GetMTime());
  lights->InitTraversal();
  while (vtkLight* light = lights->GetNextItem())
  {
    t = light->LightTypeIsSceneLight() ? std::max(t, light->GetMTime()) : t;
  }
  return t;
}

int vtkBrumeRendererScene::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  auto* output = vtkPartitionedDataSetCollection::GetData(outputVector, 0);
  vtkRenderer* renderer = this->Internals->Renderer;
  if (!renderer)
  {
    vtkErrorMacro("No renderer: SetRenderer first.");
    return 0;
  }
  vtkNew<vtkPartitionedDataSetCollection> scene;
  std::set<vtkProp*>& translated = this->Internals->Translated;
  translated.clear();
  int index = 0;
  for (vtkActor* actor : OwnActors(renderer))
  {
    const std::string name = "actor " + std::to_string(index++);
    if (!actor->GetVisibility() || actor->GetProperty()->GetOpacity() < 1.0)
    {
      continue; // Brume's surfaces are opaque
    }
    // One surface per dataset (per block of a composite input).
    const std::vector<vtkDataSet*> datasets = MapperDatasets(actor->GetMapper());
    int block = 0;
    for (vtkDataSet* data : datasets)
    {
      const WorldPolygons world = WorldSurface(data, actor->GetMatrix());
      if (!world.Surface)
      {
        continue;
      }
      int cellFlag = 0;
      if (vtkSmartPointer<vtkUnsignedCharArray> colours =
            MappedColours(actor->GetMapper(), data, cellFlag))
      {
        WriteColours(world, colours, cellFlag, actor->GetProperty());
      }
      vtkSmartPointer<vtkPolyData> surface =
        FacingViewer(world.Surface, renderer->GetActiveCamera());
      WriteMaterial(actor->GetProperty(), surface->GetFieldData());
      const std::string named = block == 0 ? name : name + " block " + std::to_string(block);
      ++block;
      vtkBrumeSceneConversion::AddObject(scene, surface, named);
      translated.insert(actor);
    }
  }
  index = 0;
  for (vtkVolume* volume : OwnVolumes(renderer))
  {
    const std::string name = "volume " + std::to_string(index++);
    vtkDataSet* data = volume->GetVisibility() ? MapperInput(volume->GetMapper()) : nullptr;
    if (!data)
    {
      continue;
    }
    vtkMatrix4x4* m = volume->GetMatrix();
    for (int r = 0; r < 3; ++r)
    {
      for (int c = 0; c < 3; ++c)
      {
        if ((r != c && m->GetElement(r, c) != 0.0) || (r == c && !(m->GetElement(r, c) > 0.0)))
        {
          vtkErrorMacro("" << name << " is rotated, mirrored or sheared: only a translation and "
                           << "an axis-aligned scale of a volume can be lit.");
          return 0;
        }
      }
    }
    vtkNew<vtkBrumeVolumePropertyMedium> medium;
    medium->SetInputData(data);
    // The array the volume mapper draws, where it names one.
    vtkAbstractVolumeMapper* volumeMapper = volume->GetMapper();
    const char* array = volumeMapper ? volumeMapper->GetArrayName() : nullptr;
    if (array && *array && volumeMapper->GetArrayAccessMode() == VTK_GET_ARRAY_BY_NAME &&
      (volumeMapper->GetScalarMode() == VTK_SCALAR_MODE_USE_POINT_FIELD_DATA ||
        volumeMapper->GetScalarMode() == VTK_SCALAR_MODE_USE_CELL_FIELD_DATA))
    {
      medium->SetInputArrayToProcess(0, 0, 0,
        volumeMapper->GetScalarMode() == VTK_SCALAR_MODE_USE_POINT_FIELD_DATA
          ? vtkDataObject::FIELD_ASSOCIATION_POINTS
          : vtkDataObject::FIELD_ASSOCIATION_CELLS,
        array);
    }
    medium->SetVolumeProperty(volume->GetProperty());
    medium->SetAlbedo(this->Albedo);
    if (!medium->GetExecutive()->Update())
    {
      vtkErrorMacro("" << name << " could not be made a medium (see the error above).");
      return 0;
    }
    vtkNew<vtkImageData> placed;
    placed->ShallowCopy(medium->GetOutput());
    double origin[3], spacing[3];
    placed->GetOrigin(origin);
    placed->GetSpacing(spacing);
    for (int a = 0; a < 3; ++a)
    {
      origin[a] = m->GetElement(a, a) * origin[a] + m->GetElement(a, 3);
      spacing[a] *= m->GetElement(a, a);
    }
    placed->SetOrigin(origin);
    placed->SetSpacing(spacing);
    vtkBrumeSceneConversion::AddObject(scene, placed, name);
    translated.insert(volume);
  }
  if (scene->GetNumberOfPartitionedDataSets() == 0)
  {
    if (!this->AllowEmpty)
    {
      vtkErrorMacro("The renderer holds no opaque actor with polygons and no volume to light.");
      return 0;
    }
    this->Internals->CameraLights.clear();
    output->ShallowCopy(scene);
    return 1;
  }

  // The lights, as vtkBrumeLightTracer reads vtkLights, in the scene.
  vtkNew<vtkLightCollection> lights;
  std::vector<bool>& cameraLights = this->Internals->CameraLights;
  cameraLights.clear();
  vtkLightCollection* given = renderer->GetLights();
  given->InitTraversal();
  while (vtkLight* light = given->GetNextItem())
  {
    if (light->GetSwitch())
    {
      lights->AddItem(SceneLight(light, this->LightScale, !this->PhysicalLights));
      cameraLights.push_back(!light->LightTypeIsSceneLight());
    }
  }
  if (lights->GetNumberOfItems() == 0)
  {
    cameraLights.push_back(true);
    // What VTK gives a renderer without lights: a headlight.
    vtkNew<vtkLight> headlight;
    vtkCamera* camera = renderer->GetActiveCamera();
    headlight->SetPosition(camera->GetPosition());
    headlight->SetFocalPoint(camera->GetFocalPoint());
    lights->AddItem(SceneLight(headlight, this->LightScale, !this->PhysicalLights));
  }
  brume::Scene converted;
  const std::string error = vtkBrumeSceneConversion::ConvertLights(lights, converted);
  if (!error.empty())
  {
    vtkErrorMacro("The renderer's lights: " << error << ".");
    return 0;
  }
  AimPointLights(scene, converted.Lights);
  vtkBrumeSceneConversion::AppendFieldLights(converted.Lights, scene->GetFieldData());
  output->ShallowCopy(scene);
  return 1;
}

namespace
{
// FNV-1a, 64 bits.
struct Hash
{
  vtkTypeUInt64 Value = 14695981039346656037ull;
  void Bytes(const void* data, std::size_t size)
  {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i)
    {
      this->Value = (this->Value ^ bytes[i]) * 1099511628211ull;
    }
  }
  template <typename T>
  void Add(const T& value)
  {
    this->Bytes(&value, sizeof(value));
  }
  void Text(const char* text)
  {
    const std::string s = text ? text : "";
    this->Add(s.size());
    this->Bytes(s.data(), s.size());
  }
  // An array's name, type, shape and values (by identity with `values` off).
  void Array(vtkAbstractArray* array, bool values = true)
  {
    if (!array)
    {
      this->Add(0);
      return;
    }
    this->Text(array->GetName());
    this->Add(array->GetDataType());
    this->Add(array->GetNumberOfComponents());
    this->Add(array->GetNumberOfTuples());
    if (!values)
    {
      this->Add(reinterpret_cast<std::uintptr_t>(array));
      this->Add(array->GetMTime());
    }
    else if (auto* strings = vtkStringArray::SafeDownCast(array))
    {
      for (vtkIdType i = 0; i < strings->GetNumberOfValues(); ++i)
      {
        this->Text(strings->GetValue(i).c_str());
      }
    }
    else if (auto* data = vtkDataArray::SafeDownCast(array))
    {
      this->Bytes(data->GetVoidPointer(0),
        static_cast<std::size_t>(data->GetNumberOfValues()) * data->GetDataTypeSize());
    }
  }
  void Arrays(vtkFieldData* fields, bool values = true)
  {
    this->Add(fields ? fields->GetNumberOfArrays() : -1);
    for (int i = 0; fields && i < fields->GetNumberOfArrays(); ++i)
    {
      this->Array(fields->GetAbstractArray(i), values);
    }
  }
  void Cells(vtkCellArray* cells)
  {
    this->Array(cells ? cells->GetOffsetsArray() : nullptr);
    this->Array(cells ? cells->GetConnectivityArray() : nullptr);
  }
};
}

vtkTypeUInt64 vtkBrumeRendererScene::GetContentSignature()
{
  Hash hash;
  vtkPartitionedDataSetCollection* scene = this->GetOutput();
  if (!scene)
  {
    return hash.Value;
  }
  // The lights: camera lights' placement left out.
  vtkFieldData* lights = scene->GetFieldData();
  const std::vector<bool>& cameraLights = this->Internals->CameraLights;
  for (int i = 0; i < lights->GetNumberOfArrays(); ++i)
  {
    vtkAbstractArray* array = lights->GetAbstractArray(i);
    const std::string name = array && array->GetName() ? array->GetName() : "";
    auto* values = vtkDataArray::SafeDownCast(array);
    if (values && (name == vtkBrumeNames::LightPosition || name == vtkBrumeNames::LightDirection))
    {
      for (vtkIdType k = 0; k < values->GetNumberOfTuples(); ++k)
      {
        const bool placed = static_cast<std::size_t>(k) < cameraLights.size() && cameraLights[k];
        for (int c = 0; c < values->GetNumberOfComponents() && !placed; ++c)
        {
          hash.Add(values->GetComponent(k, c));
        }
      }
      continue;
    }
    hash.Array(array);
  }
  hash.Add(scene->GetNumberOfPartitionedDataSets());
  for (unsigned int i = 0; i < scene->GetNumberOfPartitionedDataSets(); ++i)
  {
    hash.Text(
      scene->HasMetaData(i) ? scene->GetMetaData(i)->Get(vtkCompositeDataSet::NAME()) : nullptr);
    vtkPartitionedDataSet* partitions = scene->GetPartitionedDataSet(i);
    for (unsigned int k = 0; partitions && k < partitions->GetNumberOfPartitions(); ++k)
    {
      vtkDataSet* data = partitions->GetPartition(k);
      hash.Text(data ? data->GetClassName() : nullptr);
      if (!data)
      {
        continue;
      }
      hash.Arrays(data->GetFieldData());
      if (auto* surface = vtkPolyData::SafeDownCast(data))
      {
        hash.Array(surface->GetPoints() ? surface->GetPoints()->GetData() : nullptr);
        hash.Cells(surface->GetPolys());
        hash.Cells(surface->GetStrips());
        hash.Arrays(surface->GetPointData());
        hash.Arrays(surface->GetCellData());
      }
      else if (auto* image = vtkImageData::SafeDownCast(data))
      {
        int dims[3];
        double origin[3], spacing[3];
        image->GetDimensions(dims);
        image->GetOrigin(origin);
        image->GetSpacing(spacing);
        hash.Add(dims);
        hash.Add(origin);
        hash.Add(spacing);
        hash.Arrays(image->GetPointData(), false);
        hash.Arrays(image->GetCellData(), false);
      }
      else
      {
        hash.Add(reinterpret_cast<std::uintptr_t>(data));
        hash.Add(data->GetMTime());
      }
    }
  }
  return hash.Value;
}

bool vtkBrumeRendererScene::Translates(vtkProp* prop)
{
  return this->Internals->Translated.count(prop) > 0;
}

void vtkBrumeRendererScene::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Renderer: " << this->Internals->Renderer.GetPointer() << "\n";
  os << indent << "PhysicalLights: " << this->PhysicalLights << "\n";
  os << indent << "AllowEmpty: " << this->AllowEmpty << "\n";
  os << indent << "LightScale: " << this->LightScale << "\n";
  os << indent << "Albedo: " << this->Albedo[0] << " " << this->Albedo[1] << " " << this->Albedo[2]
     << "\n";
}
