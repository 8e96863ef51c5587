// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeHeadlessRenderWindow.h"

#include "vtkOpenGLState.h"
#include "vtk_glew.h"

#include <atomic>
#include <cstdlib>

namespace
{
std::atomic<bool> Exiting{ false };

void MarkExiting()
{
  Exiting = true;
}
}

void vtkBrumeHeadlessRenderWindow::WatchForExit()
{
  std::atexit(MarkExiting);
}

bool vtkBrumeHeadlessRenderWindow::IsExiting()
{
  return Exiting;
}

vtkBrumeHeadlessRenderWindow::vtkBrumeHeadlessRenderWindow()
{
  this->SetOffScreenRendering(1);
  this->OwnContext = 1;
}

vtkBrumeHeadlessRenderWindow::~vtkBrumeHeadlessRenderWindow() = default;

bool vtkBrumeHeadlessRenderWindow::Bind()
{
  if (!this->HasContext() && !this->CreateContext())
  {
    return false; // the error is reported
  }
  return this->IsContextCurrent() || this->MakeContextCurrent();
}

void vtkBrumeHeadlessRenderWindow::Initialize()
{
  if (this->Bind() && !this->Initialized)
  {
    this->OpenGLInit();
  }
}

void vtkBrumeHeadlessRenderWindow::Render()
{
  // Nothing is drawn where the context cannot be made current: the error
  // says why, and no other context is drawn into instead.
  if (!this->Bind())
  {
    return;
  }
  if (!this->Initialized)
  {
    this->OpenGLInit();
    if (!this->Initialized)
    {
      return; // the error is reported
    }
  }
  this->Superclass::Render();
}

void vtkBrumeHeadlessRenderWindow::OpenGLInitContext()
{
  this->ContextCreationTime.Modified();
  if (this->Initialized)
  {
    return;
  }
  // GLEW loads every OpenGL entry point, then looks for a GLX display:
  // GLEW_ERROR_GLX_VERSION_11_ONLY (3) and GLEW_ERROR_NO_GLX_DISPLAY (4)
  // say only that there is no GLX, which this window does not use.
  const GLenum result = glewInit();
  if (result != GLEW_OK && result != GLEW_ERROR_GLX_VERSION_11_ONLY &&
    result != GLEW_ERROR_NO_GLX_DISPLAY)
  {
    vtkErrorMacro("GLEW could not be initialized on the "
      << this->GetContextAPI()
      << " context: " << reinterpret_cast<const char*>(glewGetErrorString(result)));
    return;
  }
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  if (major < 3 || (major == 3 && minor < 2))
  {
    vtkErrorMacro("The " << this->GetContextAPI() << " context offers OpenGL " << major << "."
                         << minor << ", and Brume needs 3.2 or later.");
    return;
  }
  this->GlewInitValid = true;
  this->Initialized = true;
  GLfloat range[2] = { 1.f, 1.f };
  glGetFloatv(GL_ALIASED_LINE_WIDTH_RANGE, range);
  this->MaximumHardwareLineWidth = glGetError() == GL_NO_ERROR ? range[1] : 1.f;
}

void vtkBrumeHeadlessRenderWindow::MakeCurrent()
{
  if (this->HasContext())
  {
    this->MakeContextCurrent();
  }
}

void vtkBrumeHeadlessRenderWindow::ReleaseCurrent()
{
  if (this->IsCurrent())
  {
    this->ReleaseContext();
  }
}

bool vtkBrumeHeadlessRenderWindow::IsCurrent()
{
  return this->HasContext() && this->IsContextCurrent();
}

int vtkBrumeHeadlessRenderWindow::SupportsOpenGL()
{
  return this->CanCreateContext() ? 1 : 0;
}

vtkTypeBool vtkBrumeHeadlessRenderWindow::IsDirect()
{
  return 1;
}

void vtkBrumeHeadlessRenderWindow::Frame()
{
  // Off screen: VTK's framebuffers hold the image; nothing to swap.
  this->MakeCurrent();
  this->Superclass::Frame();
}

void vtkBrumeHeadlessRenderWindow::Finalize()
{
  // With another API's context current on the thread, VTK's objects are not
  // released into it (that would delete its objects): destroying this
  // context frees theirs.
  if (this->HasContext() && (this->IsContextCurrent() || this->MakeContextCurrent()))
  {
    this->ReleaseGraphicsResources(this);
  }
  this->DestroyContext();
  this->Initialized = false;
}

void vtkBrumeHeadlessRenderWindow::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Context API: " << this->GetContextAPI() << "\n";
  os << indent << "Has a context: " << (this->HasContext() ? "yes" : "no") << "\n";
}
