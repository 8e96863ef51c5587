// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeRadianceRepresentation.h"

#include "vtkBoundingBox.h"
#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeRadianceReconstruction.h"
#include "vtkBrumeSceneActors.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkMath.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"
#include "vtkPVRenderView.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPolyData.h"
#include "vtkProcessModule.h"
#include "vtkPropCollection.h"
#include "vtkRenderer.h"

vtkStandardNewMacro(vtkBrumeRadianceRepresentation);

namespace
{
// "" when `data` is a collection of Brume textures, else why not. Also
// the objects' kinds in order (the props' layout) and their world bounds:
// surfaces' geometry and media's boxes, not the texture-space images.
std::string Inspect(vtkDataObject* data, std::string& layout, vtkBoundingBox& box)
{
  auto* textures = vtkPartitionedDataSetCollection::SafeDownCast(data);
  const std::string intro = "Brume Radiance shows the output of Brume Radiance Reconstruction";
  if (!textures)
  {
    return intro + "; this input is a " + std::string(data ? data->GetClassName() : "nothing");
  }
  layout.clear();
  for (unsigned int i = 0; i < textures->GetNumberOfPartitionedDataSets(); ++i)
  {
    vtkPartitionedDataSet* pds = textures->GetPartitionedDataSet(i);
    vtkDataObject* first = pds && pds->GetNumberOfPartitions() > 0 ? pds->GetPartition(0) : nullptr;
    const std::string kind = vtkBrumeSceneActors::GetObjectKind(first);
    auto* image = vtkImageData::SafeDownCast(first);
    auto* surface = pds && pds->GetNumberOfPartitions() > 1
      ? vtkPolyData::SafeDownCast(pds->GetPartition(1))
      : nullptr;
    if (kind == "surface" && image && surface)
    {
      box.AddBounds(surface->GetBounds());
    }
    else if (kind == "medium" && image)
    {
      box.AddBounds(image->GetBounds());
    }
    else
    {
      return intro + "; object " + std::to_string(i) +
        " of this collection is not a radiance texture (no BrumeObjectKind)";
    }
    layout += kind + ";";
  }
  return std::string();
}

std::string LayoutOf(vtkDataObject* data)
{
  std::string layout;
  vtkBoundingBox box;
  return Inspect(data, layout, box).empty() ? layout : std::string("?");
}

bool EyeOf(vtkPartitionedDataSetCollection* textures, double eye[3])
{
  auto* array = vtkDoubleArray::SafeDownCast(
    textures ? textures->GetFieldData()->GetArray(vtkBrumeNames::EyePosition) : nullptr);
  if (!array || array->GetNumberOfComponents() != 3 || array->GetNumberOfTuples() < 1)
  {
    return false;
  }
  array->GetTypedTuple(0, eye);
  return true;
}

// The reconstruction holds its viewpoint in single precision.
bool SameEye(const double textures[3], const double camera[3])
{
  for (int a = 0; a < 3; ++a)
  {
    if (static_cast<float>(textures[a]) != static_cast<float>(camera[a]))
    {
      return false;
    }
  }
  return true;
}

// The reconstruction upstream of `algorithm`, through algorithms that
// pass their one input on (ParaView may put such producers in between).
vtkBrumeRadianceReconstruction* FindReconstruction(vtkAlgorithm* algorithm)
{
  for (int depth = 0; algorithm && depth < 8; ++depth)
  {
    if (auto* reconstruction = vtkBrumeRadianceReconstruction::SafeDownCast(algorithm))
    {
      return reconstruction;
    }
    algorithm =
      algorithm->GetNumberOfInputPorts() == 1 && algorithm->GetNumberOfInputConnections(0) == 1
      ? algorithm->GetInputAlgorithm(0, 0)
      : nullptr;
  }
  return nullptr;
}

int ViewDependentObjects(vtkPartitionedDataSetCollection* textures)
{
  auto* array = vtkIntArray::SafeDownCast(
    textures ? textures->GetFieldData()->GetArray(vtkBrumeNames::ViewDependentObjects) : nullptr);
  return array && array->GetNumberOfValues() > 0 ? array->GetValue(0) : 0;
}
}

vtkBrumeRadianceRepresentation::vtkBrumeRadianceRepresentation()
  : Actors(vtkSmartPointer<vtkBrumeSceneActors>::New())
{
  vtkMath::UninitializeBounds(this->Bounds);
}

vtkBrumeRadianceRepresentation::~vtkBrumeRadianceRepresentation()
{
  this->Hide();
}

