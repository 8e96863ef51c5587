// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumePipeline.h"

#include "vtkAlgorithmOutput.h"
#include "vtkAutoInit.h"
#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeFloatImageCapture.h"
#include "vtkBrumeLightTracer.h"
#include "vtkBrumeOpenGLSliceVolumeMapper.h"
#include "vtkBrumeProcesses.h"
#include "vtkBrumeRadianceReconstruction.h"
#include "vtkBrumeSMP.h"
#include "vtkBrumeSceneActors.h"
#include "vtkBrumeSceneCamera.h"
#include "vtkCamera.h"
#include "vtkCommunicator.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkRendererCollection.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTrivialProducer.h"

#include <algorithm>
#include <chrono>
#include <cmath>

// The OpenGL slice volume mapper and float capture, whoever links us.
VTK_MODULE_INIT(vtkBrumeRenderingOpenGL2);

vtkStandardNewMacro(vtkBrumePipeline);

namespace
{
double Seconds(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Component `component` of the scene's field array `name`, when present.
bool SceneValue(vtkDataObject* scene, const char* name, int component, double& out)
{
  vtkDataArray* a = scene->GetFieldData()->GetArray(name);
  if (a && a->GetNumberOfTuples() > 0 && component < a->GetNumberOfComponents())
  {
    out = a->GetComponent(0, component);
    return true;
  }
  return false;
}
}

vtkBrumePipeline::vtkBrumePipeline()
  : Camera(vtkSmartPointer<vtkCamera>::New())
{
  vtkBrumeSceneCamera::SetToDefault(this->Camera);
  this->CameraDefaultTime = this->Camera->GetMTime();
  this->SetController(vtkBrumeProcesses::GetGlobalController());
}

vtkMultiProcessController* vtkBrumePipeline::GetController()
{
  return this->Controller;
}

void vtkBrumePipeline::SetController(vtkMultiProcessController* controller)
{
  this->Controller = controller;
  this->Reconstruction->SetController(controller);
}

vtkBrumePipeline::~vtkBrumePipeline() = default;

void vtkBrumePipeline::SetInputConnection(vtkAlgorithmOutput* scene)
{
  if (this->SceneOutput != scene)
  {
    this->SceneOutput = scene;
    this->ConnectPhases();
    this->Modified();
  }
}

void vtkBrumePipeline::SetInputData(vtkDataObject* scene)
{
  this->SceneData->SetOutput(scene);
  this->SetInputConnection(scene ? this->SceneData->GetOutputPort() : nullptr);
}

vtkAlgorithmOutput* vtkBrumePipeline::GetInputConnection()
{
  return this->SceneOutput;
}

void vtkBrumePipeline::ConnectPhases()
{
  this->Tracer->SetInputConnection(this->SceneOutput);
  this->Reconstruction->SetInputConnection(0, this->SceneOutput);
  this->Reconstruction->SetInputConnection(1, this->Tracer->GetOutputPort());
  this->Reconstruction->SetCamera(this->Camera);
}

vtkBrumeLightTracer* vtkBrumePipeline::GetTracer()
{
  return this->Tracer;
}

vtkBrumeRadianceReconstruction* vtkBrumePipeline::GetReconstruction()
{
  return this->Reconstruction;
}

vtkBrumeSceneActors* vtkBrumePipeline::GetActors()
{
  return this->Actors;
}

vtkCamera* vtkBrumePipeline::GetCamera()
{
  return this->Camera;
}

void vtkBrumePipeline::SetCamera(vtkCamera* camera)
{
  if (!camera)
  {
    vtkErrorMacro("SetCamera needs a camera.");
    return;
  }
  this->CameraChosen = true;
  if (this->Camera == camera)
  {
    return;
  }
  this->Camera = camera;
  this->Reconstruction->SetCamera(camera);
  if (this->ActorsRenderer)
  {
    this->ActorsRenderer->SetActiveCamera(camera);
  }
  this->Modified();
}

bool vtkBrumePipeline::Fail(const char* phase)
{
  this->FailedPhase = phase;
  return false;
}

const char* vtkBrumePipeline::GetFailedPhase()
{
  return this->FailedPhase;
}

bool vtkBrumePipeline::UpdateScene()
{
  this->FailedPhase = "";
  if (!this->SceneOutput)
  {
    vtkErrorMacro("No scene: SetInputConnection or SetInputData first.");
    return this->Fail("the scene");
  }
  vtkAlgorithm* source = this->SceneOutput->GetProducer();
  if (!(this->TimeSet ? this->UpdateAt(source, this->SceneOutput->GetIndex(), 0, 1)
                      : source->GetExecutive()->Update() != 0))
  {
    return this->Fail("the scene");
  }
  return true;
}

void vtkBrumePipeline::SetTime(double time)
{
  if (!this->TimeSet || this->Time != time)
  {
    this->Time = time;
    this->TimeSet = true;
    this->Modified();
  }
}

bool vtkBrumePipeline::UpdateAt(vtkAlgorithm* algorithm, int port, int piece, int pieces)
{
  if (!this->TimeSet)
  {
    return algorithm->UpdatePiece(piece, pieces, 0) != 0;
  }
  vtkNew<vtkInformation> request;
  request->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), piece);
  request->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), pieces);
  request->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
  request->Set(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP(), this->Time);
  vtkNew<vtkInformationVector> requests;
  requests->SetNumberOfInformationObjects(algorithm->GetNumberOfOutputPorts());
  requests->SetInformationObject(port, request);
  return algorithm->Update(port, requests) != 0;
}

