// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeStabilitySweep.h"

#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeErrorPlot.h"
#include "vtkBrumeEvaluationTable.h"
#include "vtkBrumeEvaluationView.h"
#include "vtkBrumeImageError.h"
#include "vtkBrumeReferenceCache.h"
#include "vtkBrumeSceneConversion.h"
#include "vtkBrumeTimedPipeline.h"
#include "vtkCamera.h"
#include "vtkCompositeDataSet.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkMath.h"
#include "vtkObjectFactory.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkTable.h"

#include "brume/RayCaster.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkBrumeStabilitySweep);

namespace
{
using Scene = vtkPartitionedDataSetCollection;

// The reference's seed is apart from the images' (as in vtkBrumeErrorChart).
constexpr vtkIdType ReferenceSeedOffset = 1000003;

// An object's name as the scene conversion gives it.
std::string NameOf(Scene* scene, unsigned int i)
{
  if (scene->HasMetaData(i) && scene->GetMetaData(i)->Has(vtkCompositeDataSet::NAME()))
  {
    return scene->GetMetaData(i)->Get(vtkCompositeDataSet::NAME());
  }
  return "object" + std::to_string(i);
}

vtkDataObject* ObjectData(Scene* scene, unsigned int i)
{
  vtkPartitionedDataSet* object = scene->GetPartitionedDataSet(i);
  return object && object->GetNumberOfPartitions() > 0 ? object->GetPartition(0) : nullptr;
}

// Sets a field array of the scene object `object`.
void SetField(Scene* scene, int object, const char* array, const std::vector<double>& values)
{
  vtkFieldData* fd = ObjectData(scene, object)->GetFieldData();
  vtkNew<vtkDoubleArray> a;
  a->SetName(array);
  a->SetNumberOfComponents(static_cast<int>(values.size()));
  a->InsertNextTuple(values.data());
  fd->RemoveArray(array);
  fd->AddArray(a);
}

void SetMaterial(Scene* scene, int object, const char* type)
{
  vtkFieldData* fd = ObjectData(scene, object)->GetFieldData();
  vtkNew<vtkStringArray> a;
  a->SetName(vtkBrumeNames::Material);
  a->InsertNextValue(type);
  fd->RemoveArray(vtkBrumeNames::Material);
  fd->AddArray(a);
}

struct Case
{
  std::string Parameter, Value;
  std::string Object; // the edited medium's name, for the cache key
  std::function<void(Scene*)> Edit;
  vtkTypeInt64 Particles;
};

// The medium made a sheet through its box's centre, tilted 45 degrees
// about y (seen obliquely from a camera on z), `voxels` cells of a 64^3
// grid over the box thick, of optical depth 1 across (albedo 0.9): a
// structure thinner than the textures' texels, whatever its thickness.
void MakeSheet(Scene* scene, int medium, double voxels)
{
  auto* image = vtkImageData::SafeDownCast(ObjectData(scene, medium));
  if (!image)
  {
    return;
  }
  double b[6];
  image->GetBounds(b);
  constexpr int N = 64;
  const double h[3] = { (b[1] - b[0]) / (N - 1), (b[3] - b[2]) / (N - 1), (b[5] - b[4]) / (N - 1) };
  const double cell = std::cbrt(h[0] * h[1] * h[2]), thickness = voxels * cell;
  const double centre[3] = { 0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]) };
  image->SetOrigin(b[0], b[2], b[4]);
  image->SetSpacing(h[0], h[1], h[2]);
  image->SetDimensions(N, N, N);
  vtkNew<vtkDoubleArray> density;
  density->SetName("density");
  density->SetNumberOfTuples(static_cast<vtkIdType>(N) * N * N);
  for (int k = 0; k < N; ++k)
  {
    for (int j = 0; j < N; ++j)
    {
      for (int i = 0; i < N; ++i)
      {
        // Distance to the sheet's mid-plane (normal (1, 0, 1) / sqrt(2)),
        // the profile box-filtered over one cell.
        const double d =
          std::abs((b[0] + i * h[0] - centre[0]) + (b[4] + k * h[2] - centre[2])) / std::sqrt(2.0);
        density->SetValue((static_cast<vtkIdType>(k) * N + j) * N + i,
          std::clamp((0.5 * thickness - d) / cell + 0.5, 0.0, 1.0));
      }
    }
  }
  image->GetPointData()->SetScalars(density);
  SetField(
    scene, medium, vtkBrumeNames::SigmaS, { 0.9 / thickness, 0.9 / thickness, 0.9 / thickness });
  SetField(
    scene, medium, vtkBrumeNames::SigmaA, { 0.1 / thickness, 0.1 / thickness, 0.1 / thickness });
}

