// SPDX-License-Identifier: BSD-3-Clause
// The check of binary STL files (vtkBrumeSceneFileChecks.h).
#include "vtkBrumeSceneFileChecks.h"

#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>

namespace
{
std::string Count(double n)
{
  return vtkBrumeSceneFileChecks::Count(n);
}

// A binary STL announces its triangle count after an 80-byte header and
// holds 50 bytes per triangle; VTK's reader trusts whatever is there (a
// truncated file renders its first triangles). ASCII files (the word 'solid'
// followed by text only) have no count to check.
bool StlLooksComplete(const std::filesystem::path& file, std::string& error)
{
  std::ifstream in(file, std::ios::binary);
  if (!in)
  {
    error = "cannot open '" + file.string() + "'";
    return false;
  }
  in.seekg(0, std::ios::end);
  const double size = static_cast<double>(in.tellg());
  in.seekg(0);
  char head[512] = {};
  in.read(head, sizeof(head));
  const std::streamsize got = in.gcount();
  bool text = got >= 5 && std::string(head, 5) == "solid";
  for (std::streamsize i = 0; text && i < got; ++i)
  {
    const auto c = static_cast<unsigned char>(head[i]);
    text = c == '\n' || c == '\r' || c == '\t' || (c >= 32 && c < 127);
  }
  if (text)
  {
    return true;
  }
  if (size < 84)
  {
    error = "'" + file.string() +
      "' is truncated: a binary STL file has an 84-byte header, the file holds " + Count(size) +
      " bytes";
    return false;
  }
  const auto* b = reinterpret_cast<const unsigned char*>(head + 80);
  const double triangles =
    static_cast<double>(static_cast<std::uint32_t>(b[0]) | static_cast<std::uint32_t>(b[1]) << 8 |
      static_cast<std::uint32_t>(b[2]) << 16 | static_cast<std::uint32_t>(b[3]) << 24);
  const double needed = 84.0 + 50.0 * triangles;
  if (size < needed)
  {
    error = "'" + file.string() + "' is truncated: its header announces " + Count(triangles) +
      " triangles (" + Count(needed) + " bytes), the file holds " + Count(size) + " bytes";
    return false;
  }
  // VTK's reader ignores the count and reads triangles to the end of the
  // file: one that holds more than a triangle beyond its count is refused
  // (a body of zeros would be read as millions of empty triangles).
  if (size >= needed + 50.0)
  {
    error = "'" + file.string() + "' holds " + Count(size) + " bytes, but its header announces " +
      Count(triangles) + " triangles (" + Count(needed) +
      " bytes): not a binary STL file as written";
    return false;
  }
  return true;
}
}

bool vtkBrumeSceneFileChecks::Stl(const std::filesystem::path& file, std::string& error)
{
  return StlLooksComplete(file, error);
}
