// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeSceneGeometry.h"

#include "vtkAlgorithm.h"
#include "vtkDataSetSurfaceFilter.h"
#include "vtkExecutive.h"
#include "vtkOBJReader.h"
#include "vtkPLYReader.h"
#include "vtkPolyData.h"
#include "vtkSTLReader.h"
#include "vtkXMLPolyDataReader.h"
#include "vtkXMLUnstructuredDataReader.h"
#include "vtkXMLUnstructuredGridReader.h"

#include <vtksys/SystemInformation.hxx>

#include <cstdint>
#include <fstream>
#include <sstream>
#include <vector>

namespace
{
// Runs `f` with VTK's error and warning display off (readers report through
// errors that the caller turns into one message).
template <typename F>
auto Quietly(F&& f)
{
  const bool display = vtkObject::GetGlobalWarningDisplay();
  vtkObject::GlobalWarningDisplayOff();
  auto result = f();
  vtkObject::SetGlobalWarningDisplay(display);
  return result;
}

std::string Count(double n)
{
  std::ostringstream os;
  os.precision(15);
  os << n;
  return os.str();
}

// VTK's PLY parser asserts on a file shorter than its header promises: check
// the header's element counts against what the file holds first.
bool PlyLooksComplete(const std::filesystem::path& file, std::string& error)
{
  std::ifstream in(file, std::ios::binary);
  std::string line, format;
  double minimumBytes = 0, rows = 0, rowBytes = 0, allRows = 0;
  bool headerEnded = false;
  // Bytes of a PLY scalar type; 0 for a word that is none.
  auto size = [](const std::string& type) -> double
  {
    if (type == "char" || type == "uchar" || type == "int8" || type == "uint8")
      return 1;
    if (type == "short" || type == "ushort" || type == "int16" || type == "uint16")
      return 2;
    if (type == "int" || type == "uint" || type == "float" || type == "int32" ||
      type == "uint32" || type == "float32")
      return 4;
    if (type == "double" || type == "float64")
      return 8;
    return 0;
  };
  // VTK's parser dereferences what a malformed header leaves out (a property
  // before any element, a property with no type): accept the grammar only.
  auto malformed = [&](const std::string& why)
  {
    error = "'" + file.string() + "': malformed PLY header line '" + line + "' (" + why + ")";
    return false;
  };
  bool inElement = false;
  if (!in)
  {
    error = "cannot open '" + file.string() + "'";
    return false;
  }
  if (!std::getline(in, line) || line.rfind("ply", 0) != 0)
  {
    error = "'" + file.string() + "' is not a PLY file (no 'ply' magic)";
    return false;
  }
  while (std::getline(in, line))
  {
    if (!line.empty() && line.back() == '\r')
    {
      line.pop_back();
    }
    // The line's first word, then the others.
    std::istringstream words(line);
    std::string word;
    words >> word;
    std::vector<std::string> rest;
    for (std::string w; words >> w;)
    {
      rest.push_back(w);
    }
    if (word == "format")
    {
      if (rest.size() != 2 ||
        (rest[0] != "ascii" && rest[0] != "binary_little_endian" &&
          rest[0] != "binary_big_endian"))
      {
        return malformed(
          "expected 'format ascii|binary_little_endian|binary_big_endian VERSION'");
      }
      format = rest[0];
    }
    else if (word == "element")
    {
      minimumBytes += rows * rowBytes;
      rowBytes = 0;
      if (rest.size() != 2 || rest[1].empty() ||
        rest[1].find_first_not_of("0123456789") != std::string::npos)
      {
        return malformed("expected 'element NAME COUNT'");
      }
      rows = std::stod(rest[1]);
      if (rows > 1e10)
      {
        error = "'" + file.string() + "': bad element count in '" + line + "'";
        return false;
      }
      allRows += rows;
      inElement = true;
    }
    else if (word == "property")
    {
      if (!inElement)
      {
        return malformed("a property before any element");
      }
      if (!rest.empty() && rest[0] == "list")
      {
        if (rest.size() != 4 || size(rest[1]) == 0 || size(rest[2]) == 0)
        {
          return malformed("expected 'property list COUNT_TYPE ITEM_TYPE NAME'");
        }
        rowBytes += size(rest[1]); // a list holds at least its count
      }
      else
      {
        if (rest.size() != 2 || size(rest[0]) == 0)
        {
          return malformed("expected 'property TYPE NAME'");
        }
        rowBytes += size(rest[0]);
      }
    }
    else if (word != "comment" && word != "obj_info" && word != "end_header" && !word.empty())
    {
      return malformed("not a PLY header keyword");
    }
    else if (word == "end_header")
    {
      minimumBytes += rows * rowBytes;
      headerEnded = true;
      break;
    }
  }
  if (!headerEnded)
  {
    error = "'" + file.string() + "': the PLY header has no end_header";
    return false;
  }
  if (format.empty())
  {
    error = "'" + file.string() + "': the PLY header has no format line";
    return false;
  }
  double available = 0, lines = 0;
  const auto body = in.tellg();
  in.seekg(0, std::ios::end);
  available = static_cast<double>(in.tellg() - body);
  if (format == "ascii")
  {
    in.seekg(body);
    while (std::getline(in, line))
    {
      lines += line.find_first_not_of(" \t\r") != std::string::npos ? 1 : 0;
    }
    // One line per element row.
    if (lines < allRows)
    {
      error = "'" + file.string() + "' is truncated: the header announces " +
        std::to_string(static_cast<long long>(allRows)) + " rows, the file holds " +
        std::to_string(static_cast<long long>(lines));
      return false;
    }
    return true;
  }
  if (available < minimumBytes)
  {
    error = "'" + file.string() + "' is truncated: the header needs at least " +
      std::to_string(static_cast<long long>(minimumBytes)) + " bytes of data, the file holds " +
      std::to_string(static_cast<long long>(available));
    return false;
  }
  return true;
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
    error = "'" + file.string() + "' is truncated: a binary STL file has an 84-byte header, the file holds " + Count(size) + " bytes";
    return false;
  }
  const auto* b = reinterpret_cast<const unsigned char*>(head + 80);
  const double triangles = static_cast<double>(static_cast<std::uint32_t>(b[0]) |
    static_cast<std::uint32_t>(b[1]) << 8 | static_cast<std::uint32_t>(b[2]) << 16 |
    static_cast<std::uint32_t>(b[3]) << 24);
  const double needed = 84.0 + 50.0 * triangles;
  if (size < needed)
  {
    error = "'" + file.string() + "' is truncated: its header announces " + Count(triangles) +
      " triangles (" + Count(needed) + " bytes), the file holds " + Count(size) + " bytes";
    return false;
  }
  return true;
}

