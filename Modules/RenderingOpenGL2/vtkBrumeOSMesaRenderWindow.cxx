// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeOSMesaRenderWindow.h"

#include "vtkObjectFactory.h"
#include "vtk_glew.h"

// OSMesa's types and constants (its functions are looked up at run time);
// GLEW's header leaves GLAPI undefined.
#ifndef GLAPI
#define GLAPI extern
#endif
#ifndef GLAPIENTRY
#define GLAPIENTRY
#endif
#include <GL/osmesa.h>

#include <dlfcn.h>

#include <cstdlib>
#include <cstring>
#include <mutex>
#include <string>

vtkStandardNewMacro(vtkBrumeOSMesaRenderWindow);

namespace
{
// libGLdispatch's thread state, ABI version 1 (glvnd's GLdispatch.h, which
// is not installed: the window-system libraries libGLX and libEGL are built
// with it). A thread with a current context has one; glvnd's libGLX and
// libEGL tag theirs 0 and 1 and leave a thread alone whose state is not
// theirs, so this tag keeps an OSMesa context and theirs apart.
struct DispatchThreadState
{
  int Tag;
  void (*ThreadDestroyed)(DispatchThreadState*);
  void* Private; // libGLdispatch's
};
struct DispatchTable;
constexpr int DispatchABIVersion = 1;
constexpr int OSMesaTag = 0x4f534d41; // "OSMA"

// This thread's state while one of these windows is current on it.
thread_local DispatchThreadState ThisThreadState{ OSMesaTag, nullptr, nullptr };

// Loads a symbol into a typed pointer; false (and Missing set) if absent.
template <typename F>
bool Load(void* library, const char* name, F& function, std::string& missing)
{
  function = reinterpret_cast<F>(dlsym(library, name));
  if (!function && missing.empty())
  {
    missing = name;
  }
  return function != nullptr;
}

// OSMesa's entry points and libGLdispatch's, loaded once per process.
struct OSMesaState
{
  std::string Library;
  std::string Error;

  OSMesaContext (*CreateContextAttribs)(const int*, OSMesaContext) = nullptr;
  GLboolean (*MakeCurrent)(OSMesaContext, void*, GLenum, GLsizei, GLsizei) = nullptr;
  OSMesaContext (*GetCurrentContext)() = nullptr;
  void (*DestroyContext)(OSMesaContext) = nullptr;
  OSMESAproc (*GetProcAddress)(const char*) = nullptr;

  int (*GetABIVersion)() = nullptr;
  void (*Init)() = nullptr;
  int (*NewVendorID)() = nullptr;
  DispatchTable* (*CreateTable)(void* (*)(const char*, void*), void*) = nullptr;
  GLboolean (*DispatchMakeCurrent)(
    DispatchThreadState*, DispatchTable*, int, const void*) = nullptr;
  void (*LoseCurrent)() = nullptr;
  DispatchThreadState* (*GetCurrentThreadState)() = nullptr;

  DispatchTable* Table = nullptr;
  int Vendor = 0;

  OSMesaContext NewContext() const
  {
    const int attributes[] = { OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24,
      OSMESA_STENCIL_BITS, 8, OSMESA_PROFILE, OSMESA_CORE_PROFILE, OSMESA_CONTEXT_MAJOR_VERSION, 3,
      OSMESA_CONTEXT_MINOR_VERSION, 2, 0 };
    return this->CreateContextAttribs(attributes, nullptr);
  }

  // Makes context current in OSMesa and, for this thread, in libglvnd; an
  // error message if another API's context is current on this thread.
  std::string Bind(OSMesaContext context, unsigned char* pixel) const
  {
    const DispatchThreadState* current = this->GetCurrentThreadState();
    if (current && current != &ThisThreadState)
    {
      return "another OpenGL context (EGL or GLX) is current on this thread";
    }
    if (this->GetCurrentContext() != context &&
      !this->MakeCurrent(context, pixel, GL_UNSIGNED_BYTE, 1, 1))
    {
      return "OSMesaMakeCurrent failed";
    }
    if (!current &&
      !this->DispatchMakeCurrent(&ThisThreadState, this->Table, this->Vendor, nullptr))
    {
      this->MakeCurrent(nullptr, nullptr, 0, 0, 0);
      return "libglvnd refused to make the OSMesa context current";
    }
    return std::string();
  }

