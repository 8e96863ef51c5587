// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeRadianceReconstruction.h"

#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeHitConversion.h"
#include "vtkBrumeProcesses.h"
#include "vtkBrumeRadianceTextures.h"
#include "vtkBrumeSMP.h"
#include "vtkBrumeSceneConversion.h"
#include "vtkCamera.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPolyData.h"

#include "brume/Camera.h"
#include "brume/FloatBuffer.h"
#include "brume/SphericalHarmonics.h"

#include <algorithm>
#include <cmath>
#include <new>

vtkStandardNewMacro(vtkBrumeRadianceReconstruction);
vtkCxxSetObjectMacro(vtkBrumeRadianceReconstruction, Camera, vtkCamera);
vtkCxxSetObjectMacro(vtkBrumeRadianceReconstruction, Controller, vtkMultiProcessController);

vtkBrumeRadianceReconstruction::vtkBrumeRadianceReconstruction()
  : WorkDone(new vtkBrumeReconstructionWork)
{
  this->SetNumberOfInputPorts(2);
  this->SetController(vtkMultiProcessController::GetGlobalController());
  const brume::PinholeCamera defaultView;
  for (int a = 0; a < 3; ++a)
  {
    this->EyePosition[a] = defaultView.Position[a];
  }
}

vtkBrumeRadianceReconstruction::~vtkBrumeRadianceReconstruction()
{
  this->SetCamera(nullptr);
  this->SetController(nullptr);
}

vtkMTimeType vtkBrumeRadianceReconstruction::GetMTime()
{
  const vtkMTimeType t = this->Superclass::GetMTime();
  return this->Camera ? std::max(t, this->Camera->GetMTime()) : t;
}

int vtkBrumeRadianceReconstruction::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), port == 0 ? "vtkDataObject" : "vtkPolyData");
  return 1;
}

vtkTypeInt64 vtkBrumeRadianceReconstruction::ReleaseBuildState()
{
  // The output's arrays hold what they share by their own references.
  this->Textures.reset();
  return static_cast<vtkTypeInt64>(brume::FloatBuffer::ReleaseKept());
}

vtkTypeBool vtkBrumeRadianceReconstruction::ProcessRequest(
  vtkInformation* request, vtkInformationVector** inputs, vtkInformationVector* outputs)
{
  try
  {
    return this->Superclass::ProcessRequest(request, inputs, outputs);
  }
  catch (const std::bad_alloc&)
  {
    if (this->Controller && this->Controller->GetNumberOfProcesses() > 1)
    {
      throw; // mpirun ends the run, where a failed request would leave the others waiting
    }
    vtkErrorMacro("ran out of memory reconstructing the textures: fewer particles, a larger "
                  "RadiosityThreshold or smaller resolutions");
    return 0;
  }
}

int vtkBrumeRadianceReconstruction::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // Distributed runs: every process must reach the same collective calls,
  // so a process that fails still takes part in the next agreement, and the
  // others stop there (no process is left waiting).
  vtkBrumeReconstructionRequest request;
  const bool valid = this->Validate(inputVector, request);
  if (!this->Agree(valid) || !valid)
  {
    return 0;
  }
  this->LastReductionBytes = 0;
  this->LastReductionSeconds = 0.0;
  const bool planned = this->Plan(request);
  auto* output = vtkPartitionedDataSetCollection::GetData(outputVector, 0);
  if (planned && !this->Textures->IsComplete())
  {
    // A batch of a run binned: the textures come with its last batch. The
    // output says how far the run is.
    this->CountWork();
    vtkNew<vtkDoubleArray> binned;
    binned->SetName(vtkBrumeNames::ParticlesBinned);
    binned->SetNumberOfComponents(2);
    binned->InsertNextTuple2(this->Textures->GetEndParticle(), this->Textures->GetParticles());
    output->GetFieldData()->AddArray(binned);
    this->UpdateProgress(1.0);
    return 1;
  }
  if (!planned ||
    !this->Textures->SetDirectional(
      this->DirectionalRadiance, this->DirectionalOrder, *this->WorkDone))
  {
    if (planned)
    {
      this->Textures.reset();
    }
    this->CountWork();
    return 0;
  }
  if (!this->Textures->FollowView(request, this->IncrementalUpdate, *this->WorkDone))
  {
    this->CountWork();
    return 0;
  }
  this->CountWork();
  this->Textures->TakeReduction(this->LastReductionBytes, this->LastReductionSeconds);
  // The textures are the same on every process, and every process gives
  // them: renderers that composite (IceT under mpirun) draw on each.
  {
    this->Textures->Emit(output);
    // Where the textures radiate toward, and whether any depends on it:
    // what a renderer that follows its camera compares with.
    vtkNew<vtkDoubleArray> eye;
    eye->SetName(vtkBrumeNames::EyePosition);
    eye->SetNumberOfComponents(3);
    eye->InsertNextTuple3(request.Eye.x, request.Eye.y, request.Eye.z);
    output->GetFieldData()->AddArray(eye);
    vtkNew<vtkIntArray> viewDependent;
    viewDependent->SetName(vtkBrumeNames::ViewDependentObjects);
    viewDependent->InsertNextValue(this->Textures->NumberOfViewDependentOutputs());
    output->GetFieldData()->AddArray(viewDependent);
  }
  this->UpdateProgress(1.0);
  return 1;
}