// Whether the medium is read from an OpenVDB file (BrumeVDBFile), which
// gives its box and density: its image's geometry and arrays are not used.
bool FromVdbFile(Scene* scene, int medium)
{
  vtkDataObject* data = ObjectData(scene, medium);
  return data && data->GetFieldData()->GetAbstractArray(vtkBrumeNames::VDBFile);
}

// `reshape`: the sheet cases too, which replace the medium's grid.
void AddMediumCases(
  std::vector<Case>& cases, int medium, const std::string& name, vtkTypeInt64 n, bool reshape)
{
  for (double g : { -0.99, -0.5, 0.0, 0.5, 0.75, 0.8, 0.9, 0.95, 0.99 })
  {
    cases.push_back({ "g", std::to_string(g), name,
      [=](Scene* s) { SetField(s, medium, vtkBrumeNames::G, { g }); }, n });
  }
  for (double k : { 0.001, 0.1, 1.0, 10.0, 100.0, 1000.0 })
  {
    cases.push_back({ "optical thickness", std::to_string(1.1 * k), name,
      [=](Scene* s)
      {
        SetField(s, medium, vtkBrumeNames::SigmaS, { k, k, k });
        SetField(s, medium, vtkBrumeNames::SigmaA, { 0.1 * k, 0.1 * k, 0.1 * k });
      },
      n });
  }
  for (double a : { 0.0, 0.5, 0.9, 0.99, 0.999, 1.0 })
  {
    cases.push_back({ "albedo", std::to_string(a), name,
      [=](Scene* s)
      {
        SetField(s, medium, vtkBrumeNames::SigmaS, { 1.1 * a, 1.1 * a, 1.1 * a });
        SetField(s, medium, vtkBrumeNames::SigmaA, { 1.1 * (1 - a), 1.1 * (1 - a), 1.1 * (1 - a) });
      },
      n });
  }
  for (double voxels : { 1.0, 2.0, 4.0 })
  {
    if (!reshape)
    {
      break;
    }
    cases.push_back({ "sheet voxels", std::to_string(voxels), name,
      [=](Scene* s) { MakeSheet(s, medium, voxels); }, n });
  }
}

void AddSurfaceCases(std::vector<Case>& cases, int surface, const std::string& name, vtkTypeInt64 n)
{
  cases.push_back({ name, "glossy", "",
    [=](Scene* s)
    {
      SetMaterial(s, surface, "phong");
      SetField(s, surface, vtkBrumeNames::Reflectance, { 0.2, 0.2, 0.2 });
      SetField(s, surface, vtkBrumeNames::Specular, { 0.6, 0.6, 0.6 });
      SetField(s, surface, vtkBrumeNames::Exponent, { 50 });
    },
    n });
  cases.push_back({ name, "glossy e=1000", "",
    [=](Scene* s)
    {
      SetMaterial(s, surface, "phong");
      SetField(s, surface, vtkBrumeNames::Reflectance, { 0.2, 0.2, 0.2 });
      SetField(s, surface, vtkBrumeNames::Specular, { 0.6, 0.6, 0.6 });
      SetField(s, surface, vtkBrumeNames::Exponent, { 1000 });
    },
    n });
  cases.push_back({ name, "mirror", "",
    [=](Scene* s)
    {
      SetMaterial(s, surface, "mirror");
      SetField(s, surface, vtkBrumeNames::Reflectance, { 0, 0, 0 });
      SetField(s, surface, vtkBrumeNames::Specular, { 0.9, 0.9, 0.9 });
    },
    n });
}

