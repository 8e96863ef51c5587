// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeRadianceTextures.h"

#include "vtkAlgorithm.h"
#include "vtkBrumeProcesses.h"
#include "vtkBrumeRadianceConversion.h"
#include "vtkBrumeSMP.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <string>

namespace
{

// The per-vertex texture coordinates of a scene surface, if it has some.
std::vector<std::array<float, 2>> TextureCoordinates(vtkPolyData* polyData)
{
  std::vector<std::array<float, 2>> tcoords;
  vtkDataArray* tc = polyData->GetPointData()->GetTCoords();
  if (tc && tc->GetNumberOfComponents() >= 2)
  {
    tcoords.resize(static_cast<std::size_t>(tc->GetNumberOfTuples()));
    for (vtkIdType i = 0; i < tc->GetNumberOfTuples(); ++i)
    {
      tcoords[i] = { static_cast<float>(tc->GetComponent(i, 0)),
        static_cast<float>(tc->GetComponent(i, 1)) };
    }
  }
  return tcoords;
}
}

std::array<int, 3> vtkBrumeRadianceTextures::FixedResolution(const brume::Vec3& extent, int n)
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

vtkBrumeRadianceTextures::vtkBrumeRadianceTextures(
  vtkAlgorithm* filter, vtkMultiProcessController* controller)
  : Filter(filter)
  , Controller(controller)
{
}

vtkBrumeRadianceTextures::~vtkBrumeRadianceTextures() = default;

bool vtkBrumeRadianceTextures::Distributed() const
{
  return vtkBrumeProcesses::IsDistributed(this->Controller);
}

bool vtkBrumeRadianceTextures::Agree(bool ok)
{
  const bool all = vtkBrumeProcesses::Agree(this->Controller, ok);
  if (ok && !all)
  {
    vtkErrorWithObjectMacro(this->Filter, "Another process failed (see its errors): stopping.");
  }
  return all;
}

bool vtkBrumeRadianceTextures::SameSceneAndSettings(
  const vtkBrumeReconstructionRequest& request, const vtkBrumeReconstructionSettings& s) const
{
  return this->SceneData == request.SceneInput &&
    this->SceneTime == request.SceneInput->GetMTime() && this->Settings == s;
}

bool vtkBrumeRadianceTextures::HoldsHits(vtkPolyData* hits) const
{
  return this->HitsData == hits && this->HitsTime == hits->GetMTime();
}

bool vtkBrumeRadianceTextures::HoldsStep(const vtkBrumeHitConversion::RunInfo& run) const
{
  return run.FirstParticle > 0.0 && this->Accumulated &&
    this->LastFirstParticle == run.FirstParticle && this->EndParticle == run.EndParticle &&
    this->Particles == run.Particles && this->Seed == run.Seed;
}

bool vtkBrumeRadianceTextures::Continues(const vtkBrumeHitConversion::RunInfo& run) const
{
  if (this->Seed != run.Seed || this->EndParticle != run.FirstParticle)
  {
    return false;
  }
  // The next batch of the same run, or a complete run extended.
  return run.Particles == this->Particles || this->EndParticle == this->Particles;
}

bool vtkBrumeRadianceTextures::Build(const vtkBrumeReconstructionRequest& request,
  const vtkBrumeReconstructionSettings& settings, vtkBrumeReconstructionWork& work)
{
  this->SceneCollection = request.Scene;
  const std::string error =
    vtkBrumeSceneConversion::ToScene(request.Scene, this->Scene, &this->Sources);
  brume::ObjectHits groups;
  const std::string groupError = error.empty()
    ? brume::GroupHitsByObject(
        request.Hits, this->Scene.NumberOfObjects(), groups, vtkBrumeSMP::ParallelFor())
    : std::string();
  if (!error.empty())
  {
    vtkErrorWithObjectMacro(this->Filter, "Invalid scene: " << error << ".");
  }
  else if (!groupError.empty())
  {
    vtkErrorWithObjectMacro(this->Filter, "Invalid particle hits: " << groupError << ".");
  }
  if (!this->Agree(error.empty() && groupError.empty()))
  {
    return false;
  }
  if (!this->CreateObjects(settings, request.Hits, groups, request.Run) ||
    !this->CreateDirectLight(settings, request.Hits) || !this->PlanReflections() ||
    !this->CheckHits(request.Hits, groups) || !this->BuildObjects(request, groups, work))
  {
    return false;
  }
  // The first batch of a run only bins: the last one estimates.
  if (request.Run.Completes())
  {
    this->ComputeDirect();
  }
  this->SceneData = request.SceneInput;
  this->HitsData = request.HitData;
  this->SceneTime = request.SceneInput->GetMTime();
  this->HitsTime = request.HitData->GetMTime();
  this->Settings = settings;
  this->ObjectEye.assign(this->Objects.size(), request.Eye);
  this->ObjectDirectional.assign(this->Objects.size(), false);
  this->Particles = request.Run.Particles;
  this->EndParticle = request.Run.EndParticle;
  this->Seed = request.Run.Seed;
  return true;
}

