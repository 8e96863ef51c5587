// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeReferencePathTracer.h"

#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeSceneCamera.h"
#include "vtkBrumeSceneConversion.h"
#include "vtkCamera.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkObjectFactory.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPointData.h"
#include "vtkSMPTools.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include "brume/PathTracer.h"

#include <algorithm>
#include <cmath>

vtkStandardNewMacro(vtkBrumeReferencePathTracer);
vtkCxxSetObjectMacro(vtkBrumeReferencePathTracer, Camera, vtkCamera);

vtkBrumeReferencePathTracer::vtkBrumeReferencePathTracer()
  : Lights(vtkSmartPointer<vtkLightCollection>::New())
{
  this->SetNumberOfInputPorts(1);
}

vtkBrumeReferencePathTracer::~vtkBrumeReferencePathTracer()
{
  this->SetCamera(nullptr);
}

void vtkBrumeReferencePathTracer::AddLight(vtkLight* light)
{
  this->Lights->AddItem(light);
  this->Modified();
}

void vtkBrumeReferencePathTracer::RemoveAllLights()
{
  this->Lights->RemoveAllItems();
  this->Modified();
}

vtkMTimeType vtkBrumeReferencePathTracer::GetMTime()
{
  vtkMTimeType t = this->Superclass::GetMTime();
  if (this->Camera)
  {
    t = std::max(t, this->Camera->GetMTime());
  }
  return t;
}

int vtkBrumeReferencePathTracer::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataObject");
  return 1;
}

int vtkBrumeReferencePathTracer::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  const int w = std::max(1, this->Size[0]), h = std::max(1, this->Size[1]);
  const int extent[6] = { 0, w - 1, 0, h - 1, 0, 0 };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  const double origin[3] = { 0, 0, 0 }, spacing[3] = { 1, 1, 1 };
  outInfo->Set(vtkDataObject::ORIGIN(), origin, 3);
  outInfo->Set(vtkDataObject::SPACING(), spacing, 3);
  return 1;
}

int vtkBrumeReferencePathTracer::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  const auto collection =
    vtkBrumeSceneConversion::AsCollection(vtkDataObject::GetData(inputVector[0], 0));
  vtkPartitionedDataSetCollection* input = collection;
  auto* output = vtkImageData::GetData(outputVector, 0);
  if (this->Size[0] < 1 || this->Size[1] < 1 || this->Size[0] > 16384 || this->Size[1] > 16384)
  {
    vtkErrorMacro("Size must be in [1, 16384] on each axis, not " << this->Size[0] << " x "
                                                                  << this->Size[1] << ".");
    return 0;
  }
  if (this->SamplesPerPixel < 1 || this->SamplesPerPixel > 1000000)
  {
    vtkErrorMacro("SamplesPerPixel must be in [1, 1e6], not " << this->SamplesPerPixel << ".");
    return 0;
  }
  brume::Scene scene;
  if (!vtkBrumeSceneConversion::ToTracedScene(this, input, this->Seed, this->Lights, scene))
  {
    return 0;
  }
  brume::PinholeCamera camera;
  double position[3], focal[3], up[3], angle;
  if (this->Camera)
  {
    this->Camera->GetPosition(position);
    this->Camera->GetFocalPoint(focal);
    this->Camera->GetViewUp(up);
    angle = this->Camera->GetViewAngle();
  }
  else
  {
    vtkBrumeSceneCamera::GetSceneCamera(input, position, focal, up, angle);
  }
  camera.Position = { static_cast<float>(position[0]), static_cast<float>(position[1]),
    static_cast<float>(position[2]) };
  camera.FocalPoint = { static_cast<float>(focal[0]), static_cast<float>(focal[1]),
    static_cast<float>(focal[2]) };
  camera.ViewUp = { static_cast<float>(up[0]), static_cast<float>(up[1]),
    static_cast<float>(up[2]) };
  camera.ViewAngle = static_cast<float>(angle);
  camera.Width = this->Size[0];
  camera.Height = this->Size[1];
  if (!(Length(camera.FocalPoint - camera.Position) > 0.f) || !(camera.ViewAngle > 0.f) ||
    !(camera.ViewAngle < 180.f))
  {
    vtkErrorMacro(
      "The camera needs a focal point apart from its position and a view angle in (0, 180).");
    return 0;
  }
  const brume::RayCaster caster(scene);
  if (!caster.GetError().empty())
  {
    vtkErrorMacro("Could not build the ray-casting structure: " << caster.GetError());
    return 0;
  }
  brume::PathSettings settings;
  settings.Seed = static_cast<std::uint64_t>(this->Seed);
  settings.SamplesPerPixel = this->SamplesPerPixel;
  settings.MaxDepth = this->MaximumDepth;
  const brume::PathTracer tracer(scene, caster, settings);

  const vtkIdType pixels = static_cast<vtkIdType>(camera.Width) * camera.Height;
  vtkNew<vtkFloatArray> radiance, variance;
  radiance->SetName(vtkBrumeNames::Radiance);
  radiance->SetNumberOfComponents(3);
  radiance->SetNumberOfTuples(pixels);
  variance->SetName(vtkBrumeNames::Variance);
  variance->SetNumberOfComponents(3);
  variance->SetNumberOfTuples(pixels);
  float* mean = radiance->GetPointer(0);
  float* var = variance->GetPointer(0);
  // Rows in a few batches, so that progress reaches the user.
  const int batches = std::min(camera.Height, 20);
  for (int b = 0; b < batches && !this->GetAbortExecute(); ++b)
  {
    const int y0 = camera.Height * b / batches, y1 = camera.Height * (b + 1) / batches;
    vtkSMPTools::For(y0, y1, 1,
      [&](vtkIdType begin, vtkIdType end)
      {
        for (vtkIdType y = begin; y < end; ++y)
        {
          const std::size_t o = 3 * static_cast<std::size_t>(y) * camera.Width;
          tracer.RenderRows(
            camera, static_cast<int>(y), static_cast<int>(y) + 1, mean + o, var + o);
        }
      });
    this->UpdateProgress(static_cast<double>(b + 1) / batches);
  }
  output->SetExtent(0, camera.Width - 1, 0, camera.Height - 1, 0, 0);
  output->GetPointData()->SetScalars(radiance);
  output->GetPointData()->AddArray(variance);
  return 1;
}

void vtkBrumeReferencePathTracer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Size: " << this->Size[0] << " x " << this->Size[1] << "\n";
  os << indent << "SamplesPerPixel: " << this->SamplesPerPixel << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "MaximumDepth: " << this->MaximumDepth << "\n";
  os << indent << "Camera: " << this->Camera << "\n";
}
