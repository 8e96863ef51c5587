// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeEGLRenderWindow.h"

#include "vtkObjectFactory.h"
#include "vtk_glew.h"

// EGL without X11 types: this window never talks to an X server.
#define EGL_NO_X11
#define MESA_EGL_NO_X11_HEADERS
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstring>
#include <mutex>
#include <sstream>
#include <string>

vtkStandardNewMacro(vtkBrumeEGLRenderWindow);

namespace
{
// One EGL display for the process (initialized once, never terminated:
// other windows' contexts live on it).
struct EGLState
{
  EGLDisplay Handle = EGL_NO_DISPLAY;
  EGLConfig Config = nullptr;
  std::string Error;
};

// The device platform where EGL is NVIDIA's (a GPU without a display),
// else Mesa's surfaceless platform, else the default display.
EGLDisplay OpenDisplay()
{
  auto getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
    eglGetProcAddress("eglGetPlatformDisplayEXT"));
  const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  auto has = [&](const char* name)
  { return clientExtensions && std::strstr(clientExtensions, name) != nullptr; };
  if (getPlatformDisplay && has("EGL_EXT_platform_device"))
  {
    auto queryDevices =
      reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    auto queryDeviceString = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(
      eglGetProcAddress("eglQueryDeviceStringEXT"));
    EGLDeviceEXT devices[16];
    EGLint count = 0;
    if (queryDevices && queryDevices(16, devices, &count))
    {
      for (EGLint d = 0; d < count; ++d)
      {
        // A hardware device: one that names a DRM node and is not Mesa's
        // software device (surfaceless is preferred for that one).
        const char* extensions =
          queryDeviceString ? queryDeviceString(devices[d], EGL_EXTENSIONS) : nullptr;
        if (extensions && std::strstr(extensions, "EGL_EXT_device_drm") &&
          !std::strstr(extensions, "EGL_MESA_device_software"))
        {
          EGLDisplay display = getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[d], nullptr);
          if (display != EGL_NO_DISPLAY)
          {
            return display;
          }
        }
      }
    }
  }
  if (getPlatformDisplay && has("EGL_MESA_platform_surfaceless"))
  {
    EGLDisplay display =
      getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display != EGL_NO_DISPLAY)
    {
      return display;
    }
  }
  return eglGetDisplay(EGL_DEFAULT_DISPLAY);
}

const EGLint ContextAttributes[] = { EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 2,
  EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE };
const EGLint SurfaceAttributes[] = { EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE };

std::string EGLError(const char* what)
{
  std::ostringstream os;
  os << what << " (EGL error 0x" << std::hex << eglGetError() << ")";
  return os.str();
}

// Whether an OpenGL 3.2 core context really starts here: made once, current
// long enough to ask its version, then destroyed.
std::string ProbeContext(EGLDisplay display, EGLConfig config)
{
  EGLSurface surface = eglCreatePbufferSurface(display, config, SurfaceAttributes);
  if (surface == EGL_NO_SURFACE)
  {
    return EGLError("no EGL pbuffer could be made");
  }
  EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, ContextAttributes);
  std::string error;
  if (context == EGL_NO_CONTEXT)
  {
    error = EGLError("no OpenGL 3.2 core context could be made through EGL");
  }
  else if (!eglMakeCurrent(display, surface, surface, context))
  {
    error = EGLError("the EGL context could not be made current");
  }
  else
  {
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    if (major < 3 || (major == 3 && minor < 2))
    {
      error = "the EGL context offers OpenGL " + std::to_string(major) + "." +
        std::to_string(minor) + ", and Brume needs 3.2 or later";
    }
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  }
  if (context != EGL_NO_CONTEXT)
  {
    eglDestroyContext(display, context);
  }
  eglDestroySurface(display, surface);
  return error;
}

EGLState& SharedDisplay()
{
  static EGLState display;
  static std::once_flag once;
  std::call_once(once,
    []()
    {
      display.Handle = OpenDisplay();
      EGLint major = 0, minor = 0;
      if (display.Handle == EGL_NO_DISPLAY || !eglInitialize(display.Handle, &major, &minor))
      {
        display.Error = "no EGL display could be initialized (is Mesa's libegl-mesa0, or a "
                        "GPU driver's EGL, installed?)";
        display.Handle = EGL_NO_DISPLAY;
        return;
      }
      vtkBrumeHeadlessRenderWindow::WatchForExit(); // after Mesa's own exit handler
      if (!eglBindAPI(EGL_OPENGL_API))
      {
        display.Error = "this EGL does not offer desktop OpenGL";
        return;
      }
      const EGLint attributes[] = { EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RED_SIZE, 8,
        EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8, EGL_ALPHA_SIZE, 8, EGL_DEPTH_SIZE, 24,
        EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE };
      EGLint count = 0;
      if (!eglChooseConfig(display.Handle, attributes, &display.Config, 1, &count) || count < 1)
      {
        display.Error = "no EGL configuration offers an RGBA, depth-buffered OpenGL pbuffer";
        return;
      }
      display.Error = ProbeContext(display.Handle, display.Config);
    });
  return display;
}
}