std::unique_ptr<brume::ObjectRadiance> vtkBrumeRadianceTextures::CreateObject(std::size_t o,
  std::size_t hitCount, double concentration, const vtkBrumeReconstructionSettings& settings)
{
  const auto& source = this->Sources[o];
  vtkDataObject* sceneObject =
    this->SceneCollection->GetPartitionedDataSet(source.CollectionIndex)->GetPartition(0);
  vtkDataArray* override = sceneObject->GetFieldData()->GetArray("BrumeTextureResolution");
  const int perObject =
    override && override->GetNumberOfTuples() > 0 ? static_cast<int>(override->GetTuple1(0)) : 0;
  if (hitCount == 0)
  {
    vtkWarningWithObjectMacro(this->Filter,
      "Object '" << source.Name
                 << "' received no particle: its texture holds only its "
                    "emission (more particles, or a light that reaches it).");
  }
  // The object's own resolution, the filter's, or one chosen from its hits.
  bool tooLarge = false;
  auto resolution =
    [&](const brume::Vec3& extent, int global, int maximum, int automatic, double hitsPerTexel)
  {
    const int fixed = perObject > 0 ? perObject : global;
    if (fixed > maximum)
    {
      vtkErrorWithObjectMacro(this->Filter,
        "BrumeTextureResolution of '" << source.Name << "' exceeds " << maximum << ".");
      tooLarge = true;
      return std::array<int, 3>{ 0, 0, 0 };
    }
    return fixed > 0 ? FixedResolution(extent, fixed)
                     : brume::ChooseResolution(extent, hitCount, hitsPerTexel, 4, automatic);
  };
  std::unique_ptr<brume::ObjectRadiance> radiance;
  const int refinement = settings.HistogramRefinement;
  if (!this->Scene.IsMedium(o))
  {
    const brume::Surface& surface = this->Scene.Surfaces[o];
    const auto tcoords = TextureCoordinates(vtkPolyData::SafeDownCast(sceneObject));
    brume::SurfaceChart chart = brume::MakeChart(surface, tcoords.empty() ? nullptr : &tcoords);
    // Evenly lit surfaces keep their texels (brume::MinSurfaceConcentration).
    const double factor = concentration >= brume::MinSurfaceConcentration ? concentration : 1.0;
    const auto res = resolution(brume::Vec3(chart.Width, chart.Height, 0.f),
      settings.SurfaceResolution, MaxSurfaceResolution, 1024, settings.RadiosityThreshold / factor);
    if (!tooLarge)
    {
      radiance.reset(new brume::ObjectRadiance(surface, chart, { res[0], res[1] }, refinement));
    }
  }
  else
  {
    const brume::Medium& medium = this->Scene.Media[o - this->Scene.Surfaces.size()];
    const auto res =
      resolution(medium.Bounds.Extent(), settings.MediumResolution, MaxMediumResolution, 256,
        brume::MediumHitsPerTexel(medium, hitCount, settings.RadiosityThreshold) / concentration);
    if (!tooLarge)
    {
      radiance.reset(new brume::ObjectRadiance(medium, res, refinement));
    }
  }
  return radiance;
}