// The medium's box grown along one axis until the surface stands inside
// it: along the axis where the surface lies beside the box (the two
// overlapping across the other axes; the nearest such, where several),
// the face nearest the surface moved past it by a quarter of the distance
// from the surface to the far face, as a fog bank or a cloud reaching
// into the ground. The density grid is stretched with it. `bounds` gets
// the new box; true also when the surface already crosses the box (kept);
// false when the surface is beside the box along no axis.
bool GrownThrough(Scene* scene, int medium, int surface, double bounds[6])
{
  auto* image = vtkImageData::SafeDownCast(ObjectData(scene, medium));
  auto* mesh = vtkPolyData::SafeDownCast(ObjectData(scene, surface));
  if (!image || !mesh || mesh->GetNumberOfPoints() == 0 || FromVdbFile(scene, medium))
  {
    return false;
  }
  double s[6];
  image->GetBounds(bounds);
  mesh->GetBounds(s);
  auto overlaps = [&](int a)
  { return s[2 * a] < bounds[2 * a + 1] && s[2 * a + 1] > bounds[2 * a]; };
  if (overlaps(0) && overlaps(1) && overlaps(2))
  {
    return true; // the surface crosses the box already
  }
  int axis = -1;
  double gap = std::numeric_limits<double>::infinity();
  bool below = false;
  for (int a = 0; a < 3; ++a)
  {
    if (!overlaps((a + 1) % 3) || !overlaps((a + 2) % 3))
    {
      continue;
    }
    if (s[2 * a + 1] <= bounds[2 * a] && bounds[2 * a] - s[2 * a + 1] < gap)
    {
      axis = a;
      gap = bounds[2 * a] - s[2 * a + 1];
      below = true;
    }
    else if (s[2 * a] >= bounds[2 * a + 1] && s[2 * a] - bounds[2 * a + 1] < gap)
    {
      axis = a;
      gap = s[2 * a] - bounds[2 * a + 1];
      below = false;
    }
  }
  if (axis < 0)
  {
    return false;
  }
  const int a = axis;
  if (below)
  {
    bounds[2 * a] = s[2 * a] - 0.25 * (bounds[2 * a + 1] - s[2 * a]);
  }
  else
  {
    bounds[2 * a + 1] = s[2 * a + 1] + 0.25 * (s[2 * a + 1] - bounds[2 * a]);
  }
  return true;
}

// Its references are cached under the medium's and the surface's names:
// each surface makes another scene.
void AddSurfaceInMediumCases(std::vector<Case>& cases, int medium, const std::string& name,
  const std::string& surface, const double bounds[6], vtkTypeInt64 n)
{
  const std::array<double, 6> box{ bounds[0], bounds[1], bounds[2], bounds[3], bounds[4],
    bounds[5] };
  for (double k : { 1.0, 10.0, 100.0 })
  {
    cases.push_back({ "surface in medium", std::to_string(1.1 * k), name + " through " + surface,
      [=](Scene* s)
      {
        auto* image = vtkImageData::SafeDownCast(ObjectData(s, medium));
        int extent[6];
        image->GetExtent(extent);
        double spacing[3], origin[3];
        image->GetSpacing(spacing);
        for (int a = 0; a < 3; ++a)
        {
          const int cells = extent[2 * a + 1] - extent[2 * a];
          spacing[a] = cells > 0 ? (box[2 * a + 1] - box[2 * a]) / cells : spacing[a];
          origin[a] = box[2 * a] - extent[2 * a] * spacing[a];
        }
        image->SetOrigin(origin);
        image->SetSpacing(spacing);
        SetField(s, medium, vtkBrumeNames::SigmaS, { k, k, k });
        SetField(s, medium, vtkBrumeNames::SigmaA, { 0.1 * k, 0.1 * k, 0.1 * k });
      },
      n });
  }
}

// The collection index of the non-emissive surface hit by the most pixels'
// primary rays (ties: the first); -1 when the scene has none.
int MostVisibleSurface(Scene* collection, const brume::PinholeCamera& camera, std::string& error)
{
  brume::Scene scene;
  std::vector<vtkBrumeSceneConversion::ObjectSource> sources;
  error = vtkBrumeSceneConversion::ToScene(collection, scene, &sources);
  if (!error.empty())
  {
    return -1;
  }
  std::vector<long long> pixels(scene.Surfaces.size(), 0);
  if (!scene.Surfaces.empty())
  {
    const brume::RayCaster caster(scene);
    if (!caster.GetError().empty())
    {
      error = caster.GetError();
      return -1;
    }
    for (int y = 0; y < camera.Height; ++y)
    {
      for (int x = 0; x < camera.Width; ++x)
      {
        brume::Vec3 o, d;
        camera.Ray(x + 0.5f, y + 0.5f, o, d);
        brume::SurfaceHit hit;
        if (caster.Intersect(o, d, 0.f, std::numeric_limits<float>::infinity(), hit))
        {
          ++pixels[hit.Surface];
        }
      }
    }
  }
  int best = -1;
  for (std::size_t s = 0; s < scene.Surfaces.size(); ++s)
  {
    if (!scene.Surfaces[s].IsEmitter() && (best < 0 || pixels[s] > pixels[best]))
    {
      best = static_cast<int>(s);
    }
  }
  return best < 0 ? -1 : static_cast<int>(sources[best].CollectionIndex);
}

