// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeRadianceReconstruction.h"

#include "vtkBrumeSceneConversion.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCommunicator.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMultiProcessController.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkStringArray.h"
#include "vtkUnsignedIntArray.h"
#include "vtkUnsignedShortArray.h"

#include "brume/Reconstruction.h"
#include "brume/SphericalHarmonics.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

vtkStandardNewMacro(vtkBrumeRadianceReconstruction);
vtkCxxSetObjectMacro(vtkBrumeRadianceReconstruction, Camera, vtkCamera);
vtkCxxSetObjectMacro(vtkBrumeRadianceReconstruction, Controller, vtkMultiProcessController);

namespace
{
constexpr int MaxSurfaceResolution = 4096;
constexpr int MaxMediumResolution = 512;

void AddVec3(vtkFieldData* fd, const char* name, const brume::Vec3& v)
{
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->SetNumberOfComponents(3);
  a->InsertNextTuple3(v.x, v.y, v.z);
  fd->AddArray(a);
}

void AddKind(vtkFieldData* fd, const char* kind)
{
  vtkNew<vtkStringArray> a;
  a->SetName("BrumeObjectKind");
  a->InsertNextValue(kind);
  fd->AddArray(a);
}

vtkSmartPointer<vtkFloatArray> NewRGB(const char* name, const std::vector<float>& values)
{
  auto a = vtkSmartPointer<vtkFloatArray>::New();
  a->SetName(name);
  a->SetNumberOfComponents(3);
  a->SetNumberOfTuples(static_cast<vtkIdType>(values.size() / 3));
  std::copy(values.begin(), values.end(), a->GetPointer(0));
  return a;
}

// Resolution along the longer axis `n`, the others in proportion.
std::array<int, 3> FixedResolution(const brume::Vec3& extent, int n)
{
  const float longest = MaxComponent(extent);
  std::array<int, 3> res{ 1, 1, 1 };
  for (int a = 0; a < 3; ++a)
  {
    if (extent[a] > 0.f)
    {
      res[a] = std::max(1, static_cast<int>(std::lround(n * extent[a] / longest)));
    }
  }
  return res;
}

// A float view of a 3-component array: the array itself, or a float copy.
const float* FloatView(vtkDataArray* a, std::vector<float>& copy)
{
  if (auto* f = vtkFloatArray::SafeDownCast(a))
  {
    return f->GetPointer(0);
  }
  copy.resize(static_cast<std::size_t>(a->GetNumberOfValues()));
  for (vtkIdType i = 0; i < a->GetNumberOfValues(); ++i)
  {
    copy[i] = static_cast<float>(a->GetVariantValue(i).ToDouble());
  }
  return copy.data();
}
}

// Histograms summed along the processes of a controller, in rank order.
class ControllerChain : public brume::HistogramChain
{
public:
  explicit ControllerChain(vtkMultiProcessController* controller)
    : Controller(controller)
  {
  }
  void Receive(std::vector<double>& values) override
  {
    const auto start = std::chrono::steady_clock::now();
    const int rank = this->Controller->GetLocalProcessId();
    if (rank > 0)
    {
      this->Controller->Receive(
        values.data(), static_cast<vtkIdType>(values.size()), rank - 1, ChainTag);
      this->Bytes += values.size() * sizeof(double);
    }
    this->Seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  void Forward(std::vector<double>& values) override
  {
    const auto start = std::chrono::steady_clock::now();
    const int rank = this->Controller->GetLocalProcessId();
    const int last = this->Controller->GetNumberOfProcesses() - 1;
    if (rank < last)
    {
      this->Controller->Send(
        values.data(), static_cast<vtkIdType>(values.size()), rank + 1, ChainTag);
      this->Bytes += values.size() * sizeof(double);
    }
    this->Controller->Broadcast(values.data(), static_cast<vtkIdType>(values.size()), last);
    this->Bytes += values.size() * sizeof(double);
    this->Seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  /// Time spent in the chain (waiting for the processes before included).
  double Seconds = 0.0;

private:
  static constexpr int ChainTag = 24101;
  vtkMultiProcessController* Controller;
};

// Textures and what they were built from, kept between executions.
struct vtkBrumeRadianceReconstruction::Cache
{
  std::unique_ptr<ControllerChain> Chain; // distributed runs
  vtkMTimeType SceneTime = 0, HitsTime = 0;
  vtkDataObject* SceneData = nullptr; // the input as given
  vtkSmartPointer<vtkPartitionedDataSetCollection> SceneCollection; // as a collection
  vtkDataObject* HitsData = nullptr;
  double Threshold = 0.0;
  int SurfaceResolution = 0, MediumResolution = 0, Refinement = 0;
  brume::Scene Scene;
  std::vector<vtkBrumeSceneConversion::ObjectSource> Sources;
  std::vector<std::unique_ptr<brume::ObjectRadiance>> Objects;
  std::vector<vtkSmartPointer<vtkPartitionedDataSet>> Outputs;
  std::vector<brume::Vec3> ObjectEye; // the eye each texture was estimated toward
  std::vector<bool> ObjectDirectional; // whose output holds directional radiance
  double Particles = 0.0, Seed = 0.0;
  bool Accumulated = false; // particles were added after the build
  double LastFirstParticle = 0.0; // the first particle of the last step added
};

vtkBrumeRadianceReconstruction::vtkBrumeRadianceReconstruction()
{
  this->SetNumberOfInputPorts(2);
  this->SetController(vtkMultiProcessController::GetGlobalController());
}

vtkBrumeRadianceReconstruction::~vtkBrumeRadianceReconstruction()
{
  this->SetCamera(nullptr);
  this->SetController(nullptr);
}

vtkMTimeType vtkBrumeRadianceReconstruction::GetMTime()
{
  const vtkMTimeType t = this->Superclass::GetMTime();
  return this->Camera ? std::max(t, this->Camera->GetMTime()) : t;
}

int vtkBrumeRadianceReconstruction::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), port == 0 ? "vtkDataObject" : "vtkPolyData");
  return 1;
}