bool vtkBrumeRadianceTextures::CreateObjects(const vtkBrumeReconstructionSettings& settings,
  const brume::HitArrays& hits, const brume::ObjectHits& groups,
  const vtkBrumeHitConversion::RunInfo& run)
{
  // Resolutions follow the hits of the whole run, on every process; from
  // the first batch of a run traced in batches, its hits scaled to the run.
  // After the counts of every object come the hits of the media and of the
  // planar surfaces counted over their pilot grids (where the hits are,
  // brume::HitConcentration; a surface's without those the direct light
  // replaces).
  const double scale = run.Particles / (run.EndParticle - run.FirstParticle);
  const std::size_t objects = this->Scene.NumberOfObjects();
  const std::size_t surfaces = this->Scene.Surfaces.size();
  std::vector<vtkTypeInt64> counts(objects);
  for (std::size_t o = 0; o < objects; ++o)
  {
    counts[o] = static_cast<vtkTypeInt64>(
      std::llround(scale * static_cast<double>(groups.Offset[o + 1] - groups.Offset[o])));
  }
  std::vector<std::size_t> pilotStart(objects + 1, objects);
  // Surfaces only where the direct light of delta lights is computed: their
  // scattered light gathers around its patches. Lit by emissive surfaces
  // alone (the default scene), walls are lit evenly and skip the pass.
  const std::size_t deltaLights = settings.DirectLightResolution > 0 && hits.Emitter && hits.Depth
    ? this->Scene.Lights.size()
    : 0;
  for (std::size_t o = 0; o < objects; ++o)
  {
    pilotStart[o + 1] = pilotStart[o];
    brume::PlanarFrame frame;
    if (o < surfaces && deltaLights > 0 && this->Scene.Surfaces[o].ComputePlanarFrame(frame))
    {
      std::vector<std::int64_t> pilot;
      const std::size_t first = groups.Offset[o];
      brume::CountHitsOverPilotGrid(hits, groups.Index.data() + first, groups.Offset[o + 1] - first,
        frame, this->Scene.LightEmitterId(0), deltaLights, pilot);
      counts.insert(counts.end(), pilot.begin(), pilot.end());
      pilotStart[o + 1] += pilot.size();
    }
    else if (o >= surfaces)
    {
      std::vector<std::int64_t> pilot;
      const std::size_t first = groups.Offset[o];
      brume::CountHitsOverPilotGrid(hits, groups.Index.data() + first, groups.Offset[o + 1] - first,
        this->Scene.Media[o - surfaces].Bounds, pilot);
      counts.insert(counts.end(), pilot.begin(), pilot.end());
      pilotStart[o + 1] += pilot.size();
    }
  }
  if (this->Distributed() && !counts.empty())
  {
    vtkBrumeProcesses::Sum(this->Controller, counts);
    this->Reduction.reset(new vtkBrumeHistogramReduction(this->Controller));
  }
  for (std::size_t o = 0; o < objects; ++o)
  {
    const double concentration = pilotStart[o + 1] > pilotStart[o]
      ? brume::HitConcentration(
          std::vector<std::int64_t>(counts.begin() + static_cast<std::ptrdiff_t>(pilotStart[o]),
            counts.begin() + static_cast<std::ptrdiff_t>(pilotStart[o + 1])))
      : 1.0;
    auto radiance =
      this->CreateObject(o, static_cast<std::size_t>(counts[o]), concentration, settings);
    if (!radiance)
    {
      return false;
    }
    radiance->SetReduction(this->Reduction.get());
    this->Objects.push_back(std::move(radiance));
    this->Outputs.push_back(nullptr);
  }
  if (this->Reduction)
  {
    // Each texture estimated by one process, the work shared out evenly:
    // the same resolutions give the same owners on every process.
    std::vector<double> costs;
    for (const auto& object : this->Objects)
    {
      costs.push_back(object->EstimateCost());
    }
    const std::vector<int> owners =
      brume::AssignOwners(costs, this->Reduction->NumberOfProcesses());
    for (std::size_t o = 0; o < objects; ++o)
    {
      this->Objects[o]->SetOwner(owners[o]);
    }
  }
  return true;
}