// What one case needs besides its scene.
struct Settings
{
  vtkCamera* Camera;
  const int* Size;
  double Threshold;
  vtkIdType Seed;
  int Order;
  int Supersampling;
  int ReferenceSamples;
  const char* CacheDirectory;
  std::string Key;
};

// One case's measurements.
struct Row
{
  double PipelineSeconds = 0, PipelineMae = 0, PipelineBlock = 0;
  int Spp = 0;
  double TracerSeconds = 0, TracerMae = 0, TracerBlock = 0;
  bool Finite = true;
  double ShMae = 0, ShBlock = 0;
  double ReferenceNoise = 0;
};

// The reference's own noise, as a relative MAE would see it: the mean
// absolute deviation of a normal error of the pixels' standard errors
// (sqrt(2/pi) of them; the Variance array: of each pixel's mean), over the
// mean radiance. An image equal to the truth would score about this much.
double ReferenceNoise(vtkImageData* reference)
{
  vtkDataArray* radiance = reference->GetPointData()->GetArray(vtkBrumeNames::Radiance);
  vtkDataArray* variance = reference->GetPointData()->GetArray(vtkBrumeNames::Variance);
  if (!radiance || !variance || variance->GetNumberOfTuples() != radiance->GetNumberOfTuples())
  {
    return 0.0;
  }
  double deviation = 0.0, mean = 0.0;
  const int channels = std::min(3, radiance->GetNumberOfComponents());
  for (vtkIdType i = 0; i < radiance->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < channels; ++c)
    {
      deviation += std::sqrt(std::max(0.0, variance->GetComponent(i, c)));
      mean += radiance->GetComponent(i, c);
    }
  }
  return mean > 0.0 ? std::sqrt(2.0 / vtkMath::Pi()) * deviation / mean : 0.0;
}

vtkSmartPointer<vtkBrumeTimedPipeline> Pipeline(
  const Settings& s, vtkDataObject* scene, vtkTypeInt64 particles, bool directional)
{
  auto run = vtkSmartPointer<vtkBrumeTimedPipeline>::New();
  run->SetInputData(scene);
  run->SetCamera(s.Camera);
  run->SetSize(s.Size[0], s.Size[1]);
  run->SetNumberOfParticles(particles);
  run->SetRadiosityThreshold(s.Threshold);
  run->SetSeed(s.Seed);
  run->SetDirectionalRadiance(directional);
  run->SetDirectionalOrder(s.Order);
  run->SetSupersampling(s.Supersampling);
  return run->GetExecutive()->Update() ? run : nullptr;
}

// A path-traced image: cached when `directory` is given.
vtkSmartPointer<vtkBrumeReferenceCache> PathTrace(const Settings& s, vtkDataObject* scene, int spp,
  vtkIdType seed, const char* directory = nullptr, const std::string& key = "")
{
  auto tracer = vtkSmartPointer<vtkBrumeReferenceCache>::New();
  tracer->SetInputData(scene);
  tracer->SetCamera(s.Camera);
  tracer->SetSize(s.Size[0], s.Size[1]);
  tracer->SetSamplesPerPixel(spp);
  tracer->SetSeed(seed);
  tracer->SetCacheDirectory(directory);
  tracer->SetSceneKey(key.c_str());
  return tracer->GetExecutive()->Update() ? tracer : nullptr;
}

