// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeTimedPipeline.h"

#include "vtkAutoInit.h"
#include "vtkBrumeEvaluationView.h"
#include "vtkBrumeFloatImageCapture.h"
#include "vtkBrumeLightTracer.h"
#include "vtkBrumeRadianceReconstruction.h"
#include "vtkBrumeSceneActors.h"
#include "vtkCamera.h"
#include "vtkExecutive.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <chrono>

// The OpenGL render window and Brume's slice volume mapper, whoever links us.
VTK_MODULE_INIT(vtkBrumeRenderingOpenGL2);

vtkStandardNewMacro(vtkBrumeTimedPipeline);

namespace
{
double Seconds(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// One frame of `window`, finished.
void Draw(vtkRenderWindow* window)
{
  window->Render();
  window->WaitForCompletion();
}
}

vtkBrumeTimedPipeline::vtkBrumeTimedPipeline() = default;

vtkBrumeTimedPipeline::~vtkBrumeTimedPipeline() = default;

int vtkBrumeTimedPipeline::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkDataObject* scene = vtkDataObject::GetData(inputVector[0], 0);
  this->FullSeconds = this->NewViewSeconds = 0;
  if (this->Size[0] < 1 || this->Size[1] < 1 || this->Size[0] > 16384 || this->Size[1] > 16384)
  {
    vtkErrorMacro("Size must be in [1, 16384] on each axis, not " << this->Size[0] << " x "
                                                                  << this->Size[1] << ".");
    return 0;
  }
  const vtkSmartPointer<vtkCamera> camera = vtkBrumeEvaluationView::Camera(scene, this->Camera);
  vtkNew<vtkRenderer> renderer;
  renderer->SetActiveCamera(camera);
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->SetSize(this->Size[0], this->Size[1]);
  window->AddRenderer(renderer);
  vtkNew<vtkBrumeFloatImageCapture> capture;
  capture->Attach(renderer);

  const auto start = std::chrono::steady_clock::now();
  vtkNew<vtkBrumeLightTracer> tracer;
  tracer->SetInputData(scene);
  tracer->SetNumberOfParticles(this->NumberOfParticles);
  tracer->SetSeed(this->Seed);
  tracer->SetMaximumDepth(this->MaximumDepth);
  tracer->SetMediumAimFraction(this->MediumAimFraction);
  tracer->SetSplitHeavyParticles(this->SplitHeavyParticles);
  vtkNew<vtkBrumeRadianceReconstruction> reconstruction;
  reconstruction->SetInputDataObject(0, scene);
  reconstruction->SetInputConnection(1, tracer->GetOutputPort());
  reconstruction->SetCamera(camera);
  reconstruction->SetRadiosityThreshold(this->RadiosityThreshold);
  reconstruction->SetCentroidMatching(this->CentroidMatching);
  reconstruction->SetDirectionalRadiance(this->DirectionalRadiance);
  reconstruction->SetDirectionalOrder(this->DirectionalOrder);
  if (!reconstruction->GetExecutive()->Update())
  {
    vtkErrorMacro("The pipeline failed on this scene (see the error above).");
    return 0;
  }
  vtkNew<vtkBrumeSceneActors> actors;
  actors->SetInputData(reconstruction->GetOutput());
  if (!actors->AddToRenderer(renderer))
  {
    vtkErrorMacro("Could not make the scene's props (see the error above).");
    return 0;
  }
  renderer->ResetCameraClippingRange();
  const vtkSmartPointer<vtkImageData> frame = capture->CaptureSupersampled(this->Supersampling);
  this->FullSeconds = Seconds(start);
  if (!frame)
  {
    vtkErrorMacro("Could not read the frame back.");
    return 0;
  }
  vtkImageData::GetData(outputVector, 0)->ShallowCopy(frame);
  if (!this->MeasureNewView)
  {
    return 1;
  }

  // A new viewpoint: come back to this one from 2 degrees away (drawn
  // there, so that every per-view step runs again).
  camera->Azimuth(-2.0);
  reconstruction->Update();
  actors->UpdateInputs(reconstruction->GetOutput());
  Draw(window);
  camera->Azimuth(2.0);
  const auto viewStart = std::chrono::steady_clock::now();
  reconstruction->Update();
  actors->UpdateInputs(reconstruction->GetOutput());
  if (!capture->CaptureSupersampled(this->Supersampling))
  {
    vtkErrorMacro("Could not read the new view's frame back.");
    return 0;
  }
  this->NewViewSeconds = Seconds(viewStart);
  return 1;
}

void vtkBrumeTimedPipeline::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Size: " << this->Size[0] << " x " << this->Size[1] << "\n";
  os << indent << "Supersampling: " << this->Supersampling << "\n";
  os << indent << "NumberOfParticles: " << this->NumberOfParticles << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "MaximumDepth: " << this->MaximumDepth << "\n";
  os << indent << "RadiosityThreshold: " << this->RadiosityThreshold << "\n";
  os << indent << "CentroidMatching: " << this->CentroidMatching << "\n";
  os << indent << "MediumAimFraction: " << this->MediumAimFraction << "\n";
  os << indent << "SplitHeavyParticles: " << this->SplitHeavyParticles << "\n";
  os << indent << "DirectionalRadiance: " << this->DirectionalRadiance << "\n";
  os << indent << "DirectionalOrder: " << this->DirectionalOrder << "\n";
  os << indent << "MeasureNewView: " << this->MeasureNewView << "\n";
  os << indent << "Camera: " << this->Camera << "\n";
  os << indent << "NewViewSeconds: " << this->NewViewSeconds << "\n";
  os << indent << "FullSeconds: " << this->FullSeconds << "\n";
}
