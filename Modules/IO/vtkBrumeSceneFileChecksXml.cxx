// SPDX-License-Identifier: BSD-3-Clause
// The checks of VTK XML files (vtkBrumeSceneFileChecks.h): what their
// headers announce, read before VTK's readers allocate it.
#include "vtkBrumeSceneFileChecks.h"

#include "vtkExecutive.h"
#include "vtkNew.h"
#include "vtkXMLDataElement.h"
#include "vtkXMLDataParser.h"
#include "vtkXMLReader.h"
#include "vtkXMLUnstructuredDataReader.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>

namespace
{
std::string Count(double n)
{
  return vtkBrumeSceneFileChecks::Count(n);
}

// A VTK XML file announces its points and cells in its Piece elements; VTK
// allocates them before it reads a value (an absurd count aborts the
// process). After the reader has parsed the header (UpdateInformation), the
// counts must fit in memory and, unless the data are compressed, in the file:
// every coordinate and every cell takes at least one byte in any encoding.
bool XmlCountsFit(
  vtkXMLUnstructuredDataReader* reader, const std::filesystem::path& file, std::string& error)
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
  const bool compressed =
    root != std::string::npos && start.find("compressor=", root) < start.find('>', root);
  // In memory: float coordinates, and per cell an offset and one index.
  const double bytes = 12.0 * points + 16.0 * cells;
  const double memory = vtkBrumeSceneFileChecks::UsableMemory();
  const std::string announced =
    "'" + file.string() + "' announces " + Count(points) + " points and " + Count(cells) + " cells";
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

// Bytes per value of a VTK XML DataArray type (0: unknown).
double TypeSize(const char* type)
{
  if (!type)
  {
    return 0.0;
  }
  const std::string t = type;
  if (t == "Int8" || t == "UInt8" || t == "Char" || t == "UnsignedChar" || t == "Bit" ||
    t == "String")
  {
    return 1.0;
  }
  if (t == "Int16" || t == "UInt16")
  {
    return 2.0;
  }
  if (t == "Int32" || t == "UInt32" || t == "Float32")
  {
    return 4.0;
  }
  return 8.0; // Int64, UInt64, Float64, IdType
}

// A numeric attribute of an element, as a double (`otherwise` when absent
// or not a number).
double Number(vtkXMLDataElement* element, const char* name, double otherwise)
{
  const char* text = element->GetAttribute(name);
  if (!text)
  {
    return otherwise;
  }
  char* end = nullptr;
  const double value = std::strtod(text, &end);
  return end != text ? value : otherwise;
}

// The points and cells of an image's extent attribute ("x0 x1 y0 y1 z0 z1"),
// and its points per axis ("nx x ny x nz").
bool ExtentCounts(
  vtkXMLDataElement* element, const char* name, double& points, double& cells, std::string& dims)
{
  const char* text = element->GetAttribute(name);
  if (!text)
  {
    return false;
  }
  std::istringstream in(text);
  double e[6];
  for (double& x : e)
  {
    if (!(in >> x))
    {
      return false;
    }
  }
  points = cells = 1.0;
  dims.clear();
  for (int a = 0; a < 3; ++a)
  {
    const double n = std::max(0.0, e[2 * a + 1] - e[2 * a] + 1.0);
    points *= n;
    cells *= std::max(1.0, n - 1.0);
    dims += (a ? " x " : "") + Count(n);
  }
  return true;
}

// The arrays of one data set element's pieces: false, with `error`, when
// an array announces more than MaxComponents components; else their bytes
// (components x values x type size) added to `bytes`, and the first piece's
// size in `dims`. An image's arrays are allocated for its whole extent,
// whatever its pieces say.
bool DataSetArrays(vtkXMLDataElement* dataset, const std::filesystem::path& file, double& bytes,
  std::string& dims, std::string& error)
{
  double wholePoints = 0.0, wholeCells = 0.0;
  std::string wholeDims;
  const bool whole = ExtentCounts(dataset, "WholeExtent", wholePoints, wholeCells, wholeDims);
  for (int p = 0; p < dataset->GetNumberOfNestedElements(); ++p)
  {
    vtkXMLDataElement* piece = dataset->GetNestedElement(p);
    if (!piece || std::strcmp(piece->GetName(), "Piece") != 0)
    {
      continue;
    }
    double points = Number(piece, "NumberOfPoints", 0.0);
    double cells = Number(piece, "NumberOfCells", 0.0) + Number(piece, "NumberOfPolys", 0.0) +
      Number(piece, "NumberOfStrips", 0.0) + Number(piece, "NumberOfLines", 0.0) +
      Number(piece, "NumberOfVerts", 0.0);
    std::string pieceDims;
    const bool extent = ExtentCounts(piece, "Extent", points, cells, pieceDims);
    if (whole && !(points >= wholePoints))
    {
      points = wholePoints;
      cells = wholeCells;
      pieceDims = wholeDims;
    }
    if ((extent || whole) && dims.empty())
    {
      dims = pieceDims + " points and ";
    }
    else if (dims.empty() && piece->GetAttribute("NumberOfPoints"))
    {
      dims = Count(points) + " points and " + Count(cells) + " cells and ";
    }
    for (int g = 0; g < piece->GetNumberOfNestedElements(); ++g)
    {
      vtkXMLDataElement* group = piece->GetNestedElement(g);
      const char* kind = group ? group->GetName() : nullptr;
      const bool perPoint =
        kind && (!std::strcmp(kind, "PointData") || !std::strcmp(kind, "Points"));
      const bool perCell = kind && !std::strcmp(kind, "CellData");
      for (int a = 0; (perPoint || perCell) && a < group->GetNumberOfNestedElements(); ++a)
      {
        vtkXMLDataElement* array = group->GetNestedElement(a);
        if (!array || std::strcmp(array->GetName(), "DataArray") != 0)
        {
          continue;
        }
        const double components = Number(array, "NumberOfComponents", 1.0);
        const char* name = array->GetAttribute("Name");
        const std::string which =
          name ? "array '" + std::string(name).substr(0, 80) + "'" : "an array";
        if (!(components >= 1.0) || components > vtkBrumeSceneFileChecks::MaxComponents)
        {
          error = "'" + file.string() + "' announces " + Count(components) + " components in " +
            which + ": Brume reads arrays of 1 to " +
            Count(vtkBrumeSceneFileChecks::MaxComponents) + " components";
          return false;
        }
        bytes += components * (perPoint ? points : cells) * TypeSize(array->GetAttribute("type"));
      }
    }
  }
  return true;
}

// Every DataArray of a VTK XML file's pieces, from the file's parsed XML
// (`root`: its VTKFile element): at most MaxComponents components each, and
// all of them within memory. Read before a reader sets up its arrays (VTK's
// readers loop over every component an array announces, and allocate
// components x values, when they read the data, not when they parse the
// header). Every element under the root is checked: VTK's readers take the
// first whose name is their data set's, wherever it is among the root's
// children.
bool XmlArraysFit(vtkXMLDataElement* root, const std::filesystem::path& file, std::string& error)
{
  double bytes = 0.0;
  std::string dims; // the first piece's size, as it announces it
  for (int d = 0; d < root->GetNumberOfNestedElements(); ++d)
  {
    vtkXMLDataElement* dataset = root->GetNestedElement(d);
    if (dataset && !DataSetArrays(dataset, file, bytes, dims, error))
    {
      return false;
    }
  }
  const double memory = vtkBrumeSceneFileChecks::UsableMemory();
  if (memory > 0.0 && bytes > memory)
  {
    error = "'" + file.string() + "' announces " + dims + "arrays of " + Count(bytes) +
      " bytes (components x values x type): more than half of this machine's memory (" +
      Count(memory) + " bytes)";
    return false;
  }
  // What the file can hold: a value takes at least 2 characters in ASCII
  // (8 bytes at most in memory), and no compressor VTK writes (LZ4, zlib,
  // LZMA) shrinks data 10,000 times. A 64 KB file announcing 10 GB of
  // arrays within memory was allocated before its data were found missing.
  std::error_code failed;
  const double size = static_cast<double>(std::filesystem::file_size(file, failed));
  const bool compressed = root->GetAttribute("compressor") != nullptr;
  const double expansion = compressed ? 10000.0 : 8.0;
  if (!failed && bytes > size * expansion)
  {
    error = "'" + file.string() + "' announces " + dims + "arrays of " + Count(bytes) +
      " bytes (components x values x type), more than its " + Count(size) + " bytes can hold " +
      (compressed ? "compressed (10,000 times at most)" : "(8 times at most)");
    return false;
  }
  return true;
}
}

bool vtkBrumeSceneFileChecks::XmlArrays(
  vtkXMLReader* reader, const std::filesystem::path& file, std::string& error)
{
  // The reader's own parse of the header: parsing a file of inline data a
  // second time took as long as the reader's (1.5 s for 500 MB).
  if (!reader->GetExecutive()->UpdateInformation())
  {
    return true; // not VTK XML, or not of this reader's type: its Update() says so
  }
  vtkXMLDataParser* parser = reader->GetXMLParser();
  vtkXMLDataElement* root = parser ? parser->GetRootElement() : nullptr;
  return !root || XmlArraysFit(root, file, error);
}

bool vtkBrumeSceneFileChecks::VtkXml(
  vtkXMLUnstructuredDataReader* reader, const std::filesystem::path& file, std::string& error)
{
  return XmlArrays(reader, file, error) && XmlCountsFit(reader, file, error);
}
