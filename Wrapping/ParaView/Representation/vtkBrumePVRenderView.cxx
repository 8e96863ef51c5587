// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumePVRenderView.h"

#include "vtkBrumeLightTracer.h"
#include "vtkBrumePass.h"
#include "vtkBrumePipeline.h"
#include "vtkBrumeRendererScene.h"
#include "vtkBrumeSceneActors.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"
#include "vtkPVSession.h"
#include "vtkPVSynchronizedRenderer.h"
#include "vtkProcessModule.h"
#include "vtkRenderWindowInteractor.h"

vtkStandardNewMacro(vtkBrumePVRenderView);

namespace
{
// Message tags between the client and the server's root (ParaView's own
// view messages use 41232-41235).
constexpr int ProgressiveTag = 41281;
constexpr int StateTag = 41282;

enum class Side
{
  Alone,  // built-in session, pvbatch: nothing to exchange
  Client, // a client connected to a server
  Server  // a server's process (its root talks to the client)
};

Side SideOf(vtkPVSession* session)
{
  vtkProcessModule* module = vtkProcessModule::GetProcessModule();
  if (!module || !session)
  {
    return Side::Alone;
  }
  switch (module->GetProcessType())
  {
    case vtkProcessModule::PROCESS_CLIENT:
      return session->GetController(vtkPVSession::RENDER_SERVER_ROOT) ? Side::Client : Side::Alone;
    case vtkProcessModule::PROCESS_SERVER:
    case vtkProcessModule::PROCESS_RENDER_SERVER:
      return Side::Server;
    default:
      return Side::Alone;
  }
}
}

vtkBrumePVRenderView::vtkBrumePVRenderView()
{
  this->Pass->ProgressiveOff();
  // Under mpirun each process holds its own part of what is shown: the
  // parts are gathered, and the processes share the particles.
  this->Pass->DistributedSceneOn();
  // The scene pass: ParaView's camera pass, then Brume's (its own display
  // transform: exposure, clamp, sRGB). FXAA would smear Brume's image.
  this->SynchronizedRenderers->SetRenderPass(this->Pass);
  this->UseFXAA = false;
}

vtkBrumePVRenderView::~vtkBrumePVRenderView() = default;

void vtkBrumePVRenderView::SetNumberOfParticles(vtkIdType particles)
{
  this->Pass->SetNumberOfParticles(particles);
}

vtkIdType vtkBrumePVRenderView::GetNumberOfParticles()
{
  return static_cast<vtkIdType>(this->Pass->GetNumberOfParticles());
}

void vtkBrumePVRenderView::Update()
{
  this->Superclass::Update();
  vtkMultiProcessController* ranks = vtkMultiProcessController::GetGlobalController();
  if (this->Pass->GetDistributedScene() && ranks && ranks->GetNumberOfProcesses() > 1)
  {
    // Ordered compositing (asked for by a volume or a translucent surface)
    // would blend the media every process draws once per process:
    // composited by depth instead (their images are the same).
    this->NeedsOrderedCompositing = false;
  }
}

void vtkBrumePVRenderView::SetUseFXAA(bool)
{
  this->Superclass::SetUseFXAA(false);
}

void vtkBrumePVRenderView::SetSeed(vtkIdType seed)
{
  if (this->Pass->GetPipeline()->GetTracer()->GetSeed() != seed)
  {
    this->Pass->GetPipeline()->GetTracer()->SetSeed(seed);
    this->Pass->Modified(); // traced again
  }
}

void vtkBrumePVRenderView::SetExposure(double exposure)
{
  this->Pass->GetPipeline()->SetExposure(exposure);
}

void vtkBrumePVRenderView::SetProgressive(int mode)
{
  this->ProgressiveMode = mode;
}

bool vtkBrumePVRenderView::RendersProgressively()
{
  // The GUI's own window (Qt's interactor): there the view renders again
  // by itself while it refines (vtkBrumeRenderViewInitializationHelper).
  vtkRenderWindowInteractor* interactor = this->GetInteractor();
  return this->ProgressiveMode == 1 ||
    (this->ProgressiveMode == 2 && interactor && interactor->IsA("QVTKInteractor"));
}

void vtkBrumePVRenderView::Render(bool interactive, bool skipRendering)
{
  // Rendered on the server for a client: both call Render() in step (a
  // selection's renders run on the server alone and exchange nothing).
  const bool distributed = interactive ? this->GetUseDistributedRenderingForLODRender()
                                       : this->GetUseDistributedRenderingForRender();
  const Side side =
    distributed && !this->GetMakingSelection() ? SideOf(this->GetSession()) : Side::Alone;
  bool progressive = this->RendersProgressively();
  if (side != Side::Alone)
  {
    progressive = this->ShareProgressive(progressive);
  }
  this->Pass->SetProgressive(progressive);
  this->Superclass::Render(interactive, skipRendering);
  this->LastRenderOnServer = side == Side::Client;
  if (side != Side::Alone)
  {
    this->ShareServerState();
  }
}