bool vtkBrumeRadianceReconstruction::Agree(bool ok)
{
  const bool all = vtkBrumeProcesses::Agree(this->Controller, ok);
  if (ok && !all)
  {
    vtkErrorMacro("Another process failed (see its errors): stopping.");
  }
  return all;
}

bool vtkBrumeRadianceReconstruction::ValidateSettings()
{
  if (!(this->RadiosityThreshold > 0.0) || !std::isfinite(this->RadiosityThreshold))
  {
    vtkErrorMacro(
      "RadiosityThreshold must be positive and finite, not " << this->RadiosityThreshold << ".");
    return false;
  }
  const int maxSurface = vtkBrumeRadianceTextures::MaxSurfaceResolution;
  const int maxMedium = vtkBrumeRadianceTextures::MaxMediumResolution;
  if (this->SurfaceResolution < 0 || this->SurfaceResolution > maxSurface ||
    this->MediumResolution < 0 || this->MediumResolution > maxMedium)
  {
    vtkErrorMacro("SurfaceResolution must be in [0, "
      << maxSurface << "] and MediumResolution in [0, " << maxMedium << "].");
    return false;
  }
  if (this->MirrorResolution < 1 || this->MirrorResolution > maxSurface)
  {
    vtkErrorMacro("MirrorResolution must be in [1, " << maxSurface << "], not "
                                                     << this->MirrorResolution << ".");
    return false;
  }
  if (this->HistogramRefinement < 1 || this->HistogramRefinement > 16)
  {
    vtkErrorMacro(
      "HistogramRefinement must be in [1, 16], not " << this->HistogramRefinement << ".");
    return false;
  }
  return true;
}

bool vtkBrumeRadianceReconstruction::Validate(
  vtkInformationVector** inputVector, vtkBrumeReconstructionRequest& request)
{
  request.SceneInput = vtkDataObject::GetData(inputVector[0], 0);
  request.Scene = vtkBrumeSceneConversion::AsCollection(request.SceneInput);
  if (!request.Scene)
  {
    vtkErrorMacro("The scene must be a vtkPartitionedDataSetCollection, a vtkMultiBlockDataSet, "
                  "a vtkPolyData or a vtkImageData.");
    return false;
  }
  if (!this->ValidateSettings())
  {
    return false;
  }
  double eye[3] = { this->EyePosition[0], this->EyePosition[1], this->EyePosition[2] };
  if (this->Camera)
  {
    this->Camera->GetPosition(eye);
  }
  request.Eye =
    brume::Vec3(static_cast<float>(eye[0]), static_cast<float>(eye[1]), static_cast<float>(eye[2]));
  if (!brume::IsFinite(request.Eye))
  {
    vtkErrorMacro("The viewpoint must be finite.");
    return false;
  }
  // The hits, read in place.
  request.HitData = vtkPolyData::GetData(inputVector[1], 0);
  const std::string error = vtkBrumeHitConversion::ReadHits(
    request.HitData, request.Hits, request.Run, request.PositionCopy);
  if (!error.empty())
  {
    vtkErrorMacro(<< error << ".");
    return false;
  }
  if (this->DirectionalOrder < 1 || this->DirectionalOrder > brume::MaxShOrder)
  {
    vtkErrorMacro("DirectionalOrder must be in [1, " << brume::MaxShOrder << "], not "
                                                     << this->DirectionalOrder << ".");
    return false;
  }
  const auto& run = request.Run;
  if (run.FirstParticle > 0.0 && !this->AccumulateParticles)
  {
    vtkErrorMacro("These hits are the particles ["
      << run.FirstParticle << ", " << run.EndParticle << ") of a run of " << run.Particles
      << ": turn AccumulateParticles on to add them to the earlier ones.");
    return false;
  }
  if (run.FirstParticle > 0.0 && vtkBrumeProcesses::IsDistributed(this->Controller))
  {
    vtkErrorMacro("Adding particles (AccumulateParticles) is not supported across processes.");
    return false;
  }
  const double* power = run.TotalPower;
  const double particleFlux = (power[0] + power[1] + power[2]) / 3.0 / run.Particles;
  request.ParticleFlux = particleFlux;
  request.ThresholdFlux = this->RadiosityThreshold * particleFlux;
  return true;
}