int vtkBrumePipeline::GetNumberOfTimeSteps()
{
  vtkInformation* info = this->SceneOutput
    ? this->SceneOutput->GetProducer()->GetOutputInformation(this->SceneOutput->GetIndex())
    : nullptr;
  return info && info->Has(vtkStreamingDemandDrivenPipeline::TIME_STEPS())
    ? info->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS())
    : 0;
}

double vtkBrumePipeline::GetTimeStep(int step)
{
  if (step < 0 || step >= this->GetNumberOfTimeSteps())
  {
    vtkErrorMacro(
      "No time step " << step << ": the scene has " << this->GetNumberOfTimeSteps() << ".");
    return 0.0;
  }
  return this->SceneOutput->GetProducer()
    ->GetOutputInformation(this->SceneOutput->GetIndex())
    ->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS())[step];
}

vtkDataObject* vtkBrumePipeline::GetScene()
{
  return this->SceneOutput
    ? this->SceneOutput->GetProducer()->GetOutputDataObject(this->SceneOutput->GetIndex())
    : nullptr;
}

bool vtkBrumePipeline::TakeSceneCamera()
{
  vtkDataObject* scene = this->GetScene();
  if (!scene)
  {
    return false;
  }
  // The default view overridden by each camera array the scene has.
  double position[3], focal[3], up[3], angle;
  vtkBrumeSceneCamera::GetSceneCamera(scene, position, focal, up, angle);
  this->Camera->SetPosition(position);
  this->Camera->SetFocalPoint(focal);
  this->Camera->SetViewUp(up);
  this->Camera->SetViewAngle(angle);
  return true;
}

bool vtkBrumePipeline::ApplySceneSettings()
{
  if (!this->UpdateScene())
  {
    return false;
  }
  vtkDataObject* scene = this->GetScene();
  double v = 0.0;
  if (SceneValue(scene, vtkBrumeNames::RenderParticles, 0, v))
  {
    this->Tracer->SetNumberOfParticles(static_cast<vtkTypeInt64>(v));
  }
  if (SceneValue(scene, vtkBrumeNames::RenderSeed, 0, v))
  {
    this->Tracer->SetSeed(static_cast<vtkIdType>(v));
  }
  if (SceneValue(scene, vtkBrumeNames::RenderThreshold, 0, v))
  {
    this->Reconstruction->SetRadiosityThreshold(v);
  }
  double height = 0.0;
  if (SceneValue(scene, vtkBrumeNames::RenderSize, 0, v) &&
    SceneValue(scene, vtkBrumeNames::RenderSize, 1, height))
  {
    this->SetSize(static_cast<int>(v), static_cast<int>(height));
  }
  if (SceneValue(scene, vtkBrumeNames::RenderExposure, 0, v))
  {
    this->SetExposure(v);
  }
  this->TakeSceneCamera();
  this->CameraChosen = true;
  return true;
}

vtkTypeInt64 vtkBrumePipeline::GetPlannedBatchSize()
{
  const vtkTypeInt64 particles = this->Tracer->GetNumberOfParticles();
  if (this->BatchSize > 0)
  {
    return std::min(this->BatchSize, particles);
  }
  const double limit = static_cast<double>(this->Tracer->GetMemoryLimit());
  if (vtkBrumeProcesses::IsDistributed(this->Controller) ||
    vtkBrumeLightTracer::ExpectedHitBytes(particles) <= limit)
  {
    return particles;
  }
  const auto fit = static_cast<vtkTypeInt64>(limit / vtkBrumeLightTracer::ExpectedHitBytes(1));
  return std::max<vtkTypeInt64>(1, std::min(GetLargestAutomaticBatch(), fit));
}

