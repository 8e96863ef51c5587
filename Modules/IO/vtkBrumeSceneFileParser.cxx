// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeSceneFileParser.h"

#include "vtkBrumeSceneCamera.h"
#include "vtkBrumeSceneConversion.h"
#include "vtkBrumeSceneFileChecks.h"
#include "vtkBrumeSceneGeometry.h"
#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtkXMLImageDataReader.h"

#include "brume/Scene.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>
#include <utility>

namespace
{
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
}

// Reads values with errors that name the file and the field.
class vtkBrumeSceneFileParser::Parser
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

  /// A whole number in [lo, hi] (2.0 is accepted, 2.5 is not).
  bool Integer(const json& j, const std::string& path, double& out, double lo, double hi)
  {
    if (!this->Number(j, path, out, lo, hi))
    {
      return false;
    }
    if (out != std::floor(out))
    {
      std::ostringstream os;
      os << "expected a whole number in [" << lo << ", " << hi << "], not " << out;
      return this->Fail(path, os.str());
    }
    return true;
  }

  bool IntegerVector(
    const json& j, const std::string& path, double* out, int n, double lo, double hi)
  {
    if (!j.is_array() || static_cast<int>(j.size()) != n)
    {
      return this->Fail(path, "expected " + std::to_string(n) + " whole numbers");
    }
    for (int i = 0; i < n; ++i)
    {
      if (!this->Integer(j[i], path + "[" + std::to_string(i) + "]", out[i], lo, hi))
      {
        return false;
      }
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

vtkBrumeSceneFileParser::vtkBrumeSceneFileParser(const std::string& fileName)
  : P(new Parser(fileName))
  , Directory(std::filesystem::path(fileName).parent_path())
{
}

vtkBrumeSceneFileParser::~vtkBrumeSceneFileParser() = default;

const std::string& vtkBrumeSceneFileParser::GetError() const
{
  return this->P->Error;
}

std::filesystem::path vtkBrumeSceneFileParser::Relative(const std::string& name) const
{
  return this->Directory / std::filesystem::path(name);
}

bool vtkBrumeSceneFileParser::Parse(const json& root, vtkPartitionedDataSetCollection* scene)
{
  Parser& p = *this->P;
  this->Scene = scene;
  if (!p.Keys(root, "(top)",
        { "brume_scene", "name", "camera", "render", "surfaces", "media", "lights" }))
  {
    return false;
  }
  double version = 0;
  if (!root.contains("brume_scene"))
  {
    return p.Fail("brume_scene", "missing: the format version (1)");
  }
  std::string name;
  if (root.contains("name") && !p.String(root["name"], "name", name))
  {
    return false;
  }
  return p.Number(root["brume_scene"], "brume_scene", version, 1, 1) &&
    this->ParseArray(root, "surfaces", &vtkBrumeSceneFileParser::ParseSurface) &&
    this->ParseArray(root, "media", &vtkBrumeSceneFileParser::ParseMedium) &&
    this->ParseArray(root, "lights", &vtkBrumeSceneFileParser::ParseLight) &&
    this->ParseCamera(root) && this->ParseRender(root) && this->CheckScene();
}

bool vtkBrumeSceneFileParser::ParseArray(const json& root, const char* key,
  bool (vtkBrumeSceneFileParser::*parseOne)(const json&, std::size_t))
{
  if (root.contains(key) && !root[key].is_array())
  {
    this->P->Fail(key, "expected an array");
    return false;
  }
  const json items = root.value(key, json::array());
  for (std::size_t i = 0; i < items.size(); ++i)
  {
    if (!(this->*parseOne)(items[i], i))
    {
      return false;
    }
  }
  return true;
}

bool vtkBrumeSceneFileParser::ParseSurface(const json& s, std::size_t i)
{
  Parser& p = *this->P;
  auto relative = [this](const std::string& name) { return this->Relative(name); };
  const std::string at = "surfaces[" + std::to_string(i) + "]";
  std::string name;
  if (!p.Keys(s, at, { "name", "file", "quad", "material" }) ||
    !p.String(s.value("name", json()), at + ".name", name))
  {
    return false;
  }
  vtkSmartPointer<vtkPolyData> surface;
  if (s.contains("file") == s.contains("quad"))
  {
    p.Fail(at, "needs exactly one of 'file' and 'quad'");
    return false;
  }
  if (s.contains("file"))
  {
    std::string file, error;
    if (!p.String(s["file"], at + ".file", file))
    {
      return false;
    }
    surface = vtkBrumeSceneGeometry::Read(relative(file), error);
    if (!surface)
    {
      p.Fail(at + ".file", error);
      return false;
    }
  }
  else
  {
    const json& quad = s["quad"];
    if (!quad.is_array() || quad.size() != 4)
    {
      p.Fail(at + ".quad", "expected 4 corners");
      return false;
    }
    vtkNew<vtkPoints> points;
    for (int k = 0; k < 4; ++k)
    {
      double v[3];
      if (!p.Vector(quad[k], at + ".quad[" + std::to_string(k) + "]", v, 3, -Huge, Huge))
      {
        return false;
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
  if (!this->ParseMaterial(s.value("material", json::object()), at + ".material", surface))
  {
    return false;
  }
  vtkBrumeSceneConversion::AddObject(this->Scene, surface, name);
  this->ObjectFields.emplace_back(name, at);
  return true;
}

bool vtkBrumeSceneFileParser::ParseMaterial(
  const json& material, const std::string& m, vtkPolyData* surface)
{
  Parser& p = *this->P;
  if (!p.Keys(material, m, { "type", "reflectance", "specular", "exponent", "emission" }))
  {
    return false;
  }
  vtkFieldData* sfd = surface->GetFieldData();
  if (material.contains("type"))
  {
    std::string type;
    if (!p.String(material["type"], m + ".type", type))
    {
      return false;
    }
    if (type != "lambertian" && type != "phong" && type != "mirror")
    {
      p.Fail(m + ".type", "expected 'lambertian', 'phong' or 'mirror', not '" + type + "'");
      return false;
    }
    AddString(sfd, "BrumeMaterial", type);
  }
  for (const auto& key : { std::make_pair("reflectance", "BrumeReflectance"),
         std::make_pair("specular", "BrumeSpecular"), std::make_pair("emission", "BrumeEmission") })
  {
    if (material.contains(key.first))
    {
      double v[3];
      const double hi = std::string(key.first) == "emission" ? Huge : 1.0;
      if (!p.Vector(material[key.first], m + "." + key.first, v, 3, 0.0, hi))
      {
        return false;
      }
      AddTuple(sfd, key.second, v, 3);
    }
  }
  if (material.contains("exponent"))
  {
    double e = 0;
    if (!p.Number(material["exponent"], m + ".exponent", e, 1e-6, 1e6))
    {
      return false;
    }
    AddTuple(sfd, "BrumeExponent", &e, 1);
  }
  return true;
}

bool vtkBrumeSceneFileParser::ParseMedium(const json& m, std::size_t i)
{
  Parser& p = *this->P;
  const std::string at = "media[" + std::to_string(i) + "]";
  std::string name;
  if (!p.Keys(m, at,
        { "name", "box", "sigma_a", "sigma_s", "albedo", "g", "density_scale", "density" }) ||
    !p.String(m.value("name", json()), at + ".name", name))
  {
    return false;
  }
  double sa[3], ss[3], g = 0, scale = 1;
  const bool classified =
    m.contains("density") && m["density"].is_object() && m["density"].contains("transfer_function");
  if (m.contains("albedo"))
  {
    // A transfer function's extinction split by one albedo colour.
    if (!classified)
    {
      return p.Fail(at + ".albedo",
        "needs a density.transfer_function (a medium without one gives sigma_a and sigma_s)");
    }
    if (m.contains("sigma_a") || m.contains("sigma_s"))
    {
      return p.Fail(at + ".albedo", "give either albedo or sigma_a and sigma_s, not both");
    }
    if (!p.Vector(m["albedo"], at + ".albedo", ss, 3, 0, 1))
    {
      return false;
    }
    for (int c = 0; c < 3; ++c)
    {
      sa[c] = 1.0 - ss[c];
    }
  }
  else if (!p.Vector(m.value("sigma_a", json()), at + ".sigma_a", sa, 3, 0, Huge) ||
    !p.Vector(m.value("sigma_s", json()), at + ".sigma_s", ss, 3, 0, Huge))
  {
    return false;
  }
  if (m.contains("g") && !p.Number(m["g"], at + ".g", g, -0.999999, 0.999999))
  {
    return false;
  }
  if (m.contains("density_scale") &&
    !p.Number(m["density_scale"], at + ".density_scale", scale, 0, Huge))
  {
    return false;
  }
  vtkSmartPointer<vtkImageData> image = this->ParseDensity(m, at);
  if (!image)
  {
    return false;
  }
  vtkFieldData* mfd = image->GetFieldData();
  AddTuple(mfd, "BrumeSigmaA", sa, 3);
  AddTuple(mfd, "BrumeSigmaS", ss, 3);
  AddTuple(mfd, "BrumeG", &g, 1);
  AddTuple(mfd, "BrumeDensityScale", &scale, 1);
  vtkBrumeSceneConversion::AddObject(this->Scene, image, name);
  this->ObjectFields.emplace_back(name, at);
  return true;
}

bool vtkBrumeSceneFileParser::ParseVdb(
  const json& density, const std::string& at, vtkImageData* image)
{
  Parser& p = *this->P;
  auto relative = [this](const std::string& name) { return this->Relative(name); };
  std::string file, grid;
  if (!p.String(density["vdb"], at + ".density.vdb", file))
  {
    return false;
  }
  if (!std::filesystem::exists(relative(file)))
  {
    p.Fail(at + ".density.vdb", "no file '" + relative(file).string() + "'");
    return false;
  }
  AddString(image->GetFieldData(), "BrumeVDBFile", relative(file).string());
  if (density.contains("grid"))
  {
    if (!p.String(density["grid"], at + ".density.grid", grid))
    {
      return false;
    }
    AddString(image->GetFieldData(), "BrumeVDBGrid", grid);
  }
  if (density.contains("transfer_function") &&
    !this->ParseTransferFunction(density, at + ".density", image))
  {
    return false;
  }
  return true;
}

bool vtkBrumeSceneFileParser::ParseTransferFunction(
  const json& density, const std::string& at, vtkImageData* image)
{
  Parser& p = *this->P;
  vtkFieldData* fd = image->GetFieldData();
  if (density.contains("component"))
  {
    double component = 0;
    if (!p.Integer(density["component"], at + ".component", component, 0, 3))
    {
      return false;
    }
    AddTuple(fd, "BrumeScalarComponent", &component, 1);
  }
  const json& f = density["transfer_function"];
  const std::string tf = at + ".transfer_function";
  if (!p.Keys(f, tf, { "opacity", "unit_distance", "interpolation" }))
  {
    return false;
  }
  const json& opacity = f.value("opacity", json());
  if (!opacity.is_array() || opacity.empty())
  {
    return p.Fail(tf + ".opacity", "expected [[scalar, opacity], ...] with at least one point");
  }
  vtkNew<vtkDoubleArray> points;
  points->SetName("BrumeScalarOpacity");
  points->SetNumberOfComponents(2);
  for (std::size_t i = 0; i < opacity.size(); ++i)
  {
    const std::string point = tf + ".opacity[" + std::to_string(i) + "]";
    double pair[2];
    if (!opacity[i].is_array() || opacity[i].size() != 2)
    {
      return p.Fail(point, "expected [scalar, opacity]");
    }
    if (!p.Number(opacity[i][0], point + "[0]", pair[0], -Huge, Huge) ||
      !p.Number(opacity[i][1], point + "[1]", pair[1], 0, 1))
    {
      return false;
    }
    if (i > 0 && pair[0] < points->GetComponent(static_cast<vtkIdType>(i) - 1, 0))
    {
      return p.Fail(point + "[0]", "scalars must not decrease from point to point");
    }
    points->InsertNextTuple(pair);
  }
  fd->AddArray(points);
  double unit = 1;
  if (f.contains("unit_distance") &&
    (!p.Number(f["unit_distance"], tf + ".unit_distance", unit, 0, Huge) ||
      (!(unit > 0) && !p.Fail(tf + ".unit_distance", "expected a length above 0"))))
  {
    return false;
  }
  AddTuple(fd, "BrumeScalarOpacityUnitDistance", &unit, 1);
  if (f.contains("interpolation"))
  {
    std::string interpolation;
    if (!p.String(f["interpolation"], tf + ".interpolation", interpolation))
    {
      return false;
    }
    if (interpolation != "linear" && interpolation != "nearest")
    {
      return p.Fail(
        tf + ".interpolation", "expected 'linear' or 'nearest', not '" + interpolation + "'");
    }
    AddString(fd, "BrumeInterpolation", interpolation);
  }
  return true;
}

void vtkBrumeSceneFileParser::SetBoxesFromGrids(
  const brume::Scene& scene, const std::vector<vtkBrumeSceneConversion::ObjectSource>& sources)
{
  for (std::size_t o = scene.Surfaces.size(); o < sources.size(); ++o)
  {
    auto* image = vtkImageData::SafeDownCast(
      this->Scene->GetPartitionedDataSet(sources[o].CollectionIndex)->GetPartition(0));
    if (std::find(this->BoxesFromGrids.begin(), this->BoxesFromGrids.end(), image) ==
      this->BoxesFromGrids.end())
    {
      continue;
    }
    const brume::Box& box = scene.Media[o - scene.Surfaces.size()].Bounds;
    image->SetOrigin(box.lower.x, box.lower.y, box.lower.z);
    const brume::Vec3 extent = box.Extent();
    image->SetSpacing(extent.x, extent.y, extent.z);
  }
}

namespace
{
// Why an image whose header announces `information`'s whole extent cannot
// be read (empty when it can): more than MaxDensityPoints points, or more
// bytes of float densities than half this machine's memory.
std::string CheckAnnouncedExtent(vtkInformation* information, const std::string& file)
{
  constexpr double MaxDensityPoints = 1073741824.0; // 2^30
  int extent[6] = { 0, -1, 0, -1, 0, -1 };
  if (!information || !information->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    return {};
  }
  information->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent);
  double points = 1.0;
  std::ostringstream dims;
  for (int a = 0; a < 3; ++a)
  {
    const double n = static_cast<double>(extent[2 * a + 1]) - extent[2 * a] + 1.0;
    points *= std::max(n, 0.0);
    dims << (a ? " x " : "") << static_cast<long long>(n);
  }
  const double memory = 2.0 * vtkBrumeSceneFileChecks::UsableMemory();
  const double bytes = points * static_cast<double>(sizeof(float));
  if (points > MaxDensityPoints || (memory > 0.0 && bytes > 0.5 * memory))
  {
    std::ostringstream os;
    os << "'" << file << "' announces " << dims.str() << " points (" << bytes
       << " bytes of densities): more than a density image may hold here (2^30 points, half of "
       << memory << " bytes of memory)";
    return os.str();
  }
  return {};
}
}

vtkSmartPointer<vtkImageData> vtkBrumeSceneFileParser::ParseDensity(
  const json& m, const std::string& at)
{
  Parser& p = *this->P;
  auto relative = [this](const std::string& name) { return this->Relative(name); };
  vtkSmartPointer<vtkImageData> image;
  const json density = m.value("density", json::object());
  if (!p.Keys(density, at + ".density",
        { "vdb", "grid", "vti", "array", "component", "transfer_function" }))
  {
    return nullptr;
  }
  if (density.contains("transfer_function") && !density.contains("vti") && !density.contains("vdb"))
  {
    p.Fail(at + ".density.transfer_function", "needs a 'vti' or 'vdb' density to classify");
    return nullptr;
  }
  if (density.contains("component") && !density.contains("vti"))
  {
    p.Fail(at + ".density.component", "needs a 'vti' density (an OpenVDB float grid has one)");
    return nullptr;
  }
  if (density.contains("component") && !density.contains("transfer_function"))
  {
    p.Fail(
      at + ".density.component", "needs a transfer_function (a density array has one component)");
    return nullptr;
  }
  if (density.contains("vdb") && density.contains("vti"))
  {
    p.Fail(at + ".density", "needs at most one of 'vdb' and 'vti'");
    return nullptr;
  }
  if (density.contains("vti"))
  {
    std::string file;
    if (!p.String(density["vti"], at + ".density.vti", file))
    {
      return nullptr;
    }
    vtkNew<vtkXMLImageDataReader> reader;
    reader->SetFileName(relative(file).string().c_str());
    const bool display = vtkObject::GetGlobalWarningDisplay();
    vtkObject::GlobalWarningDisplayOff();
    // The extent the header announces, before anything is allocated for it.
    const std::string tooLarge = reader->GetExecutive()->UpdateInformation() != 0
      ? CheckAnnouncedExtent(reader->GetOutputInformation(0), relative(file).string())
      : std::string();
    if (!tooLarge.empty())
    {
      vtkObject::SetGlobalWarningDisplay(display);
      p.Fail(at + ".density.vti", tooLarge);
      return nullptr;
    }
    const int ok = reader->GetExecutive()->Update();
    vtkObject::SetGlobalWarningDisplay(display);
    if (!ok || reader->GetOutput()->GetNumberOfPoints() == 0)
    {
      p.Fail(at + ".density.vti", "cannot read '" + relative(file).string() + "'");
      return nullptr;
    }
    image = vtkSmartPointer<vtkImageData>::New();
    image->ShallowCopy(reader->GetOutput());
    image->GetFieldData()->Initialize();
    if (density.contains("array"))
    {
      std::string array;
      if (!p.String(density["array"], at + ".density.array", array))
      {
        return nullptr;
      }
      AddString(image->GetFieldData(), "BrumeDensityArray", array);
    }
    if (density.contains("transfer_function") &&
      !this->ParseTransferFunction(density, at + ".density", image))
    {
      return nullptr;
    }
  }
  else if (density.contains("vdb") && !m.contains("box"))
  {
    // An OpenVDB medium without a box: the grid's active box, set once the
    // grid is read (CheckScene).
    image = vtkSmartPointer<vtkImageData>::New();
    image->SetDimensions(2, 2, 2);
    this->BoxesFromGrids.push_back(image);
    if (!this->ParseVdb(density, at, image))
    {
      return nullptr;
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
      return nullptr;
    }
    for (int a = 0; a < 3; ++a)
    {
      if (!(box[3 + a] > box[a]))
      {
        p.Fail(at + ".box", "the box is empty (max <= min)");
        return nullptr;
      }
    }
    image = vtkSmartPointer<vtkImageData>::New();
    image->SetOrigin(box[0], box[1], box[2]);
    image->SetSpacing(box[3] - box[0], box[4] - box[1], box[5] - box[2]);
    image->SetDimensions(2, 2, 2);
    if (density.contains("vdb") && !this->ParseVdb(density, at, image))
    {
      return nullptr;
    }
  }
  return image;
}

bool vtkBrumeSceneFileParser::ParseLight(const json& l, std::size_t i)
{
  Parser& p = *this->P;
  vtkFieldData* fd = this->Scene->GetFieldData();
  const std::string at = "lights[" + std::to_string(i) + "]";
  std::string type;
  if (!p.Keys(
        l, at, { "type", "position", "direction", "intensity", "irradiance", "cone_angle" }) ||
    !p.String(l.value("type", json()), at + ".type", type))
  {
    return false;
  }
  double position[3] = { 0, 0, 0 }, direction[3] = { 0, -1, 0 }, power[3], cone = 180;
  if (type == "point" || type == "spot")
  {
    if (!p.Vector(l.value("position", json()), at + ".position", position, 3, -Huge, Huge) ||
      !p.Vector(l.value("intensity", json()), at + ".intensity", power, 3, 0, Huge))
    {
      return false;
    }
    if (type == "spot" &&
      (!p.Vector(l.value("direction", json()), at + ".direction", direction, 3, -Huge, Huge) ||
        !p.Number(l.value("cone_angle", json()), at + ".cone_angle", cone, 1e-6, 180)))
    {
      return false;
    }
  }
  else if (type == "directional")
  {
    if (!p.Vector(l.value("direction", json()), at + ".direction", direction, 3, -Huge, Huge) ||
      !p.Vector(l.value("irradiance", json()), at + ".irradiance", power, 3, 0, Huge))
    {
      return false;
    }
  }
  else
  {
    p.Fail(at + ".type", "expected 'point', 'spot' or 'directional', not '" + type + "'");
    return false;
  }
  if (type != "point" &&
    !(std::sqrt(direction[0] * direction[0] + direction[1] * direction[1] +
        direction[2] * direction[2]) > 0))
  {
    p.Fail(at + ".direction", "the direction is zero");
    return false;
  }
  if (!(power[0] + power[1] + power[2] > 0))
  {
    p.Fail(at + (type == "directional" ? ".irradiance" : ".intensity"), "the light has zero power");
    return false;
  }
  AddString(fd, "BrumeLightType", type);
  AddTuple(fd, "BrumeLightPosition", position, 3);
  AddTuple(fd, "BrumeLightDirection", direction, 3);
  AddTuple(fd, "BrumeLightIntensity", power, 3);
  AddTuple(fd, "BrumeLightConeAngle", &cone, 1);
  return true;
}

bool vtkBrumeSceneFileParser::ParseCamera(const json& root)
{
  Parser& p = *this->P;
  vtkFieldData* fd = this->Scene->GetFieldData();
  const json camera = root.value("camera", json::object());
  if (!p.Keys(camera, "camera", { "position", "focal_point", "view_up", "view_angle" }))
  {
    return false;
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
    return false;
  }
  const double view[3] = { focal[0] - position[0], focal[1] - position[1], focal[2] - position[2] };
  const double cross[3] = { view[1] * up[2] - view[2] * up[1], view[2] * up[0] - view[0] * up[2],
    view[0] * up[1] - view[1] * up[0] };
  if (!(view[0] * view[0] + view[1] * view[1] + view[2] * view[2] > 0))
  {
    p.Fail("camera.position", "the camera sits on its focal point");
    return false;
  }
  if (!(cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2] > 0))
  {
    p.Fail("camera.view_up", "zero or parallel to the view direction");
    return false;
  }
  AddTuple(fd, "BrumeCameraPosition", position, 3);
  AddTuple(fd, "BrumeCameraFocalPoint", focal, 3);
  AddTuple(fd, "BrumeCameraViewUp", up, 3);
  AddTuple(fd, "BrumeCameraViewAngle", &angle, 1);
  return true;
}

bool vtkBrumeSceneFileParser::ParseRender(const json& root)
{
  Parser& p = *this->P;
  vtkFieldData* fd = this->Scene->GetFieldData();
  const json render = root.value("render", json::object());
  if (!p.Keys(render, "render", { "particles", "size", "threshold", "seed", "exposure" }))
  {
    return false;
  }
  double particles = 1e6, size[2] = { 512, 512 }, threshold = 128, seed = 0, exposure = 1;
  if ((render.contains("particles") &&
        !p.Integer(render["particles"], "render.particles", particles, 1, 1e10)) ||
    (render.contains("size") &&
      !p.IntegerVector(render["size"], "render.size", size, 2, 1, 16384)) ||
    (render.contains("threshold") &&
      !p.Number(render["threshold"], "render.threshold", threshold, 1e-6, 1e12)) ||
    (render.contains("seed") && !p.Integer(render["seed"], "render.seed", seed, 0, 9e15)) ||
    (render.contains("exposure") &&
      !p.Number(render["exposure"], "render.exposure", exposure, 0, 1e12)))
  {
    return false;
  }
  AddTuple(fd, "BrumeRenderParticles", &particles, 1);
  AddTuple(fd, "BrumeRenderSize", size, 2);
  AddTuple(fd, "BrumeRenderThreshold", &threshold, 1);
  AddTuple(fd, "BrumeRenderSeed", &seed, 1);
  AddTuple(fd, "BrumeRenderExposure", &exposure, 1);
  return true;
}

bool vtkBrumeSceneFileParser::CheckScene()
{
  Parser& p = *this->P;
  vtkPartitionedDataSetCollection* scene = this->Scene;
  if (scene->GetNumberOfPartitionedDataSets() == 0)
  {
    p.Fail("surfaces", "the scene has no surfaces and no media");
    return false;
  }
  // Everything the tracer will check (zero-area geometry, densities read from
  // VTI or VDB files, material energy) is checked here, so that a bad file
  // fails when it is read and the message names the file.
  brume::Scene check;
  std::vector<vtkBrumeSceneConversion::ObjectSource> sources;
  const std::string invalid = vtkBrumeSceneConversion::ToScene(scene, check, &sources);
  if (invalid.empty())
  {
    this->SetBoxesFromGrids(check, sources);
  }
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
      for (const auto& object : this->ObjectFields)
      {
        if (object.first == quoted)
        {
          field = object.second;
          break;
        }
      }
    }
    p.Fail(field, invalid);
    return false;
  }
  return true;
}
