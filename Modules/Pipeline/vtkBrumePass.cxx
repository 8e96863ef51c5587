// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumePass.h"

#include "vtkBrumeArrayBytes.h"
#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeDisplayPass.h"
#include "vtkBrumeLightTracer.h"
#include "vtkBrumePipeline.h"
#include "vtkBrumeProcesses.h"
#include "vtkBrumeRadianceConversion.h"
#include "vtkBrumeRadianceReconstruction.h"
#include "vtkBrumeRendererScene.h"
#include "vtkBrumeSceneActors.h"
#include "vtkBrumeSliceVolumeMapper.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkProp.h"
#include "vtkPropCollection.h"
#include "vtkRenderState.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkVolume.h"
#include "vtkVolumeCollection.h"

#include <algorithm>
#include <array>
#include <string>
#include <utility>
#include <vector>

vtkStandardNewMacro(vtkBrumePass);

namespace
{
// The eye: what the view-dependent textures radiate toward.
std::array<double, 3> Eye(vtkCamera* camera)
{
  std::array<double, 3> eye{};
  camera->GetPosition(eye.data());
  return eye;
}

}

struct vtkBrumePass::vtkInternals
{
  vtkNew<vtkBrumeRendererScene> Scene;
  vtkNew<vtkBrumePipeline> Pipeline;
  vtkNew<vtkBrumeDisplayPass> Display;
  // Holds Brume's props out of the user's renderer (whose actors make the
  // scene); they are drawn through the render state.
  vtkSmartPointer<vtkRenderer> Holder;
  // Brume's volumes, which their slice mappers draw together (they are not
  // in the renderer, whose volumes the mappers would otherwise draw).
  vtkNew<vtkVolumeCollection> Volumes;
  // The scene last traced, its content's signature, the scene's and the
  // pass's MTimes then.
  vtkSmartPointer<vtkPartitionedDataSetCollection> Traced;
  vtkTypeUInt64 TracedSignature = 0;
  vtkMTimeType TracedScene = 0;
  vtkMTimeType TracedSettings = 0;
  bool Tried = false;               // traced (or tried to) at least once
  bool Empty = false;               // nothing to light: VTK draws the renderer
  std::array<double, 3> ShownEye{}; // the eye at the last frame
  bool Failed = false;
  bool PendingTrace = false;      // a preview was drawn; the next frame traces
  double ShownDistance = 0.0;     // the actors' image sample distance before a preview (0: none)
  double ShownSpacingScale = 1.0; // and their slice spacing's factor
};

vtkBrumePass::vtkBrumePass()
  : Internals(new vtkInternals)
{
  this->Internals->Scene->AllowEmptyOn();
}

vtkBrumePass::~vtkBrumePass()
{
  delete this->Internals;
}

vtkBrumePipeline* vtkBrumePass::GetPipeline()
{
  return this->Internals->Pipeline;
}

vtkBrumeRendererScene* vtkBrumePass::GetScene()
{
  return this->Internals->Scene;
}

bool vtkBrumePass::IsConverged()
{
  const vtkInternals& in = *this->Internals;
  return in.Tried && !in.Failed && !in.PendingTrace &&
    (in.Empty ||
      (in.Holder && in.Pipeline->GetTracer()->GetNumberOfParticles() >= this->NumberOfParticles));
}

bool vtkBrumePass::IsRefining()
{
  const vtkInternals& in = *this->Internals;
  return in.Tried && !in.Failed && !in.Empty && !this->IsConverged();
}