  void Unbind() const
  {
    this->MakeCurrent(nullptr, nullptr, 0, 0, 0);
    if (this->GetCurrentThreadState() == &ThisThreadState)
    {
      this->LoseCurrent();
    }
  }

  bool IsBound(OSMesaContext context) const
  {
    return this->GetCurrentContext() == context &&
      this->GetCurrentThreadState() == &ThisThreadState;
  }
};

// libglvnd fills its dispatch table through this, lazily, by name.
void* LookUp(const char* name, void* state)
{
  return reinterpret_cast<void*>(static_cast<OSMesaState*>(state)->GetProcAddress(name));
}

std::string LoadLibraries(OSMesaState& s)
{
  const char* requested = std::getenv("BRUME_OSMESA_LIBRARY");
  s.Library = requested && *requested ? requested : "libOSMesa.so.8";
  void* osmesa = dlopen(s.Library.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!osmesa)
  {
    const char* why = dlerror();
    return "the OSMesa library could not be loaded (" + std::string(why ? why : s.Library) +
      "; Debian's is in libosmesa6, BRUME_OSMESA_LIBRARY names another)";
  }
  std::string missing;
  Load(osmesa, "OSMesaCreateContextAttribs", s.CreateContextAttribs, missing);
  Load(osmesa, "OSMesaMakeCurrent", s.MakeCurrent, missing);
  Load(osmesa, "OSMesaGetCurrentContext", s.GetCurrentContext, missing);
  Load(osmesa, "OSMesaDestroyContext", s.DestroyContext, missing);
  Load(osmesa, "OSMesaGetProcAddress", s.GetProcAddress, missing);
  if (!missing.empty())
  {
    return s.Library + " has no " + missing + ": it is not an OSMesa library with OpenGL 3.2";
  }
  // The process's OpenGL library must be libglvnd's, already loaded.
  void* dispatch = dlopen("libGLdispatch.so.0", RTLD_NOW | RTLD_NOLOAD);
  if (!dispatch)
  {
    return "this process's OpenGL library is not libglvnd's (libGLdispatch.so.0 is not "
           "loaded), so its OpenGL calls cannot be given to OSMesa";
  }
  Load(dispatch, "__glDispatchGetABIVersion", s.GetABIVersion, missing);
  Load(dispatch, "__glDispatchInit", s.Init, missing);
  Load(dispatch, "__glDispatchNewVendorID", s.NewVendorID, missing);
  Load(dispatch, "__glDispatchCreateTable", s.CreateTable, missing);
  Load(dispatch, "__glDispatchMakeCurrent", s.DispatchMakeCurrent, missing);
  Load(dispatch, "__glDispatchLoseCurrent", s.LoseCurrent, missing);
  Load(dispatch, "__glDispatchGetCurrentThreadState", s.GetCurrentThreadState, missing);
  if (!missing.empty())
  {
    return "libGLdispatch.so.0 has no " + missing;
  }
  if (s.GetABIVersion() != DispatchABIVersion)
  {
    return "libglvnd's dispatch ABI is version " + std::to_string(s.GetABIVersion()) +
      ", and Brume's OSMesa window knows version " + std::to_string(DispatchABIVersion);
  }
  s.Init();
  s.Vendor = s.NewVendorID();
  s.Table = s.CreateTable(LookUp, &s);
  return s.Table ? std::string() : "libglvnd could not make a dispatch table";
}

// Whether the process's own OpenGL calls reach an OSMesa context with
// OpenGL 3.2: made once, current long enough to ask, then destroyed.
std::string ProbeContext(OSMesaState& s)
{
  OSMesaContext context = s.NewContext();
  if (!context)
  {
    return "OSMesa could not make an OpenGL 3.2 core context";
  }
  vtkBrumeOSMesaRenderWindow::WatchForExit(); // after Mesa's own exit handler
  unsigned char pixel[4] = { 0, 0, 0, 0 };
  std::string error = s.Bind(context, pixel);
  if (error.empty())
  {
    using GetString = const GLubyte* (*)(GLenum);
    auto own = reinterpret_cast<GetString>(s.GetProcAddress("glGetString"));
    const GLubyte* theirs = own ? own(GL_RENDERER) : nullptr;
    const GLubyte* ours = glGetString(GL_RENDERER); // as VTK calls it
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    if (!theirs || !ours ||
      std::strcmp(reinterpret_cast<const char*>(theirs), reinterpret_cast<const char*>(ours)))
    {
      error = "this process's OpenGL calls do not reach the OSMesa context (glGetString "
              "answers '" +
        std::string(ours ? reinterpret_cast<const char*>(ours) : "nothing") + "', OSMesa '" +
        std::string(theirs ? reinterpret_cast<const char*>(theirs) : "nothing") + "')";
    }
    else if (major < 3 || (major == 3 && minor < 2))
    {
      error = "the OSMesa context offers OpenGL " + std::to_string(major) + "." +
        std::to_string(minor) + ", and Brume needs 3.2 or later";
    }
    s.Unbind();
  }
  s.DestroyContext(context);
  return error;
}

OSMesaState& Shared()
{
  static OSMesaState state;
  static std::once_flag once;
  std::call_once(once,
    []()
    {
      state.Error = LoadLibraries(state);
      if (state.Error.empty())
      {
        state.Error = ProbeContext(state);
      }
    });
  return state;
}
}

