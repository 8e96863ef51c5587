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
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPointData.h"
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

// Averages blocks of `factor` x `factor` pixels: the supersampled frame as
// pixel-area (box-filtered) radiance, as the reference path tracer's pixels.
vtkSmartPointer<vtkImageData> Downsample(vtkImageData* image, int factor)
{
  int dims[3];
  image->GetDimensions(dims);
  const int w = dims[0] / factor, h = dims[1] / factor;
  auto* in = vtkFloatArray::SafeDownCast(image->GetPointData()->GetArray("Radiance"));
  vtkNew<vtkFloatArray> out;
  out->SetName("Radiance");
  out->SetNumberOfComponents(3);
  out->SetNumberOfTuples(static_cast<vtkIdType>(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c)
      {
        double sum = 0;
        for (int j = 0; j < factor; ++j)
          for (int i = 0; i < factor; ++i)
          {
            sum += in->GetValue(
              3 * ((static_cast<vtkIdType>(y) * factor + j) * dims[0] + x * factor + i) + c);
          }
        out->SetValue(
          3 * (static_cast<vtkIdType>(y) * w + x) + c, static_cast<float>(sum / (factor * factor)));
      }
  auto result = vtkSmartPointer<vtkImageData>::New();
  result->SetDimensions(w, h, 1);
  result->GetPointData()->SetScalars(out);
  return result;
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
  window->SetSize(this->Size[0] * this->Supersampling, this->Size[1] * this->Supersampling);
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
  Draw(window);
  this->FullSeconds = Seconds(start);
  const vtkSmartPointer<vtkImageData> frame = capture->Capture();
  if (!frame)
  {
    vtkErrorMacro("Could not read the frame back.");
    return 0;
  }
  vtkImageData::GetData(outputVector, 0)->ShallowCopy(Downsample(frame, this->Supersampling));
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
  Draw(window);
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