// The pipeline and the path tracer given the pipeline's time, against a
// converged reference of the case.
bool RunCase(const Settings& s, const Case& k, Scene* scene, Row& row)
{
  std::string name = (k.Object.empty() ? "" : k.Object + "-") + k.Parameter + "-" + k.Value;
  std::replace(name.begin(), name.end(), ' ', '_');
  const auto converged = PathTrace(s, scene, s.ReferenceSamples, s.Seed + ReferenceSeedOffset,
    s.CacheDirectory, s.Key + "-sweep-" + name);
  const auto run = converged ? Pipeline(s, scene, k.Particles, false) : nullptr;
  vtkNew<vtkBrumeImageError> error;
  if (!run || !error->Compare(run->GetOutput(), converged->GetOutput()))
  {
    return false;
  }
  row.PipelineSeconds = run->GetFullSeconds();
  row.PipelineMae = error->GetRelativeMAE();
  row.ReferenceNoise = ReferenceNoise(converged->GetOutput());
  row.PipelineBlock = error->GetBlockError();
  // The path tracer given the pipeline's time: its speed from one sample.
  const auto oneSample = PathTrace(s, scene, 1, s.Seed);
  if (!oneSample)
  {
    return false;
  }
  row.Spp = std::max(
    1, static_cast<int>(row.PipelineSeconds / std::max(oneSample->GetRenderSeconds(), 1e-6)));
  const auto tracer = PathTrace(s, scene, row.Spp, s.Seed);
  if (!tracer || !error->Compare(tracer->GetOutput(), converged->GetOutput()))
  {
    return false;
  }
  row.TracerSeconds = tracer->GetRenderSeconds();
  row.TracerMae = error->GetRelativeMAE();
  row.TracerBlock = error->GetBlockError();
  // The same budget with directional (spherical-harmonics) media.
  const auto sh = Pipeline(s, scene, k.Particles, true);
  if (!sh || !error->Compare(sh->GetOutput(), converged->GetOutput()))
  {
    return false;
  }
  row.ShMae = error->GetRelativeMAE();
  row.ShBlock = error->GetBlockError();
  row.Finite = vtkBrumeImageError::IsFinite(run->GetOutput()) &&
    vtkBrumeImageError::IsFinite(sh->GetOutput()) &&
    vtkBrumeImageError::IsFinite(tracer->GetOutput()) &&
    vtkBrumeImageError::IsFinite(converged->GetOutput());
  return true;
}

// The table's columns, in the CSV's order.
struct Columns
{
  vtkStringArray *Parameter, *Value;
  vtkDoubleArray *PipelineSeconds, *PipelineMae, *TracerSeconds, *TracerMae, *ShMae;
  vtkIntArray *Spp, *Finite;
  vtkDoubleArray *PipelineBlock, *TracerBlock, *ShBlock, *ReferenceNoise;

  explicit Columns(vtkTable* table)
  {
    using T = vtkBrumeEvaluationTable;
    this->Parameter = T::AddColumn<vtkStringArray>(table, "parameter");
    this->Value = T::AddColumn<vtkStringArray>(table, "value");
    this->PipelineSeconds = T::AddColumn<vtkDoubleArray>(table, "pipeline_seconds");
    this->PipelineMae = T::AddColumn<vtkDoubleArray>(table, "pipeline_rel_mae");
    this->Spp = T::AddColumn<vtkIntArray>(table, "pathtracer_spp");
    this->TracerSeconds = T::AddColumn<vtkDoubleArray>(table, "pathtracer_seconds");
    this->TracerMae = T::AddColumn<vtkDoubleArray>(table, "pathtracer_rel_mae");
    this->Finite = T::AddColumn<vtkIntArray>(table, "finite");
    this->ShMae = T::AddColumn<vtkDoubleArray>(table, "pipeline_sh_rel_mae");
    this->PipelineBlock = T::AddColumn<vtkDoubleArray>(table, "pipeline_block_error");
    this->TracerBlock = T::AddColumn<vtkDoubleArray>(table, "pathtracer_block_error");
    this->ShBlock = T::AddColumn<vtkDoubleArray>(table, "pipeline_sh_block_error");
    this->ReferenceNoise = T::AddColumn<vtkDoubleArray>(table, "reference_noise");
  }

  void Add(const Case& k, const Row& row)
  {
    this->Value->InsertNextValue(k.Value);
    this->PipelineSeconds->InsertNextValue(row.PipelineSeconds);
    this->PipelineMae->InsertNextValue(row.PipelineMae);
    this->Spp->InsertNextValue(row.Spp);
    this->TracerSeconds->InsertNextValue(row.TracerSeconds);
    this->TracerMae->InsertNextValue(row.TracerMae);
    this->Finite->InsertNextValue(row.Finite ? 1 : 0);
    this->ShMae->InsertNextValue(row.ShMae);
    this->PipelineBlock->InsertNextValue(row.PipelineBlock);
    this->TracerBlock->InsertNextValue(row.TracerBlock);
    this->ShBlock->InsertNextValue(row.ShBlock);
    this->ReferenceNoise->InsertNextValue(row.ReferenceNoise);
    // Last: the first column counts the table's rows.
    this->Parameter->InsertNextValue(k.Parameter);
  }
};
}