std::array<int, 3> vtkBrumeRadianceTextures::DirectResolution(std::size_t o, int n) const
{
  // n texels along the longest axis, at most the density's own resolution,
  // at most MaxDirectTexels in all.
  std::array<int, 3> res{ 1, 1, 1 };
  const double limit = MaxDirectTexels;
  if (this->Scene.IsMedium(o))
  {
    const brume::Medium& medium = this->Scene.Media[o - this->Scene.Surfaces.size()];
    res = FixedResolution(medium.Bounds.Extent(), n);
    if (medium.Density)
    {
      const std::array<int, 3> native = medium.Density->NativeResolution();
      for (int a = 0; a < 3; ++a)
      {
        res[a] = std::max(1, std::min(res[a], native[a]));
      }
    }
  }
  else
  {
    const brume::SurfaceChart& chart = this->Objects[o]->GetChart();
    res = FixedResolution(brume::Vec3(chart.Width, chart.Height, 0.f), n);
  }
  const double texels = static_cast<double>(res[0]) * res[1] * res[2];
  if (texels > limit)
  {
    const int used = this->Scene.IsMedium(o) ? 3 : 2;
    const double scale = std::pow(limit / texels, 1.0 / used);
    for (int a = 0; a < used; ++a)
    {
      res[a] = std::max(1, static_cast<int>(std::floor(res[a] * scale)));
    }
  }
  return res;
}

bool vtkBrumeRadianceTextures::CreateDirectLight(
  const vtkBrumeReconstructionSettings& settings, const brume::HitArrays& hits)
{
  this->Direct.reset();
  this->Caster.reset();
  if (settings.DirectLightResolution <= 0 || this->Scene.Lights.empty())
  {
    return true;
  }
  if (hits.Count > 0 && (!hits.Emitter || !hits.Depth))
  {
    vtkWarningWithObjectMacro(this->Filter,
      "The particle hits have no 'EmitterId' and 'Depth' arrays: direct light is estimated from "
      "them, not computed.");
    return true;
  }
  this->Caster.reset(new brume::RayCaster(this->Scene));
  if (!this->Caster->GetError().empty())
  {
    vtkErrorWithObjectMacro(
      this->Filter, "Cannot cast shadow rays: " << this->Caster->GetError() << ".");
    return this->Agree(false);
  }
  this->Direct.reset(new brume::DirectLight(this->Scene, *this->Caster));
  for (std::size_t o = 0; o < this->Objects.size(); ++o)
  {
    if (this->Objects[o]->SupportsDirect())
    {
      this->Objects[o]->EnableDirect(
        this->Direct.get(), this->DirectResolution(o, settings.DirectLightResolution));
    }
  }
  return this->Agree(true);
}

void vtkBrumeRadianceTextures::ComputeDirect()
{
  if (!this->Direct)
  {
    return;
  }
  // Shadow rays march the media's grids of density means, made with the
  // textures.
  const std::size_t surfaces = this->Scene.Surfaces.size();
  for (std::size_t o = surfaces; o < this->Objects.size(); ++o)
  {
    const brume::ObjectRadiance& medium = *this->Objects[o];
    if (!medium.GetNativeDensity().Empty())
    {
      this->Direct->SetMediumGrid(o - surfaces, &medium.GetNativeDensity());
    }
  }
  const brume::ParallelFor parallelFor = vtkBrumeSMP::ParallelFor();
  for (auto& object : this->Objects)
  {
    if (object->IsDirectEnabled())
    {
      object->ComputeDirect(parallelFor);
    }
  }
}

bool vtkBrumeRadianceTextures::CheckHits(
  const brume::HitArrays& hits, const brume::ObjectHits& groups)
{
  // Every process checks its hits before any enters a reduction.
  if (!this->Distributed())
  {
    return true;
  }
  bool hitsOk = true;
  for (std::size_t o = 0; o < this->Objects.size(); ++o)
  {
    const std::string problem = this->Objects[o]->Check(
      hits, groups.Index.data() + groups.Offset[o], groups.Offset[o + 1] - groups.Offset[o]);
    if (!problem.empty())
    {
      vtkErrorWithObjectMacro(
        this->Filter, "Cannot reconstruct '" << this->Sources[o].Name << "': " << problem << ".");
      hitsOk = false;
    }
  }
  return this->Agree(hitsOk);
}