// A VTK XML file announces its points and cells in its Piece elements; VTK
// allocates them before it reads a value (an absurd count aborts the
// process). After the reader has parsed the header (UpdateInformation), the
// counts must fit in memory and, unless the data are compressed, in the file:
// every coordinate and every cell takes at least one byte in any encoding.
bool XmlCountsFit(vtkXMLUnstructuredDataReader* reader, const std::filesystem::path& file,
  std::string& error)
{
  if (!reader->GetExecutive()->UpdateInformation())
  {
    error = "cannot read geometry from '" + file.string() + "' (missing, corrupt or empty)";
    return false;
  }
  reader->SetupUpdateExtent(0, 1, 0);
  const double points = static_cast<double>(reader->GetNumberOfPoints());
  const double cells = static_cast<double>(reader->GetNumberOfCells());
  std::ifstream in(file, std::ios::binary);
  in.seekg(0, std::ios::end);
  const double size = static_cast<double>(in.tellg());
  in.seekg(0);
  char head[1024] = {};
  in.read(head, sizeof(head));
  const std::string start(head, static_cast<std::size_t>(in.gcount()));
  const auto root = start.find("<VTKFile");
  const bool compressed = root != std::string::npos &&
    start.find("compressor=", root) < start.find('>', root);
  // In memory: float coordinates, and per cell an offset and one index.
  const double bytes = 12.0 * points + 16.0 * cells;
  const double memory = vtkBrumeSceneGeometry::UsableMemory();
  const std::string announced = "'" + file.string() + "' announces " + Count(points) +
    " points and " + Count(cells) + " cells";
  if (points < 0 || cells < 0)
  {
    error = announced + ": counts cannot be negative";
    return false;
  }
  if (memory > 0.0 && bytes > memory)
  {
    error = announced + " (at least " + Count(bytes) +
      " bytes): more than half of this machine's memory (" + Count(memory) + " bytes)";
    return false;
  }
  if (!compressed && size < 3.0 * points + cells)
  {
    error = announced + " (at least " + Count(3.0 * points + cells) +
      " bytes of data), the file holds " + Count(size) + " bytes";
    return false;
  }
  return true;
}
}