// Traces the scene anew: the whole budget, or its first progressive step
// (the budget divided by 4, rounding up, until it is at most
// FirstStepParticles),
// at the resolutions the budget calls for.
bool vtkBrumePass::Trace(bool built)
{
  vtkInternals& in = *this->Internals;
  // The pipeline reads a copy of the scene, given anew only here: building
  // the scene again (to compare it) traces nothing.
  // Camera lights where the camera stands now: the scene was maybe built
  // at an earlier camera (ParaView touches mappers at its first renders,
  // and a settings change traces the last scene built).
  bool behind = built && in.Scene->AreCameraLightsBehind();
  if (this->Gathers())
  {
    // Collective: the processes build again together (their cameras agree,
    // their MTimes need not).
    behind = !vtkBrumeProcesses::Agree(in.Pipeline->GetController(), !behind);
  }
  if (behind)
  {
    in.Scene->Modified();
    built = in.Scene->GetExecutive()->Update() != 0;
    if (this->Gathers())
    {
      built = vtkBrumeProcesses::Agree(in.Pipeline->GetController(), built);
    }
  }
  if (!built)
  {
    ++this->NumberOfTraces;
    vtkErrorMacro("The renderer's scene could not be made (see the error above).");
    in.Failed = true;
    return false;
  }
  in.Traced = vtkSmartPointer<vtkPartitionedDataSetCollection>::New();
  in.Traced->ShallowCopy(in.Scene->GetOutput());
  in.TracedSignature = in.Scene->GetContentSignature();
  in.Empty = in.Traced->GetNumberOfPartitionedDataSets() == 0;
  if (in.Empty)
  {
    // Nothing to light (an empty view): VTK draws the renderer's props.
    in.Failed = false;
    in.Holder = nullptr;
    return false;
  }
  ++this->NumberOfTraces;
  in.Pipeline->SetInputData(in.Traced);
  const bool progressive = this->Progressive && !this->Gathers();
  vtkTypeInt64 first = this->NumberOfParticles;
  while (progressive && first > this->FirstStepParticles)
  {
    first = first / 4 + (first % 4 != 0 ? 1 : 0);
  }
  in.Pipeline->SetProgressive(progressive);
  in.Pipeline->GetTracer()->SetNumberOfParticles(first);
  in.Pipeline->GetReconstruction()->SetPlannedParticles(progressive ? this->NumberOfParticles : 0);
  // A volume this GPU cannot hold at its own resolution is coarsened to
  // fit (collective where the pipeline's processes trace together).
  vtkRenderer* renderer = in.Scene->GetRenderer();
  in.Pipeline->LimitToGPUMemory(renderer ? renderer->GetRenderWindow() : nullptr);
  if (!in.Pipeline->Update())
  {
    vtkErrorMacro("Brume's " << in.Pipeline->GetFailedPhase()
                             << " failed on the renderer's scene (see the error above).");
    in.Failed = true;
    return false;
  }
  in.Failed = false;
  // One holder for every trace: the props of the same objects as the last
  // scene's take the new textures (vtkBrumePipeline::AddToRenderer), and
  // their mappers keep on the GPU what did not change (a medium's atlas of
  // scalars, 0.5 GB for a 512^3 field).
  if (!in.Holder)
  {
    in.Holder = vtkSmartPointer<vtkRenderer>::New();
  }
  if (!in.Pipeline->AddToRenderer(in.Holder))
  {
    in.Failed = true;
    return false;
  }
  in.Volumes->RemoveAllItems();
  vtkPropCollection* props = in.Pipeline->GetActors()->GetProps();
  props->InitTraversal();
  while (vtkProp* prop = props->GetNextProp())
  {
    if (auto* volume = vtkVolume::SafeDownCast(prop))
    {
      in.Volumes->AddItem(volume);
      if (auto* mapper = vtkBrumeSliceVolumeMapper::SafeDownCast(volume->GetMapper()))
      {
        mapper->SetVolumeGroup(in.Volumes);
      }
    }
  }
  this->ReportProgress();
  return true;
}

// A progressive step: three times as many particles as the textures hold
// (what is left of the budget at most), added to them: the count grows
// fourfold, a rescaling of the binned particles that is exact in binary.
bool vtkBrumePass::Step()
{
  vtkInternals& in = *this->Internals;
  const vtkTypeInt64 traced = in.Pipeline->GetTracer()->GetNumberOfParticles();
  ++this->NumberOfSteps;
  if (!in.Pipeline->AddParticles(std::min(3 * traced, this->NumberOfParticles - traced)))
  {
    vtkErrorMacro("Brume's " << in.Pipeline->GetFailedPhase()
                             << " failed adding particles (see the error above).");
    in.Failed = true;
    return false;
  }
  this->ReportProgress();
  return true;
}

