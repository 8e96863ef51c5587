// SPDX-License-Identifier: BSD-3-Clause
// Surface files named by scene files (private to Brume::IO): .obj, .ply,
// .stl, .vtp and .vtu through VTK's readers, with the checks that keep a
// truncated or corrupt file, or one whose header announces more than the
// file or this machine's memory can hold, from reaching them.
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
  /// What a file's announced sizes may ask for: half of this machine's
  /// physical memory, in bytes (0 when it cannot be told).
  static double UsableMemory();
};

#endif
