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

std::vector<brume::KeptHits> vtkBrumeRadianceTextures::ReleaseKeptMemory()
{
  std::vector<brume::KeptHits> memory;
  for (auto& object : this->Objects)
  {
    memory.push_back(object->ReleaseKeptMemory());
  }
  return memory;
}

std::vector<brume::NativeMediumGrid> vtkBrumeRadianceTextures::ReleaseNativeGrids()
{
  std::vector<brume::NativeMediumGrid> grids;
  for (auto& object : this->Objects)
  {
    if (!object->GetNative().Empty())
    {
      grids.push_back(object->ReleaseNative());
    }
  }
  return grids;
}

bool vtkBrumeRadianceTextures::Build(const vtkBrumeReconstructionRequest& request,
  const vtkBrumeReconstructionSettings& settings, vtkBrumeReconstructionWork& work,
  std::vector<brume::KeptHits> spare)
{
  this->SceneCollection = request.Scene;
  // The scene's lights and those its tracer was given (the hits name them).
  const std::string error = vtkBrumeSceneConversion::ToScene(request.Scene, this->Scene,
    &this->Sources, nullptr, request.HitData ? request.HitData->GetFieldData() : nullptr);
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
    !this->CreateDirectLight(settings, request.Hits) || !this->PlanReflections())
  {
    return false;
  }
  this->FixViews(settings, request.Eye);
  // The objects that keep hits write them where the last build's were.
  for (std::size_t o = 0; o < spare.size() && o < this->Objects.size(); ++o)
  {
    this->Objects[o]->ReuseKeptMemory(std::move(spare[o]), groups.Offset[o + 1] - groups.Offset[o]);
  }
  spare.clear();
  if (!this->CheckHits(request.Hits, groups) || !this->BuildObjects(request, groups, work))
  {
    return false;
  }
  // The first batch of a run only bins: the last one estimates.
  if (request.Run.Completes())
  {
    this->ComputeDirect(work);
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

void vtkBrumeRadianceTextures::FixViews(
  const vtkBrumeReconstructionSettings& settings, const brume::Vec3& eye)
{
  if (!settings.FixedView)
  {
    return;
  }
  for (std::size_t o = 0; o < this->Objects.size(); ++o)
  {
    // A mirror or a cast lobe looks the other view-dependent objects up
    // toward its mirrored eye (ReflectMirrors()): those keep their hits.
    const bool reflected = !this->Mirrors.empty() &&
      std::find(this->Mirrors.begin(), this->Mirrors.end(), o) == this->Mirrors.end();
    if (!reflected && !(settings.DirectionalMedia && this->Scene.IsMedium(o)))
    {
      this->Objects[o]->FixView(eye);
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

void vtkBrumeRadianceTextures::ForEachObject(const brume::ObjectHits& groups,
  const std::function<void(std::size_t, const brume::ParallelFor&)>& step)
{
  const brume::ParallelFor serialFor = brume::SerialFor();
  // Objects that bin in place (view-independent ones, fixed views) take
  // one thread each; those that keep hits group them on every thread.
  std::vector<std::size_t> independent;
  for (std::size_t o = 0; o < this->Objects.size(); ++o)
  {
    if (!this->Objects[o]->GetBinning().KeepsHits())
    {
      independent.push_back(o);
    }
  }
  // The most hits first (their work is about proportional to their hits):
  // the threads that take the small objects last end about together.
  // Each object's result does not depend on which thread builds it when.
  auto hitsOf = [&](std::size_t o) { return groups.Offset[o + 1] - groups.Offset[o]; };
  std::stable_sort(independent.begin(), independent.end(),
    [&](std::size_t a, std::size_t b) { return hitsOf(a) > hitsOf(b); });
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
    if (this->Objects[o]->GetBinning().KeepsHits())
    {
      step(o, parallelFor);
    }
  }
}

std::vector<char> vtkBrumeRadianceTextures::BinWide(const brume::ObjectHits& groups,
  const std::function<void(std::size_t, const brume::ParallelFor&)>& bin)
{
  // One thread an object left the others waiting for the one with the most
  // hits: past four threads the reconstruction no longer scaled.
  // Its exact sums take its hits split between threads instead
  // (brume::HitBinning), the same bits whatever the split.
  std::vector<char> wide(this->Objects.size(), 0);
  const auto threads =
    static_cast<std::size_t>(std::max(1, vtkSMPTools::GetEstimatedNumberOfThreads()));
  auto hitsOf = [&](std::size_t o) { return groups.Offset[o + 1] - groups.Offset[o]; };
  std::size_t total = 0; // the hits of the objects built one thread each
  for (std::size_t o = 0; o < this->Objects.size(); ++o)
  {
    total += this->Objects[o]->GetBinning().KeepsHits() ? 0 : hitsOf(o);
  }
  const brume::ParallelFor parallelFor = vtkBrumeSMP::ParallelFor();
  for (std::size_t o = 0; threads > 1 && o < this->Objects.size(); ++o)
  {
    // More than a thread's even share: on one thread, it would keep the
    // others waiting after they had built the rest.
    if (!this->Objects[o]->GetBinning().KeepsHits() && hitsOf(o) >= WideObjectHits &&
      hitsOf(o) * threads > total)
    {
      this->Objects[o]->Options().BinOnEveryThread = true;
      bin(o, parallelFor);
      this->Objects[o]->Options().BinOnEveryThread = false;
      wide[o] = 1;
    }
  }
  return wide;
}

bool vtkBrumeRadianceTextures::BuildObjects(const vtkBrumeReconstructionRequest& request,
  const brume::ObjectHits& groups, vtkBrumeReconstructionWork& work)
{
  this->SampleMedia(work);
  std::vector<std::string> errors(this->Objects.size());
  if (this->Distributed())
  {
    if (!this->BuildDistributed(request, groups, errors))
    {
      return false; // reported on every process
    }
  }
  else
  {
    const bool estimate = request.Run.Completes();
    auto binHits = [&](std::size_t o, const brume::ParallelFor& objectFor)
    {
      this->Objects[o]->Options().ParticleFlux = request.ParticleFlux;
      this->Objects[o]->Options().RunShare = request.Run.EndParticle / request.Run.Particles;
      errors[o] = this->Objects[o]->BuildHits(request.Hits, groups.Index.data() + groups.Offset[o],
        groups.Offset[o + 1] - groups.Offset[o], request.Eye, request.ThresholdFlux, objectFor,
        estimate);
    };
    // The objects with many hits binned first, each on every thread; then
    // every object estimated (and the others binned) as ForEachObject()
    // shares them out.
    const std::vector<char> wide = this->BinWide(groups, binHits);
    this->ForEachObject(groups,
      [&](std::size_t o, const brume::ParallelFor& objectFor)
      {
        if (!wide[o])
        {
          binHits(o, objectFor);
        }
        if (errors[o].empty() && estimate)
        {
          errors[o] = this->Objects[o]->Finish(request.Eye, objectFor);
        }
      });
  }
  this->Filter->UpdateProgress(0.5);
  if (!this->AgreeOnObjects(errors, "Cannot reconstruct"))
  {
    return false;
  }
  work.TextureBuilds += static_cast<vtkIdType>(this->Objects.size());
  return true;
}

bool vtkBrumeRadianceTextures::AgreeOnObjects(
  const std::vector<std::string>& errors, const char* what)
{
  bool ok = true;
  for (std::size_t o = 0; o < errors.size(); ++o)
  {
    if (!errors[o].empty())
    {
      vtkErrorWithObjectMacro(
        this->Filter, "" << what << " '" << this->Sources[o].Name << "': " << errors[o] << ".");
      ok = false;
    }
  }
  return this->Agree(ok);
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
    this->Objects[o]->Options().ParticleFlux = request.ParticleFlux;
    this->Objects[o]->Options().RunShare = request.Run.EndParticle / request.Run.Particles;
    errors[o] =
      this->Objects[o]->BuildHistograms(request.Hits, groups.Index.data() + groups.Offset[o],
        groups.Offset[o + 1] - groups.Offset[o], request.ThresholdFlux, objectFor, estimate);
  };
  // Every process's hits were checked before (CheckHits): a failure here
  // is one process's alone (a term beyond the exact sums' bound), and every
  // process stops, without entering a reduction.
  const std::vector<char> wide = this->BinWide(groups, bin);
  this->ForEachObject(groups,
    [&](std::size_t o, const brume::ParallelFor& objectFor)
    {
      if (!wide[o])
      {
        bin(o, objectFor);
      }
    });
  if (!this->AgreeOnObjects(errors, "Cannot reconstruct"))
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
  this->ForEachObject(groups,
    [&](std::size_t o, const brume::ParallelFor& objectFor)
    { errors[o] = this->Objects[o]->EstimateTexture(objectFor); });
  if (!this->AgreeOnObjects(errors, "Cannot reconstruct"))
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
    this->Objects[o]->Options().ParticleFlux = request.ParticleFlux;
    this->Objects[o]->Options().RunShare = request.Run.EndParticle / request.Run.Particles;
    // A fixed view estimates toward the eye it binned toward; FollowView()
    // then says whether the viewpoint has moved since.
    brume::ObjectRadiance& radiance = *this->Objects[o];
    brume::Vec3 eye = firstEstimate ? request.Eye : this->ObjectEye[o];
    if (radiance.GetBinning().IsViewFixed())
    {
      eye = radiance.GetBinning().GetFixedEye();
    }
    errors[o] = radiance.Add(request.Hits, groups.Index.data() + groups.Offset[o],
      groups.Offset[o + 1] - groups.Offset[o], this->Particles / request.Run.Particles, eye,
      request.ThresholdFlux, objectFor, complete);
  };
  // A batch that only bins: the objects with many hits on every thread
  // first (BinWide()); the one that estimates builds each on one thread.
  const std::vector<char> wide =
    complete ? std::vector<char>(this->Objects.size(), 0) : this->BinWide(groups, add);
  this->ForEachObject(groups,
    [&](std::size_t o, const brume::ParallelFor& objectFor)
    {
      if (!wide[o])
      {
        add(o, objectFor);
      }
    });
  if (!this->AgreeOnObjects(errors, "Cannot add particles to"))
  {
    return false;
  }
  for (auto& output : this->Outputs)
  {
    output = nullptr;
    ++work.ParticleAdditions;
  }
  this->HitsData = request.HitData;
  this->HitsTime = request.HitData->GetMTime();
  this->Particles = request.Run.Particles;
  this->EndParticle = request.Run.EndParticle;
  this->LastFirstParticle = request.Run.FirstParticle;
  if (firstEstimate)
  {
    this->ComputeDirect(work);
    for (std::size_t o = 0; o < this->Objects.size(); ++o)
    {
      const brume::ObjectRadiance& radiance = *this->Objects[o];
      this->ObjectEye[o] =
        radiance.GetBinning().IsViewFixed() ? radiance.GetBinning().GetFixedEye() : request.Eye;
    }
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
    if (!radiance.GetLayout().ViewDependent)
    {
      continue;
    }
    const bool directional = directionalMedia && this->Scene.IsMedium(o);
    const bool project = directional && radiance.GetDirectional().GetOrder() != order;
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

bool vtkBrumeRadianceTextures::FollowView(
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
    if (!radiance.GetLayout().ViewDependent || this->ObjectDirectional[o] ||
      (last.x == eye.x && last.y == eye.y && last.z == eye.z))
    {
      if (moved[o])
      {
        radiance.UpdateView(last, parallelFor); // never fixed: no mirror sees those
      }
      continue;
    }
    if (radiance.GetBinning().IsViewFixed() && this->Accumulated)
    {
      vtkErrorWithObjectMacro(this->Filter,
        "The viewpoint changed, but '"
          << this->Sources[o].Name
          << "' was binned toward the last one (FixedView) from particles the hits no longer "
             "hold (batches or added particles): trace from FirstParticle 0 again, or turn "
             "FixedView off.");
      return false;
    }
    // Textures that hold added particles have no single hits input to be
    // rebuilt from: they are always updated incrementally.
    if ((incremental || this->Accumulated) && !radiance.GetBinning().IsViewFixed())
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
      if (radiance.GetBinning().IsViewFixed())
      {
        radiance.FixView(eye);
      }
      radiance.Options().ParticleFlux = request.ParticleFlux;
      radiance.Build(request.Hits, groups.Index.data() + groups.Offset[o],
        groups.Offset[o + 1] - groups.Offset[o], eye, request.ThresholdFlux, parallelFor);
      ++work.TextureBuilds;
    }
    this->Outputs[o] = nullptr;
    this->ObjectEye[o] = eye;
  }
  return true;
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
    count += this->Objects[o]->GetLayout().ViewDependent && !this->ObjectDirectional[o] ? 1 : 0;
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
        // The bricks the source radiance needs, kept while the resolution
        // stays (a view update changes only the values).
        const brume::SparseTexture* bricks = nullptr;
        if (this->Settings.SparseMedia && this->NativeExtinction[o])
        {
          this->SourceBricks.resize(this->Objects.size());
          const bool directional = this->ObjectDirectional[o];
          const auto& res =
            directional ? radiance.GetLayout().Resolution : radiance.GetOutput().Dims;
          if (this->SourceBricks[o].GetDims() != res)
          {
            this->SourceBricks[o] =
              vtkBrumeRadianceConversion::SourceBricks(radiance, medium, directional);
          }
          bricks = &this->SourceBricks[o];
        }
        this->Outputs[o] =
          vtkBrumeRadianceConversion::FromMedium(radiance, medium, this->ObjectDirectional[o],
            this->NativeExtinction[o], this->LastMediumTextures[o], bricks);
        this->LastMediumTextures[o] = vtkImageData::SafeDownCast(this->Outputs[o]->GetPartition(0));
      }
    }
    output->SetPartitionedDataSet(source.CollectionIndex, this->Outputs[o]);
    output->GetMetaData(source.CollectionIndex)
      ->Set(vtkCompositeDataSet::NAME(), source.Name.c_str());
  }
}