vtkTypeInt64 vtkBrumePipeline::GetLargestAutomaticBatch()
{
  return 10000000;
}

bool vtkBrumePipeline::IsBatchedForMemory()
{
  return this->BatchSize == 0 && this->GetPlannedBatchSize() < this->Tracer->GetNumberOfParticles();
}

bool vtkBrumePipeline::Update()
{
  this->TracingSeconds = this->ReconstructionSeconds = this->ReductionSeconds = 0.0;
  this->NumberOfHits = this->NumberOfRays = this->ReductionBytes = 0;
  vtkMultiProcessController* controller = this->Controller;
  const int rank = vtkBrumeProcesses::GetRank(controller);
  const int processes = vtkBrumeProcesses::GetSize(controller);
  if (!vtkBrumeProcesses::AllSucceeded(controller, this->UpdateScene(), "loading the scene"))
  {
    return this->Fail("the scene");
  }
  if (this->BatchSize > 0 && processes > 1)
  {
    vtkErrorMacro("Batches run in one process only (distributed, every process traces its "
                  "share at once).");
    return this->Fail("particle tracing");
  }
  // The scene's camera, unless one was set, or this one moved, before.
  if (!this->CameraChosen && this->Camera->GetMTime() == this->CameraDefaultTime)
  {
    this->TakeSceneCamera();
  }
  this->CameraChosen = true;
  this->ConnectPhases();
  const vtkTypeInt64 particles = this->Tracer->GetNumberOfParticles();
  const vtkTypeInt64 batch = std::max<vtkTypeInt64>(1, this->GetPlannedBatchSize());
  this->Reconstruction->SetAccumulateParticles(this->Progressive || batch < particles);
  // Phases 1 and 2, at once or batch by batch (each batch's hits binned,
  // then released when the next is traced). Once at least: the tracer says
  // what is wrong with a count below one.
  for (vtkTypeInt64 first = 0; first == 0 || first < particles; first += batch)
  {
    this->Tracer->SetFirstParticle(first);
    this->Tracer->SetEndParticle(std::min(first + batch, particles));
    auto start = std::chrono::steady_clock::now();
    const bool traced = this->UpdateAt(this->Tracer, 0, rank, processes);
    if (!vtkBrumeProcesses::AllSucceeded(controller, traced, "particle tracing"))
    {
      return this->Fail("particle tracing");
    }
    // The slowest process's tracing time.
    this->TracingSeconds += vtkBrumeProcesses::Max(controller, Seconds(start));
    this->NumberOfHits += this->Tracer->GetOutput()->GetNumberOfPoints();
    this->NumberOfRays += this->Tracer->GetLastRayCount();
    start = std::chrono::steady_clock::now();
    const bool reconstructed = this->UpdateAt(this->Reconstruction, 0, rank, processes);
    if (!vtkBrumeProcesses::AllSucceeded(controller, reconstructed, "reconstruction"))
    {
      return this->Fail("reconstruction");
    }
    this->ReconstructionSeconds += Seconds(start);
  }
  this->ReductionBytes =
    vtkBrumeProcesses::Sum(controller, this->Reconstruction->GetLastReductionBytes());
  this->ReductionSeconds =
    vtkBrumeProcesses::Max(controller, this->Reconstruction->GetLastReductionSeconds());
  return true;
}

bool vtkBrumePipeline::AddParticles(vtkTypeInt64 count)
{
  this->FailedPhase = "";
  if (!this->Progressive)
  {
    vtkErrorMacro("AddParticles needs Progressive on (before the first Update).");
    return this->Fail("particle tracing");
  }
  const vtkTypeInt64 first = this->Tracer->GetFirstParticle();
  const vtkTypeInt64 end = this->Tracer->GetEndParticle();
  const vtkTypeInt64 total = this->Tracer->GetNumberOfParticles();
  if (vtkBrumeProcesses::IsDistributed(this->Controller))
  {
    vtkErrorMacro("AddParticles runs in one process only.");
    return this->Fail("particle tracing");
  }
  if (count < 1 || count > VTK_TYPE_INT64_MAX - total)
  {
    vtkErrorMacro("Cannot add " << count << " particles to " << total << ".");
    return this->Fail("particle tracing");
  }
  this->Tracer->SetFirstParticle(total);
  this->Tracer->SetEndParticle(0);
  this->Tracer->SetNumberOfParticles(total + count);
  const auto start = std::chrono::steady_clock::now();
  if (this->TimeSet ? this->UpdateAt(this->Tracer, 0, 0, 1)
                    : this->Tracer->GetExecutive()->Update() != 0)
  {
    this->TracingSeconds = Seconds(start);
    if (this->UpdateView())
    {
      return true;
    }
  }
  else
  {
    this->Fail("particle tracing");
  }
  // Back to the step the textures hold: the tracer runs it again and the
  // reconstruction recognizes it as nothing new.
  this->Tracer->SetFirstParticle(first);
  this->Tracer->SetEndParticle(end);
  this->Tracer->SetNumberOfParticles(total);
  return false;
}

