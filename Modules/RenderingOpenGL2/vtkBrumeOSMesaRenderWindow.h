// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeOSMesaRenderWindow
 * @brief   an off-screen render window on Mesa's OSMesa: rendering with no
 *          X server and no EGL
 *
 * OSMesa renders in software (llvmpipe) into memory of the process, with no
 * window system and no device at all. This window makes an OpenGL 3.2 core
 * context with it (a 1x1 buffer as its default framebuffer) and renders off
 * screen into VTK's own framebuffers at any size: the same pixels as a
 * window on X or EGL with the same driver (vtkBrumeHeadlessRenderWindow).
 *
 * ParaView 5.11's VTK makes its OpenGL calls through libglvnd (libGL,
 * libOpenGL), which forwards them to whichever vendor made its context
 * current; Debian's libOSMesa dispatches through Mesa's own libglapi and is
 * no glvnd vendor, so VTK's calls would reach glvnd's no-op stubs. This
 * window therefore makes its context current in libglvnd itself, as glvnd's
 * libGLX and libEGL do for theirs, with a dispatch table filled from
 * OSMesaGetProcAddress (libGLdispatch's ABI version 1, the one libGLX and
 * libEGL check). Nothing is interposed and no symbol order is assumed:
 * libOSMesa is loaded (dlopen, local symbols) only when this window is
 * asked for, and a process that never asks is untouched.
 *
 * The library is `libOSMesa.so.8` (Debian's libosmesa6), or the file named
 * by BRUME_OSMESA_LIBRARY. Before the first window, IsAvailable() makes a
 * context once and checks that the process's own OpenGL calls reach it
 * (glGetString answers as OSMesa does); if they do not — a libGL that is
 * not glvnd's, an OSMesa without OpenGL 3.2 — GetAvailabilityError() says
 * why, and no window is made rather than one that draws black. An EGL or
 * GLX context current on the same thread is refused the same way.
 *
 * Programs get it through the object factory: vtkBrumeRenderWindowSelection
 * makes vtkRenderWindow::New() return it when BRUME_RENDER_WINDOW=osmesa.
 *
 * @sa vtkBrumeRenderWindowSelection vtkBrumeEGLRenderWindow
 */
#ifndef vtkBrumeOSMesaRenderWindow_h
#define vtkBrumeOSMesaRenderWindow_h

#include "vtkBrumeHeadlessRenderWindow.h"
#include "vtkBrumeRenderingOpenGL2Module.h" // For export macro

#include <memory> // For the OSMesa state
#include <string> // For GetAvailabilityError

class VTKBRUMERENDERINGOPENGL2_EXPORT vtkBrumeOSMesaRenderWindow
  : public vtkBrumeHeadlessRenderWindow
{
public:
  static vtkBrumeOSMesaRenderWindow* New();
  vtkTypeMacro(vtkBrumeOSMesaRenderWindow, vtkBrumeHeadlessRenderWindow);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Whether OSMesa is installed and serves this process's OpenGL calls with
   * OpenGL 3.2; otherwise GetAvailabilityError() says why not. The first
   * call loads the library and checks it, once per process.
   */
  static bool IsAvailable();
  static std::string GetAvailabilityError();

  void* GetGenericContext() override;

protected:
  vtkBrumeOSMesaRenderWindow();
  ~vtkBrumeOSMesaRenderWindow() override;

  const char* GetContextAPI() override { return "OSMesa"; }
  bool CanCreateContext() override { return IsAvailable(); }
  bool HasContext() override;
  bool CreateContext() override;
  void DestroyContext() override;
  bool MakeContextCurrent() override;
  void ReleaseContext() override;
  bool IsContextCurrent() override;

private:
  vtkBrumeOSMesaRenderWindow(const vtkBrumeOSMesaRenderWindow&) = delete;
  void operator=(const vtkBrumeOSMesaRenderWindow&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Impl;
};

#endif
