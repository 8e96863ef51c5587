// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeSceneFileChecks.h"

#include "vtkBrumeSMP.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <vector>

namespace
{
std::string Count(double n)
{
  return vtkBrumeSceneFileChecks::Count(n);
}

// Reads one line (without its end of line) of at most `limit` characters:
// a longer line sets `tooLong` and ends the read there, so that a file with
// no line breaks costs `limit` bytes, not its size. False at the end of the
// stream with nothing read.
constexpr std::size_t MaxLine = std::size_t(1) << 20; // 1 MiB
bool ReadLine(std::istream& in, std::string& line, bool& tooLong, std::size_t limit = MaxLine)
{
  line.clear();
  tooLong = false;
  std::streambuf* buffer = in.rdbuf();
  for (bool any = false;; any = true)
  {
    const int c = buffer->sbumpc();
    if (c == std::char_traits<char>::eof())
    {
      if (!any)
      {
        in.setstate(std::ios::eofbit | std::ios::failbit);
      }
      return any;
    }
    if (c == '\n')
    {
      return true;
    }
    if (line.size() >= limit)
    {
      tooLong = true;
      return true;
    }
    line.push_back(static_cast<char>(c));
  }
}

struct PlyProperty
{
  bool List = false;
  std::string CountType, Type, Name;
};

struct PlyElement
{
  std::string Name;
  double Rows = 0;
  std::vector<PlyProperty> Properties;
};

// Bytes of a PLY scalar type; 0 for a word that is none.
double PlyTypeSize(const std::string& type)
{
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8")
    return 1;
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16")
    return 2;
  if (type == "int" || type == "uint" || type == "float" || type == "int32" || type == "uint32" ||
    type == "float32")
    return 4;
  if (type == "double" || type == "float64")
    return 8;
  return 0;
}

// Binary PLY values through a buffer (one stream read per value would cost
// more than VTK's own parse).
class PlyBytes
{
public:
  PlyBytes(std::istream& in, bool bigEndian)
    : In(in)
    , Buffer(1 << 20)
  {
    const std::uint16_t probe = 1;
    this->Swap = bigEndian == (*reinterpret_cast<const unsigned char*>(&probe) == 1);
  }

  /// The next value of `type` (a PLY scalar type name), as a double.
  bool Read(const std::string& type, double& value)
  {
    const auto n = static_cast<std::size_t>(PlyTypeSize(type));
    unsigned char b[8] = {};
    for (std::size_t i = 0; i < n; ++i)
    {
      if (this->Position == this->Length && !this->Fill())
      {
        return false;
      }
      b[i] = static_cast<unsigned char>(this->Buffer[this->Position++]);
    }
    if (this->Swap)
    {
      std::reverse(b, b + n);
    }
    auto as = [&](auto v)
    {
      std::memcpy(&v, b, sizeof(v));
      value = static_cast<double>(v);
      return true;
    };
    if (type == "char" || type == "int8")
      return as(std::int8_t());
    if (type == "uchar" || type == "uint8")
      return as(std::uint8_t());
    if (type == "short" || type == "int16")
      return as(std::int16_t());
    if (type == "ushort" || type == "uint16")
      return as(std::uint16_t());
    if (type == "int" || type == "int32")
      return as(std::int32_t());
    if (type == "uint" || type == "uint32")
      return as(std::uint32_t());
    if (type == "double" || type == "float64")
      return as(double());
    return as(float());
  }

  /// Skips `bytes` bytes.
  bool Skip(double bytes)
  {
    const double buffered = static_cast<double>(this->Length - this->Position);
    if (bytes <= buffered)
    {
      this->Position += static_cast<std::size_t>(bytes);
      return true;
    }
    this->Position = this->Length = 0;
    this->In.seekg(static_cast<std::streamoff>(bytes - buffered), std::ios::cur);
    return static_cast<bool>(this->In);
  }

private:
  bool Fill()
  {
    this->In.read(this->Buffer.data(), static_cast<std::streamsize>(this->Buffer.size()));
    this->Length = static_cast<std::size_t>(this->In.gcount());
    this->Position = 0;
    return this->Length > 0;
  }

