// SPDX-License-Identifier: BSD-3-Clause
// vtkBrumeSceneFileParser's media: coefficients, boxes, densities (OpenVDB
// and .vti files, announced extents checked before reading) and transfer
// functions.
#include "vtkBrumeSceneFileParser.h"
#include "vtkBrumeSceneFileParserInternals.h"

#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeSceneFileCache.h"
#include "vtkBrumeSceneFileChecks.h"
#include "vtkBrumeXMLReaders.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include "brume/Scene.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <vector>

using namespace vtkBrumeSceneFileParserInternals;

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
  AddTuple(mfd, vtkBrumeNames::SigmaA, sa, 3);
  AddTuple(mfd, vtkBrumeNames::SigmaS, ss, 3);
  AddTuple(mfd, vtkBrumeNames::G, &g, 1);
  AddTuple(mfd, vtkBrumeNames::DensityScale, &scale, 1);
  vtkBrumeSceneConversion::AddObject(this->Scene, image, name);
  // A step of a time series names its file in later messages.
  this->ObjectFields.emplace_back(name, this->StepField.empty() ? at : this->StepField);
  this->StepField.clear();
  return true;
}

bool vtkBrumeSceneFileParser::ParseVdb(
  const json& density, const std::string& at, vtkImageData* image)
{
  Parser& p = *this->P;
  auto relative = [this](const std::string& name) { return this->Relative(name); };
  std::string file, field, grid;
  if (!this->StepFile(density, "vdb", at + ".density", file, field))
  {
    return false;
  }
  if (!std::filesystem::exists(relative(file)))
  {
    p.Fail(field, "no file '" + relative(file).string() + "'");
    return false;
  }
  AddString(image->GetFieldData(), vtkBrumeNames::VDBFile, relative(file).string());
  if (density.contains("grid"))
  {
    if (!p.String(density["grid"], at + ".density.grid", grid))
    {
      return false;
    }
    AddString(image->GetFieldData(), vtkBrumeNames::VDBGrid, grid);
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
    AddTuple(fd, vtkBrumeNames::ScalarComponent, &component, 1);
  }
  const json& f = density["transfer_function"];
  const std::string tf = at + ".transfer_function";
  if (!p.Keys(f, tf, { "opacity", "color", "unit_distance", "interpolation" }))
  {
    return false;
  }
  const json& opacity = f.value("opacity", json());
  if (!opacity.is_array() || opacity.empty())
  {
    return p.Fail(tf + ".opacity", "expected [[scalar, opacity], ...] with at least one point");
  }
  vtkNew<vtkDoubleArray> points;
  points->SetName(vtkBrumeNames::ScalarOpacity);
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
  // The colour: a factor on the albedo, point by point.
  if (f.contains("color"))
  {
    const json& color = f["color"];
    if (!color.is_array() || color.empty())
    {
      return p.Fail(
        tf + ".color", "expected [[scalar, red, green, blue], ...] with at least one point");
    }
    vtkNew<vtkDoubleArray> colors;
    colors->SetName(vtkBrumeNames::ScalarColor);
    colors->SetNumberOfComponents(4);
    for (std::size_t i = 0; i < color.size(); ++i)
    {
      const std::string point = tf + ".color[" + std::to_string(i) + "]";
      double tuple[4];
      if (!color[i].is_array() || color[i].size() != 4)
      {
        return p.Fail(point, "expected [scalar, red, green, blue]");
      }
      if (!p.Number(color[i][0], point + "[0]", tuple[0], -Huge, Huge))
      {
        return false;
      }
      for (int c = 1; c < 4; ++c)
      {
        if (!p.Number(color[i][c], point + "[" + std::to_string(c) + "]", tuple[c], 0, 1))
        {
          return false;
        }
      }
      if (i > 0 && tuple[0] < colors->GetComponent(static_cast<vtkIdType>(i) - 1, 0))
      {
        return p.Fail(point + "[0]", "scalars must not decrease from point to point");
      }
      colors->InsertNextTuple(tuple);
    }
    fd->AddArray(colors);
  }
  double unit = 1;
  if (f.contains("unit_distance") &&
    (!p.Number(f["unit_distance"], tf + ".unit_distance", unit, 0, Huge) ||
      (!(unit > 0) && !p.Fail(tf + ".unit_distance", "expected a length above 0"))))
  {
    return false;
  }
  AddTuple(fd, vtkBrumeNames::ScalarOpacityUnitDistance, &unit, 1);
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
    AddString(fd, vtkBrumeNames::Interpolation, interpolation);
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
  bool empty = false;
  for (int a = 0; a < 3; ++a)
  {
    const double n = static_cast<double>(extent[2 * a + 1]) - extent[2 * a] + 1.0;
    points *= std::max(n, 0.0);
    empty = empty || n < 1.0;
    dims << (a ? " x " : "") << static_cast<long long>(n);
  }
  if (empty)
  {
    // An inverted extent (a fuzzer's "0 1023 0 1023 8 0") gives VTK an
    // image of negative dimensions.
    std::ostringstream os;
    os << "'" << file << "' announces the whole extent " << extent[0] << " " << extent[1] << " "
       << extent[2] << " " << extent[3] << " " << extent[4] << " " << extent[5] << ", "
       << dims.str() << " points: none";
    return os.str();
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

namespace
{
// The times of a density given as `n` files (time steps): its "times",
// strictly increasing, or 0, 1, ..., n - 1; false with `problem` (the
// message, after the field) otherwise.
bool StepTimes(const nlohmann::json& density, std::size_t n, std::vector<double>& times,
  std::string& field, std::string& problem)
{
  times.clear();
  if (!density.contains("times"))
  {
    for (std::size_t k = 0; k < n; ++k)
    {
      times.push_back(static_cast<double>(k));
    }
    return true;
  }
  const nlohmann::json& given = density["times"];
  if (!given.is_array() || given.size() != n)
  {
    problem = "expected " + std::to_string(n) + " numbers, one time per file";
    return false;
  }
  for (std::size_t k = 0; k < n; ++k)
  {
    const double t = given[k].is_number() ? given[k].get<double>() : std::nan("");
    if (!std::isfinite(t) || std::abs(t) > Huge || (k > 0 && !(t > times.back())))
    {
      field = "[" + std::to_string(k) + "]";
      problem = "expected finite numbers, each greater than the one before";
      return false;
    }
    times.push_back(t);
  }
  return true;
}
}

std::vector<double> vtkBrumeSceneFileParser::TimeSteps(const json& root)
{
  std::vector<double> all;
  const json media = root.is_object() && root.contains("media") ? root["media"] : json::array();
  for (std::size_t i = 0; media.is_array() && i < media.size(); ++i)
  {
    const json& m = media[i];
    const json density = m.is_object() ? m.value("density", json::object()) : json::object();
    for (const char* key : { "vti", "vdb" })
    {
      std::vector<double> times;
      std::string field, problem;
      if (density.is_object() && density.contains(key) && density[key].is_array() &&
        StepTimes(density, density[key].size(), times, field, problem))
      {
        all.insert(all.end(), times.begin(), times.end());
      }
    }
  }
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  return all;
}

bool vtkBrumeSceneFileParser::StepFile(const json& density, const std::string& key,
  const std::string& at, std::string& file, std::string& field)
{
  Parser& p = *this->P;
  field = at + "." + key;
  const json& given = density[key];
  if (!given.is_array())
  {
    if (density.contains("times"))
    {
      return p.Fail(at + ".times", "needs a list of files in '" + key + "', one per time");
    }
    return p.String(given, field, file);
  }
  if (given.empty())
  {
    return p.Fail(field, "expected a file, or a list of files (the time steps), not []");
  }
  std::vector<double> times;
  std::string suffix, problem;
  if (!StepTimes(density, given.size(), times, suffix, problem))
  {
    return p.Fail(at + ".times" + suffix, problem);
  }
  // Every step named and there, before any is read.
  for (std::size_t k = 0; k < given.size(); ++k)
  {
    const std::string step = field + "[" + std::to_string(k) + "]";
    std::string name;
    if (!p.String(given[k], step, name))
    {
      return false;
    }
    if (!std::filesystem::exists(this->Relative(name)))
    {
      return p.Fail(step, "no file '" + this->Relative(name).string() + "'");
    }
  }
  // The last step at or before the time asked for; the first before it.
  std::size_t step = 0;
  while (this->HasTime && step + 1 < times.size() && times[step + 1] <= this->Time)
  {
    ++step;
  }
  field += "[" + std::to_string(step) + "]";
  file = given[step].get<std::string>();
  this->StepField = field;
  return true;
}

vtkSmartPointer<vtkImageData> vtkBrumeSceneFileParser::ReadImage(
  const std::filesystem::path& file, const std::string& field)
{
  Parser& p = *this->P;
  if (this->Cache)
  {
    if (auto* kept = vtkImageData::SafeDownCast(this->Cache->Find(file, "vti")))
    {
      return kept;
    }
  }
  vtkNew<vtkBrumeXMLImageDataReader> reader; // appended data too, whatever the expat
  reader->SetFileName(file.string().c_str());
  const bool display = vtkObject::GetGlobalWarningDisplay();
  vtkObject::GlobalWarningDisplayOff();
  // The arrays and the extent the header announces, before anything is
  // allocated for them: VTK's reader sets up every component an array
  // announces when it reads the data.
  std::string announced;
  const bool fits = vtkBrumeSceneFileChecks::XmlArrays(reader, file, announced);
  const std::string tooLarge = !fits ? announced
    : reader->GetExecutive()->UpdateInformation() != 0
    ? CheckAnnouncedExtent(reader->GetOutputInformation(0), file.string())
    : std::string();
  if (!tooLarge.empty())
  {
    vtkObject::SetGlobalWarningDisplay(display);
    p.Fail(field, tooLarge);
    return nullptr;
  }
  const int ok = reader->GetExecutive()->Update();
  vtkObject::SetGlobalWarningDisplay(display);
  if (!ok || reader->GetOutput()->GetNumberOfPoints() == 0)
  {
    p.Fail(field, "cannot read '" + file.string() + "'");
    return nullptr;
  }
  vtkSmartPointer<vtkImageData> read = reader->GetOutput();
  if (this->Cache)
  {
    this->Cache->Keep(file, "vti", read);
  }
  return read;
}

vtkSmartPointer<vtkImageData> vtkBrumeSceneFileParser::ParseDensity(
  const json& m, const std::string& at)
{
  Parser& p = *this->P;
  auto relative = [this](const std::string& name) { return this->Relative(name); };
  vtkSmartPointer<vtkImageData> image;
  const json density = m.value("density", json::object());
  if (!p.Keys(density, at + ".density",
        { "vdb", "grid", "vti", "array", "component", "transfer_function", "times" }))
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
    std::string file, field;
    if (!this->StepFile(density, "vti", at + ".density", file, field))
    {
      return nullptr;
    }
    vtkSmartPointer<vtkImageData> read = this->ReadImage(relative(file), field);
    if (!read)
    {
      return nullptr;
    }
    image = vtkSmartPointer<vtkImageData>::New();
    image->ShallowCopy(read);
    image->GetFieldData()->Initialize();
    if (density.contains("array"))
    {
      std::string array;
      if (!p.String(density["array"], at + ".density.array", array))
      {
        return nullptr;
      }
      AddString(image->GetFieldData(), vtkBrumeNames::DensityArray, array);
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