void vtkBrumeRadianceTextures::ForEachObject(
  const std::function<void(std::size_t, const brume::ParallelFor&)>& step)
{
  const brume::ParallelFor serialFor = brume::SerialFor();
  std::vector<std::size_t> independent;
  for (std::size_t o = 0; o < this->Objects.size(); ++o)
  {
    if (!this->Objects[o]->IsViewDependent())
    {
      independent.push_back(o);
    }
  }
  vtkSMPTools::For(0, static_cast<vtkIdType>(independent.size()), 1,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType k = begin; k < end; ++k)
      {
        step(independent[k], serialFor);
      }
    });
  const brume::ParallelFor parallelFor = vtkBrumeSMP::ParallelFor();
  for (std::size_t o = 0; o < this->Objects.size(); ++o)
  {
    if (this->Objects[o]->IsViewDependent())
    {
      step(o, parallelFor);
    }
  }
}

bool vtkBrumeRadianceTextures::BuildObjects(const vtkBrumeReconstructionRequest& request,
  const brume::ObjectHits& groups, vtkBrumeReconstructionWork& work)
{
  std::vector<std::string> errors(this->Objects.size());
  if (this->Distributed())
  {
    if (!this->BuildDistributed(request, groups, errors))
    {
      return false; // reported
    }
  }
  else
  {
    this->ForEachObject(
      [&](std::size_t o, const brume::ParallelFor& objectFor)
      {
        this->Objects[o]->SetParticleFlux(request.ParticleFlux);
        this->Objects[o]->SetRunShare(request.Run.EndParticle / request.Run.Particles);
        errors[o] = this->Objects[o]->Build(request.Hits, groups.Index.data() + groups.Offset[o],
          groups.Offset[o + 1] - groups.Offset[o], request.Eye, request.ThresholdFlux, objectFor,
          request.Run.Completes());
      });
  }
  this->Filter->UpdateProgress(0.5);
  for (std::size_t o = 0; o < this->Objects.size(); ++o)
  {
    if (!errors[o].empty())
    {
      vtkErrorWithObjectMacro(
        this->Filter, "Cannot reconstruct '" << this->Sources[o].Name << "': " << errors[o] << ".");
      return false;
    }
    ++work.TextureBuilds;
  }
  return true;
}

bool vtkBrumeRadianceTextures::BuildDistributed(const vtkBrumeReconstructionRequest& request,
  const brume::ObjectHits& groups, std::vector<std::string>& errors)
{
  // Each step for every object before the next (ObjectRadiance::Build()'s
  // four steps): the processes bin their hits, sum every object's
  // histograms onto its owner in the objects' order, then estimate their
  // own objects all at once, instead of in turn, and give them to the
  // others. The binning needs no communication (the particle flux is set).
  const bool estimate = request.Run.Completes();
  const brume::ParallelFor parallelFor = vtkBrumeSMP::ParallelFor();
  auto bin = [&](std::size_t o, const brume::ParallelFor& objectFor)
  {
    this->Objects[o]->SetParticleFlux(request.ParticleFlux);
    this->Objects[o]->SetRunShare(request.Run.EndParticle / request.Run.Particles);
    errors[o] =
      this->Objects[o]->BuildHistograms(request.Hits, groups.Index.data() + groups.Offset[o],
        groups.Offset[o + 1] - groups.Offset[o], request.ThresholdFlux, objectFor, estimate);
  };
  // Every process's hits were checked before (CheckHits): a failure here
  // is one process's alone (a term beyond the exact sums' bound), and every
  // process stops, without entering a reduction.
  auto agree = [&]()
  {
    bool ok = true;
    for (std::size_t o = 0; o < errors.size(); ++o)
    {
      if (!errors[o].empty())
      {
        vtkErrorWithObjectMacro(this->Filter,
          "Cannot reconstruct '" << this->Sources[o].Name << "': " << errors[o] << ".");
        ok = false;
      }
    }
    return this->Agree(ok);
  };
  this->ForEachObject(bin);
  if (!agree())
  {
    return false;
  }
  if (!estimate)
  {
    return true;
  }
  this->Filter->UpdateProgress(0.4);
  for (auto& object : this->Objects)
  {
    object->SumHistograms(request.Eye, parallelFor);
  }
  this->Filter->UpdateProgress(0.6);
  this->ForEachObject([&](std::size_t o, const brume::ParallelFor& objectFor)
    { errors[o] = this->Objects[o]->EstimateTexture(objectFor); });
  if (!agree())
  {
    return false;
  }
  for (auto& object : this->Objects)
  {
    object->ShareTexture(parallelFor);
  }
  return true;
}

