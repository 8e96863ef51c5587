// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeEGLRenderWindow
 * @brief   an off-screen render window on EGL: rendering with no X server
 *
 * ParaView 5.11's VTK is built for X11/GLX. This window creates an OpenGL
 * 3.2 core context through EGL instead (Mesa's surfaceless platform, or
 * the device platform where EGL is NVIDIA's), with a 1x1 pbuffer as its
 * default framebuffer, and renders off screen into VTK's own framebuffers
 * at any size: the same pixels as a window on X with the same driver.
 * VTK's GLEW looks for a GLX display after loading every OpenGL entry
 * point; that last step's failure is accepted here (OpenGL 3.2 is still
 * required).
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

#include "vtkBrumeRenderingOpenGL2Module.h" // For export macro
#include "vtkGenericOpenGLRenderWindow.h"

#include <memory> // For the EGL state
#include <string> // For IsAvailable

class VTKBRUMERENDERINGOPENGL2_EXPORT vtkBrumeEGLRenderWindow : public vtkGenericOpenGLRenderWindow
{
public:
  static vtkBrumeEGLRenderWindow* New();
  vtkTypeMacro(vtkBrumeEGLRenderWindow, vtkGenericOpenGLRenderWindow);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Whether an EGL context with OpenGL 3.2 can be made on this machine;
   * otherwise GetAvailabilityError() says why not.
   */
  static bool IsAvailable();
  static std::string GetAvailabilityError();

  void Initialize() override;
  void Finalize() override;
  void Render() override;
  void MakeCurrent() override;
  void ReleaseCurrent() override;
  bool IsCurrent() override;
  int SupportsOpenGL() override;
  vtkTypeBool IsDirect() override;
  void Frame() override;
  void* GetGenericContext() override;

protected:
  vtkBrumeEGLRenderWindow();
  ~vtkBrumeEGLRenderWindow() override;

  /// GLEW's GLX-only failures are accepted: the context is EGL's.
  void OpenGLInitContext() override;

private:
  vtkBrumeEGLRenderWindow(const vtkBrumeEGLRenderWindow&) = delete;
  void operator=(const vtkBrumeEGLRenderWindow&) = delete;

  bool EnsureContext();
  struct Internals;
  std::unique_ptr<Internals> Impl;
};

#endif