bool vtkBrumePass::Preview()
{
  vtkInternals& in = *this->Internals;
  vtkPartitionedDataSetCollection* scene = in.Scene->GetOutput();
  if (!in.Holder || in.Failed || in.Empty || !in.Traced || !scene ||
    scene->GetNumberOfPartitionedDataSets() != in.Traced->GetNumberOfPartitionedDataSets())
  {
    return false;
  }
  // Both without the array, or both with the same values.
  auto same = [](vtkFieldData* a, vtkFieldData* b, const char* name)
  {
    vtkDataArray* x = a->GetArray(name);
    vtkDataArray* y = b->GetArray(name);
    return (!x && !y) || vtkBrumeArrayBytes::Same(x, y);
  };
  vtkBrumeSceneActors* actors = in.Pipeline->GetActors();
  std::vector<std::pair<vtkBrumeSliceVolumeMapper*, vtkSmartPointer<vtkImageData>>> previews;
  bool changed = false;
  for (unsigned int i = 0; i < scene->GetNumberOfPartitionedDataSets(); ++i)
  {
    vtkBrumeSliceVolumeMapper* mapper = actors->GetMediumMapper(i);
    vtkImageData* shown = mapper ? mapper->GetExtinctionData() : nullptr;
    if (!shown || !shown->GetFieldData()->GetArray(vtkBrumeNames::ExtinctionTransferFunction))
    {
      continue; // not classified by its mapper: shown as it was until the trace
    }
    auto mediumOf = [i](vtkPartitionedDataSetCollection* c)
    {
      vtkPartitionedDataSet* pds = c->GetPartitionedDataSet(i);
      return pds && pds->GetNumberOfPartitions() > 0 ? pds->GetPartition(0) : nullptr;
    };
    vtkDataObject* before = mediumOf(in.Traced);
    vtkDataObject* medium = mediumOf(scene);
    std::string why;
    vtkSmartPointer<vtkImageData> preview = before && medium
      ? vtkBrumeRadianceConversion::Reclassified(
          shown, before->GetFieldData(), medium->GetFieldData(), why)
      : nullptr;
    if (!preview)
    {
      return false;
    }
    vtkFieldData* a = shown->GetFieldData();
    vtkFieldData* b = preview->GetFieldData();
    changed = changed || !same(a, b, vtkBrumeNames::ExtinctionTransferFunction) ||
      !same(a, b, vtkBrumeNames::AlbedoTransferFunction) ||
      !same(a, b, vtkBrumeNames::ExtinctionTransferRange) ||
      !same(a, b, vtkBrumeNames::ExtinctionScale);
    previews.emplace_back(mapper, preview);
  }
  if (!changed)
  {
    return false; // nothing the mappers classify changed: a preview would show the old frame
  }
  for (const auto& [mapper, preview] : previews)
  {
    mapper->SetExtinctionData(preview);
  }
  in.ShownDistance = actors->GetImageSampleDistance();
  in.ShownSpacingScale = actors->GetSliceSpacingScale();
  actors->SetImageSampleDistance(this->PreviewImageSampleDistance);
  actors->SetSliceSpacingScale(this->PreviewSliceSpacingScale);
  return true;
}

void vtkBrumePass::ReportProgress()
{
  double fraction =
    static_cast<double>(this->Internals->Pipeline->GetTracer()->GetNumberOfParticles()) /
    static_cast<double>(this->NumberOfParticles);
  fraction = std::min(1.0, fraction);
  this->InvokeEvent(vtkCommand::ProgressEvent, &fraction);
}

// Brings the textures and Brume's props up to date with the renderer's
// scene and camera: a trace after a change of the scene (or of the pass's
// settings), a progressive step until the budget is reached, otherwise a
// view update. False (the reason said) when a phase fails.
bool vtkBrumePass::Prepare(vtkRenderer* renderer)
{
  vtkInternals& in = *this->Internals;
  in.Scene->SetRenderer(renderer);
  in.Pipeline->SetCamera(renderer->GetActiveCamera());
  if (in.ShownDistance > 0.0)
  {
    // After a preview, the media at the distance and spacing they had.
    in.Pipeline->GetActors()->SetImageSampleDistance(in.ShownDistance);
    in.Pipeline->GetActors()->SetSliceSpacingScale(in.ShownSpacingScale);
    in.ShownDistance = 0.0;
  }
  const vtkMTimeType scene = in.Scene->GetMTime();
  const bool settings = this->GetMTime() > in.TracedSettings;
  // With a distributed scene, the processes decide together: each looks
  // at its part when any one's changed, and all trace when any part did.
  vtkMultiProcessController* controller = in.Pipeline->GetController();
  const bool gathers = this->Gathers();
  const bool look = !in.Tried || settings || scene > in.TracedScene;
  in.Scene->SetController(gathers ? controller : nullptr);
  if (gathers ? !vtkBrumeProcesses::Agree(controller, !look) : look)
  {
    if (gathers)
    {
      in.Scene->Modified(); // built on every process: the gathering is collective
    }
    // Tried once per change: a failing scene is not traced again every frame.
    in.Tried = true;
    in.TracedScene = scene;
    in.TracedSettings = this->GetMTime();
    // A prop's MTime moves without a change that matters (ParaView's
    // representations touch their mappers at their first renders): the
    // scene is built again and traced only where its content differs.
    // Built once here: VTK's executive does not run a filter that failed
    // again until something changes, so a second Update() would succeed
    // on the last scene's output.
    bool built = in.Scene->GetExecutive()->Update() != 0;
    bool same = built && !settings && in.Traced && !in.Failed &&
      in.Scene->GetContentSignature() == in.TracedSignature;
    if (gathers)
    {
      built = vtkBrumeProcesses::Agree(controller, built);
      same = vtkBrumeProcesses::Agree(controller, same);
    }
    // What building the scene touched (a mapper's default colour map, made
    // on first use) is not an edit.
    in.TracedScene = std::max(in.TracedScene, in.Scene->GetMTime());
    if (!same && this->PreviewEdits && this->Progressive && !gathers && built && this->Preview())
    {
      ++this->NumberOfPreviews;
      in.PendingTrace = true;
      return true;
    }
    if (!same)
    {
      in.PendingTrace = false;
      const bool traced = this->Trace(built);
      in.TracedScene = std::max(in.TracedScene, in.Scene->GetMTime());
      return traced;
    }
    // Back to the traced scene before a previewed edit's trace: nothing to
    // trace; the update below shows the mappers the traced textures again.
    in.PendingTrace = false;
  }
  if (in.PendingTrace)
  {
    // The edit previewed: traced now, from the scene built then.
    in.PendingTrace = false;
    const bool traced = this->Trace(true);
    in.TracedScene = std::max(in.TracedScene, in.Scene->GetMTime());
    return traced;
  }
  if (in.Failed || in.Empty)
  {
    return false;
  }
  if (Eye(in.Pipeline->GetCamera()) != in.ShownEye)
  {
    ++this->NumberOfViewUpdates;
  }
  if (!this->IsConverged())
  {
    return this->Step();
  }
  if (!in.Pipeline->UpdateView())
  {
    vtkErrorMacro("Brume's " << in.Pipeline->GetFailedPhase() << " failed on a new view.");
    return false;
  }
  return true;
}