vtkTypeInt64 vtkBrumeRadianceReconstruction::GetEffectiveNativeMemoryLimit() const
{
  if (this->NativeMemoryLimit > 0)
  {
    return this->NativeMemoryLimit;
  }
  const auto machine = static_cast<vtkTypeInt64>(0.25 * vtkBrumeSMP::UsableMemory());
  return this->GPUMemoryLimit > 0 ? std::min(machine, this->GPUMemoryLimit) : machine;
}

bool vtkBrumeRadianceReconstruction::IsNativeMemoryLimitedByGPU() const
{
  return this->NativeMemoryLimit <= 0 && this->GPUMemoryLimit > 0 &&
    this->GetEffectiveNativeMemoryLimit() == this->GPUMemoryLimit;
}

bool vtkBrumeRadianceReconstruction::Plan(const vtkBrumeReconstructionRequest& request)
{
  // Rebuild everything when the inputs or the settings changed; add the
  // hits when they continue the run the textures hold; otherwise only the
  // view-dependent textures follow the viewpoint.
  const vtkBrumeReconstructionSettings settings{ this->RadiosityThreshold, this->SurfaceResolution,
    this->MediumResolution, this->HistogramRefinement,
    this->DirectLighting ? this->DirectLightResolution : 0, this->MirrorResolution,
    this->CentroidMatching, this->SparseMedia, this->FixedView,
    this->FixedView && this->DirectionalRadiance, static_cast<double>(this->PlannedParticles),
    this->GetEffectiveNativeMemoryLimit(), this->IsNativeMemoryLimitedByGPU() };
  vtkBrumeRadianceTextures* textures = this->Textures.get();
  const auto& run = request.Run;
  const bool sameSettings = textures && textures->SameSceneAndSettings(request, settings);
  // A tracer that ran again with the settings of the step already added
  // (same seed, particles [first, total)) brings nothing new.
  const bool sameStep = textures && textures->HoldsStep(run);
  const bool newHits = !sameStep && (!textures || !textures->HoldsHits(request.HitData));
  if (run.FirstParticle > 0.0 && !newHits && !sameSettings)
  {
    // The hits hold only the last step's particles: the textures cannot be
    // rebuilt from them.
    vtkErrorMacro("The settings or the scene changed, but the hits are only the particles ["
      << run.FirstParticle << ", " << run.EndParticle << ") of a run of " << run.Particles
      << ": trace from FirstParticle 0 again to rebuild the textures.");
    this->Textures.reset();
    return false;
  }
  if (run.FirstParticle > 0.0 && newHits)
  {
    if (!sameSettings || !textures->Continues(run))
    {
      vtkErrorMacro("These hits are the particles ["
        << run.FirstParticle << ", " << run.EndParticle << ") of a run of " << run.Particles
        << " (seed " << run.Seed << ") but the textures hold the particles [0, "
        << (textures ? textures->GetEndParticle() : 0.0) << ") of a run of "
        << (textures ? textures->GetParticles() : 0.0) << " (seed "
        << (textures ? textures->GetSeed() : 0.0)
        << ") of the same scene and settings: trace from FirstParticle 0 again.");
      return false; // the textures stay as they are
    }
    if (!textures->Add(request, *this->WorkDone))
    {
      this->Textures.reset();
      return false;
    }
    return true;
  }
  if (sameSettings && !newHits)
  {
    return true;
  }
  // The kept hits' buffers of the textures replaced go to the new ones (a
  // rebuild after new hits writes where the last build's were); the rest of
  // the textures replaced is freed before the new ones are built.
  std::vector<brume::KeptHits> spare;
  // The replaced textures' ray caster, kept through the build: the new
  // textures' shadow rays find it where the surfaces are the same (a new
  // time step, a new trace of the same scene).
  std::shared_ptr<const brume::RayCaster> caster;
  // And its media's grids at their own resolution: an edit of a transfer
  // function keeps what it did not change.
  std::vector<brume::NativeMediumGrid> natives;
  // And the direct light's shadow rays, for a scene whose lights, surfaces
  // and extinction are the same (an edit of a colour).
  std::shared_ptr<vtkBrumeRadianceTextures::KeptDirect> direct;
  if (textures)
  {
    spare = textures->ReleaseKeptMemory();
    caster = textures->GetCaster();
    direct = textures->ReleaseDirect();
    natives = textures->ReleaseNativeGrids();
  }
  this->Textures.reset(new vtkBrumeRadianceTextures(this, this->Controller));
  this->Textures->OfferNativeGrids(std::move(natives));
  this->Textures->OfferDirect(std::move(direct));
  if (!this->Textures->Build(request, settings, *this->WorkDone, std::move(spare)))
  {
    this->Textures.reset();
    return false;
  }
  return true;
}