vtkBrumeStabilitySweep::vtkBrumeStabilitySweep() = default;

vtkBrumeStabilitySweep::~vtkBrumeStabilitySweep()
{
  this->SetMediumName(nullptr);
  this->SetSurfaceName(nullptr);
  this->SetParameter(nullptr);
}

bool vtkBrumeStabilitySweep::FindMedium(vtkDataObject* input, int& index)
{
  index = -1;
  this->ChosenMedium.clear();
  const auto scene = vtkBrumeSceneConversion::AsCollection(input);
  if (!scene)
  {
    vtkErrorMacro("The input must be a Brume scene (a vtkPartitionedDataSetCollection).");
    return false;
  }
  const std::string wanted = this->MediumName ? this->MediumName : "";
  for (unsigned int i = 0; i < scene->GetNumberOfPartitionedDataSets() && index < 0; ++i)
  {
    const bool medium = vtkImageData::SafeDownCast(ObjectData(scene, i)) != nullptr;
    if (!wanted.empty() && NameOf(scene, i) == wanted && !medium)
    {
      vtkErrorMacro("The scene object '" << wanted << "' is not a medium (a vtkImageData).");
      return false;
    }
    if (medium && (wanted.empty() || NameOf(scene, i) == wanted))
    {
      index = static_cast<int>(i);
      this->ChosenMedium = NameOf(scene, i);
    }
  }
  if (!wanted.empty() && index < 0)
  {
    vtkErrorMacro("The scene has no medium named '" << wanted << "'.");
    return false;
  }
  return true;
}

bool vtkBrumeStabilitySweep::FindSurface(vtkDataObject* input, int& index)
{
  index = -1;
  this->ChosenSurface.clear();
  const auto scene = vtkBrumeSceneConversion::AsCollection(input);
  if (!scene)
  {
    vtkErrorMacro("The input must be a Brume scene (a vtkPartitionedDataSetCollection).");
    return false;
  }
  const std::string wanted = this->SurfaceName ? this->SurfaceName : "";
  if (wanted.empty())
  {
    // On a grid 128 rays wide, whatever the image size, so that the choice
    // does not depend on it.
    const int width = 128;
    const int height = std::max(1, static_cast<int>(width * this->Size[1] / this->Size[0]));
    const brume::PinholeCamera camera = vtkBrumeEvaluationView::Pinhole(
      vtkBrumeEvaluationView::Camera(scene, this->Camera), width, height);
    std::string error;
    index = MostVisibleSurface(scene, camera, error);
    if (!error.empty())
    {
      vtkErrorMacro("Cannot choose a surface: invalid scene: " << error << ".");
      return false;
    }
  }
  for (unsigned int i = 0; i < scene->GetNumberOfPartitionedDataSets() && !wanted.empty(); ++i)
  {
    if (NameOf(scene, i) == wanted)
    {
      if (!vtkPolyData::SafeDownCast(ObjectData(scene, i)))
      {
        vtkErrorMacro("The scene object '" << wanted << "' is not a surface (a vtkPolyData).");
        return false;
      }
      index = static_cast<int>(i);
      break;
    }
  }
  if (!wanted.empty() && index < 0)
  {
    vtkErrorMacro("The scene has no surface named '" << wanted << "'.");
    return false;
  }
  this->ChosenSurface = index < 0 ? "" : NameOf(scene, index);
  return true;
}

const char* vtkBrumeStabilitySweep::ChooseMedium(vtkDataObject* scene)
{
  int index = -1;
  return this->FindMedium(scene, index) ? this->ChosenMedium.c_str() : nullptr;
}

const char* vtkBrumeStabilitySweep::ChooseSurface(vtkDataObject* scene)
{
  int index = -1;
  return this->FindSurface(scene, index) ? this->ChosenSurface.c_str() : nullptr;
}