int vtkBrumeRadianceRepresentation::FillInputPortInformation(int, vtkInformation* info)
{
  // Any data object: a composite representation connects every input to
  // each of its representations; what is not Brume's is refused at render.
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataObject");
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

namespace
{
// Several processes that each render (mpirun pvbatch, a parallel server
// rendering remotely): every process holds the textures (the
// reconstruction gives them on each), draws them, and IceT composites
// identical images; a parallel server's client gets process 0's copy.
int Processes()
{
  vtkMultiProcessController* processes = vtkMultiProcessController::GetGlobalController();
  return processes ? processes->GetNumberOfProcesses() : 1;
}

bool ParallelBatch()
{
  return Processes() > 1 && vtkProcessModule::GetProcessType() == vtkProcessModule::PROCESS_BATCH;
}
}

int vtkBrumeRadianceRepresentation::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkMath::UninitializeBounds(this->Bounds);
  this->InputProblem.clear();
  this->Cache = vtkSmartPointer<vtkPartitionedDataSetCollection>::New();
  if (inputVector[0]->GetNumberOfInformationObjects() == 1)
  {
    vtkDataObject* input = vtkDataObject::GetData(inputVector[0], 0);
    std::string layout;
    vtkBoundingBox box;
    this->InputProblem = Inspect(input, layout, box);
    if (this->InputProblem.empty())
    {
      this->Cache->ShallowCopy(input);
      if (box.IsValid())
      {
        box.GetBounds(this->Bounds);
      }
    }
  }
  // else: a process without the data (the client of a remote server).
  return this->Superclass::RequestData(request, inputVector, outputVector);
}

int vtkBrumeRadianceRepresentation::ProcessViewRequest(
  vtkInformationRequestKey* request, vtkInformation* inInfo, vtkInformation* outInfo)
{
  if (!this->Superclass::ProcessViewRequest(request, inInfo, outInfo))
  {
    return 0;
  }
  if (request == vtkPVView::REQUEST_UPDATE())
  {
    // One process draws the textures, with their per-channel
    // transmittance: nothing is composited.
    vtkPVView::SetPiece(inInfo, this, this->Cache);
    vtkPVRenderView::SetGeometryBounds(inInfo, this, this->Bounds);
    // Several processes (mpirun pvbatch, a parallel server) hold the same
    // textures: each draws its own copy (and its slices write their depth,
    // for IceT's z-buffer compositing), and a client gets process 0's copy
    // alone, not a gather of all of them.
    if (Processes() > 1 && !ParallelBatch())
    {
      vtkPVRenderView::SetDeliverToClientAndRenderingProcesses(inInfo, this, true, false);
    }
    else if (Processes() == 1)
    {
      vtkPVRenderView::SetRequiresDistributedRendering(inInfo, this, false);
    }
  }
  else if (request == vtkPVView::REQUEST_UPDATE_LOD())
  {
    // The level of detail of interactive renders is the same textures,
    // their media drawn coarser (InteractiveImageSampleDistance): without
    // it, nothing would be delivered for them, and nothing drawn.
    vtkPVView::SetPieceLOD(inInfo, this, this->Cache);
  }
  else if (request == vtkPVView::REQUEST_RENDER())
  {
    if (!this->InputProblem.empty())
    {
      this->Hide();
      this->Warn(this->InputProblem + ": nothing is drawn.");
      return 1;
    }
    const bool lod = inInfo->Has(vtkPVRenderView::USE_LOD()) != 0;
    auto* delivered = vtkPartitionedDataSetCollection::SafeDownCast(lod
        ? vtkPVView::GetDeliveredPieceLOD(inInfo, this)
        : vtkPVView::GetDeliveredPiece(inInfo, this));
    if (!delivered || delivered->GetNumberOfPartitionedDataSets() == 0)
    {
      this->Hide(); // a process without the textures
      return 1;
    }
    auto* view = vtkPVRenderView::SafeDownCast(inInfo->Get(vtkPVView::VIEW()));
    this->Actors->SetMediaWriteDepth(Processes() > 1);
    // ParaView's level of detail (interactive renders of large data): the
    // media coarser; still renders at full resolution.
    this->Actors->SetImageSampleDistance(lod ? this->InteractiveImageSampleDistance : 1.0);
    this->Show(this->FollowCamera ? this->Follow(view, delivered) : delivered);
    // With translucent geometry in the view, the render view's default
    // (DepthPeelingForVolumes) would draw the media inside VTK's dual depth
    // peeling, once per peel; Brume's slices blend themselves, once.
    // Documentation/paraview.md says so; the view's property shows the old value.
    if (this->Renderer && this->ShowMedia)
    {
      this->Renderer->SetUseDepthPeelingForVolumes(false);
    }
  }
  return 1;
}

