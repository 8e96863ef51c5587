// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeSceneReader.h"

#include "vtkAlgorithm.h"
#include "vtkBrumeSceneCamera.h"
#include "vtkBrumeSceneConversion.h"
#include "vtkCellArray.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataSetSurfaceFilter.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkOBJReader.h"
#include "vtkObjectFactory.h"
#include "vtkPLYReader.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSTLReader.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"
#include "vtkUnstructuredGrid.h"
#include "vtkXMLImageDataReader.h"
#include "vtkXMLPolyDataReader.h"
#include "vtkXMLUnstructuredGridReader.h"

#include "vtk_nlohmannjson.h"
#include VTK_NLOHMANN_JSON(json.hpp)

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <utility>
#include <vector>

vtkStandardNewMacro(vtkBrumeSceneReader);

namespace
{
using json = nlohmann::json;

// Reads values with errors that name the file and the field.
class Parser
{
public:
  explicit Parser(std::string file)
    : File(std::move(file))
  {
  }
  std::string Error;

  bool Fail(const std::string& path, const std::string& message)
  {
    if (this->Error.empty())
    {
      this->Error = this->File + ": " + path + ": " + message;
    }
    return false;
  }

  // Only the listed keys may appear in an object.
  bool Keys(const json& j, const std::string& path, const std::set<std::string>& allowed)
  {
    if (!j.is_object())
    {
      return this->Fail(path, "expected an object");
    }
    for (auto it = j.begin(); it != j.end(); ++it)
    {
      if (!allowed.count(it.key()))
      {
        return this->Fail(path, "unknown key '" + it.key() + "'");
      }
    }
    return true;
  }

  bool Number(const json& j, const std::string& path, double& out, double lo, double hi)
  {
    if (!j.is_number())
    {
      return this->Fail(path, "expected a number");
    }
    out = j.get<double>();
    if (!std::isfinite(out) || out < lo || out > hi)
    {
      std::ostringstream os;
      os << "expected a finite number in [" << lo << ", " << hi << "], not " << out;
      return this->Fail(path, os.str());
    }
    return true;
  }

  bool Vector(const json& j, const std::string& path, double* out, int n, double lo, double hi)
  {
    if (!j.is_array() || static_cast<int>(j.size()) != n)
    {
      return this->Fail(path, "expected " + std::to_string(n) + " numbers");
    }
    for (int i = 0; i < n; ++i)
    {
      if (!this->Number(j[i], path + "[" + std::to_string(i) + "]", out[i], lo, hi))
      {
        return false;
      }
    }
    return true;
  }

  bool String(const json& j, const std::string& path, std::string& out)
  {
    if (!j.is_string() || j.get<std::string>().empty())
    {
      return this->Fail(path, "expected a non-empty string");
    }
    out = j.get<std::string>();
    return true;
  }

  std::string File;
};

constexpr double Huge = 1e12;

void AddTuple(vtkFieldData* fd, const char* name, const double* v, int n)
{
  vtkBrumeSceneConversion::AppendTuple(fd, name, v, n);
}

void AddString(vtkFieldData* fd, const char* name, const std::string& value)
{
  auto* existing = vtkStringArray::SafeDownCast(fd->GetAbstractArray(name));
  vtkSmartPointer<vtkStringArray> a = existing;
  if (!a)
  {
    a = vtkSmartPointer<vtkStringArray>::New();
    a->SetName(name);
    fd->AddArray(a);
  }
  a->InsertNextValue(value);
}

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

vtkSmartPointer<vtkPolyData> ReadGeometry(const std::filesystem::path& file, std::string& error)
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
}

vtkBrumeSceneReader::vtkBrumeSceneReader()
{
  this->SetNumberOfInputPorts(0);
}

int vtkBrumeSceneReader::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  // A scene is replicated, not split: every piece (every process of a
  // distributed run) gets all of it.
  outputVector->GetInformationObject(0)->Set(CAN_HANDLE_PIECE_REQUEST(), 1);
  return 1;
}

int vtkBrumeSceneReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  auto* output = vtkPartitionedDataSetCollection::GetData(outputVector, 0);
  const std::filesystem::path path(this->FileName);
  std::ifstream in(path);
  if (this->FileName.empty() || !in)
  {
    vtkErrorMacro("Cannot open the scene file '" << this->FileName << "'.");
    return 0;
  }
  json root;
  try
  {
    root = json::parse(in);
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< this->FileName << ": not valid JSON: " << e.what());
    return 0;
  }
  Parser p(this->FileName);
  const std::filesystem::path dir = path.parent_path();
  auto relative = [&](const std::string& name) { return dir / std::filesystem::path(name); };
  vtkNew<vtkPartitionedDataSetCollection> scene;
  vtkFieldData* fd = scene->GetFieldData();
  auto fail = [&]()
  {
    vtkErrorMacro(<< p.Error);
    return 0;
  };

  if (!p.Keys(root, "(top)",
        { "brume_scene", "name", "camera", "render", "surfaces", "media", "lights" }))
  {
    return fail();
  }
  double version = 0;
  if (!root.contains("brume_scene"))
  {
    p.Fail("brume_scene", "missing: the format version (1)");
    return fail();
  }
  if (!p.Number(root["brume_scene"], "brume_scene", version, 1, 1))
  {
    return fail();
  }

  // The field each object came from, to name it in later messages.
  std::vector<std::pair<std::string, std::string>> objectFields;

  // Surfaces.
  if (root.contains("surfaces") && !root["surfaces"].is_array())
  {
    p.Fail("surfaces", "expected an array");
    return fail();
  }
  const json surfaces = root.value("surfaces", json::array());
  for (std::size_t i = 0; i < surfaces.size(); ++i)
  {
    const std::string at = "surfaces[" + std::to_string(i) + "]";
    const json& s = surfaces[i];
    std::string name;
    if (!p.Keys(s, at, { "name", "file", "quad", "material" }) ||
      !p.String(s.value("name", json()), at + ".name", name))
    {
      return fail();
    }
    vtkSmartPointer<vtkPolyData> surface;
    if (s.contains("file") == s.contains("quad"))
    {
      p.Fail(at, "needs exactly one of 'file' and 'quad'");
      return fail();
    }
    if (s.contains("file"))
    {
      std::string file, error;
      if (!p.String(s["file"], at + ".file", file))
      {
        return fail();
      }
      surface = ReadGeometry(relative(file), error);
      if (!surface)
      {
        p.Fail(at + ".file", error);
        return fail();
      }
    }
    else
    {
      const json& quad = s["quad"];
      if (!quad.is_array() || quad.size() != 4)
      {
        p.Fail(at + ".quad", "expected 4 corners");
        return fail();
      }
      vtkNew<vtkPoints> points;
      for (int k = 0; k < 4; ++k)
      {
        double v[3];
        if (!p.Vector(quad[k], at + ".quad[" + std::to_string(k) + "]", v, 3, -Huge, Huge))
        {
          return fail();
        }
        points->InsertNextPoint(v);
      }
      vtkNew<vtkCellArray> polys;
      const vtkIdType ids[4] = { 0, 1, 2, 3 };
      polys->InsertNextCell(4, ids);
      surface = vtkSmartPointer<vtkPolyData>::New();
      surface->SetPoints(points);
      surface->SetPolys(polys);
    }
    const json material = s.value("material", json::object());
    const std::string m = at + ".material";
    if (!p.Keys(material, m, { "type", "reflectance", "specular", "exponent", "emission" }))
    {
      return fail();
    }
    vtkFieldData* sfd = surface->GetFieldData();
    if (material.contains("type"))
    {
      std::string type;
      if (!p.String(material["type"], m + ".type", type))
      {
        return fail();
      }
      if (type != "lambertian" && type != "phong" && type != "mirror")
      {
        p.Fail(m + ".type", "expected 'lambertian', 'phong' or 'mirror', not '" + type + "'");
        return fail();
      }
      AddString(sfd, "BrumeMaterial", type);
    }
    for (const auto& key :
      { std::make_pair("reflectance", "BrumeReflectance"),
        std::make_pair("specular", "BrumeSpecular"), std::make_pair("emission", "BrumeEmission") })
    {
      if (material.contains(key.first))
      {
        double v[3];
        const double hi = std::string(key.first) == "emission" ? Huge : 1.0;
        if (!p.Vector(material[key.first], m + "." + key.first, v, 3, 0.0, hi))
        {
          return fail();
        }
        AddTuple(sfd, key.second, v, 3);
      }
    }
    if (material.contains("exponent"))
    {
      double e = 0;
      if (!p.Number(material["exponent"], m + ".exponent", e, 1e-6, 1e6))
      {
        return fail();
      }
      AddTuple(sfd, "BrumeExponent", &e, 1);
    }
    vtkBrumeSceneConversion::AddObject(scene, surface, name);
    objectFields.emplace_back(name, at);
  }

  // Media.
  if (root.contains("media") && !root["media"].is_array())
  {
    p.Fail("media", "expected an array");
    return fail();
  }
  const json media = root.value("media", json::array());
  for (std::size_t i = 0; i < media.size(); ++i)
  {
    const std::string at = "media[" + std::to_string(i) + "]";
    const json& m = media[i];
    std::string name;
    if (!p.Keys(m, at, { "name", "box", "sigma_a", "sigma_s", "g", "density_scale", "density" }) ||
      !p.String(m.value("name", json()), at + ".name", name))
    {
      return fail();
    }
    double sa[3], ss[3], g = 0, scale = 1;
    if (!p.Vector(m.value("sigma_a", json()), at + ".sigma_a", sa, 3, 0, Huge) ||
      !p.Vector(m.value("sigma_s", json()), at + ".sigma_s", ss, 3, 0, Huge))
    {
      return fail();
    }
    if (m.contains("g") && !p.Number(m["g"], at + ".g", g, -0.999999, 0.999999))
    {
      return fail();
    }
    if (m.contains("density_scale") &&
      !p.Number(m["density_scale"], at + ".density_scale", scale, 0, Huge))
    {
      return fail();
    }
    vtkSmartPointer<vtkImageData> image;
    const json density = m.value("density", json::object());
    if (!p.Keys(density, at + ".density", { "vdb", "grid", "vti", "array" }))
    {
      return fail();
    }
    if (density.contains("vdb") && density.contains("vti"))
    {
      p.Fail(at + ".density", "needs at most one of 'vdb' and 'vti'");
      return fail();
    }
    if (density.contains("vti"))
    {
      std::string file;
      if (!p.String(density["vti"], at + ".density.vti", file))
      {
        return fail();
      }
      vtkNew<vtkXMLImageDataReader> reader;
      reader->SetFileName(relative(file).string().c_str());
      const bool display = vtkObject::GetGlobalWarningDisplay();
      vtkObject::GlobalWarningDisplayOff();
      const int ok = reader->GetExecutive()->Update();
      vtkObject::SetGlobalWarningDisplay(display);
      if (!ok || reader->GetOutput()->GetNumberOfPoints() == 0)
      {
        p.Fail(at + ".density.vti", "cannot read '" + relative(file).string() + "'");
        return fail();
      }
      image = vtkSmartPointer<vtkImageData>::New();
      image->ShallowCopy(reader->GetOutput());
      image->GetFieldData()->Initialize();
      if (density.contains("array"))
      {
        std::string array;
        if (!p.String(density["array"], at + ".density.array", array))
        {
          return fail();
        }
        AddString(image->GetFieldData(), "BrumeDensityArray", array);
      }
    }
    else
    {
      double box[6];
      const json& b = m.value("box", json());
      if (!b.is_array() || b.size() != 2 || !p.Vector(b[0], at + ".box[0]", box, 3, -Huge, Huge) ||
        !p.Vector(b[1], at + ".box[1]", box + 3, 3, -Huge, Huge))
      {
        if (p.Error.empty())
        {
          p.Fail(at + ".box", "expected [[xmin, ymin, zmin], [xmax, ymax, zmax]]");
        }
        return fail();
      }
      for (int a = 0; a < 3; ++a)
      {
        if (!(box[3 + a] > box[a]))
        {
          p.Fail(at + ".box", "the box is empty (max <= min)");
          return fail();
        }
      }
      image = vtkSmartPointer<vtkImageData>::New();
      image->SetOrigin(box[0], box[1], box[2]);
      image->SetSpacing(box[3] - box[0], box[4] - box[1], box[5] - box[2]);
      image->SetDimensions(2, 2, 2);
      if (density.contains("vdb"))
      {
        std::string file, grid;
        if (!p.String(density["vdb"], at + ".density.vdb", file))
        {
          return fail();
        }
        if (!std::filesystem::exists(relative(file)))
        {
          p.Fail(at + ".density.vdb", "no file '" + relative(file).string() + "'");
          return fail();
        }
        AddString(image->GetFieldData(), "BrumeVDBFile", relative(file).string());
        if (density.contains("grid"))
        {
          if (!p.String(density["grid"], at + ".density.grid", grid))
          {
            return fail();
          }
          AddString(image->GetFieldData(), "BrumeVDBGrid", grid);
        }
      }
    }
    vtkFieldData* mfd = image->GetFieldData();
    AddTuple(mfd, "BrumeSigmaA", sa, 3);
    AddTuple(mfd, "BrumeSigmaS", ss, 3);
    AddTuple(mfd, "BrumeG", &g, 1);
    AddTuple(mfd, "BrumeDensityScale", &scale, 1);
    vtkBrumeSceneConversion::AddObject(scene, image, name);
    objectFields.emplace_back(name, at);
  }

  // Lights.
  if (root.contains("lights") && !root["lights"].is_array())
  {
    p.Fail("lights", "expected an array");
    return fail();
  }
  const json lights = root.value("lights", json::array());
  for (std::size_t i = 0; i < lights.size(); ++i)
  {
    const std::string at = "lights[" + std::to_string(i) + "]";
    const json& l = lights[i];
    std::string type;
    if (!p.Keys(
          l, at, { "type", "position", "direction", "intensity", "irradiance", "cone_angle" }) ||
      !p.String(l.value("type", json()), at + ".type", type))
    {
      return fail();
    }
    double position[3] = { 0, 0, 0 }, direction[3] = { 0, -1, 0 }, power[3], cone = 180;
    if (type == "point" || type == "spot")
    {
      if (!p.Vector(l.value("position", json()), at + ".position", position, 3, -Huge, Huge) ||
        !p.Vector(l.value("intensity", json()), at + ".intensity", power, 3, 0, Huge))
      {
        return fail();
      }
      if (type == "spot" &&
        (!p.Vector(l.value("direction", json()), at + ".direction", direction, 3, -Huge, Huge) ||
          !p.Number(l.value("cone_angle", json()), at + ".cone_angle", cone, 1e-6, 180)))
      {
        return fail();
      }
    }
    else if (type == "directional")
    {
      if (!p.Vector(l.value("direction", json()), at + ".direction", direction, 3, -Huge, Huge) ||
        !p.Vector(l.value("irradiance", json()), at + ".irradiance", power, 3, 0, Huge))
      {
        return fail();
      }
    }
    else
    {
      p.Fail(at + ".type", "expected 'point', 'spot' or 'directional', not '" + type + "'");
      return fail();
    }
    if (type != "point" &&
      !(std::sqrt(direction[0] * direction[0] + direction[1] * direction[1] +
          direction[2] * direction[2]) > 0))
    {
      p.Fail(at + ".direction", "the direction is zero");
      return fail();
    }
    if (!(power[0] + power[1] + power[2] > 0))
    {
      p.Fail(
        at + (type == "directional" ? ".irradiance" : ".intensity"), "the light has zero power");
      return fail();
    }
    AddString(fd, "BrumeLightType", type);
    AddTuple(fd, "BrumeLightPosition", position, 3);
    AddTuple(fd, "BrumeLightDirection", direction, 3);
    AddTuple(fd, "BrumeLightIntensity", power, 3);
    AddTuple(fd, "BrumeLightConeAngle", &cone, 1);
  }

  // Camera and render settings.
  const json camera = root.value("camera", json::object());
  if (!p.Keys(camera, "camera", { "position", "focal_point", "view_up", "view_angle" }))
  {
    return fail();
  }
  double position[3], focal[3], up[3], angle;
  vtkBrumeSceneCamera::GetDefault(position, focal, up, angle);
  if ((camera.contains("position") &&
        !p.Vector(camera["position"], "camera.position", position, 3, -Huge, Huge)) ||
    (camera.contains("focal_point") &&
      !p.Vector(camera["focal_point"], "camera.focal_point", focal, 3, -Huge, Huge)) ||
    (camera.contains("view_up") &&
      !p.Vector(camera["view_up"], "camera.view_up", up, 3, -Huge, Huge)) ||
    (camera.contains("view_angle") &&
      !p.Number(camera["view_angle"], "camera.view_angle", angle, 1e-3, 179)))
  {
    return fail();
  }
  const double view[3] = { focal[0] - position[0], focal[1] - position[1], focal[2] - position[2] };
  const double cross[3] = { view[1] * up[2] - view[2] * up[1], view[2] * up[0] - view[0] * up[2],
    view[0] * up[1] - view[1] * up[0] };
  if (!(view[0] * view[0] + view[1] * view[1] + view[2] * view[2] > 0))
  {
    p.Fail("camera.position", "the camera sits on its focal point");
    return fail();
  }
  if (!(cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2] > 0))
  {
    p.Fail("camera.view_up", "zero or parallel to the view direction");
    return fail();
  }
  AddTuple(fd, "BrumeCameraPosition", position, 3);
  AddTuple(fd, "BrumeCameraFocalPoint", focal, 3);
  AddTuple(fd, "BrumeCameraViewUp", up, 3);
  AddTuple(fd, "BrumeCameraViewAngle", &angle, 1);
  const json render = root.value("render", json::object());
  if (!p.Keys(render, "render", { "particles", "size", "threshold", "seed", "exposure" }))
  {
    return fail();
  }
  double particles = 1e6, size[2] = { 512, 512 }, threshold = 128, seed = 0, exposure = 1;
  if ((render.contains("particles") &&
        !p.Number(render["particles"], "render.particles", particles, 1, 1e10)) ||
    (render.contains("size") && !p.Vector(render["size"], "render.size", size, 2, 1, 16384)) ||
    (render.contains("threshold") &&
      !p.Number(render["threshold"], "render.threshold", threshold, 1e-6, 1e12)) ||
    (render.contains("seed") && !p.Number(render["seed"], "render.seed", seed, 0, 9e15)) ||
    (render.contains("exposure") &&
      !p.Number(render["exposure"], "render.exposure", exposure, 0, 1e12)))
  {
    return fail();
  }
  AddTuple(fd, "BrumeRenderParticles", &particles, 1);
  AddTuple(fd, "BrumeRenderSize", size, 2);
  AddTuple(fd, "BrumeRenderThreshold", &threshold, 1);
  AddTuple(fd, "BrumeRenderSeed", &seed, 1);
  AddTuple(fd, "BrumeRenderExposure", &exposure, 1);
  if (scene->GetNumberOfPartitionedDataSets() == 0)
  {
    p.Fail("surfaces", "the scene has no surfaces and no media");
    return fail();
  }
  // Everything the tracer will check (zero-area geometry, densities read from
  // VTI or VDB files, material energy) is checked here, so that a bad file
  // fails when it is read and the message names the file.
  brume::Scene check;
  const std::string invalid = vtkBrumeSceneConversion::ToScene(scene, check);
  if (!invalid.empty())
  {
    // Name the field: the object the message quotes, else its kind.
    std::string field = invalid.rfind("medium", 0) == 0 ? "media"
      : invalid.rfind("light", 0) == 0 || invalid.find("no light") != std::string::npos
      ? "lights"
      : "surfaces";
    const auto open = invalid.find('\''), close = invalid.find('\'', open + 1);
    if (open != std::string::npos && close != std::string::npos)
    {
      const std::string quoted = invalid.substr(open + 1, close - open - 1);
      for (const auto& object : objectFields)
      {
        if (object.first == quoted)
        {
          field = object.second;
          break;
        }
      }
    }
    p.Fail(field, invalid);
    return fail();
  }
  output->ShallowCopy(scene);
  return 1;
}

void vtkBrumeSceneReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
}
