// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeRenderWindowSelection
 * @brief   which render window vtkRenderWindow::New() makes: X, EGL or OSMesa
 *
 * Brume renders on machines with an X server (VTK's own window) and on
 * machines with none at all (cluster nodes, containers, CI) through
 * vtkBrumeEGLRenderWindow or vtkBrumeOSMesaRenderWindow. Install() chooses
 * once per process and puts the choice in VTK's object factory, so that
 * every vtkRenderWindow::New() of the process, Brume's and VTK's own
 * (charts, context views), gets it:
 *
 * - `BRUME_RENDER_WINDOW=x`, `egl` or `osmesa` chooses (the `brume`
 *   program's `--window` too); `auto` (or unset) takes X when DISPLAY names
 *   a display and EGL otherwise;
 * - an unknown value, or EGL or OSMesa chosen where no context of theirs
 *   can be made (a library missing, a driver without OpenGL 3.2), is an
 *   error (GetLastError()), and the factory is left as it was.
 *
 * The `brume` program, its tests, the Python package and the ParaView
 * plugin call Install() at start-up; a C++ program of yours may call it
 * before it makes a window.
 *
 * @code{.py}
 * import brume   # installs the choice
 * print(brume.vtkBrumeRenderWindowSelection.GetInstalled())   # "x", "egl" or "osmesa"
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
   * Chooses the window kind ("x", "egl", "osmesa" or "auto"; without one,
   * BRUME_RENDER_WINDOW, else "auto") and installs it. Returns true on
   * success; a second call changes nothing and returns the first's result.
   */
  static bool Install();
  static bool Install(const char* kind);
  ///@}

  /// The kind installed: "x", "egl", "osmesa", or "" before Install() or after a failure.
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