  std::istream& In;
  std::vector<char> Buffer;
  std::size_t Position = 0, Length = 0;
  bool Swap = false;
};

// Walks a PLY body row by row: every value present, every list's count a
// whole non-negative number, and every face's vertex index inside the vertex
// element (VTK's reader indexes the points with them unchecked). Binary
// elements without lists are skipped; every ASCII row is read.
bool PlyBodyConsistent(std::istream& in, const std::filesystem::path& file,
  const std::string& format, const std::vector<PlyElement>& elements, std::string& error)
{
  double vertices = 0, fileSize = 0;
  for (const PlyElement& e : elements)
  {
    vertices = e.Name == "vertex" ? e.Rows : vertices;
  }
  {
    const auto here = in.tellg();
    in.seekg(0, std::ios::end);
    fileSize = static_cast<double>(in.tellg());
    in.seekg(here);
  }
  const bool text = format == "ascii";
  PlyBytes bytes(in, format == "binary_big_endian");
  std::string line;
  std::istringstream words;
  auto read = [&](const std::string& type, double& value)
  {
    if (!text)
    {
      return bytes.Read(type, value);
    }
    std::string word;
    if (!(words >> word))
    {
      return false;
    }
    char* end = nullptr;
    value = std::strtod(word.c_str(), &end);
    return end && *end == '\0' && end != word.c_str();
  };
  const std::string name = "'" + file.string() + "'";
  for (const PlyElement& e : elements)
  {
    double rowBytes = 0;
    bool lists = false;
    for (const PlyProperty& property : e.Properties)
    {
      lists = lists || property.List;
      rowBytes += PlyTypeSize(property.Type);
    }
    if (!lists && !text)
    {
      if (rowBytes * e.Rows > fileSize || !bytes.Skip(rowBytes * e.Rows))
      {
        error = name + " is truncated: element '" + e.Name + "' does not fit in the file";
        return false;
      }
      continue;
    }
    for (double row = 0; row < e.Rows; ++row)
    {
      if (text)
      {
        // VTK reads an ASCII row as one line, a blank one too (and then
        // aborts on an assertion at the file's end: a fuzzer's find).
        bool tooLong = false;
        if (!ReadLine(in, line, tooLong))
        {
          error = name + " is truncated: element '" + e.Name + "' has fewer rows than announced";
          return false;
        }
        if (tooLong)
        {
          error = name + ": a row of element '" + e.Name + "' is longer than 1 MiB";
          return false;
        }
        if (line.find_first_not_of(" \t\r\v\f") == std::string::npos)
        {
          error = name + ": row " + Count(row) + " of element '" + e.Name + "' is an empty line";
          return false;
        }
        // VTK's parser reads a row as a C string and indexes its words
        // unchecked: a NUL (or another control character) ends the row
        // early there, where words here would run on (a fuzzer's find, a
        // segmentation fault in VTK's strtod).
        if (std::any_of(line.begin(), line.end(),
              [](char c)
              {
                return static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\r' &&
                  c != '\v' && c != '\f';
              }))
        {
          error =
            name + ": a control character in row " + Count(row) + " of element '" + e.Name + "'";
          return false;
        }
        // VTK's parser indexes the line's words unchecked: each row's line
        // must hold every value of the row.
        words.clear();
        words.str(line);
      }
      for (const PlyProperty& property : e.Properties)
      {
        auto where = [&] {
          return " (element '" + e.Name + "', row " + Count(row) + ", property '" + property.Name +
            "')";
        };
        double count = 1;
        if (property.List &&
          (!read(property.CountType, count) || !(count >= 0) || count != std::floor(count)))
        {
          error = name + " is truncated or corrupt: no list count" + where();
          return false;
        }
        const bool indices = e.Name == "face" && property.Name == "vertex_indices";
        if (indices && count < 3)
        {
          // Also what ends a body of zeros announcing billions of faces at
          // its first row, not after reading them all.
          error = name + ": a face has " + Count(count) + " vertices, not at least 3" + where();
          return false;
        }
        for (double k = 0; k < count; ++k)
        {
          double value = 0;
          if (!read(property.Type, value))
          {
            error = name + " is truncated or corrupt: a value is missing" + where();
            return false;
          }
          if (indices && !(value >= 0 && value < vertices && value == std::floor(value)))
          {
            error = name + ": vertex index " + Count(value) + " is not one of the " +
              Count(vertices) + " vertices" + where();
            return false;
          }
        }
      }
    }
  }
  return true;
}

// A PLY header line's first 120 bytes as printable text (control and
// non-ASCII bytes as \xHH).
std::string PlyShownLine(const std::string& line)
{
  std::string shown;
  for (const char c : line.substr(0, 120))
  {
    const auto b = static_cast<unsigned char>(c);
    if (b >= 32 && b < 127)
    {
      shown += c;
    }
    else
    {
      const char* hex = "0123456789abcdef";
      shown += std::string("\\x") + hex[b >> 4] + hex[b & 15];
    }
  }
  return shown;
}

// Adds a 'property' line's property (`rest`: the words after the keyword) to
// the last element and its least bytes to `rowBytes`; returns why the line is
// malformed, empty when it is not.
std::string AddPlyProperty(const std::string& line, const std::vector<std::string>& rest,
  std::vector<PlyElement>& elements, double& rowBytes)
{
  const std::string& name = rest.empty() ? line : rest.back();
  const auto& properties = elements.back().Properties;
  if (std::any_of(
        properties.begin(), properties.end(), [&](const PlyProperty& p) { return p.Name == name; }))
  {
    return "a second property of that name in its element";
  }
  if (!rest.empty() && rest[0] == "list")
  {
    if (rest.size() != 4 || PlyTypeSize(rest[1]) == 0 || PlyTypeSize(rest[2]) == 0)
    {
      return "expected 'property list COUNT_TYPE ITEM_TYPE NAME'";
    }
    rowBytes += PlyTypeSize(rest[1]); // a list holds at least its count
    elements.back().Properties.push_back({ true, rest[1], rest[2], rest[3] });
  }
  else
  {
    if (rest.size() != 2 || PlyTypeSize(rest[0]) == 0)
    {
      return "expected 'property TYPE NAME'";
    }
    rowBytes += PlyTypeSize(rest[0]);
    elements.back().Properties.push_back({ false, "", rest[0], rest[1] });
  }
  return std::string();
}

struct PlyHeader
{
  std::string Format;
  std::vector<PlyElement> Elements;
  double MinimumBytes = 0; // of data, with each list counted by its count
};

// Reads the header lines after the 'ply' magic, through end_header. VTK's
// parser dereferences what a malformed header leaves out (a property before
// any element, a property with no type): accept the grammar only.
bool ReadPlyHeader(
  std::istream& in, const std::filesystem::path& file, PlyHeader& header, std::string& error)
{
  std::string line;
  double rows = 0, rowBytes = 0;
  bool headerEnded = false, inElement = false;
  auto malformed = [&](const std::string& why)
  {
    error = "'" + file.string() + "': malformed PLY header line '" + PlyShownLine(line) + "' (" +
      why + ")";
    return false;
  };
  std::vector<PlyElement>& elements = header.Elements;
  bool tooLong = false;
  while (ReadLine(in, line, tooLong, 4096))
  {
    if (tooLong)
    {
      return malformed("longer than 4096 characters");
    }
    if (!line.empty() && line.back() == '\r')
    {
      line.pop_back();
    }
    // Words are split at spaces and tabs only, as VTK's parser does: any
    // other control character would make the two read different headers.
    // Names and keywords are ASCII (comments may hold any text).
    const bool comment = line.rfind("comment", 0) == 0 || line.rfind("obj_info", 0) == 0;
    if (std::any_of(line.begin(), line.end(),
          [&](char c)
          {
            const auto b = static_cast<unsigned char>(c);
            return c != '\t' && (b < 32 || b == 127 || (b > 127 && !comment));
          }))
    {
      return malformed("a control character, or a non-ASCII byte outside a comment");
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
    if (word.empty())
    {
      // VTK's parser finds no word on such a line and compares the first
      // it did not set (a fuzzer's find: a segmentation fault).
      return malformed("an empty line");
    }
    if (word == "format")
    {
      if (rest.size() != 2 ||
        (rest[0] != "ascii" && rest[0] != "binary_little_endian" && rest[0] != "binary_big_endian"))
      {
        return malformed("expected 'format ascii|binary_little_endian|binary_big_endian VERSION'");
      }
      header.Format = rest[0];
    }
    else if (word == "element")
    {
      header.MinimumBytes += rows * rowBytes;
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
      if (std::any_of(elements.begin(), elements.end(),
            [&](const PlyElement& e) { return e.Name == rest[0]; }))
      {
        return malformed("a second element of that name");
      }
      if (!elements.empty() && elements.back().Properties.empty())
      {
        return malformed("the element before has no property");
      }
      inElement = true;
      elements.push_back({ rest[0], rows, {} });
    }
    else if (word == "property")
    {
      if (!inElement)
      {
        return malformed("a property before any element");
      }
      const std::string why = AddPlyProperty(line, rest, elements, rowBytes);
      if (!why.empty())
      {
        return malformed(why);
      }
    }
    else if (word != "comment" && word != "obj_info" && word != "end_header")
    {
      return malformed("not a PLY header keyword");
    }
    else if (word == "end_header")
    {
      if (!elements.empty() && elements.back().Properties.empty())
      {
        return malformed("the element before has no property");
      }
      header.MinimumBytes += rows * rowBytes;
      headerEnded = true;
      break;
    }
  }
  if (!headerEnded)
  {
    error = "'" + file.string() + "': the PLY header has no end_header";
    return false;
  }
  if (header.Format.empty())
  {
    error = "'" + file.string() + "': the PLY header has no format line";
    return false;
  }
  return true;
}

// VTK's PLY parser asserts on a file shorter than its header promises: check
// the header's element counts against what the file holds first.
bool PlyLooksComplete(const std::filesystem::path& file, std::string& error)
{
  std::ifstream in(file, std::ios::binary);
  std::string line;
  if (!in)
  {
    error = "cannot open '" + file.string() + "'";
    return false;
  }
  bool tooLong = false;
  if (!ReadLine(in, line, tooLong, 16) || line.rfind("ply", 0) != 0)
  {
    error = "'" + file.string() + "' is not a PLY file (no 'ply' magic)";
    return false;
  }
  PlyHeader header;
  if (!ReadPlyHeader(in, file, header, error))
  {
    return false;
  }
  // What VTK's reader dereferences without checking: a vertex element with
  // x, y and z, and the faces' vertex_indices list.
  const std::vector<PlyElement>& elements = header.Elements;
  auto has = [&](const char* element, const char* property, bool list)
  {
    for (const PlyElement& e : elements)
    {
      for (const PlyProperty& p : e.Properties)
      {
        if (e.Name == element && p.Name == property && p.List == list)
        {
          return true;
        }
      }
    }
    return false;
  };
  const bool faces = std::any_of(
    elements.begin(), elements.end(), [](const PlyElement& e) { return e.Name == "face"; });
  if (!has("vertex", "x", false) || !has("vertex", "y", false) || !has("vertex", "z", false) ||
    (faces && !has("face", "vertex_indices", true)))
  {
    error = "'" + file.string() +
      "': the PLY header needs a 'vertex' element with x, y and z, and its 'face' element a "
      "'vertex_indices' list";
    return false;
  }
  // Binary: the bytes the counts need at least, before the walk. ASCII
  // files are read once, by the walk (one line per row).
  const auto body = in.tellg();
  in.seekg(0, std::ios::end);
  const double available = static_cast<double>(in.tellg() - body);
  if (header.Format != "ascii" && available < header.MinimumBytes)
  {
    error = "'" + file.string() + "' is truncated: the header needs at least " +
      std::to_string(static_cast<long long>(header.MinimumBytes)) +
      " bytes of data, the file holds " + std::to_string(static_cast<long long>(available));
    return false;
  }
  in.clear();
  in.seekg(body);
  return PlyBodyConsistent(in, file, header.Format, header.Elements, error);
}

// VTK's OBJ reader indexes its points, texture coordinates and normals with
// the face, line and point entries it reads, unchecked. Every entry must be
// 'v', 'v/t', 'v//n' or 'v/t/n' with each index nonzero and naming one
// defined before it (negative indices count back from the last), and every
// vertex must have three coordinates.
bool ObjIndicesInRange(const std::filesystem::path& file, std::string& error)
{
  std::ifstream in(file, std::ios::binary);
  if (!in)
  {
    error = "cannot read geometry from '" + file.string() + "' (missing, corrupt or empty)";
    return false;
  }
  double defined[3] = { 0, 0, 0 }; // v, vt, vn
  std::string line;
  double number = 0;
  auto fail = [&](const std::string& why)
  {
    error = "'" + file.string() + "' line " + Count(number) + ": " + why + " ('" +
      line.substr(0, 80) + "')";
    return false;
  };
  auto index = [&](const std::string& text, int kind, bool optional)
  {
    if (text.empty())
    {
      return optional;
    }
    char* end = nullptr;
    const double i = std::strtod(text.c_str(), &end);
    return *end == '\0' && i == std::floor(i) && i != 0 &&
      (i > 0 ? i <= defined[kind] : -i <= defined[kind]);
  };
  bool tooLong = false;
  while (ReadLine(in, line, tooLong))
  {
    ++number;
    if (tooLong)
    {
      error =
        "'" + file.string() + "' line " + Count(number) + ": longer than 1 MiB: not an OBJ file";
      return false;
    }
    std::istringstream words(line);
    std::string word;
    words >> word;
    if (word == "v" || word == "vt" || word == "vn")
    {
      int values = 0;
      for (std::string w; words >> w && values < 3; ++values)
      {
        char* end = nullptr;
        std::strtod(w.c_str(), &end);
        if (*end != '\0' || end == w.c_str())
        {
          return fail("'" + w + "' is not a number");
        }
      }
      if (word == "v" && values < 3)
      {
        return fail("a vertex needs three coordinates");
      }
      ++defined[word == "v" ? 0 : word == "vt" ? 1 : 2];
    }
    else if (word == "f" || word == "l" || word == "p")
    {
      for (std::string entry; words >> entry;)
      {
        const auto a = entry.find('/');
        const auto b = a == std::string::npos ? a : entry.find('/', a + 1);
        const std::string v = entry.substr(0, a);
        const std::string t = a == std::string::npos ? "" : entry.substr(a + 1, b - a - 1);
        const std::string n = b == std::string::npos ? "" : entry.substr(b + 1);
        const bool shape = (a == std::string::npos) || (b == std::string::npos && !t.empty()) ||
          (b != std::string::npos && !n.empty() && entry.find('/', b + 1) == std::string::npos);
        if (!shape || !index(v, 0, false) || !index(t, 1, true) || !index(n, 2, true))
        {
          return fail(
            "'" + entry + "' is not v, v/t, v//n or v/t/n indexing what is defined above it");
        }
      }
    }
  }
  return true;
}

}

bool vtkBrumeSceneFileChecks::Ply(const std::filesystem::path& file, std::string& error)
{
  return PlyLooksComplete(file, error);
}

bool vtkBrumeSceneFileChecks::Obj(const std::filesystem::path& file, std::string& error)
{
  return ObjIndicesInRange(file, error);
}

double vtkBrumeSceneFileChecks::UsableMemory()
{
  return vtkBrumeSMP::UsableMemory();
}

std::string vtkBrumeSceneFileChecks::Count(double n)
{
  std::ostringstream os;
  os.precision(15);
  os << n;
  return os.str();
}