vtkPartitionedDataSetCollection* vtkBrumeRadianceRepresentation::Follow(
  vtkPVRenderView* view, vtkPartitionedDataSetCollection* textures)
{
  // The plugin's client side (vtkBrumeCameraFollower) has already moved the
  // reconstruction's EyePosition to the camera before this render's update,
  // wherever the reconstruction runs. What is left here is the built-in
  // session's case of a camera moved without its view proxy (a VTK render
  // of the view's window): the reconstruction runs here, and follows.
  // Textures that came from a server lose the collection's field data on
  // the way: no eye to compare with, and no reconstruction here.
  double eye[3];
  const bool known = EyeOf(textures, eye);
  if (!view || !known || ViewDependentObjects(textures) == 0)
  {
    return textures;
  }
  vtkCamera* camera = view->GetActiveCamera();
  double position[3];
  camera->GetPosition(position);
  if (SameEye(eye, position))
  {
    return textures;
  }
  // Under mpirun the reconstruction's update is a collective step, and at
  // this point of a render the other processes may not have the camera
  // yet: only the client-side follower moves it there.
  auto* reconstruction = this->GetNumberOfInputConnections(0) == 1
    ? FindReconstruction(this->GetInputAlgorithm(0, 0))
    : nullptr;
  vtkMultiProcessController* controller =
    reconstruction ? reconstruction->GetController() : nullptr;
  if (!reconstruction || Processes() > 1 || (controller && controller->GetNumberOfProcesses() > 1))
  {
    return textures;
  }
  if (reconstruction->GetCamera() != camera)
  {
    reconstruction->SetCamera(camera);
  }
  this->FollowedReconstruction = reconstruction;
  reconstruction->Update();
  vtkPartitionedDataSetCollection* output = reconstruction->GetOutput();
  double followed[3];
  if (!EyeOf(output, followed) || !SameEye(followed, position) ||
    LayoutOf(output) != LayoutOf(textures))
  {
    this->Warn("Brume Radiance could not update the textures toward the camera (the "
               "reconstruction failed): they stay where they were.");
    return textures;
  }
  return output;
}

void vtkBrumeRadianceRepresentation::Show(vtkPartitionedDataSetCollection* textures)
{
  if (!this->Renderer)
  {
    return;
  }
  // The same objects: point the props at the new textures (only new images
  // are uploaded again). Other objects: new props.
  // The actors keep the representation's settings (its setters pass them on).
  const std::string layout = LayoutOf(textures);
  const bool newTextures = this->Shown && this->Shown != textures;
  if (this->Shown && this->ShownLayout == layout && this->Actors->UpdateInputs(textures))
  {
    if (newTextures)
    {
      int changed = this->Actors->GetNumberOfChangedDataSets();
      this->InvokeEvent(TexturesShownEvent, &changed);
    }
  }
  else
  {
    this->Actors->RemoveFromRenderer(this->Renderer);
    this->Actors->SetInputData(textures);
    if (!this->Actors->AddToRenderer(this->Renderer))
    {
      this->Actors->RemoveFromRenderer(this->Renderer);
      this->Shown = nullptr;
      return; // the error is reported
    }
  }
  this->Shown = textures;
  this->ShownLayout = layout;
  this->ApplyVisibility();
}

void vtkBrumeRadianceRepresentation::Hide()
{
  this->Actors->RemoveFromRenderer(this->Renderer);
  this->Shown = nullptr;
}

void vtkBrumeRadianceRepresentation::Warn(const std::string& message)
{
  if (message != this->LastWarning)
  {
    this->LastWarning = message;
    vtkWarningMacro(<< message);
  }
}

void vtkBrumeRadianceRepresentation::ApplyVisibility()
{
  const bool visible = this->GetVisibility();
  this->Actors->SetSurfaceVisibility(visible && this->ShowSurfaces);
  this->Actors->SetMediaVisibility(visible && this->ShowMedia);
}

void vtkBrumeRadianceRepresentation::SetVisibility(bool visible)
{
  this->Superclass::SetVisibility(visible);
  this->ApplyVisibility();
}

void vtkBrumeRadianceRepresentation::SetShowSurfaces(bool show)
{
  if (this->ShowSurfaces != show)
  {
    this->ShowSurfaces = show;
    this->ApplyVisibility();
    this->Modified();
  }
}