bool vtkBrumeRadianceTextures::Add(
  const vtkBrumeReconstructionRequest& request, vtkBrumeReconstructionWork& work)
{
  const brume::ParallelFor parallelFor = vtkBrumeSMP::ParallelFor();
  brume::ObjectHits groups;
  const std::string groupError =
    brume::GroupHitsByObject(request.Hits, this->Scene.NumberOfObjects(), groups, parallelFor);
  // Batches of a run: only the last estimates the textures (and, the first
  // time, computes the direct light).
  const bool complete = request.Run.Completes();
  const bool firstEstimate = complete && !this->IsComplete();
  if (!groupError.empty())
  {
    vtkErrorWithObjectMacro(this->Filter, "Invalid particle hits: " << groupError << ".");
    return false;
  }
  std::vector<std::string> errors(this->Objects.size());
  auto add = [&](std::size_t o, const brume::ParallelFor& objectFor)
  {
    this->Objects[o]->SetParticleFlux(request.ParticleFlux);
    this->Objects[o]->SetRunShare(request.Run.EndParticle / request.Run.Particles);
    errors[o] = this->Objects[o]->Add(request.Hits, groups.Index.data() + groups.Offset[o],
      groups.Offset[o + 1] - groups.Offset[o], this->Particles / request.Run.Particles,
      firstEstimate ? request.Eye : this->ObjectEye[o], request.ThresholdFlux, objectFor, complete);
  };
  this->ForEachObject(add);
  for (std::size_t o = 0; o < this->Objects.size(); ++o)
  {
    if (!errors[o].empty())
    {
      vtkErrorWithObjectMacro(this->Filter,
        "Cannot add particles to '" << this->Sources[o].Name << "': " << errors[o] << ".");
      return false;
    }
    this->Outputs[o] = nullptr;
    ++work.ParticleAdditions;
  }
  this->HitsData = request.HitData;
  this->HitsTime = request.HitData->GetMTime();
  this->Particles = request.Run.Particles;
  this->EndParticle = request.Run.EndParticle;
  this->LastFirstParticle = request.Run.FirstParticle;
  if (firstEstimate)
  {
    this->ComputeDirect();
    this->ObjectEye.assign(this->Objects.size(), request.Eye);
  }
  this->Accumulated = true;
  this->MirrorsCurrent = false;
  return true;
}

bool vtkBrumeRadianceTextures::SetDirectional(
  bool directionalMedia, int order, vtkBrumeReconstructionWork& work)
{
  // Directional mode: anisotropic media carry their projection (made once,
  // kept up to date by added particles) and follow no viewpoint.
  const brume::ParallelFor parallelFor = vtkBrumeSMP::ParallelFor();
  for (std::size_t o = 0; o < this->Objects.size(); ++o)
  {
    brume::ObjectRadiance& radiance = *this->Objects[o];
    if (!radiance.IsViewDependent())
    {
      continue;
    }
    const bool directional = directionalMedia && this->Scene.IsMedium(o);
    const bool project = directional && radiance.GetDirectionalOrder() != order;
    if (directional == this->ObjectDirectional[o] && !project)
    {
      continue;
    }
    if (project)
    {
      const std::string error = radiance.BuildDirectional(order, parallelFor);
      if (!error.empty())
      {
        vtkErrorWithObjectMacro(
          this->Filter, "Cannot project '" << this->Sources[o].Name << "': " << error << ".");
        return false;
      }
      ++work.DirectionalBuilds;
    }
    this->ObjectDirectional[o] = directional;
    this->Outputs[o] = nullptr;
    this->MirrorsCurrent = false;
  }
  return true;
}