vtkSmartPointer<vtkPolyData> vtkBrumeSceneGeometry::Read(
  const std::filesystem::path& file, std::string& error)
{
  const std::string ext = file.extension().string();
  vtkSmartPointer<vtkAlgorithm> reader;
  if (ext == ".obj")
  {
    auto r = vtkSmartPointer<vtkOBJReader>::New();
    r->SetFileName(file.string().c_str());
    reader = r;
  }
  else if (ext == ".ply")
  {
    if (!PlyLooksComplete(file, error))
    {
      return nullptr;
    }
    auto r = vtkSmartPointer<vtkPLYReader>::New();
    r->SetFileName(file.string().c_str());
    reader = r;
  }
  else if (ext == ".stl")
  {
    if (!StlLooksComplete(file, error))
    {
      return nullptr;
    }
    auto r = vtkSmartPointer<vtkSTLReader>::New();
    r->SetFileName(file.string().c_str());
    reader = r;
  }
  else if (ext == ".vtp")
  {
    auto r = vtkSmartPointer<vtkXMLPolyDataReader>::New();
    r->SetFileName(file.string().c_str());
    if (!Quietly([&] { return XmlCountsFit(r, file, error); }))
    {
      return nullptr;
    }
    reader = r;
  }
  else if (ext == ".vtu")
  {
    auto r = vtkSmartPointer<vtkXMLUnstructuredGridReader>::New();
    r->SetFileName(file.string().c_str());
    if (!Quietly([&] { return XmlCountsFit(r, file, error); }))
    {
      return nullptr;
    }
    auto surface = vtkSmartPointer<vtkDataSetSurfaceFilter>::New();
    surface->SetInputConnection(r->GetOutputPort());
    reader = surface;
  }
  else
  {
    error = "unsupported geometry file type '" + ext + "' (.obj, .ply, .stl, .vtp, .vtu)";
    return nullptr;
  }
  // Readers report problems through errors, not return values: silence and check.
  const int ok = Quietly([&] { return reader->GetExecutive() ? reader->GetExecutive()->Update() : 0; });
  auto* output = vtkPolyData::SafeDownCast(reader->GetOutputDataObject(0));
  if (!ok || !output || output->GetNumberOfCells() == 0)
  {
    error = "cannot read geometry from '" + file.string() + "' (missing, corrupt or empty)";
    return nullptr;
  }
  auto copy = vtkSmartPointer<vtkPolyData>::New();
  copy->ShallowCopy(output);
  return copy;
}

double vtkBrumeSceneGeometry::UsableMemory()
{
  vtksys::SystemInformation system;
  system.RunMemoryCheck();
  return 0.5 * static_cast<double>(system.GetTotalPhysicalMemory()) * 1048576.0;
}
