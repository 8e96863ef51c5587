// SPDX-License-Identifier: BSD-3-Clause
// When ParaView loads the plugin, the process's render windows are chosen
// as in every Brume program (vtkBrumeRenderWindowSelection): on a machine
// with no X display, pvbatch and pvpython render through EGL (or OSMesa
// with BRUME_RENDER_WINDOW=osmesa) instead of failing to open an X window.
// ParaView 5.11 makes its batch render windows through
// vtkRenderWindow::New(), after the script's LoadPlugin().
// Where the process has a server manager (the GUI, pvpython, pvbatch), the
// "Brume Radiance" representations follow their views' cameras from the
// client side (vtkBrumeCameraFollower), and a Brume Render View that
// replaces a view takes what it showed (vtkBrumeRenderViewInitializationHelper).
#include "vtkBrumePluginStartup.h"

#include "vtkBrumeCameraFollower.h"
#include "vtkBrumeRenderViewInitializationHelper.h"
#include "vtkBrumeRenderWindowSelection.h"
#include "vtkBrumeSMP.h"
#include "vtkOutputWindow.h"

#include <string>

void BrumePluginStartup()
{
  if (!vtkBrumeRenderWindowSelection::Install())
  {
    vtkOutputWindow::GetInstance()->DisplayWarningText(
      ("Brume: " + std::string(vtkBrumeRenderWindowSelection::GetLastError()) + ".\n").c_str());
  }
  vtkBrumeCameraFollower::Install();
  // A Brume Render View made by "Convert To" shows what the view it
  // replaces showed.
  vtkBrumeRenderViewInitializationHelper::Install();
  // Debian's ParaView leaves vtkSMPTools on its Sequential backend: every
  // phase would run on one core.
  vtkBrumeSMP::UseAllCoresUnlessChosen();
}