int vtkBrumeStabilitySweep::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  const auto scene =
    vtkBrumeSceneConversion::AsCollection(vtkDataObject::GetData(inputVector[0], 0));
  vtkTable* output = vtkTable::GetData(outputVector, 0);
  this->AllFinite = true;
  if (!this->CheckCommonSettings())
  {
    return 0;
  }
  if (this->MaxParticles < 1)
  {
    vtkErrorMacro("MaxParticles must be at least 1, not " << this->MaxParticles << ".");
    return 0;
  }
  int medium = -1, surface = -1;
  if (!this->FindMedium(scene, medium) || !this->FindSurface(scene, surface))
  {
    return 0;
  }
  const vtkTypeInt64 particles = this->MaxParticles;
  std::vector<Case> cases;
  if (medium >= 0)
  {
    AddMediumCases(cases, medium, this->ChosenMedium, particles, !FromVdbFile(scene, medium));
  }
  for (vtkTypeInt64 n = std::max<vtkTypeInt64>(100, this->MinParticles); n <= particles; n *= 10)
  {
    cases.push_back({ "particles", std::to_string(n), "", [](Scene*) {}, n });
  }
  if (surface >= 0)
  {
    AddSurfaceCases(cases, surface, this->ChosenSurface, particles);
  }
  double grown[6];
  if (medium >= 0 && surface >= 0 && GrownThrough(scene, medium, surface, grown))
  {
    AddSurfaceInMediumCases(
      cases, medium, this->ChosenMedium, this->ChosenSurface, grown, particles);
  }
  if (this->Parameter && *this->Parameter)
  {
    const std::string wanted = this->Parameter;
    cases.erase(std::remove_if(
                  cases.begin(), cases.end(), [&](const Case& k) { return k.Parameter != wanted; }),
      cases.end());
    if (cases.empty())
    {
      vtkErrorMacro("No case of the sweep varies '"
        << wanted
        << "' (g, optical thickness, albedo, sheet voxels, particles, the surface's name, or "
           "surface in medium).");
      return 0;
    }
  }

  const vtkSmartPointer<vtkCamera> camera = vtkBrumeEvaluationView::Camera(scene, this->Camera);
  const Settings settings{ camera, this->Size, this->RadiosityThreshold, this->Seed,
    this->DirectionalOrder, this->Supersampling, this->ReferenceSamples, this->CacheDirectory,
    this->CacheKey && *this->CacheKey ? this->CacheKey : (this->SceneName ? this->SceneName : "") };
  // One untimed run first: OpenGL start-up and shader compilation.
  if (!Pipeline(settings, scene, 1000, false))
  {
    return 0;
  }
  Columns columns(output);
  for (std::size_t c = 0; c < cases.size(); ++c)
  {
    const Case& k = cases[c];
    auto edited = vtkSmartPointer<Scene>::New();
    edited->DeepCopy(scene);
    k.Edit(edited);
    Row row;
    if (!RunCase(settings, k, edited, row))
    {
      vtkErrorMacro("The case " << k.Parameter << " = " << k.Value << " failed.");
      return 0;
    }
    this->AllFinite = this->AllFinite && row.Finite;
    columns.Add(k, row);
    this->UpdateProgress(static_cast<double>(c + 1) / cases.size());
  }
  return 1;
}

bool vtkBrumeStabilitySweep::WriteImage(const char* fileName)
{
  vtkTable* table = this->GetOutput();
  const char* columns[3][2] = { { "pipeline_rel_mae", "pipeline" },
    { "pipeline_sh_rel_mae", "pipeline, SH media" },
    { "pathtracer_rel_mae", "path-tracer, same time" } };
  vtkNew<vtkBrumeErrorPlot> plot;
  for (const auto& column : columns)
  {
    vtkDataArray* mae = vtkArrayDownCast<vtkDataArray>(table->GetColumnByName(column[0]));
    for (vtkIdType r = 0; mae && r < mae->GetNumberOfTuples(); ++r)
    {
      plot->AddPoint(column[1], static_cast<double>(r + 1), mae->GetTuple1(r));
    }
  }
  plot->SetTitle("Brume stability sweep: error per case (see the CSV)");
  plot->SetXTitle("case");
  plot->LogXOff();
  if (!plot->Write(fileName))
  {
    vtkErrorMacro("Could not write the chart to " << (fileName ? fileName : "(no file)") << ".");
    return false;
  }
  return true;
}

void vtkBrumeStabilitySweep::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  auto text = [](const char* s) { return s ? s : ""; };
  os << indent << "MediumName: " << text(this->MediumName) << "\n";
  os << indent << "SurfaceName: " << text(this->SurfaceName) << "\n";
  os << indent << "Parameter: " << text(this->Parameter) << "\n";
  os << indent << "AllFinite: " << this->AllFinite << "\n";
}
