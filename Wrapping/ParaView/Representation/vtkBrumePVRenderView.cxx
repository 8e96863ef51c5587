// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumePVRenderView.h"

#include "vtkBrumeLightTracer.h"
#include "vtkBrumePass.h"
#include "vtkBrumePipeline.h"
#include "vtkBrumeRendererScene.h"
#include "vtkObjectFactory.h"
#include "vtkPVSynchronizedRenderer.h"
#include "vtkRenderWindowInteractor.h"

vtkStandardNewMacro(vtkBrumePVRenderView);

vtkBrumePVRenderView::vtkBrumePVRenderView()
{
  this->Pass->ProgressiveOff();
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
  this->Pass->SetProgressive(this->RendersProgressively());
  this->Superclass::Render(interactive, skipRendering);
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
  return this->Pass->IsConverged();
}

bool vtkBrumePVRenderView::IsRefining()
{
  return this->RendersProgressively() && this->Pass->IsRefining();
}

int vtkBrumePVRenderView::GetNumberOfTraces()
{
  return this->Pass->GetNumberOfTraces();
}

int vtkBrumePVRenderView::GetNumberOfSteps()
{
  return this->Pass->GetNumberOfSteps();
}

int vtkBrumePVRenderView::GetNumberOfViewUpdates()
{
  return this->Pass->GetNumberOfViewUpdates();
}

void vtkBrumePVRenderView::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ProgressiveMode: " << this->ProgressiveMode << "\n";
  os << indent << "Pass:\n";
  this->Pass->PrintSelf(os, indent.GetNextIndent());
}