struct vtkBrumeEGLRenderWindow::Internals
{
  EGLContext Context = EGL_NO_CONTEXT;
  EGLSurface Surface = EGL_NO_SURFACE;
};

vtkBrumeEGLRenderWindow::vtkBrumeEGLRenderWindow()
  : Impl(new Internals)
{
}

vtkBrumeEGLRenderWindow::~vtkBrumeEGLRenderWindow()
{
  this->Finalize();
}

bool vtkBrumeEGLRenderWindow::IsAvailable()
{
  return GetAvailabilityError().empty();
}

std::string vtkBrumeEGLRenderWindow::GetAvailabilityError()
{
  const EGLState& display = SharedDisplay();
  return display.Error;
}

bool vtkBrumeEGLRenderWindow::HasContext()
{
  // After EGL's exit handler, no context is left to use.
  return this->Impl->Context != EGL_NO_CONTEXT && !IsExiting();
}

bool vtkBrumeEGLRenderWindow::CreateContext()
{
  Internals& impl = *this->Impl;
  const EGLState& display = SharedDisplay();
  if (!display.Error.empty())
  {
    vtkErrorMacro("Cannot render through EGL: " << display.Error << ".");
    return false;
  }
  // A 1x1 pbuffer gives framebuffer 0 a colour buffer; VTK renders into
  // framebuffers of its own at the window's size.
  impl.Surface = eglCreatePbufferSurface(display.Handle, display.Config, SurfaceAttributes);
  if (impl.Surface == EGL_NO_SURFACE)
  {
    vtkErrorMacro("Cannot render through EGL: " << EGLError("no pbuffer could be made") << ".");
    return false;
  }
  eglBindAPI(EGL_OPENGL_API);
  impl.Context =
    eglCreateContext(display.Handle, display.Config, EGL_NO_CONTEXT, ContextAttributes);
  if (impl.Context == EGL_NO_CONTEXT)
  {
    vtkErrorMacro(
      "Cannot render through EGL: " << EGLError("no OpenGL 3.2 core context could be made") << ".");
    this->DestroyContext();
    return false;
  }
  return true;
}

bool vtkBrumeEGLRenderWindow::MakeContextCurrent()
{
  const Internals& impl = *this->Impl;
  eglBindAPI(EGL_OPENGL_API); // per thread: this thread may be on another API
  if (eglGetCurrentContext() != impl.Context &&
    !eglMakeCurrent(SharedDisplay().Handle, impl.Surface, impl.Surface, impl.Context))
  {
    vtkErrorMacro("Cannot make the EGL context current: "
      << EGLError("eglMakeCurrent failed; is another API's context (OSMesa, GLX) current on "
                  "this thread?")
      << ".");
    return false;
  }
  return true;
}

void vtkBrumeEGLRenderWindow::ReleaseContext()
{
  eglMakeCurrent(SharedDisplay().Handle, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
}

bool vtkBrumeEGLRenderWindow::IsContextCurrent()
{
  eglBindAPI(EGL_OPENGL_API);
  return eglGetCurrentContext() == this->Impl->Context;
}

void* vtkBrumeEGLRenderWindow::GetGenericContext()
{
  return this->Impl->Context;
}

void vtkBrumeEGLRenderWindow::DestroyContext()
{
  Internals& impl = *this->Impl;
  if ((impl.Context == EGL_NO_CONTEXT && impl.Surface == EGL_NO_SURFACE) || IsExiting())
  {
    impl.Context = EGL_NO_CONTEXT; // EGL is gone with the process
    impl.Surface = EGL_NO_SURFACE;
    return;
  }
  const EGLDisplay display = SharedDisplay().Handle;
  if (impl.Context != EGL_NO_CONTEXT && eglGetCurrentContext() == impl.Context)
  {
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  }
  if (impl.Context != EGL_NO_CONTEXT)
  {
    eglDestroyContext(display, impl.Context);
  }
  if (impl.Surface != EGL_NO_SURFACE)
  {
    eglDestroySurface(display, impl.Surface);
  }
  impl.Context = EGL_NO_CONTEXT;
  impl.Surface = EGL_NO_SURFACE;
}

void vtkBrumeEGLRenderWindow::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Context: " << this->Impl->Context << "\n";
}
