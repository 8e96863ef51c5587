// SPDX-License-Identifier: BSD-3-Clause
// Run by ParaView when it loads the plugin (paraview_add_plugin's
// INITIALIZERS): chooses the process's render windows and, with a server
// manager, makes "Brume Radiance" follow the cameras (vtkBrumeCameraFollower).
#ifndef vtkBrumePluginStartup_h
#define vtkBrumePluginStartup_h

void BrumePluginStartup();

#endif
