// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeEGLRenderWindow
 * @brief   an off-screen render window on EGL: rendering with no X server
 *
 * ParaView 5.11's VTK is built for X11/GLX. This window creates an OpenGL
 * 3.2 core context through EGL instead (Mesa's surfaceless platform, or
 * the device platform where EGL is NVIDIA's), with a 1x1 pbuffer as its
 * default framebuffer, and renders off screen into VTK's own framebuffers
 * at any size: the same pixels as a window on X with the same driver
 * (vtkBrumeHeadlessRenderWindow).
 *
 * Programs get it through the object factory: vtkBrumeRenderWindowSelection
 * makes vtkRenderWindow::New() return it when there is no DISPLAY (or when
 * BRUME_RENDER_WINDOW=egl). It cannot show anything on a screen and has no
 * interactor.
 *
 * @sa vtkBrumeRenderWindowSelection
 */
#ifndef vtkBrumeEGLRenderWindow_h
#define vtkBrumeEGLRenderWindow_h

#include "vtkBrumeHeadlessRenderWindow.h"
#include "vtkBrumeRenderingOpenGL2Module.h" // For export macro

#include <memory> // For the EGL state
#include <string> // For GetAvailabilityError

class VTKBRUMERENDERINGOPENGL2_EXPORT vtkBrumeEGLRenderWindow : public vtkBrumeHeadlessRenderWindow
{
public:
  static vtkBrumeEGLRenderWindow* New();
  vtkTypeMacro(vtkBrumeEGLRenderWindow, vtkBrumeHeadlessRenderWindow);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Whether an EGL context with OpenGL 3.2 can be made on this machine;
   * otherwise GetAvailabilityError() says why not.
   */
  static bool IsAvailable();
  static std::string GetAvailabilityError();

  void* GetGenericContext() override;

protected:
  vtkBrumeEGLRenderWindow();
  ~vtkBrumeEGLRenderWindow() override;

  const char* GetContextAPI() override { return "EGL"; }
  bool CanCreateContext() override { return IsAvailable(); }
  bool HasContext() override;
  bool CreateContext() override;
  void DestroyContext() override;
  bool MakeContextCurrent() override;
  void ReleaseContext() override;
  bool IsContextCurrent() override;

private:
  vtkBrumeEGLRenderWindow(const vtkBrumeEGLRenderWindow&) = delete;
  void operator=(const vtkBrumeEGLRenderWindow&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Impl;
};

#endif
