// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeTimedPipeline.h"

#include "vtkAutoInit.h"
#include "vtkBrumeEvaluationView.h"
#include "vtkBrumeFloatImageCapture.h"
#include "vtkBrumeLightTracer.h"
#include "vtkBrumePipeline.h"
#include "vtkBrumeRadianceReconstruction.h"
#include "vtkCamera.h"
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

vtkBrumeTimedPipeline::vtkBrumeTimedPipeline()
  : Pipeline(vtkSmartPointer<vtkBrumePipeline>::New())
{
}

vtkBrumeTimedPipeline::~vtkBrumeTimedPipeline() = default;

vtkBrumePipeline* vtkBrumeTimedPipeline::GetPipeline()
{
  return this->Pipeline;
}

vtkMTimeType vtkBrumeTimedPipeline::GetMTime()
{
  return std::max({ this->Superclass::GetMTime(), this->Pipeline->GetMTime(),
    this->Pipeline->GetTracer()->GetMTime(), this->Pipeline->GetReconstruction()->GetMTime() });
}

// A shortcut to a setting of one of the pipeline's filters.
#define brumeForward(Name, Type, Filter)                                                           \
  void vtkBrumeTimedPipeline::Set##Name(Type value)                                                \
  {                                                                                                \
    this->Pipeline->Get##Filter()->Set##Name(value);                                               \
  }                                                                                                \
  Type vtkBrumeTimedPipeline::Get##Name()                                                          \
  {                                                                                                \
    return this->Pipeline->Get##Filter()->Get##Name();                                             \
  }

brumeForward(NumberOfParticles, vtkTypeInt64, Tracer);
brumeForward(Seed, vtkIdType, Tracer);
brumeForward(MaximumDepth, int, Tracer);
brumeForward(MediumAimFraction, double, Tracer);
brumeForward(SplitHeavyParticles, bool, Tracer);
brumeForward(RadiosityThreshold, double, Reconstruction);
brumeForward(CentroidMatching, bool, Reconstruction);
brumeForward(DirectionalRadiance, bool, Reconstruction);
brumeForward(DirectionalOrder, int, Reconstruction);
#undef brumeForward

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
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->SetSize(this->Size[0], this->Size[1]);
  window->AddRenderer(renderer);
  vtkNew<vtkBrumeFloatImageCapture> capture;
  capture->Attach(renderer);

  const auto start = std::chrono::steady_clock::now();
  vtkBrumePipeline* pipeline = this->Pipeline;
  pipeline->SetInputData(scene);
  pipeline->SetCamera(camera);
  // The full run every time: traced and reconstructed again even where
  // only the camera changed since the last execution.
  pipeline->GetTracer()->Modified();
  if (!pipeline->Update())
  {
    vtkErrorMacro("The pipeline failed on this scene (see the error above).");
    return 0;
  }
  if (!pipeline->AddToRenderer(renderer))
  {
    vtkErrorMacro("Could not make the scene's props (see the error above).");
    return 0;
  }
  renderer->ResetCameraClippingRange();
  // One frame a pixel reads the frame as drawn: drawn here first.
  const auto drawn = [this, window = window.Get()]()
  {
    if (this->Supersampling == 1)
    {
      Draw(window);
    }
  };
  drawn();
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
  pipeline->UpdateView();
  Draw(window);
  camera->Azimuth(2.0);
  const auto viewStart = std::chrono::steady_clock::now();
  pipeline->UpdateView();
  drawn();
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
  os << indent << "MeasureNewView: " << this->MeasureNewView << "\n";
  os << indent << "Camera: " << this->Camera << "\n";
  os << indent << "NewViewSeconds: " << this->NewViewSeconds << "\n";
  os << indent << "FullSeconds: " << this->FullSeconds << "\n";
  os << indent << "Pipeline:\n";
  this->Pipeline->PrintSelf(os, indent.GetNextIndent());
}
