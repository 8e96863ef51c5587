// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeRenderWindowSelection.h"

#include "vtkBrumeEGLRenderWindow.h"
#include "vtkBrumeOSMesaRenderWindow.h"
#include "vtkGenericRenderWindowInteractor.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkVersion.h"

#include <cstdlib>
#include <mutex>
#include <string>

vtkStandardNewMacro(vtkBrumeRenderWindowSelection);

namespace
{
vtkObject* NewEGLWindow()
{
  return vtkBrumeEGLRenderWindow::New();
}

vtkObject* NewOSMesaWindow()
{
  return vtkBrumeOSMesaRenderWindow::New();
}

vtkObject* NewInteractor()
{
  return vtkGenericRenderWindowInteractor::New();
}

// Gives vtkRenderWindow::New() a window with no window system.
class HeadlessWindowFactory : public vtkObjectFactory
{
public:
  static HeadlessWindowFactory* New()
  {
    auto* factory = new HeadlessWindowFactory;
    factory->InitializeObjectBase();
    return factory;
  }
  vtkTypeMacro(HeadlessWindowFactory, vtkObjectFactory);
  const char* GetVTKSourceVersion() override { return VTK_SOURCE_VERSION; }
  const char* GetDescription() override
  {
    return "Brume: render windows with no window system (EGL or OSMesa)";
  }

  void Override(bool osmesa)
  {
    if (osmesa)
    {
      this->RegisterOverride("vtkRenderWindow", "vtkBrumeOSMesaRenderWindow",
        "an off-screen OpenGL window on OSMesa", 1, NewOSMesaWindow);
    }
    else
    {
      this->RegisterOverride("vtkRenderWindow", "vtkBrumeEGLRenderWindow",
        "an off-screen OpenGL window on EGL", 1, NewEGLWindow);
    }
    // Windows that get an interactor (charts' context views) must not open
    // an X connection for it.
    this->RegisterOverride("vtkRenderWindowInteractor", "vtkGenericRenderWindowInteractor",
      "an interactor with no window system", 1, NewInteractor);
  }

protected:
  HeadlessWindowFactory() = default;
};

struct Selection
{
  std::mutex Mutex;
  bool Done = false;
  bool Ok = false;
  std::string Installed;
  std::string Error;
};

Selection& State()
{
  static Selection selection;
  return selection;
}

bool Choose(const std::string& requested, Selection& s)
{
  std::string kind = requested.empty() ? "auto" : requested;
  if (kind != "auto" && kind != "x" && kind != "egl" && kind != "osmesa")
  {
    s.Error = "the render window must be 'x', 'egl', 'osmesa' or 'auto', not '" + kind + "'";
    return false;
  }
  const char* display = std::getenv("DISPLAY");
  const bool hasDisplay = display && *display;
  if (kind == "auto")
  {
    kind = hasDisplay ? "x" : "egl";
  }
  if (kind == "x" && !hasDisplay)
  {
    // VTK's X window would abort the process on its first render.
    s.Error = "the X window needs an X display, and DISPLAY is not set (egl and osmesa need "
              "none)";
    return false;
  }
  if (kind == "x")
  {
    s.Installed = "x"; // VTK's own window, as the factory has it
    return true;
  }
  const bool osmesa = kind == "osmesa";
  if (osmesa && !vtkBrumeOSMesaRenderWindow::IsAvailable())
  {
    s.Error = "OSMesa cannot render here: " + vtkBrumeOSMesaRenderWindow::GetAvailabilityError();
    return false;
  }
  if (!osmesa && !vtkBrumeEGLRenderWindow::IsAvailable())
  {
    s.Error = requested == "egl"
      ? "EGL cannot render here: " + vtkBrumeEGLRenderWindow::GetAvailabilityError()
      : "no X display and no EGL: " + vtkBrumeEGLRenderWindow::GetAvailabilityError();
    return false;
  }
  vtkNew<HeadlessWindowFactory> factory;
  factory->Override(osmesa);
  vtkObjectFactory::RegisterFactory(factory);
  // VTK's X window must not come first.
  vtkObjectFactory::SetAllEnableFlags(0, "vtkRenderWindow", "vtkXOpenGLRenderWindow");
  vtkObjectFactory::SetAllEnableFlags(0, "vtkRenderWindowInteractor", "vtkXRenderWindowInteractor");
  s.Installed = kind;
  return true;
}
}

bool vtkBrumeRenderWindowSelection::Install()
{
  const char* kind = std::getenv("BRUME_RENDER_WINDOW");
  return Install(kind ? kind : "");
}

bool vtkBrumeRenderWindowSelection::Install(const char* kind)
{
  Selection& s = State();
  std::lock_guard<std::mutex> lock(s.Mutex);
  if (!s.Done)
  {
    s.Done = true;
    s.Ok = Choose(kind ? kind : "", s);
  }
  return s.Ok;
}

const char* vtkBrumeRenderWindowSelection::GetInstalled()
{
  return State().Installed.c_str();
}

const char* vtkBrumeRenderWindowSelection::GetLastError()
{
  return State().Error.c_str();
}
