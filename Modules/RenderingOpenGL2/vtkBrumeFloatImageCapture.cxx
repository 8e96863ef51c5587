// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeFloatImageCapture.h"

#include "vtkCamera.h"
#include "vtkFloatArray.h"
#include "vtkFramebufferPass.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPixelBufferObject.h"
#include "vtkPointData.h"
#include "vtkRenderStepsPass.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkTextureObject.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <vector>

vtkStandardNewMacro(vtkBrumeFloatImageCapture);

vtkBrumeFloatImageCapture::vtkBrumeFloatImageCapture() = default;
vtkBrumeFloatImageCapture::~vtkBrumeFloatImageCapture() = default;

void vtkBrumeFloatImageCapture::Attach(vtkRenderer* renderer)
{
  this->Renderer = renderer;
  vtkNew<vtkRenderStepsPass> steps;
  this->Pass = vtkSmartPointer<vtkFramebufferPass>::New();
  this->Pass->SetColorFormat(vtkTextureObject::Float32);
  this->Pass->SetDelegatePass(steps);
  renderer->SetPass(this->Pass);
}

vtkSmartPointer<vtkImageData> vtkBrumeFloatImageCapture::CaptureSupersampled(int k)
{
  if (!this->Renderer || !this->Renderer->GetRenderWindow() || k < 1)
  {
    vtkErrorMacro("Nothing to capture: Attach() a renderer in a window, and k >= 1.");
    return nullptr;
  }
  vtkRenderWindow* window = this->Renderer->GetRenderWindow();
  vtkCamera* camera = this->Renderer->GetActiveCamera();
  int width = 0, height = 0;
  this->Renderer->GetTiledSize(&width, &height);
  double centre[2];
  camera->GetWindowCenter(centre);
  vtkSmartPointer<vtkImageData> sum;
  std::vector<double> total;
  for (int n = 0; n < k * k; ++n)
  {
    // Sample (i, j) of the rotated grid, in pixels from the pixel's centre.
    const int i = n % k, j = n / k;
    const double x = (i + (j + 0.5) / k) / k - 0.5;
    const double y = (j + (i + 0.5) / k) / k - 0.5;
    // The window centre is in viewport units (the viewport spans [-1, 1]).
    camera->SetWindowCenter(centre[0] + 2.0 * x / width, centre[1] + 2.0 * y / height);
    window->Render();
    vtkSmartPointer<vtkImageData> frame = this->Capture();
    if (!frame)
    {
      camera->SetWindowCenter(centre[0], centre[1]);
      return nullptr;
    }
    auto* values = vtkFloatArray::SafeDownCast(frame->GetPointData()->GetArray("Radiance"));
    if (!sum)
    {
      sum = frame;
      total.assign(values->GetPointer(0), values->GetPointer(0) + values->GetNumberOfValues());
    }
    else
    {
      for (vtkIdType v = 0; v < values->GetNumberOfValues(); ++v)
      {
        total[v] += values->GetValue(v);
      }
    }
  }
  camera->SetWindowCenter(centre[0], centre[1]);
  auto* values = vtkFloatArray::SafeDownCast(sum->GetPointData()->GetArray("Radiance"));
  for (vtkIdType v = 0; v < values->GetNumberOfValues(); ++v)
  {
    values->SetValue(v, static_cast<float>(total[v] / (k * k)));
  }
  return sum;
}

vtkSmartPointer<vtkImageData> vtkBrumeFloatImageCapture::Capture()
{
  vtkTextureObject* color = this->Pass ? this->Pass->GetColorTexture() : nullptr;
  if (!this->Renderer || !color || !color->GetHandle())
  {
    vtkErrorMacro("Nothing to capture: Attach() a renderer and render first.");
    return nullptr;
  }
  this->Renderer->GetRenderWindow()->MakeCurrent();
  const int width = static_cast<int>(color->GetWidth());
  const int height = static_cast<int>(color->GetHeight());
  const int components = color->GetComponents();
  vtkPixelBufferObject* pbo = color->Download();
  if (!pbo || components < 3)
  {
    vtkErrorMacro("Could not read the float colour buffer back.");
    if (pbo)
    {
      pbo->Delete();
    }
    return nullptr;
  }
  const auto* data = static_cast<const float*>(pbo->MapPackedBuffer());
  vtkNew<vtkFloatArray> radiance;
  radiance->SetName("Radiance");
  radiance->SetNumberOfComponents(3);
  radiance->SetNumberOfTuples(static_cast<vtkIdType>(width) * height);
  float* out = radiance->GetPointer(0);
  for (vtkIdType i = 0; i < static_cast<vtkIdType>(width) * height; ++i)
  {
    out[3 * i + 0] = data[components * i + 0];
    out[3 * i + 1] = data[components * i + 1];
    out[3 * i + 2] = data[components * i + 2];
  }
  pbo->UnmapPackedBuffer();
  pbo->Delete();
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(width, height, 1);
  image->GetPointData()->SetScalars(radiance);
  return image;
}

vtkSmartPointer<vtkImageData> vtkBrumeFloatImageCapture::ToneMap(
  vtkImageData* radiance, double exposure)
{
  auto* in = radiance ? vtkFloatArray::SafeDownCast(radiance->GetPointData()->GetArray("Radiance"))
                      : nullptr;
  if (!in || in->GetNumberOfComponents() != 3)
  {
    return nullptr;
  }
  vtkNew<vtkUnsignedCharArray> rgb;
  rgb->SetNumberOfComponents(3);
  rgb->SetNumberOfTuples(in->GetNumberOfTuples());
  for (vtkIdType i = 0; i < 3 * in->GetNumberOfTuples(); ++i)
  {
    double x = std::min(1.0, std::max(0.0, exposure * in->GetValue(i)));
    x = x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055;
    rgb->SetValue(i, static_cast<unsigned char>(std::lround(255.0 * x)));
  }
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(radiance->GetDimensions());
  image->GetPointData()->SetScalars(rgb);
  return image;
}

void vtkBrumeFloatImageCapture::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Renderer: " << this->Renderer << "\n";
}