struct vtkBrumeOSMesaRenderWindow::Internals
{
  OSMesaContext Context = nullptr;
  unsigned char Pixel[4] = { 0, 0, 0, 0 }; // the 1x1 default framebuffer
};

vtkBrumeOSMesaRenderWindow::vtkBrumeOSMesaRenderWindow()
  : Impl(new Internals)
{
}

vtkBrumeOSMesaRenderWindow::~vtkBrumeOSMesaRenderWindow()
{
  this->Finalize();
}

bool vtkBrumeOSMesaRenderWindow::IsAvailable()
{
  return GetAvailabilityError().empty();
}

std::string vtkBrumeOSMesaRenderWindow::GetAvailabilityError()
{
  return Shared().Error;
}

bool vtkBrumeOSMesaRenderWindow::HasContext()
{
  // After OSMesa's exit handler, no context is left to use.
  return this->Impl->Context != nullptr && !IsExiting();
}

bool vtkBrumeOSMesaRenderWindow::CreateContext()
{
  const OSMesaState& s = Shared();
  if (!s.Error.empty())
  {
    vtkErrorMacro("Cannot render through OSMesa: " << s.Error << ".");
    return false;
  }
  this->Impl->Context = s.NewContext();
  if (!this->Impl->Context)
  {
    vtkErrorMacro("Cannot render through OSMesa: no OpenGL 3.2 core context could be made.");
    return false;
  }
  return true;
}

bool vtkBrumeOSMesaRenderWindow::MakeContextCurrent()
{
  const std::string error = Shared().Bind(this->Impl->Context, this->Impl->Pixel);
  if (!error.empty())
  {
    vtkErrorMacro("Cannot make the OSMesa context current: " << error << ".");
    return false;
  }
  return true;
}

void vtkBrumeOSMesaRenderWindow::ReleaseContext()
{
  Shared().Unbind();
}

bool vtkBrumeOSMesaRenderWindow::IsContextCurrent()
{
  return Shared().IsBound(this->Impl->Context);
}

void* vtkBrumeOSMesaRenderWindow::GetGenericContext()
{
  return this->Impl->Context;
}

void vtkBrumeOSMesaRenderWindow::DestroyContext()
{
  Internals& impl = *this->Impl;
  if (!impl.Context || IsExiting())
  {
    impl.Context = nullptr; // OSMesa is gone with the process
    return;
  }
  const OSMesaState& s = Shared();
  if (s.GetCurrentContext() == impl.Context)
  {
    s.Unbind();
  }
  s.DestroyContext(impl.Context);
  impl.Context = nullptr;
}

void vtkBrumeOSMesaRenderWindow::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Library: " << Shared().Library << "\n";
  os << indent << "Context: " << this->Impl->Context << "\n";
}