void vtkBrumeRadianceReconstruction::CountWork()
{
  this->NumberOfTextureBuilds += this->WorkDone->TextureBuilds;
  this->NumberOfViewUpdates += this->WorkDone->ViewUpdates;
  this->NumberOfParticleAdditions += this->WorkDone->ParticleAdditions;
  this->NumberOfDirectionalBuilds += this->WorkDone->DirectionalBuilds;
  this->NumberOfNativeBricksSampled += this->WorkDone->NativeBricksSampled;
  this->NumberOfNativeBricksReused += this->WorkDone->NativeBricksReused;
  this->NumberOfDirectLightsKept += this->WorkDone->DirectArrivalsKept;
  *this->WorkDone = vtkBrumeReconstructionWork();
}

void vtkBrumeRadianceReconstruction::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "EyePosition: (" << this->EyePosition[0] << ", " << this->EyePosition[1] << ", "
     << this->EyePosition[2] << ")\n";
  os << indent << "Camera: " << this->Camera << "\n";
  os << indent << "RadiosityThreshold: " << this->RadiosityThreshold << "\n";
  os << indent << "SurfaceResolution: " << this->SurfaceResolution << "\n";
  os << indent << "MirrorResolution: " << this->MirrorResolution << "\n";
  os << indent << "PlannedParticles: " << this->PlannedParticles << "\n";
  os << indent << "MediumResolution: " << this->MediumResolution << "\n";
  os << indent << "HistogramRefinement: " << this->HistogramRefinement << "\n";
  os << indent << "CentroidMatching: " << this->CentroidMatching << "\n";
  os << indent << "SparseMedia: " << this->SparseMedia << "\n";
  os << indent << "NativeMemoryLimit: " << this->NativeMemoryLimit << "\n";
  os << indent << "GPUMemoryLimit: " << this->GPUMemoryLimit << "\n";
  os << indent << "IncrementalUpdate: " << this->IncrementalUpdate << "\n";
  os << indent << "NumberOfTextureBuilds: " << this->NumberOfTextureBuilds << "\n";
  os << indent << "NumberOfViewUpdates: " << this->NumberOfViewUpdates << "\n";
  os << indent << "AccumulateParticles: " << this->AccumulateParticles << "\n";
  os << indent << "FixedView: " << this->FixedView << "\n";
  os << indent << "Controller: " << this->Controller << "\n";
  os << indent << "LastReductionBytes: " << this->LastReductionBytes << "\n";
  os << indent << "DirectionalRadiance: " << this->DirectionalRadiance << "\n";
  os << indent << "DirectionalOrder: " << this->DirectionalOrder << "\n";
  os << indent << "DirectLighting: " << this->DirectLighting << "\n";
  os << indent << "DirectLightResolution: " << this->DirectLightResolution << "\n";
  os << indent << "NumberOfParticleAdditions: " << this->NumberOfParticleAdditions << "\n";
  os << indent << "NumberOfDirectionalBuilds: " << this->NumberOfDirectionalBuilds << "\n";
  os << indent << "NumberOfNativeBricksSampled: " << this->NumberOfNativeBricksSampled << "\n";
  os << indent << "NumberOfNativeBricksReused: " << this->NumberOfNativeBricksReused << "\n";
  os << indent << "NumberOfDirectLightsKept: " << this->NumberOfDirectLightsKept << "\n";
}
