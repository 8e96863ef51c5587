// SPDX-License-Identifier: BSD-3-Clause
// Surface files named by scene files (private to Brume::IO): .obj, .ply,
// .stl, .vtp and .vtu through VTK's readers, after the checks of
// vtkBrumeSceneFileChecks.
#ifndef vtkBrumeSceneGeometry_h
#define vtkBrumeSceneGeometry_h

#include "vtkSmartPointer.h"

#include <filesystem>
#include <string>

class vtkPolyData;

class vtkBrumeSceneGeometry
{
public:
  /// The surface in `file`; null with `error` set when it cannot be read.
  static vtkSmartPointer<vtkPolyData> Read(const std::filesystem::path& file, std::string& error);
};

#endif