void vtkBrumePass::Render(const vtkRenderState* s)
{
  this->NumberOfRenderedProps = 0;
  vtkRenderer* renderer = s->GetRenderer();
  vtkInternals& in = *this->Internals;
  const bool lit = this->Prepare(renderer);
  in.ShownEye = Eye(in.Pipeline->GetCamera());
  // Frames the next steps replace take one extinction sample a slab (a
  // quicker draw); the converged one takes the full count.
  in.Pipeline->GetActors()->SetSlabSampling(!this->IsRefining());
  // Brume's props, then the renderer's that the scene does not hold.
  std::vector<vtkProp*> props;
  // A distributed scene: every process draws the whole of it (the same
  // image on each: a parallel compositing keeps of each process's image the
  // region of its own piece).
  if (lit)
  {
    vtkPropCollection* brume = in.Pipeline->GetActors()->GetProps();
    brume->InitTraversal();
    while (vtkProp* prop = brume->GetNextProp())
    {
      props.push_back(prop);
    }
  }
  for (int i = 0; i < s->GetPropArrayCount(); ++i)
  {
    vtkProp* prop = s->GetPropArray()[i];
    if (!lit || !in.Scene->Translates(prop))
    {
      props.push_back(prop);
    }
  }
  vtkRenderState state(renderer);
  state.SetPropArrayAndCount(props.data(), static_cast<int>(props.size()));
  state.SetFrameBuffer(s->GetFrameBuffer());
  in.Display->SetExposure(in.Pipeline->GetExposure());
  in.Display->Render(&state);
  this->NumberOfRenderedProps = in.Display->GetNumberOfRenderedProps();
}

bool vtkBrumePass::Gathers()
{
  return this->DistributedScene &&
    vtkBrumeProcesses::IsDistributed(this->Internals->Pipeline->GetController());
}

void vtkBrumePass::ReleaseGraphicsResources(vtkWindow* w)
{
  this->Internals->Display->ReleaseGraphicsResources(w);
  vtkPropCollection* props = this->Internals->Pipeline->GetActors()->GetProps();
  props->InitTraversal();
  while (vtkProp* prop = props->GetNextProp())
  {
    prop->ReleaseGraphicsResources(w);
  }
}

void vtkBrumePass::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfParticles: " << this->NumberOfParticles << "\n";
  os << indent << "Progressive: " << this->Progressive << "\n";
  os << indent << "DistributedScene: " << this->DistributedScene << "\n";
  os << indent << "PreviewEdits: " << this->PreviewEdits << "\n";
  os << indent << "NumberOfPreviews: " << this->NumberOfPreviews << "\n";
  os << indent << "PreviewImageSampleDistance: " << this->PreviewImageSampleDistance << "\n";
  os << indent << "PreviewSliceSpacingScale: " << this->PreviewSliceSpacingScale << "\n";
  os << indent << "FirstStepParticles: " << this->FirstStepParticles << "\n";
  os << indent << "NumberOfTraces: " << this->NumberOfTraces << "\n";
  os << indent << "NumberOfSteps: " << this->NumberOfSteps << "\n";
  os << indent << "NumberOfViewUpdates: " << this->NumberOfViewUpdates << "\n";
  os << indent << "Pipeline:\n";
  this->Internals->Pipeline->PrintSelf(os, indent.GetNextIndent());
}