void vtkBrumeRadianceRepresentation::SetShowMedia(bool show)
{
  if (this->ShowMedia != show)
  {
    this->ShowMedia = show;
    this->ApplyVisibility();
    this->Modified();
  }
}

void vtkBrumeRadianceRepresentation::SetSliceSpacing(double spacing)
{
  if (this->SliceSpacing != spacing)
  {
    this->SliceSpacing = spacing;
    this->Actors->SetSliceSpacing(spacing);
    this->Modified();
  }
}

void vtkBrumeRadianceRepresentation::SetExtinctionDepthTolerance(double tolerance)
{
  if (this->Actors->GetExtinctionDepthTolerance() != tolerance)
  {
    this->Actors->SetExtinctionDepthTolerance(tolerance);
    this->Modified();
  }
}

double vtkBrumeRadianceRepresentation::GetExtinctionDepthTolerance()
{
  return this->Actors->GetExtinctionDepthTolerance();
}

void vtkBrumeRadianceRepresentation::SetExposure(double exposure)
{
  if (this->Exposure != exposure)
  {
    this->Exposure = exposure;
    this->Actors->SetExposure(exposure);
    this->Modified();
  }
}

void vtkBrumeRadianceRepresentation::SetTextureInterpolation(bool interpolate)
{
  if (this->TextureInterpolation != interpolate)
  {
    this->TextureInterpolation = interpolate;
    this->Actors->SetInterpolate(interpolate);
    this->Modified();
  }
}

void vtkBrumeRadianceRepresentation::SetBackfaceCulling(bool cull)
{
  if (this->BackfaceCulling != cull)
  {
    this->BackfaceCulling = cull;
    this->Actors->SetBackfaceCulling(cull);
    this->Modified();
  }
}

void vtkBrumeRadianceRepresentation::SetFollowCamera(bool follow)
{
  if (this->FollowCamera == follow)
  {
    return;
  }
  this->FollowCamera = follow;
  // Off: the reconstruction goes back to its EyePosition at its next update.
  auto* reconstruction =
    vtkBrumeRadianceReconstruction::SafeDownCast(this->FollowedReconstruction.GetPointer());
  if (!follow && reconstruction)
  {
    reconstruction->SetCamera(nullptr);
    this->FollowedReconstruction = nullptr;
  }
  this->MarkModified();
}

double vtkBrumeRadianceRepresentation::GetLastImageSampleDistance()
{
  return this->Actors->GetLastImageSampleDistance();
}

int vtkBrumeRadianceRepresentation::GetNumberOfProps()
{
  return this->Shown ? this->Actors->GetProps()->GetNumberOfItems() : 0;
}

void vtkBrumeRadianceRepresentation::GetShownEyePosition(double eye[3])
{
  if (!EyeOf(this->Shown, eye))
  {
    eye[0] = eye[1] = eye[2] = vtkMath::Nan();
  }
}

bool vtkBrumeRadianceRepresentation::AddToView(vtkView* view)
{
  auto* renderView = vtkPVRenderView::SafeDownCast(view);
  if (!renderView)
  {
    return false;
  }
  if (this->Renderer != renderView->GetRenderer())
  {
    this->Hide();
    this->Renderer = renderView->GetRenderer();
  }
  return this->Superclass::AddToView(view);
}

bool vtkBrumeRadianceRepresentation::RemoveFromView(vtkView* view)
{
  auto* renderView = vtkPVRenderView::SafeDownCast(view);
  if (!renderView)
  {
    return false;
  }
  this->Hide();
  this->Renderer = nullptr;
  // The reconstruction no longer follows this view's camera.
  auto* reconstruction =
    vtkBrumeRadianceReconstruction::SafeDownCast(this->FollowedReconstruction.GetPointer());
  if (reconstruction && reconstruction->GetCamera() == renderView->GetActiveCamera())
  {
    reconstruction->SetCamera(nullptr);
  }
  this->FollowedReconstruction = nullptr;
  return this->Superclass::RemoveFromView(view);
}

void vtkBrumeRadianceRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ShowSurfaces: " << this->ShowSurfaces << "\n";
  os << indent << "ShowMedia: " << this->ShowMedia << "\n";
  os << indent << "SliceSpacing: " << this->SliceSpacing << "\n";
  os << indent << "BackfaceCulling: " << this->BackfaceCulling << "\n";
  os << indent << "TextureInterpolation: " << this->TextureInterpolation << "\n";
  os << indent << "Exposure: " << this->Exposure << "\n";
  os << indent << "FollowCamera: " << this->FollowCamera << "\n";
}
