// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeRendererScene.h"
#include "vtkBrumeProcesses.h"
#include "vtkBrumeRendererSceneParts.h"
#include "vtkMultiProcessController.h"

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
vtkCxxSetObjectMacro(vtkBrumeRendererScene, Controller, vtkMultiProcessController);

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
  // The camera and its MTime when the last scene placed those lights.
  vtkWeakPointer<vtkCamera> PlacedCamera;
  vtkMTimeType PlacedCameraTime = 0;
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
template <typename Prop>
std::vector<Prop*> OwnProps(vtkRenderer* renderer)
{
  std::vector<Prop*> own;
  vtkPropCollection* props = renderer->GetViewProps();
  vtkCollectionSimpleIterator it;
  props->InitTraversal(it);
  while (vtkProp* prop = props->GetNextProp(it))
  {
    auto* typed = Prop::SafeDownCast(prop);
    if (typed && !prop->IsA("vtkFollower") && !ShowsRadiance(prop))
    {
      own.push_back(typed);
    }
  }
  return own;
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
  this->SetController(nullptr);
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
  for (vtkActor* actor : OwnProps<vtkActor>(renderer))
  {
    if (!actor->GetVisibility())
    {
      continue;
    }
    t = std::max(t, translated.count(actor) ? actor->GetMTime() : actor->GetProperty()->GetMTime());
    input(actor->GetMapper());
    props.push_back(actor);
  }
  for (vtkVolume* volume : OwnProps<vtkVolume>(renderer))
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
  // Distributed: surfaces are turned once gathered (see Gathered).
  const bool distributed = this->Controller && this->Controller->GetNumberOfProcesses() > 1;
  std::set<vtkProp*>& translated = this->Internals->Translated;
  translated.clear();
  int index = 0;
  for (vtkActor* actor : OwnProps<vtkActor>(renderer))
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
      vtkSmartPointer<vtkPolyData> surface = vtkBrumeRendererSceneParts::ActorSurface(
        actor, data, distributed ? nullptr : renderer->GetActiveCamera());
      if (!surface)
      {
        continue;
      }
      const std::string named = block == 0 ? name : name + " block " + std::to_string(block);
      ++block;
      vtkBrumeSceneConversion::AddObject(scene, surface, named);
      translated.insert(actor);
    }
  }
  index = 0;
  bool failed = false; // a volume that cannot be lit (said), with the others still tried
  for (vtkVolume* volume : OwnProps<vtkVolume>(renderer))
  {
    const std::string name = "volume " + std::to_string(index++);
    vtkDataSet* data = volume->GetVisibility() ? MapperInput(volume->GetMapper()) : nullptr;
    if (!data)
    {
      continue;
    }
    vtkMatrix4x4* m = volume->GetMatrix();
    bool aligned = true;
    for (int r = 0; r < 3; ++r)
    {
      for (int c = 0; c < 3; ++c)
      {
        aligned = aligned &&
          !((r != c && m->GetElement(r, c) != 0.0) || (r == c && !(m->GetElement(r, c) > 0.0)));
      }
    }
    if (!aligned)
    {
      vtkErrorMacro("" << name << " is rotated, mirrored or sheared: only a translation and "
                       << "an axis-aligned scale of a volume can be lit.");
      failed = true;
      continue;
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
      failed = true;
      continue;
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
  // A distributed scene: every process's share, gathered, when every
  // process could make its own.
  if (distributed)
  {
    if (!vtkBrumeProcesses::Agree(this->Controller, !failed))
    {
      if (!failed)
      {
        vtkErrorMacro("Another process's part of the scene could not be made.");
      }
      return 0;
    }
    vtkSmartPointer<vtkPartitionedDataSetCollection> whole =
      vtkBrumeRendererSceneParts::Gathered(this->Controller, scene, renderer->GetActiveCamera());
    scene->ShallowCopy(whole);
  }
  else if (failed)
  {
    return 0;
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
  // Headlights and camera lights where the camera stands now (the renderer
  // places them at its next render; until then, where the last one stood).
  renderer->UpdateLightsGeometryToFollowCamera();
  this->Internals->PlacedCamera = renderer->GetActiveCamera();
  this->Internals->PlacedCameraTime = renderer->GetActiveCamera()->GetMTime();
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
  }
  if (distributed ? !vtkBrumeProcesses::Agree(this->Controller, error.empty()) : !error.empty())
  {
    return 0;
  }
  vtkBrumeRendererSceneParts::AimPointLights(scene, converted.Lights);
  vtkBrumeSceneConversion::AppendFieldLights(converted.Lights, scene->GetFieldData());
  if (distributed)
  {
    // Process 0's lights on every process: camera lights (ParaView's light
    // kit) stand where each renderer last placed them, which may differ
    // between processes, and the processes trace their shares of one scene.
    vtkNew<vtkPolyData> carrier;
    carrier->GetFieldData()->ShallowCopy(scene->GetFieldData());
    this->Controller->Broadcast(carrier, 0);
    scene->GetFieldData()->ShallowCopy(carrier->GetFieldData());
  }
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
        // By values where the scene is gathered: its media's arrays are
        // new objects at each gathering.
        const bool gathered = this->Controller && this->Controller->GetNumberOfProcesses() > 1;
        hash.Arrays(image->GetPointData(), gathered);
        hash.Arrays(image->GetCellData(), gathered);
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

bool vtkBrumeRendererScene::HasCameraLights()
{
  const std::vector<bool>& lights = this->Internals->CameraLights;
  return std::find(lights.begin(), lights.end(), true) != lights.end();
}

bool vtkBrumeRendererScene::AreCameraLightsBehind()
{
  vtkRenderer* renderer = this->Internals->Renderer;
  vtkCamera* camera = renderer ? renderer->GetActiveCamera() : nullptr;
  return this->HasCameraLights() &&
    (camera != this->Internals->PlacedCamera ||
      camera->GetMTime() != this->Internals->PlacedCameraTime);
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
  os << indent << "Controller: " << this->Controller << "\n";
  os << indent << "Albedo: " << this->Albedo[0] << " " << this->Albedo[1] << " " << this->Albedo[2]
     << "\n";
}
