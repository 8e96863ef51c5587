// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeHeadlessRenderWindow
 * @brief   an off-screen render window with no window system: EGL or OSMesa
 *
 * The common part of vtkBrumeEGLRenderWindow and vtkBrumeOSMesaRenderWindow:
 * an OpenGL 3.2 core context with a 1x1 default framebuffer, rendering off
 * screen into VTK's own framebuffers at any size, so that the pixels are
 * those of a window on X with the same driver. A subclass makes, binds and
 * destroys the context; this class runs VTK's OpenGL set-up on it.
 *
 * ParaView 5.11's VTK is built for X11/GLX, and its GLEW looks for a GLX
 * display after loading every OpenGL entry point; that last step's failure
 * is accepted here (OpenGL 3.2 is still required).
 *
 * @sa vtkBrumeRenderWindowSelection
 */
#ifndef vtkBrumeHeadlessRenderWindow_h
#define vtkBrumeHeadlessRenderWindow_h

#include "vtkBrumeRenderingOpenGL2Module.h" // For export macro
#include "vtkGenericOpenGLRenderWindow.h"

class VTKBRUMERENDERINGOPENGL2_EXPORT vtkBrumeHeadlessRenderWindow
  : public vtkGenericOpenGLRenderWindow
{
public:
  vtkTypeMacro(vtkBrumeHeadlessRenderWindow, vtkGenericOpenGLRenderWindow);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  void Initialize() override;
  void Finalize() override;
  void Render() override;
  void MakeCurrent() override;
  void ReleaseCurrent() override;
  bool IsCurrent() override;
  int SupportsOpenGL() override;
  vtkTypeBool IsDirect() override;
  void Frame() override;

  ///@{
  /**
   * Mesa tears EGL and OSMesa down in exit handlers of its own, registered
   * when a display or a first context is made; windows that outlive them
   * (ParaView deletes its process window from a static destructor) must
   * not call them then. A subclass calls WatchForExit() right after it has
   * initialized its library: the handler it registers runs before Mesa's,
   * and from then on IsExiting() is true and contexts are only forgotten.
   */
  static void WatchForExit();
  static bool IsExiting();
  ///@}

protected:
  vtkBrumeHeadlessRenderWindow();
  ~vtkBrumeHeadlessRenderWindow() override;

  /// GLEW's GLX-only failures are accepted: the context is not GLX's.
  void OpenGLInitContext() override;

  ///@{
  /**
   * The context, as the subclass makes it. CreateContext() and
   * MakeContextCurrent() report their own errors and return false (another
   * API's context current on the thread, say: nothing is drawn then);
   * DestroyContext() releases it first if it is current. A subclass's
   * destructor calls Finalize().
   */
  virtual const char* GetContextAPI() = 0; // "EGL", "OSMesa": for messages
  virtual bool CanCreateContext() = 0;
  virtual bool HasContext() = 0;
  virtual bool CreateContext() = 0;
  virtual void DestroyContext() = 0;
  virtual bool MakeContextCurrent() = 0;
  virtual void ReleaseContext() = 0;
  virtual bool IsContextCurrent() = 0;
  ///@}

private:
  bool Bind(); // the context current, made first if need be

  vtkBrumeHeadlessRenderWindow(const vtkBrumeHeadlessRenderWindow&) = delete;
  void operator=(const vtkBrumeHeadlessRenderWindow&) = delete;
};

#endif
