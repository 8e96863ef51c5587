// SPDX-License-Identifier: BSD-3-Clause
// vtkBrumeFloatImageCapture::CaptureSupersampled estimates pixel areas: a
// flat white quad whose edges cut pixels at known fractions gives those
// pixels their covered fraction to within 1/(2 K^2) along either axis (a
// regular K x K grid would be off by up to 1/(2 K): 0.5 or 0.75 for 0.63
// at K = 4), K = 1 samples the pixels' centres, and the camera's window
// centre is restored.
#include "vtkActor.h"
#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeFloatImageCapture.h"
#include "vtkCamera.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include <cmath>
#include <iostream>
#include <string>

namespace
{
int failures = 0;
void Check(bool ok, const std::string& what)
{
  if (!ok)
  {
    std::cerr << "FAILED: " << what << "\n";
    ++failures;
  }
}
}

int TestFloatImageCapture(int, char*[])
{
  // 16 x 16 pixels of one unit each (parallel projection, x and y in
  // [-8, 8]): the quad's left edge is 0.37 into column 3, its bottom edge
  // 0.81 into row 5.
  constexpr double Left = -8.0 + 3.0 + 0.37, Bottom = -8.0 + 5.0 + 0.81;
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(Left, Bottom, 0.0);
  plane->SetPoint1(20.0, Bottom, 0.0);
  plane->SetPoint2(Left, 20.0, 0.0);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(plane->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->LightingOff();
  actor->GetProperty()->SetColor(1.0, 1.0, 1.0);
  actor->GetProperty()->SetAmbient(1.0);
  actor->GetProperty()->SetDiffuse(0.0);
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0, 0, 0);
  renderer->AddActor(actor);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->ParallelProjectionOn();
  camera->SetParallelScale(8.0);
  camera->SetPosition(0, 0, 10);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewUp(0, 1, 0);
  renderer->ResetCameraClippingRange();
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->SetSize(16, 16);
  window->AddRenderer(renderer);
  vtkNew<vtkBrumeFloatImageCapture> capture;
  capture->Attach(renderer);

  auto pixel = [](vtkImageData* image, int x, int y)
  {
    auto* radiance =
      vtkFloatArray::SafeDownCast(image->GetPointData()->GetArray(vtkBrumeNames::Radiance));
    return radiance ? static_cast<double>(radiance->GetTypedComponent(y * 16 + x, 0)) : -1.0;
  };
  window->Render(); // K = 1 reads the frame as drawn
  for (int k : { 1, 2, 4 })
  {
    vtkSmartPointer<vtkImageData> image = capture->CaptureSupersampled(k);
    const std::string at = "K = " + std::to_string(k) + ": ";
    Check(image != nullptr, at + "an image");
    if (!image)
    {
      continue;
    }
    const double inside = pixel(image, 10, 10);
    Check(std::abs(inside - 1.0) < 1e-3, at + "a pixel inside is 1, not " + std::to_string(inside));
    Check(pixel(image, 1, 10) == 0.0 && pixel(image, 10, 2) == 0.0, at + "pixels outside are 0");
    // Column 3 is 0.63 covered, row 5 0.19: K^2 distinct offsets along
    // each axis round a fraction to 1/K^2 (K = 1: the pixel's centre).
    const double allowed = k == 1 ? 0.5 + 1e-3 : 0.5 / (k * k) + 1e-3;
    const struct
    {
      int X, Y;
      double Covered;
    } edges[] = { { 3, 10, 0.63 }, { 10, 5, 0.19 } };
    for (const auto& e : edges)
    {
      const double v = pixel(image, e.X, e.Y);
      Check(std::abs(v - e.Covered) <= allowed,
        at + "pixel (" + std::to_string(e.X) + ", " + std::to_string(e.Y) + ") covered " +
          std::to_string(e.Covered) + ", captured " + std::to_string(v));
    }
    if (k == 1)
    {
      Check(pixel(image, 3, 10) == 1.0 && pixel(image, 10, 5) == 0.0,
        "K = 1 samples the pixels' centres (0.5 into the pixel: column 3 in, row 5 out)");
    }
    double centre[2];
    camera->GetWindowCenter(centre);
    Check(centre[0] == 0.0 && centre[1] == 0.0, at + "the camera's window centre is restored");
  }
  return failures == 0 ? 0 : 1;
}
