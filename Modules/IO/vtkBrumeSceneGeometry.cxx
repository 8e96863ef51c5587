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
#include "vtkXMLUnstructuredGridReader.h"

#include <fstream>
#include <sstream>

namespace
{
// Reads a surface file with the VTK reader its extension calls for.
// VTK's PLY parser asserts on a file shorter than its header promises: check
// the header's element counts against what the file holds first.
bool PlyLooksComplete(const std::filesystem::path& file, std::string& error)
{
  std::ifstream in(file, std::ios::binary);
  std::string line, format;
  double minimumBytes = 0, rows = 0, rowBytes = 0, allRows = 0;
  bool headerEnded = false;
  auto size = [](const std::string& type) -> double
  {
    if (type == "char" || type == "uchar" || type == "int8" || type == "uint8")
      return 1;
    if (type == "short" || type == "ushort" || type == "int16" || type == "uint16")
      return 2;
    if (type == "double" || type == "float64")
      return 8;
    return 4;
  };
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
    std::istringstream words(line);
    std::string word;
    words >> word;
    if (word == "format")
    {
      words >> format;
    }
    else if (word == "element")
    {
      minimumBytes += rows * rowBytes;
      std::string name;
      rows = -1;
      words >> name >> rows;
      rowBytes = 0;
      if (!(rows >= 0) || rows > 1e10)
      {
        error = "'" + file.string() + "': bad element count in '" + line + "'";
        return false;
      }
      allRows += rows;
    }
    else if (word == "property")
    {
      std::string type, countType;
      words >> type;
      // A list needs at least its count.
      rowBytes += type == "list" ? (words >> countType, size(countType)) : size(type);
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
    auto r = vtkSmartPointer<vtkSTLReader>::New();
    r->SetFileName(file.string().c_str());
    reader = r;
  }
  else if (ext == ".vtp")
  {
    auto r = vtkSmartPointer<vtkXMLPolyDataReader>::New();
    r->SetFileName(file.string().c_str());
    reader = r;
  }
  else if (ext == ".vtu")
  {
    auto r = vtkSmartPointer<vtkXMLUnstructuredGridReader>::New();
    r->SetFileName(file.string().c_str());
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
  const bool display = vtkObject::GetGlobalWarningDisplay();
  vtkObject::GlobalWarningDisplayOff();
  const int ok = reader->GetExecutive() ? reader->GetExecutive()->Update() : 0;
  vtkObject::SetGlobalWarningDisplay(display);
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