bool vtkBrumePipeline::UpdateView()
{
  this->FailedPhase = "";
  const auto start = std::chrono::steady_clock::now();
  // The request Update() made: another (the whole for one process) would
  // trace every particle again on each process, and the reconstruction
  // would sum those traces over the processes. Collective when distributed.
  const int rank = vtkBrumeProcesses::GetRank(this->Controller);
  const int processes = vtkBrumeProcesses::GetSize(this->Controller);
  if (!this->UpdateAt(this->Reconstruction, 0, rank, processes))
  {
    return this->Fail("reconstruction");
  }
  this->ReconstructionSeconds = Seconds(start);
  return !this->ActorsRenderer || this->ShowTextures(this->ActorsRenderer);
}

bool vtkBrumePipeline::ShowTextures(vtkRenderer* renderer)
{
  vtkPartitionedDataSetCollection* textures = this->Reconstruction->GetOutput();
  if (this->ActorsRenderer == renderer && this->Actors->CanUpdateInputs(textures))
  {
    // The props of the same objects take the new textures: only what
    // changed is uploaded, and a mapper keeps on the GPU what did not.
    return this->Actors->UpdateInputs(textures) || this->Fail("rendering");
  }
  // Other objects (a first call, another renderer, a scene with objects
  // added or removed): the props made again there.
  if (this->ActorsRenderer)
  {
    this->Actors->RemoveFromRenderer(this->ActorsRenderer);
  }
  this->ActorsRenderer = nullptr;
  this->Actors->SetInputData(textures);
  if (!this->Actors->AddToRenderer(renderer))
  {
    return this->Fail("rendering");
  }
  this->ActorsRenderer = renderer;
  return true;
}

vtkPartitionedDataSetCollection* vtkBrumePipeline::GetTextures()
{
  return this->Reconstruction->GetOutput();
}

bool vtkBrumePipeline::AddToRenderer(vtkRenderer* renderer)
{
  if (!renderer)
  {
    vtkErrorMacro("AddToRenderer needs a renderer.");
    return this->Fail("rendering");
  }
  if (!this->ShowTextures(renderer))
  {
    return false;
  }
  renderer->SetActiveCamera(this->Camera);
  renderer->ResetCameraClippingRange();
  return true;
}

void vtkBrumePipeline::MakeImageWindow()
{
  if (this->ImageWindow)
  {
    return;
  }
  auto renderer = vtkSmartPointer<vtkRenderer>::New();
  renderer->SetBackground(0, 0, 0);
  this->ImageWindow = vtkSmartPointer<vtkRenderWindow>::New();
  this->ImageWindow->SetOffScreenRendering(1);
  this->ImageWindow->SetMultiSamples(0);
  this->ImageWindow->AddRenderer(renderer);
  this->ImageCapture = vtkSmartPointer<vtkBrumeFloatImageCapture>::New();
  this->ImageCapture->Attach(renderer);
}

vtkRenderWindow* vtkBrumePipeline::GetImageWindow()
{
  this->MakeImageWindow();
  this->ImageWindow->SetSize(this->Size[0], this->Size[1]);
  if (auto* gl = vtkOpenGLRenderWindow::SafeDownCast(this->ImageWindow))
  {
    gl->Initialize();
  }
  return this->ImageWindow;
}

vtkTypeInt64 vtkBrumePipeline::LimitToGPUMemory(vtkRenderWindow* window)
{
  // Asked once per window: what later textures of the same run take is
  // not to coarsen the next trace's volume.
  if (window && window != this->AskedWindow)
  {
    this->AskedWindow = window;
    this->AskedFree = vtkBrumeOpenGLSliceVolumeMapper::GetFreeGPUMemory(window);
  }
  vtkTypeInt64 limit = window && this->AskedFree > 0
    ? static_cast<vtkTypeInt64>(0.75 * static_cast<double>(this->AskedFree))
    : VTK_TYPE_INT64_MAX;
  if (vtkBrumeProcesses::IsDistributed(this->Controller))
  {
    vtkTypeInt64 least = limit;
    this->Controller->AllReduce(&limit, &least, 1, vtkCommunicator::MIN_OP);
    limit = least;
  }
  limit = limit == VTK_TYPE_INT64_MAX ? 0 : limit;
  this->Reconstruction->SetGPUMemoryLimit(limit);
  return limit;
}