int vtkBrumeRadianceReconstruction::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // Distributed runs: every process must reach the same collective calls,
  // so a process that fails still takes part in the next agreement, and
  // the others stop there (no process is left waiting).
  vtkMultiProcessController* controller = this->Controller;
  const bool distributed = controller && controller->GetNumberOfProcesses() > 1;
  auto agree = [&](bool ok)
  {
    if (!distributed)
    {
      return ok;
    }
    const int local = ok ? 1 : 0;
    int all = 0;
    controller->AllReduce(&local, &all, 1, vtkCommunicator::MIN_OP);
    if (ok && !all)
    {
      vtkErrorMacro("Another process failed (see its errors): stopping.");
    }
    return all != 0;
  };
  vtkDataObject* sceneInput = vtkDataObject::GetData(inputVector[0], 0);
  const auto sceneHolder = vtkBrumeSceneConversion::AsCollection(sceneInput);
  vtkPartitionedDataSetCollection* sceneData = sceneHolder;
  if (!sceneData)
  {
    vtkErrorMacro("The scene must be a vtkPartitionedDataSetCollection, a vtkMultiBlockDataSet, "
                  "a vtkPolyData or a vtkImageData.");
    agree(false);
    return 0;
  }
  auto* hitData = vtkPolyData::GetData(inputVector[1], 0);
  auto* output = vtkPartitionedDataSetCollection::GetData(outputVector, 0);

  if (!(this->RadiosityThreshold > 0.0) || !std::isfinite(this->RadiosityThreshold))
  {
    vtkErrorMacro(
      "RadiosityThreshold must be positive and finite, not " << this->RadiosityThreshold << ".");
    agree(false);
    return 0;
  }
  if (this->SurfaceResolution < 0 || this->SurfaceResolution > MaxSurfaceResolution ||
    this->MediumResolution < 0 || this->MediumResolution > MaxMediumResolution)
  {
    vtkErrorMacro("SurfaceResolution must be in [0, "
      << MaxSurfaceResolution << "] and MediumResolution in [0, " << MaxMediumResolution << "].");
    agree(false);
    return 0;
  }
  if (this->HistogramRefinement < 1 || this->HistogramRefinement > 16)
  {
    vtkErrorMacro(
      "HistogramRefinement must be in [1, 16], not " << this->HistogramRefinement << ".");
    agree(false);
    return 0;
  }
  double eyePosition[3] = { this->EyePosition[0], this->EyePosition[1], this->EyePosition[2] };
  if (this->Camera)
  {
    this->Camera->GetPosition(eyePosition);
  }
  const brume::Vec3 eye(static_cast<float>(eyePosition[0]), static_cast<float>(eyePosition[1]),
    static_cast<float>(eyePosition[2]));
  if (!brume::IsFinite(eye))
  {
    vtkErrorMacro("The viewpoint must be finite.");
    agree(false);
    return 0;
  }

  // The hits, read in place.
  if (!hitData)
  {
    vtkErrorMacro("No particle hits were given.");
    agree(false);
    return 0;
  }
  vtkPointData* pd = hitData->GetPointData();
  auto* direction = vtkFloatArray::SafeDownCast(pd->GetArray("Direction"));
  auto* flux = vtkFloatArray::SafeDownCast(pd->GetArray("Flux"));
  auto* objectIds = vtkUnsignedShortArray::SafeDownCast(pd->GetArray("ObjectId"));
  auto* triangleIds = vtkUnsignedIntArray::SafeDownCast(pd->GetArray("TriangleId"));
  const vtkIdType n = hitData->GetNumberOfPoints();
  if (n > 0 &&
    (!direction || !flux || !objectIds || direction->GetNumberOfComponents() != 3 ||
      flux->GetNumberOfComponents() != 3 || direction->GetNumberOfTuples() != n ||
      flux->GetNumberOfTuples() != n || objectIds->GetNumberOfTuples() != n))
  {
    vtkErrorMacro("Invalid particle hits: they lack the float[3] 'Direction' and 'Flux' or the "
                  "unsigned short 'ObjectId' point arrays.");
    agree(false);
    return 0;
  }
  if (n > static_cast<vtkIdType>(UINT32_MAX))
  {
    vtkErrorMacro("More than 2^32 particle hits: reconstruct them in parts.");
    agree(false);
    return 0;
  }
  vtkFieldData* hitFields = hitData->GetFieldData();
  vtkDataArray* powerArray = hitFields ? hitFields->GetArray("TotalPower") : nullptr;
  vtkDataArray* countArray = hitFields ? hitFields->GetArray("NumberOfParticles") : nullptr;
  if (!powerArray || !countArray || powerArray->GetNumberOfComponents() != 3 ||
    powerArray->GetNumberOfTuples() < 1 || countArray->GetNumberOfTuples() < 1 ||
    !(countArray->GetTuple1(0) >= 1.0))
  {
    vtkErrorMacro("The particle hits lack the 'TotalPower' and 'NumberOfParticles' field arrays.");
    agree(false);
    return 0;
  }
  const double* power = powerArray->GetTuple3(0);
  auto fieldValue = [&](const char* name)
  {
    vtkDataArray* a = hitFields->GetArray(name);
    return a && a->GetNumberOfTuples() > 0 ? a->GetTuple1(0) : 0.0;
  };
  const double particles = countArray->GetTuple1(0);
  const double firstParticle = fieldValue("FirstParticle");
  const double seed = fieldValue("Seed");
  if (this->DirectionalOrder < 1 || this->DirectionalOrder > brume::MaxShOrder)
  {
    vtkErrorMacro("DirectionalOrder must be in [1, " << brume::MaxShOrder << "], not "
                                                     << this->DirectionalOrder << ".");
    agree(false);
    return 0;
  }
  if (firstParticle > 0.0 && !this->AccumulateParticles)
  {
    vtkErrorMacro("These hits are the particles ["
      << firstParticle << ", " << particles
      << ") of a run: turn AccumulateParticles on to add them to the earlier ones.");
    agree(false);
    return 0;
  }
  const double particleFlux = (power[0] + power[1] + power[2]) / 3.0 / countArray->GetTuple1(0);
  const double threshold = this->RadiosityThreshold * particleFlux;
  std::vector<float> positionCopy;
  brume::HitArrays hits;
  hits.Count = static_cast<std::size_t>(n);
  if (n > 0)
  {
    hits.Position = FloatView(hitData->GetPoints()->GetData(), positionCopy);
    hits.Direction = direction->GetPointer(0);
    hits.Flux = flux->GetPointer(0);
    hits.Object = objectIds->GetPointer(0);
    hits.Triangle =
      triangleIds && triangleIds->GetNumberOfTuples() == n ? triangleIds->GetPointer(0) : nullptr;
  }
  const brume::ParallelFor parallelFor = vtkBrumeSceneConversion::ParallelFor();

  // Distributed: the hits are this process's piece of the run; every
  // histogram is summed across the processes (bitwise as one process would).
  if (distributed && firstParticle > 0.0)
  {
    vtkErrorMacro("Adding particles (AccumulateParticles) is not supported across processes.");
    agree(false);
    return 0;
  }
  if (!agree(true))
  {
    return 0;
  }
  this->LastReductionBytes = 0;
  this->LastReductionSeconds = 0.0;

  // Rebuild everything when the inputs or the settings changed; add the
  // hits when they continue the run the textures hold; otherwise only the
  // view-dependent textures follow the viewpoint.
  Cache* cache = this->Cached.get();
  const bool sameSettings = cache && cache->SceneData == sceneInput &&
    cache->SceneTime == sceneInput->GetMTime() && cache->Threshold == this->RadiosityThreshold &&
    cache->SurfaceResolution == this->SurfaceResolution &&
    cache->MediumResolution == this->MediumResolution &&
    cache->Refinement == this->HistogramRefinement;
  // A tracer that ran again with the settings of the step already added
  // (same seed, particles [first, total)) brings nothing new.
  const bool sameStep = cache && firstParticle > 0.0 && cache->Accumulated &&
    cache->LastFirstParticle == firstParticle && cache->Particles == particles &&
    cache->Seed == seed;
  const bool newHits = !sameStep &&
    (!cache || cache->HitsData != hitData || cache->HitsTime != hitData->GetMTime());
  const bool accumulate = firstParticle > 0.0 && newHits;
  if (firstParticle > 0.0 && !newHits && !sameSettings)
  {
    // The hits hold only the last step's particles: the textures cannot be
    // rebuilt from them.
    vtkErrorMacro("The settings or the scene changed, but the hits are only the particles ["
      << firstParticle << ", " << particles
      << ") of a run: trace from FirstParticle 0 again to rebuild the textures.");
    this->Cached.reset();
    return 0;
  }
  if (accumulate)
  {
    if (!sameSettings || cache->Particles != firstParticle || cache->Seed != seed ||
      !(particles > firstParticle))
    {
      vtkErrorMacro("These hits continue a run of "
        << firstParticle << " particles (seed " << seed << ") but the textures hold "
        << (cache ? cache->Particles : 0.0) << " particles (seed " << (cache ? cache->Seed : 0.0)
        << ") of the same scene and settings: trace from FirstParticle 0 again.");
      return 0;
    }
    brume::ObjectHits groups;
    const std::string groupError =
      brume::GroupHitsByObject(hits, cache->Scene.NumberOfObjects(), groups);
    for (std::size_t o = 0; o < cache->Objects.size() && groupError.empty(); ++o)
    {
      const std::string error = cache->Objects[o]->Add(hits,
        groups.Index.data() + groups.Offset[o], groups.Offset[o + 1] - groups.Offset[o],
        cache->Particles / particles, cache->ObjectEye[o], threshold, parallelFor);
      if (!error.empty())
      {
        vtkErrorMacro("Cannot add particles to '" << cache->Sources[o].Name << "': " << error
                                                  << ".");
        this->Cached.reset();
        return 0;
      }
      cache->Outputs[o] = nullptr;
      ++this->NumberOfParticleAdditions;
    }
    if (!groupError.empty())
    {
      vtkErrorMacro("Invalid particle hits: " << groupError << ".");
      this->Cached.reset();
      return 0;
    }
    cache->HitsData = hitData;
    cache->HitsTime = hitData->GetMTime();
    cache->Particles = particles;
    cache->LastFirstParticle = firstParticle;
    cache->Accumulated = true;
  }
  const bool rebuild = !accumulate && (!sameSettings || newHits);
  if (rebuild)
  {
    this->Cached.reset(new Cache);
    cache = this->Cached.get();
    const std::string error =
      vtkBrumeSceneConversion::ToScene(sceneData, cache->Scene, &cache->Sources);
    brume::ObjectHits groups;
    const std::string groupError = error.empty()
      ? brume::GroupHitsByObject(hits, cache->Scene.NumberOfObjects(), groups)
      : std::string();
    if (!error.empty())
    {
      vtkErrorMacro("Invalid scene: " << error << ".");
    }
    else if (!groupError.empty())
    {
      vtkErrorMacro("Invalid particle hits: " << groupError << ".");
    }
    if (!agree(error.empty() && groupError.empty()))
    {
      this->Cached.reset();
      return 0;
    }
    const brume::Scene& scene = cache->Scene;
    const int refinement = this->HistogramRefinement;
    // Resolutions follow the hits of the whole run, on every process.
    std::vector<vtkTypeInt64> counts(scene.NumberOfObjects()), totals(counts.size());
    for (std::size_t o = 0; o < counts.size(); ++o)
    {
      counts[o] = static_cast<vtkTypeInt64>(groups.Offset[o + 1] - groups.Offset[o]);
    }
    totals = counts;
    if (distributed && !counts.empty())
    {
      controller->AllReduce(counts.data(), totals.data(), static_cast<vtkIdType>(counts.size()),
        vtkCommunicator::SUM_OP);
      cache->Chain.reset(new ControllerChain(controller));
    }
    for (std::size_t o = 0; o < scene.NumberOfObjects(); ++o)
    {
      const auto count = static_cast<std::size_t>(totals[o]);
      const auto& source = cache->Sources[o];
      vtkDataObject* sceneObject =
        sceneData->GetPartitionedDataSet(source.CollectionIndex)->GetPartition(0);
      vtkDataArray* override = sceneObject->GetFieldData()->GetArray("BrumeTextureResolution");
      const int perObject = override && override->GetNumberOfTuples() > 0
        ? static_cast<int>(override->GetTuple1(0))
        : 0;
      if (count == 0)
      {
        vtkWarningMacro("Object '" << source.Name
                                   << "' received no particle: its texture holds only its "
                                      "emission (more particles, or a light that reaches it).");
      }
      std::unique_ptr<brume::ObjectRadiance> radiance;
      // The object's own resolution, the filter's, or one chosen from its hits;
      // {0, 0, 0} (with an error) when the object's is too large.
      auto resolution = [&](const brume::Vec3& extent, int global, int maximum, int automatic)
      {
        const int fixed = perObject > 0 ? perObject : global;
        if (fixed > maximum)
        {
          vtkErrorMacro(
            "BrumeTextureResolution of '" << source.Name << "' exceeds " << maximum << ".");
          this->Cached.reset();
          return std::array<int, 3>{ 0, 0, 0 };
        }
        return fixed > 0
          ? FixedResolution(extent, fixed)
          : brume::ChooseResolution(extent, count, this->RadiosityThreshold, 4, automatic);
      };
      if (!scene.IsMedium(o))
      {
        const brume::Surface& surface = scene.Surfaces[o];
        auto* polyData = vtkPolyData::SafeDownCast(sceneObject);
        std::vector<std::array<float, 2>> tcoords;
        if (vtkDataArray* tc = polyData->GetPointData()->GetTCoords())
        {
          if (tc->GetNumberOfComponents() >= 2)
          {
            tcoords.resize(static_cast<std::size_t>(tc->GetNumberOfTuples()));
            for (vtkIdType i = 0; i < tc->GetNumberOfTuples(); ++i)
            {
              tcoords[i] = { static_cast<float>(tc->GetComponent(i, 0)),
                static_cast<float>(tc->GetComponent(i, 1)) };
            }
          }
        }
        brume::SurfaceChart chart = brume::MakeChart(surface, tcoords.empty() ? nullptr : &tcoords);
        const auto res = resolution(brume::Vec3(chart.Width, chart.Height, 0.f),
          this->SurfaceResolution, MaxSurfaceResolution, 1024);
        if (res[0] == 0)
        {
          return 0;
        }
        radiance.reset(new brume::ObjectRadiance(surface, chart, { res[0], res[1] }, refinement));
      }
      else
      {
        const brume::Medium& medium = scene.Media[o - scene.Surfaces.size()];
        const auto res =
          resolution(medium.Bounds.Extent(), this->MediumResolution, MaxMediumResolution, 256);
        if (res[0] == 0)
        {
          return 0;
        }
        radiance.reset(new brume::ObjectRadiance(medium, res, refinement));
      }
      radiance->SetChain(cache->Chain.get());
      cache->Objects.push_back(std::move(radiance));
      cache->Outputs.push_back(nullptr);
    }
    // Every process checks its hits before any enters the chain.
    bool hitsOk = true;
    for (std::size_t o = 0; o < cache->Objects.size() && distributed; ++o)
    {
      const std::string problem = cache->Objects[o]->Check(
        hits, groups.Index.data() + groups.Offset[o], groups.Offset[o + 1] - groups.Offset[o]);
      if (!problem.empty())
      {
        vtkErrorMacro("Cannot reconstruct '" << cache->Sources[o].Name << "': " << problem << ".");
        hitsOk = false;
      }
    }
    if (!agree(hitsOk))
    {
      this->Cached.reset();
      return 0;
    }
    // View-independent objects build concurrently (each on one thread: a
    // single pass in hit order); view-dependent ones then use every thread.
    std::vector<std::string> errors(cache->Objects.size());
    std::vector<vtkIdType> independent;
    for (std::size_t o = 0; o < cache->Objects.size(); ++o)
    {
      if (!cache->Objects[o]->IsViewDependent())
      {
        independent.push_back(static_cast<vtkIdType>(o));
      }
    }
    const brume::ParallelFor serialFor = brume::SerialFor();
    auto buildIndependent = [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType k = begin; k < end; ++k)
      {
        const auto o = static_cast<std::size_t>(independent[k]);
        errors[o] = cache->Objects[o]->Build(hits, groups.Index.data() + groups.Offset[o],
          groups.Offset[o + 1] - groups.Offset[o], eye, threshold, serialFor);
      }
    };
    if (distributed)
    {
      // One object at a time: the chain's messages follow the objects' order.
      buildIndependent(0, static_cast<vtkIdType>(independent.size()));
    }
    else
    {
      vtkSMPTools::For(0, static_cast<vtkIdType>(independent.size()), 1, buildIndependent);
    }
    this->UpdateProgress(0.5);
    for (std::size_t o = 0; o < cache->Objects.size(); ++o)
    {
      if (cache->Objects[o]->IsViewDependent())
      {
        errors[o] = cache->Objects[o]->Build(hits, groups.Index.data() + groups.Offset[o],
          groups.Offset[o + 1] - groups.Offset[o], eye, threshold, parallelFor);
      }
    }
    for (std::size_t o = 0; o < cache->Objects.size(); ++o)
    {
      if (!errors[o].empty())
      {
        vtkErrorMacro(
          "Cannot reconstruct '" << cache->Sources[o].Name << "': " << errors[o] << ".");
        this->Cached.reset();
        return 0;
      }
      ++this->NumberOfTextureBuilds;
    }
    cache->SceneData = sceneInput;
    cache->SceneCollection = sceneHolder;
    cache->HitsData = hitData;
    cache->SceneTime = sceneInput->GetMTime();
    cache->HitsTime = hitData->GetMTime();
    cache->Threshold = this->RadiosityThreshold;
    cache->SurfaceResolution = this->SurfaceResolution;
    cache->MediumResolution = this->MediumResolution;
    cache->Refinement = this->HistogramRefinement;
    cache->ObjectEye.assign(cache->Objects.size(), eye);
    cache->ObjectDirectional.assign(cache->Objects.size(), false);
    cache->Particles = particles;
    cache->Seed = seed;
  }

  // Directional mode: anisotropic media carry their projection (made once,
  // kept up to date by added particles) and follow no viewpoint.
  auto directional = [&](std::size_t o)
  { return this->DirectionalRadiance && cache->Scene.IsMedium(o); };
  for (std::size_t o = 0; o < cache->Objects.size(); ++o)
  {
    brume::ObjectRadiance& radiance = *cache->Objects[o];
    if (!radiance.IsViewDependent())
    {
      continue;
    }
    const int order = this->DirectionalOrder;
    const bool project = directional(o) && radiance.GetDirectionalOrder() != order;
    if (directional(o) == cache->ObjectDirectional[o] && !project)
    {
      continue;
    }
    if (project)
    {
      const std::string error = radiance.BuildDirectional(order, parallelFor);
      if (!error.empty())
      {
        vtkErrorMacro("Cannot project '" << cache->Sources[o].Name << "': " << error << ".");
        this->Cached.reset();
        return 0;
      }
      ++this->NumberOfDirectionalBuilds;
    }
    cache->ObjectDirectional[o] = directional(o);
    cache->Outputs[o] = nullptr;
  }

  // A new viewpoint: only view-dependent textures change.
  brume::ObjectHits groups;
  for (std::size_t o = 0; o < cache->Objects.size(); ++o)
  {
    brume::ObjectRadiance& radiance = *cache->Objects[o];
    const brume::Vec3& last = cache->ObjectEye[o];
    if (!radiance.IsViewDependent() || directional(o) ||
      (last.x == eye.x && last.y == eye.y && last.z == eye.z))
    {
      continue;
    }
    // Textures that hold added particles have no single hits input to be
    // rebuilt from: they are always updated incrementally.
    if (this->IncrementalUpdate || cache->Accumulated)
    {
      radiance.UpdateView(eye, parallelFor);
      ++this->NumberOfViewUpdates;
    }
    else
    {
      if (groups.Offset.empty())
      {
        brume::GroupHitsByObject(hits, cache->Scene.NumberOfObjects(), groups);
      }
      radiance.Build(hits, groups.Index.data() + groups.Offset[o],
        groups.Offset[o + 1] - groups.Offset[o], eye, threshold, parallelFor);
      ++this->NumberOfTextureBuilds;
    }
    cache->Outputs[o] = nullptr;
    cache->ObjectEye[o] = eye;
  }

  if (cache->Chain)
  {
    this->LastReductionBytes = static_cast<vtkTypeInt64>(cache->Chain->Bytes);
    this->LastReductionSeconds = cache->Chain->Seconds;
    cache->Chain->Bytes = 0;
    cache->Chain->Seconds = 0.0;
  }
  if (distributed && controller->GetLocalProcessId() != 0)
  {
    // The textures are the same on every process; process 0 gives them.
    output->SetNumberOfPartitionedDataSets(0);
    this->UpdateProgress(1.0);
    return 1;
  }

  // Outputs: new datasets for the textures that changed, the same ones otherwise.
  output->SetNumberOfPartitionedDataSets(sceneData->GetNumberOfPartitionedDataSets());
  for (std::size_t o = 0; o < cache->Objects.size(); ++o)
  {
    const auto& source = cache->Sources[o];
    if (!cache->Outputs[o])
    {
      const brume::ObjectRadiance& radiance = *cache->Objects[o];
      const auto& res = radiance.GetResolution();
      vtkNew<vtkPartitionedDataSet> pds;
      if (!cache->Scene.IsMedium(o))
      {
        const brume::SurfaceChart& chart = radiance.GetChart();
        vtkNew<vtkImageData> texture;
        texture->SetDimensions(res[0], res[1], 1);
        texture->SetSpacing(1.0 / res[0], 1.0 / res[1], 1.0);
        texture->SetOrigin(0.5 / res[0], 0.5 / res[1], 0.0);
        texture->GetPointData()->SetScalars(NewRGB("Radiance", radiance.GetRadiance()));
        if (chart.Type == brume::SurfaceChart::Kind::Planar)
        {
          AddVec3(texture->GetFieldData(), "BrumeTextureOrigin", chart.Frame.Origin);
          AddVec3(texture->GetFieldData(), "BrumeTextureU", chart.Frame.U);
          AddVec3(texture->GetFieldData(), "BrumeTextureV", chart.Frame.V);
        }
        vtkNew<vtkStringArray> chartKind;
        chartKind->SetName("BrumeTextureChart");
        chartKind->InsertNextValue(chart.Type == brume::SurfaceChart::Kind::Planar ? "planar"
            : chart.Type == brume::SurfaceChart::Kind::TextureCoordinates ? "texture coordinates"
                                                                          : "atlas");
        texture->GetFieldData()->AddArray(chartKind);
        AddKind(texture->GetFieldData(), "surface");

        // The surface with texture coordinates that map the image.
        auto* sourceSurface = vtkPolyData::SafeDownCast(
          sceneData->GetPartitionedDataSet(source.CollectionIndex)->GetPartition(0));
        vtkNew<vtkPolyData> mapped;
        vtkNew<vtkFloatArray> tcoords;
        tcoords->SetName("TextureCoordinates");
        tcoords->SetNumberOfComponents(2);
        if (chart.Type == brume::SurfaceChart::Kind::Atlas)
        {
          // Separate points per triangle: each has its own chart.
          const brume::Surface& surface = cache->Scene.Surfaces[o];
          vtkNew<vtkPoints> points;
          vtkNew<vtkCellArray> triangles;
          for (std::size_t t = 0; t < surface.Triangles.size(); ++t)
          {
            vtkIdType ids[3];
            for (int k = 0; k < 3; ++k)
            {
              const brume::Vec3& v = surface.Vertices[surface.Triangles[t][k]];
              ids[k] = points->InsertNextPoint(v.x, v.y, v.z);
              tcoords->InsertNextTuple2(chart.TriangleUV[t][2 * k], chart.TriangleUV[t][2 * k + 1]);
            }
            triangles->InsertNextCell(3, ids);
          }
          mapped->SetPoints(points);
          mapped->SetPolys(triangles);
          mapped->GetFieldData()->ShallowCopy(sourceSurface->GetFieldData());
        }
        else
        {
          mapped->ShallowCopy(sourceSurface);
          tcoords->SetNumberOfTuples(mapped->GetNumberOfPoints());
          const float uu = Dot(chart.Frame.U, chart.Frame.U),
                      vv = Dot(chart.Frame.V, chart.Frame.V);
          vtkDataArray* given = sourceSurface->GetPointData()->GetTCoords();
          for (vtkIdType i = 0; i < mapped->GetNumberOfPoints(); ++i)
          {
            if (chart.Type == brume::SurfaceChart::Kind::Planar)
            {
              double p[3];
              mapped->GetPoint(i, p);
              const brume::Vec3 d = brume::Vec3(static_cast<float>(p[0]), static_cast<float>(p[1]),
                                      static_cast<float>(p[2])) -
                chart.Frame.Origin;
              tcoords->SetTuple2(i, Dot(d, chart.Frame.U) / uu, Dot(d, chart.Frame.V) / vv);
            }
            else
            {
              tcoords->SetTuple2(i, given->GetComponent(i, 0), given->GetComponent(i, 1));
            }
          }
        }
        mapped->GetPointData()->SetTCoords(tcoords);
        AddKind(mapped->GetFieldData(), "surface");
        pds->SetNumberOfPartitions(2);
        pds->SetPartition(0, texture);
        pds->SetPartition(1, mapped);
      }
      else
      {
        const brume::Medium& medium = cache->Scene.Media[o - cache->Scene.Surfaces.size()];
        const brume::Vec3 extent = medium.Bounds.Extent();
        vtkNew<vtkImageData> texture;
        texture->SetDimensions(res[0] + 1, res[1] + 1, res[2] + 1);
        texture->SetOrigin(medium.Bounds.lower.x, medium.Bounds.lower.y, medium.Bounds.lower.z);
        texture->SetSpacing(extent.x / res[0], extent.y / res[1], extent.z / res[2]);
        if (cache->ObjectDirectional[o])
        {
          // The projection, and as SourceRadiance its mean over directions
          // (the l = 0 term: c_00 Y_00).
          const int order = radiance.GetDirectionalOrder();
          const int components = 3 * brume::ShCoefficients(order);
          const std::vector<float>& coefficients = radiance.GetDirectional();
          vtkNew<vtkFloatArray> sh;
          sh->SetName("SourceRadianceSH");
          sh->SetNumberOfComponents(components);
          sh->SetNumberOfTuples(static_cast<vtkIdType>(coefficients.size() / components));
          std::copy(coefficients.begin(), coefficients.end(), sh->GetPointer(0));
          std::vector<float> mean(3 * static_cast<std::size_t>(sh->GetNumberOfTuples()));
          for (std::size_t t = 0; t < mean.size() / 3; ++t)
          {
            for (int c = 0; c < 3; ++c)
            {
              mean[3 * t + c] = std::max(0.f, 0.282094792f * coefficients[t * components + c]);
            }
          }
          texture->GetCellData()->SetScalars(NewRGB("SourceRadiance", mean));
          texture->GetCellData()->AddArray(sh);
          vtkNew<vtkDoubleArray> g;
          g->SetName("BrumePhaseAsymmetry");
          g->InsertNextValue(medium.G);
          texture->GetFieldData()->AddArray(g);
        }
        else
        {
          texture->GetCellData()->SetScalars(NewRGB("SourceRadiance", radiance.GetRadiance()));
        }
        texture->GetCellData()->AddArray(NewRGB("Extinction", radiance.GetExtinction()));
        AddKind(texture->GetFieldData(), "medium");
        pds->SetNumberOfPartitions(1);
        pds->SetPartition(0, texture);
      }
      cache->Outputs[o] = pds;
    }
    output->SetPartitionedDataSet(source.CollectionIndex, cache->Outputs[o]);
    output->GetMetaData(source.CollectionIndex)
      ->Set(vtkCompositeDataSet::NAME(), source.Name.c_str());
  }
  this->UpdateProgress(1.0);
  return 1;
}

