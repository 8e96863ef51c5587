// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeFloatImageCapture.h"

#include "vtkBrumeDataModelNames.h"
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
#include <functional>
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

bool vtkBrumeFloatImageCapture::Read(int size[2], const std::function<void(const float*, int)>& use)
{
  vtkTextureObject* color = this->Pass ? this->Pass->GetColorTexture() : nullptr;
  if (!this->Renderer || !color || !color->GetHandle())
  {
    vtkErrorMacro("Nothing to capture: Attach() a renderer and render first.");
    return false;
  }
  this->Renderer->GetRenderWindow()->MakeCurrent();
  size[0] = static_cast<int>(color->GetWidth());
  size[1] = static_cast<int>(color->GetHeight());
  const int components = color->GetComponents();
  vtkPixelBufferObject* pbo = color->Download();
  if (!pbo || components < 3)
  {
    vtkErrorMacro("Could not read the float colour buffer back.");
    if (pbo)
    {
      pbo->Delete();
    }
    return false;
  }
  use(static_cast<const float*>(pbo->MapPackedBuffer()), components);
  pbo->UnmapPackedBuffer();
  pbo->Delete();
  return true;
}

vtkSmartPointer<vtkImageData> vtkBrumeFloatImageCapture::Capture()
{
  return this->CaptureSupersampled(1);
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
  // The sum of the frames' RGB, read straight from each frame's buffer.
  std::vector<double> total;
  int size[2] = { 0, 0 };
  auto add = [&total, &size](const float* data, int components)
  {
    const std::size_t pixels = static_cast<std::size_t>(size[0]) * size[1];
    total.resize(3 * pixels, 0.0);
    for (std::size_t i = 0; i < pixels; ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        total[3 * i + c] += data[components * i + c];
      }
    }
  };
  // k = 1: the last frame, as drawn.
  bool ok = k > 1 || this->Read(size, add);
  for (int n = 0; k > 1 && n < k * k && ok; ++n)
  {
    // Sample (i, j) of the rotated grid, in pixels from the pixel's centre.
    const int i = n % k, j = n / k;
    const double x = (i + (j + 0.5) / k) / k - 0.5;
    const double y = (j + (i + 0.5) / k) / k - 0.5;
    // The window centre is in viewport units (the viewport spans [-1, 1]).
    camera->SetWindowCenter(centre[0] + 2.0 * x / width, centre[1] + 2.0 * y / height);
    window->Render();
    ok = this->Read(size, add);
  }
  camera->SetWindowCenter(centre[0], centre[1]);
  if (!ok)
  {
    return nullptr;
  }
  vtkNew<vtkFloatArray> radiance;
  radiance->SetName(vtkBrumeNames::Radiance);
  radiance->SetNumberOfComponents(3);
  radiance->SetNumberOfValues(static_cast<vtkIdType>(total.size()));
  for (std::size_t v = 0; v < total.size(); ++v)
  {
    radiance->SetValue(static_cast<vtkIdType>(v), static_cast<float>(total[v] / (k * k)));
  }
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(size[0], size[1], 1);
  image->GetPointData()->SetScalars(radiance);
  return image;
}

vtkSmartPointer<vtkImageData> vtkBrumeFloatImageCapture::ToneMap(
  vtkImageData* radiance, double exposure)
{
  auto* in = radiance
    ? vtkFloatArray::SafeDownCast(radiance->GetPointData()->GetArray(vtkBrumeNames::Radiance))
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