vtkSmartPointer<vtkImageData> vtkBrumePipeline::RenderImage(int supersample)
{
  this->FailedPhase = "";
  if (this->Size[0] < 1 || this->Size[1] < 1 || this->Size[0] > 16384 || this->Size[1] > 16384)
  {
    vtkErrorMacro("Size must be in [1, 16384] on each axis, not " << this->Size[0] << " x "
                                                                  << this->Size[1] << ".");
    this->Fail("rendering");
    return nullptr;
  }
  if (supersample < 1 || supersample > 16)
  {
    vtkErrorMacro("RenderImage's supersampling must be in [1, 16], not " << supersample << ".");
    this->Fail("rendering");
    return nullptr;
  }
  // The image's memory, checked before any is allocated: the window's
  // framebuffers, the float texture the capture draws into, its readback
  // and the 8-bit image, about 64 bytes a pixel (16384^2 measured 59 under
  // Mesa); beyond that the OpenGL driver fails and VTK's readback crashes.
  const double pixels = static_cast<double>(this->Size[0]) * this->Size[1];
  const double needed = 64.0 * pixels;
  const double usable = vtkBrumeSMP::UsableMemory();
  if (usable > 0.0 && needed > usable)
  {
    vtkErrorMacro("An image of " << this->Size[0] << " x " << this->Size[1] << " needs about "
                                 << std::lround(needed / 1e9)
                                 << " GB here (framebuffers and the float image): more than half "
                                    "of this machine's memory ("
                                 << std::lround(usable / 1e9)
                                 << " GB); choose a smaller Size (brume: --size).");
    this->Fail("rendering");
    return nullptr;
  }
  this->MakeImageWindow();
  vtkRenderer* renderer = this->ImageWindow->GetRenderers()->GetFirstRenderer();
  this->ImageWindow->SetSize(this->Size[0], this->Size[1]);
  // The textures toward the camera as it is now (it may have moved since
  // Update(): view-dependent textures follow it), then the props there.
  if (!this->UpdateView() || (this->ActorsRenderer != renderer && !this->AddToRenderer(renderer)))
  {
    return nullptr;
  }
  renderer->ResetCameraClippingRange();
  auto start = std::chrono::steady_clock::now();
  this->ImageWindow->Render();
  this->FirstFrameSeconds = Seconds(start);
  // The image is the first frame's (one frame of a 512^3 volume under
  // llvmpipe takes over a second); the steady per-view cost (textures
  // already resident) is a second frame's where it is measured, or the
  // mean of the k^2 frames whose mean is each pixel's area.
  start = std::chrono::steady_clock::now();
  vtkSmartPointer<vtkImageData> radiance;
  if (supersample == 1)
  {
    this->FrameSeconds = 0.0;
    if (this->MeasureFrame)
    {
      this->ImageWindow->Render();
      this->FrameSeconds = Seconds(start);
    }
    radiance = this->ImageCapture->Capture();
  }
  else
  {
    radiance = this->ImageCapture->CaptureSupersampled(supersample);
    this->FrameSeconds = Seconds(start) / (supersample * supersample);
  }
  if (!radiance)
  {
    this->Fail("rendering");
  }
  return radiance;
}

vtkTypeInt64 vtkBrumePipeline::ReleaseBuildState()
{
  return this->Reconstruction->ReleaseBuildState();
}

vtkSmartPointer<vtkImageData> vtkBrumePipeline::ToneMap(vtkImageData* radiance)
{
  return vtkBrumeFloatImageCapture::ToneMap(radiance, this->Exposure);
}

void vtkBrumePipeline::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Size: " << this->Size[0] << " x " << this->Size[1] << "\n";
  os << indent << "Exposure: " << this->Exposure << "\n";
  os << indent << "BatchSize: " << this->BatchSize << "\n";
  os << indent << "Progressive: " << this->Progressive << "\n";
  os << indent << "MeasureFrame: " << this->MeasureFrame << "\n";
  os << indent << "Camera: " << this->Camera << "\n";
  os << indent << "Tracer:\n";
  this->Tracer->PrintSelf(os, indent.GetNextIndent());
  os << indent << "Reconstruction:\n";
  this->Reconstruction->PrintSelf(os, indent.GetNextIndent());
  os << indent << "TracingSeconds: " << this->TracingSeconds << "\n";
  os << indent << "ReconstructionSeconds: " << this->ReconstructionSeconds << "\n";
  os << indent << "NumberOfHits: " << this->NumberOfHits << "\n";
  os << indent << "NumberOfRays: " << this->NumberOfRays << "\n";
}
