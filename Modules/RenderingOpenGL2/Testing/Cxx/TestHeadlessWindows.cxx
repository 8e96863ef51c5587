// SPDX-License-Identifier: BSD-3-Clause
// The windows with no window system, made directly (no object factory):
// several windows in one process, resizes, teardown in any order, the same
// pixels through EGL and OSMesa, and a window refused (nothing drawn) while
// the other API's context is current on the thread.
#include "vtkActor.h"
#include "vtkBrumeEGLRenderWindow.h"
#include "vtkBrumeOSMesaRenderWindow.h"
#include "vtkCallbackCommand.h"
#include "vtkConeSource.h"
#include "vtkNew.h"
#include "vtkPolyDataMapper.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkUnsignedCharArray.h"

#include <functional>
#include <iostream>
#include <string>
#include <vector>

namespace
{
int Failures = 0;

void Check(bool ok, const std::string& what)
{
  if (!ok)
  {
    std::cerr << "FAILED: " << what << "\n";
    ++Failures;
  }
}

// Counts VTK errors raised by a window, and remembers the last.
struct ErrorCount
{
  int Count = 0;
  std::string Last;
  vtkNew<vtkCallbackCommand> Command;
  ErrorCount()
  {
    this->Command->SetClientData(this);
    this->Command->SetCallback(
      [](vtkObject*, unsigned long, void* client, void* message)
      {
        auto* self = static_cast<ErrorCount*>(client);
        ++self->Count;
        self->Last = static_cast<const char*>(message);
      });
  }
};

using Pixels = std::vector<unsigned char>;

// A window showing a sphere (or a cone), rendered at w x h; its RGB pixels.
Pixels Draw(vtkRenderWindow* window, int w, int h)
{
  window->SetSize(w, h);
  window->Render();
  vtkNew<vtkUnsignedCharArray> rgb;
  window->GetPixelData(0, 0, w - 1, h - 1, /*front=*/0, rgb);
  const unsigned char* p = rgb->GetPointer(0);
  return Pixels(p, p + rgb->GetNumberOfValues());
}

void Populate(vtkRenderWindow* window, bool cone)
{
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkActor> actor;
  vtkNew<vtkPolyDataMapper> mapper;
  if (cone)
  {
    vtkNew<vtkConeSource> source;
    source->SetResolution(24);
    mapper->SetInputConnection(source->GetOutputPort());
  }
  else
  {
    vtkNew<vtkSphereSource> source;
    source->SetThetaResolution(32);
    source->SetPhiResolution(32);
    mapper->SetInputConnection(source->GetOutputPort());
  }
  actor->SetMapper(mapper);
  renderer->AddActor(actor);
  renderer->SetBackground(0.1, 0.2, 0.3);
  window->AddRenderer(renderer);
}

// Pixels that differ from the background: something was drawn.
std::size_t Covered(const Pixels& rgb)
{
  std::size_t n = 0;
  for (std::size_t i = 0; i + 2 < rgb.size(); i += 3)
  {
    n += rgb[i] > 40 ? 1 : 0; // the background's red is 26
  }
  return n;
}

// Two windows of one kind: drawn, resized, one deleted, the other redrawn.
Pixels Exercise(const std::string& kind, const std::function<vtkRenderWindow*()>& make)
{
  vtkSmartPointer<vtkRenderWindow> a = vtkSmartPointer<vtkRenderWindow>::Take(make());
  vtkSmartPointer<vtkRenderWindow> b = vtkSmartPointer<vtkRenderWindow>::Take(make());
  Populate(a, false);
  Populate(b, true);
  const Pixels sphere = Draw(a, 64, 64);
  const Pixels cone = Draw(b, 80, 40);
  Check(sphere.size() == 64 * 64 * 3 && Covered(sphere) > 500,
    kind + ": the first window draws the sphere");
  Check(cone.size() == 80 * 40 * 3 && Covered(cone) > 200, kind + ": the second draws the cone");
  const Pixels wide = Draw(a, 96, 48);
  Check(wide.size() == 96 * 48 * 3 && Covered(wide) > 300, kind + ": a resized window draws");
  Check(Draw(a, 64, 64) == sphere, kind + ": resized back, the same pixels");
  a = nullptr; // torn down while the other lives
  Check(Draw(b, 80, 40) == cone, kind + ": the second window, alone, the same pixels");
  return sphere;
}
}

int TestHeadlessWindows(int, char*[])
{
  const bool egl = vtkBrumeEGLRenderWindow::IsAvailable();
  const bool osmesa = vtkBrumeOSMesaRenderWindow::IsAvailable();
  if (!egl)
  {
    std::cout << "EGL: " << vtkBrumeEGLRenderWindow::GetAvailabilityError() << "\n";
  }
  if (!osmesa)
  {
    std::cout << "OSMesa: " << vtkBrumeOSMesaRenderWindow::GetAvailabilityError() << "\n";
  }
  if (!egl && !osmesa)
  {
    std::cout << "skipped: neither EGL nor OSMesa can render here\n";
    return 125;
  }
  Pixels throughEGL, throughOSMesa;
  if (egl)
  {
    throughEGL = Exercise("EGL", [] { return vtkBrumeEGLRenderWindow::New(); });
  }
  if (osmesa)
  {
    throughOSMesa = Exercise("OSMesa", [] { return vtkBrumeOSMesaRenderWindow::New(); });
  }
  if (egl && osmesa)
  {
    // The same rasteriser (ctest runs this with Mesa's llvmpipe for both).
    Check(throughEGL == throughOSMesa, "EGL and OSMesa draw the same pixels");

    // One API's context current: the other's window refuses, draws nothing.
    ErrorCount errors, eglErrors; // outlive the windows that call them
    vtkNew<vtkBrumeEGLRenderWindow> first;
    vtkNew<vtkBrumeOSMesaRenderWindow> second;
    Populate(first, false);
    Populate(second, false);
    second->AddObserver(vtkCommand::ErrorEvent, errors.Command);
    Draw(first, 32, 32); // EGL's context stays current
    second->SetSize(32, 32);
    second->Render();
    Check(errors.Count > 0 && errors.Last.find("another OpenGL context") != std::string::npos,
      "an OSMesa window is refused while EGL's context is current (" + errors.Last + ")");
    Check(!second->IsCurrent(), "the refused window's context is not current");
    first->ReleaseCurrent();
    Check(Draw(second, 64, 64) == throughOSMesa, "released, the OSMesa window draws");
    Check(errors.Count == 1, "no error once the other context is released");

    first->AddObserver(vtkCommand::ErrorEvent, eglErrors.Command);
    first->Render(); // OSMesa's context is current
    Check(eglErrors.Count > 0 &&
        eglErrors.Last.find("Cannot make the EGL context current") != std::string::npos,
      "an EGL window is refused while OSMesa's context is current (" + eglErrors.Last + ")");
    second->ReleaseCurrent();
    Check(Draw(first, 64, 64) == throughEGL, "released, the EGL window draws");
    first->ReleaseCurrent(); // so that the OSMesa window is torn down cleanly
  }
  return Failures == 0 ? 0 : 1;
}
