// SPDX-License-Identifier: BSD-3-Clause
// What Brume checks in a file a scene names before VTK's reader sees it
// (private to Brume::IO): VTK's readers trust the sizes and indices a file
// announces, and a malformed file crashes them or makes them allocate what
// no machine holds. Each check is true when the file may be read, otherwise
// false with `error` saying what is wrong (the file's name, then why).
#ifndef vtkBrumeSceneFileChecks_h
#define vtkBrumeSceneFileChecks_h

#include <filesystem>
#include <string>

class vtkXMLReader;
class vtkXMLUnstructuredDataReader;

class vtkBrumeSceneFileChecks
{
public:
  /// PLY: the header's grammar, the elements VTK's reader assumes (vertex
  /// x, y, z; the faces' vertex_indices), the bytes its counts need, and,
  /// row by row, that every face indexes only the vertices.
  static bool Ply(const std::filesystem::path& file, std::string& error);
  /// OBJ: three numeric coordinates per vertex, and every face, line and
  /// point entry v, v/t, v//n or v/t/n naming what is defined above it.
  static bool Obj(const std::filesystem::path& file, std::string& error);
  /// Binary STL: 84 + 50 n bytes for the n triangles its header announces.
  static bool Stl(const std::filesystem::path& file, std::string& error);
  /// VTP and VTU: XmlArrays(), then from the same header parse: the
  /// points and cells fit in memory and, uncompressed, in the file.
  static bool VtkXml(
    vtkXMLUnstructuredDataReader* reader, const std::filesystem::path& file, std::string& error);
  /**
   * Any VTK XML file (VTI, VTP, VTU) `reader` is given the name of, from
   * its header parse alone (UpdateInformation(), which sets up no array),
   * before it reads data: every array announces 1 to MaxComponents
   * components, and all of them (components x the piece's points or cells
   * x the type's size) fit in memory and in what the file can hold. A file
   * the reader cannot parse passes (its Update() fails).
   */
  static bool XmlArrays(
    vtkXMLReader* reader, const std::filesystem::path& file, std::string& error);
  /// The most components an array of a file a scene names may announce.
  static constexpr double MaxComponents = 256.0;
  /// What a file's announced sizes may ask for: half of this machine's
  /// physical memory, in bytes (0 when it cannot be told).
  static double UsableMemory();
  /// A count as the messages write it (every digit, no exponent below 10^15).
  static std::string Count(double n);
};

#endif