bool vtkBrumePVRenderView::ShareProgressive(bool progressive)
{
  int flag = progressive ? 1 : 0;
  vtkPVSession* session = this->GetSession();
  if (vtkMultiProcessController* server = session->GetController(vtkPVSession::RENDER_SERVER_ROOT))
  {
    server->Send(&flag, 1, 1, ProgressiveTag);
    return progressive;
  }
  if (vtkMultiProcessController* client = session->GetController(vtkPVSession::CLIENT))
  {
    client->Receive(&flag, 1, 1, ProgressiveTag);
  }
  vtkMultiProcessController* ranks = vtkMultiProcessController::GetGlobalController();
  if (ranks && ranks->GetNumberOfProcesses() > 1)
  {
    ranks->Broadcast(&flag, 1, 0);
  }
  return flag != 0;
}

void vtkBrumePVRenderView::ShareServerState()
{
  vtkPVSession* session = this->GetSession();
  int state[6] = { 0, 0, 0, 1, 0, 0 };
  if (vtkMultiProcessController* server = session->GetController(vtkPVSession::RENDER_SERVER_ROOT))
  {
    server->Receive(state, 6, 1, StateTag);
    this->ServerState = { state[0], state[1], state[2], state[3], state[4], state[5] };
  }
  else if (vtkMultiProcessController* client = session->GetController(vtkPVSession::CLIENT))
  {
    state[0] = this->Pass->GetNumberOfTraces();
    state[1] = this->Pass->GetNumberOfSteps();
    state[2] = this->Pass->GetNumberOfViewUpdates();
    state[3] = this->Pass->IsConverged() ? 1 : 0;
    state[4] = this->Pass->GetProgressive() && this->Pass->IsRefining() ? 1 : 0;
    state[5] = this->Pass->GetNumberOfPreviews();
    client->Send(state, 6, 1, StateTag);
  }
}

void vtkBrumePVRenderView::SetPreviewEdits(int preview)
{
  this->Pass->SetPreviewEdits(preview != 0);
}

void vtkBrumePVRenderView::SetPreviewSliceSpacingScale(double scale)
{
  this->Pass->SetPreviewSliceSpacingScale(scale);
}

double vtkBrumePVRenderView::GetPreviewSliceSpacingScale()
{
  return this->Pass->GetPreviewSliceSpacingScale();
}

void vtkBrumePVRenderView::SetExtinctionDepthTolerance(double tolerance)
{
  this->Pass->GetPipeline()->GetActors()->SetExtinctionDepthTolerance(tolerance);
}

double vtkBrumePVRenderView::GetExtinctionDepthTolerance()
{
  return this->Pass->GetPipeline()->GetActors()->GetExtinctionDepthTolerance();
}

void vtkBrumePVRenderView::SetVolumeAlbedo(double r, double g, double b)
{
  this->Pass->GetScene()->SetAlbedo(r, g, b);
}

void vtkBrumePVRenderView::SetPhysicalLights(int physical)
{
  this->Pass->GetScene()->SetPhysicalLights(physical != 0);
}

void vtkBrumePVRenderView::SetLightIntensityScale(double scale)
{
  this->Pass->GetScene()->SetLightScale(scale);
}

vtkBrumePass* vtkBrumePVRenderView::GetBrumePass()
{
  return this->Pass;
}

bool vtkBrumePVRenderView::IsConverged()
{
  return this->LastRenderOnServer ? this->ServerState.Converged != 0 : this->Pass->IsConverged();
}

bool vtkBrumePVRenderView::IsRefining()
{
  if (this->LastRenderOnServer)
  {
    return this->ServerState.Refining != 0;
  }
  return this->RendersProgressively() && this->Pass->IsRefining();
}

int vtkBrumePVRenderView::GetNumberOfTraces()
{
  return this->LastRenderOnServer ? this->ServerState.Traces : this->Pass->GetNumberOfTraces();
}

int vtkBrumePVRenderView::GetNumberOfSteps()
{
  return this->LastRenderOnServer ? this->ServerState.Steps : this->Pass->GetNumberOfSteps();
}

int vtkBrumePVRenderView::GetNumberOfViewUpdates()
{
  return this->LastRenderOnServer ? this->ServerState.ViewUpdates
                                  : this->Pass->GetNumberOfViewUpdates();
}

int vtkBrumePVRenderView::GetNumberOfPreviews()
{
  return this->LastRenderOnServer ? this->ServerState.Previews : this->Pass->GetNumberOfPreviews();
}

void vtkBrumePVRenderView::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ProgressiveMode: " << this->ProgressiveMode << "\n";
  os << indent << "LastRenderOnServer: " << this->LastRenderOnServer << "\n";
  os << indent << "Pass:\n";
  this->Pass->PrintSelf(os, indent.GetNextIndent());
}
