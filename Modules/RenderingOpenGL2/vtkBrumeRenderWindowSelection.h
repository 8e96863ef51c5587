// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeRenderWindowSelection
 * @brief   which render window vtkRenderWindow::New() makes: X or EGL
 *
 * Brume renders on machines with an X server (VTK's own window) and on
 * machines with none at all (cluster nodes, containers, CI) through
 * vtkBrumeEGLRenderWindow. Install() chooses once per process and puts the
 * choice in VTK's object factory, so that every vtkRenderWindow::New() of
 * the process, Brume's and VTK's own (charts, context views), gets it:
 *
 * - `BRUME_RENDER_WINDOW=x` or `egl` chooses; `auto` (or unset) takes X
 *   when DISPLAY names a display and EGL otherwise;
 * - an unknown value, or EGL chosen where no EGL context can be made, is an
 *   error (GetLastError()), and the factory is left as it was.
 *
 * The `brume` program, its tests and the Python package call Install() at
 * start-up; a C++ program of yours may call it before it makes a window.
 * OSMesa is not offered: Debian's libOSMesa does not dispatch through glvnd,
 * so it cannot serve VTK's direct OpenGL calls in a process that also links
 * libOpenGL (see the README).
 *
 * @code{.py}
 * import brume   # installs the choice
 * print(brume.vtkBrumeRenderWindowSelection.GetInstalled())   # "x" or "egl"
 * @endcode
 */
#ifndef vtkBrumeRenderWindowSelection_h
#define vtkBrumeRenderWindowSelection_h

#include "vtkBrumeRenderingOpenGL2Module.h" // For export macro
#include "vtkObject.h"

class VTKBRUMERENDERINGOPENGL2_EXPORT vtkBrumeRenderWindowSelection : public vtkObject
{
public:
  static vtkBrumeRenderWindowSelection* New();
  vtkTypeMacro(vtkBrumeRenderWindowSelection, vtkObject);

  ///@{
  /**
   * Chooses the window kind ("x", "egl" or "auto"; without one,
   * BRUME_RENDER_WINDOW, else "auto") and installs it. Returns true on
   * success; a second call changes nothing and returns the first's result.
   */
  static bool Install();
  static bool Install(const char* kind);
  ///@}

  /// The kind installed: "x", "egl", or "" before Install() or after a failure.
  static const char* GetInstalled();

  /// Why the last Install() failed ("" if it did not).
  static const char* GetLastError();

protected:
  vtkBrumeRenderWindowSelection() = default;
  ~vtkBrumeRenderWindowSelection() override = default;

private:
  vtkBrumeRenderWindowSelection(const vtkBrumeRenderWindowSelection&) = delete;
  void operator=(const vtkBrumeRenderWindowSelection&) = delete;
};

#endif
