// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeSceneFileParser.h"
#include "vtkBrumeSceneFileParserInternals.h"

#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeSceneCamera.h"
#include "vtkBrumeSceneConversion.h"
#include "vtkBrumeSceneFileCache.h"
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

#include "brume/Scene.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>
#include <utility>

using namespace vtkBrumeSceneFileParserInternals;

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
  // The objects' and lights' ids are 16-bit: vtkBrumeSceneReader counts
  // them as it reads the file, before this document is built, and refuses
  // more than brume::Scene::MaxObjectsAndLights (brume::Scene::Validate
  // holds the same limit for scenes built otherwise).
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
    // A mesh read before (a scene stepping through time) is not read
    // again: its points and cells are shared, its material set afresh.
    vtkSmartPointer<vtkPolyData> read =
      this->Cache ? vtkPolyData::SafeDownCast(this->Cache->Find(relative(file), "mesh")) : nullptr;
    if (!read)
    {
      read = vtkBrumeSceneGeometry::Read(relative(file), error);
      if (!read)
      {
        p.Fail(at + ".file", error);
        return false;
      }
      if (this->Cache)
      {
        this->Cache->Keep(relative(file), "mesh", read);
      }
    }
    surface = vtkSmartPointer<vtkPolyData>::New();
    surface->ShallowCopy(read);
    surface->GetFieldData()->DeepCopy(read->GetFieldData());
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
    AddString(sfd, vtkBrumeNames::Material, type);
  }
  for (const auto& key : { std::make_pair("reflectance", vtkBrumeNames::Reflectance),
         std::make_pair("specular", vtkBrumeNames::Specular),
         std::make_pair("emission", vtkBrumeNames::Emission) })
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
    AddTuple(sfd, vtkBrumeNames::Exponent, &e, 1);
  }
  return true;
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
  AddString(fd, vtkBrumeNames::LightType, type);
  AddTuple(fd, vtkBrumeNames::LightPosition, position, 3);
  AddTuple(fd, vtkBrumeNames::LightDirection, direction, 3);
  AddTuple(fd, vtkBrumeNames::LightIntensity, power, 3);
  AddTuple(fd, vtkBrumeNames::LightConeAngle, &cone, 1);
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
  AddTuple(fd, vtkBrumeNames::CameraPosition, position, 3);
  AddTuple(fd, vtkBrumeNames::CameraFocalPoint, focal, 3);
  AddTuple(fd, vtkBrumeNames::CameraViewUp, up, 3);
  AddTuple(fd, vtkBrumeNames::CameraViewAngle, &angle, 1);
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
  AddTuple(fd, vtkBrumeNames::RenderParticles, &particles, 1);
  AddTuple(fd, vtkBrumeNames::RenderSize, size, 2);
  AddTuple(fd, vtkBrumeNames::RenderThreshold, &threshold, 1);
  AddTuple(fd, vtkBrumeNames::RenderSeed, &seed, 1);
  AddTuple(fd, vtkBrumeNames::RenderExposure, &exposure, 1);
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
    if (this->Cache)
    {
      std::vector<std::shared_ptr<const brume::DensityField>> densities;
      for (const brume::Medium& medium : check.Media)
      {
        if (medium.Density)
        {
          densities.push_back(medium.Density);
        }
      }
      this->Cache->KeepDensities(std::move(densities));
    }
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