void vtkBrumeRadianceReconstruction::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "EyePosition: (" << this->EyePosition[0] << ", " << this->EyePosition[1] << ", "
     << this->EyePosition[2] << ")\n";
  os << indent << "Camera: " << this->Camera << "\n";
  os << indent << "RadiosityThreshold: " << this->RadiosityThreshold << "\n";
  os << indent << "SurfaceResolution: " << this->SurfaceResolution << "\n";
  os << indent << "MediumResolution: " << this->MediumResolution << "\n";
  os << indent << "HistogramRefinement: " << this->HistogramRefinement << "\n";
  os << indent << "IncrementalUpdate: " << this->IncrementalUpdate << "\n";
  os << indent << "NumberOfTextureBuilds: " << this->NumberOfTextureBuilds << "\n";
  os << indent << "NumberOfViewUpdates: " << this->NumberOfViewUpdates << "\n";
  os << indent << "AccumulateParticles: " << this->AccumulateParticles << "\n";
  os << indent << "Controller: " << this->Controller << "\n";
  os << indent << "LastReductionBytes: " << this->LastReductionBytes << "\n";
  os << indent << "DirectionalRadiance: " << this->DirectionalRadiance << "\n";
  os << indent << "DirectionalOrder: " << this->DirectionalOrder << "\n";
  os << indent << "NumberOfParticleAdditions: " << this->NumberOfParticleAdditions << "\n";
  os << indent << "NumberOfDirectionalBuilds: " << this->NumberOfDirectionalBuilds << "\n";
}