void vtkBrumeRadianceTextures::FollowView(
  const vtkBrumeReconstructionRequest& request, bool incremental, vtkBrumeReconstructionWork& work)
{
  // A new viewpoint: only view-dependent textures change.
  const brume::ParallelFor parallelFor = vtkBrumeSMP::ParallelFor();
  const brume::Vec3& eye = request.Eye;
  // The mirrors first: the objects they saw from elsewhere are turned to
  // the eye below, or back to where they were.
  const std::vector<bool> moved = this->ReflectMirrors(eye);
  brume::ObjectHits groups;
  for (std::size_t o = 0; o < this->Objects.size(); ++o)
  {
    brume::ObjectRadiance& radiance = *this->Objects[o];
    const brume::Vec3& last = this->ObjectEye[o];
    if (!radiance.IsViewDependent() || this->ObjectDirectional[o] ||
      (last.x == eye.x && last.y == eye.y && last.z == eye.z))
    {
      if (moved[o])
      {
        radiance.UpdateView(last, parallelFor);
      }
      continue;
    }
    // Textures that hold added particles have no single hits input to be
    // rebuilt from: they are always updated incrementally.
    if (incremental || this->Accumulated)
    {
      radiance.UpdateView(eye, parallelFor);
      ++work.ViewUpdates;
    }
    else
    {
      if (groups.Offset.empty())
      {
        brume::GroupHitsByObject(request.Hits, this->Scene.NumberOfObjects(), groups, parallelFor);
      }
      radiance.SetParticleFlux(request.ParticleFlux);
      radiance.Build(request.Hits, groups.Index.data() + groups.Offset[o],
        groups.Offset[o + 1] - groups.Offset[o], eye, request.ThresholdFlux, parallelFor);
      ++work.TextureBuilds;
    }
    this->Outputs[o] = nullptr;
    this->ObjectEye[o] = eye;
  }
}

void vtkBrumeRadianceTextures::TakeReduction(vtkTypeInt64& bytes, double& seconds)
{
  bytes = 0;
  seconds = 0.0;
  if (this->Reduction)
  {
    bytes = static_cast<vtkTypeInt64>(this->Reduction->Bytes);
    seconds = this->Reduction->Seconds;
    this->Reduction->Bytes = 0;
    this->Reduction->Seconds = 0.0;
  }
}

int vtkBrumeRadianceTextures::NumberOfViewDependentOutputs() const
{
  int count = 0;
  for (std::size_t o = 0; o < this->Objects.size(); ++o)
  {
    count += this->Objects[o]->IsViewDependent() && !this->ObjectDirectional[o] ? 1 : 0;
  }
  return count;
}

void vtkBrumeRadianceTextures::Emit(vtkPartitionedDataSetCollection* output)
{
  // New datasets for the textures that changed, the same ones otherwise.
  vtkPartitionedDataSetCollection* scene = this->SceneCollection;
  output->SetNumberOfPartitionedDataSets(scene->GetNumberOfPartitionedDataSets());
  for (std::size_t o = 0; o < this->Objects.size(); ++o)
  {
    const auto& source = this->Sources[o];
    if (!this->Outputs[o])
    {
      const brume::ObjectRadiance& radiance = *this->Objects[o];
      if (!this->Scene.IsMedium(o))
      {
        auto* sceneSurface = vtkPolyData::SafeDownCast(
          scene->GetPartitionedDataSet(source.CollectionIndex)->GetPartition(0));
        this->Outputs[o] =
          vtkBrumeRadianceConversion::FromSurface(radiance, this->Scene.Surfaces[o], sceneSurface);
      }
      else
      {
        const brume::Medium& medium = this->Scene.Media[o - this->Scene.Surfaces.size()];
        // The native extinction is made once: renderers keep its texture.
        if (this->NativeExtinction.size() != this->Objects.size())
        {
          this->NativeExtinction.resize(this->Objects.size());
        }
        if (!this->NativeExtinction[o])
        {
          this->NativeExtinction[o] =
            vtkBrumeRadianceConversion::NativeExtinction(radiance, medium);
        }
        // The extinction array of the last texture is kept where unchanged.
        if (this->LastMediumTextures.size() != this->Objects.size())
        {
          this->LastMediumTextures.resize(this->Objects.size());
        }
        this->Outputs[o] = vtkBrumeRadianceConversion::FromMedium(radiance, medium,
          this->ObjectDirectional[o], this->NativeExtinction[o], this->LastMediumTextures[o]);
        this->LastMediumTextures[o] = vtkImageData::SafeDownCast(this->Outputs[o]->GetPartition(0));
      }
    }
    output->SetPartitionedDataSet(source.CollectionIndex, this->Outputs[o]);
    output->GetMetaData(source.CollectionIndex)
      ->Set(vtkCompositeDataSet::NAME(), source.Name.c_str());
  }
}
