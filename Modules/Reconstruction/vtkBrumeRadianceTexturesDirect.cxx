// SPDX-License-Identifier: BSD-3-Clause
// vtkBrumeRadianceTextures' direct light of delta lights: the objects'
// grids within the scene's budget of texels x lights, then their shadow rays.
#include "vtkBrumeRadianceTextures.h"

#include "vtkAlgorithm.h"
#include "vtkBrumeSMP.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

bool vtkBrumeRadianceTextures::CreateDirectLight(
  const vtkBrumeReconstructionSettings& settings, const brume::HitArrays& hits)
{
  this->Direct.reset();
  if (settings.DirectLightResolution <= 0 || this->Scene.Lights.empty())
  {
    this->Caster.reset();
    return true;
  }
  if (hits.Count > 0 && (!hits.Emitter || !hits.Depth))
  {
    vtkWarningWithObjectMacro(this->Filter,
      "The particle hits have no 'EmitterId' and 'Depth' arrays: direct light is estimated from "
      "them, not computed.");
    this->Caster.reset();
    return true;
  }
  // The tracer's, while the surfaces are the same.
  this->Caster = vtkBrumeSceneConversion::SharedRayCaster(this->Scene);
  if (!this->Caster->GetError().empty())
  {
    vtkErrorWithObjectMacro(
      this->Filter, "Cannot cast shadow rays: " << this->Caster->GetError() << ".");
    return this->Agree(false);
  }
  this->Direct.reset(new brume::DirectLight(this->Scene, *this->Caster));
  // Each object's grid, then one factor for all where the scene's would
  // exceed MaxSceneDirectArrivals.
  const double lights = static_cast<double>(this->Scene.Lights.size());
  std::vector<std::array<int, 3>> grids(this->Objects.size(), std::array<int, 3>{ 0, 0, 0 });
  double arrivals = 0.0;
  for (std::size_t o = 0; o < this->Objects.size(); ++o)
  {
    if (brume::DirectTexture::Supports(this->Objects[o]->GetLayout()))
    {
      grids[o] = this->DirectResolution(o, settings.DirectLightResolution);
      arrivals += static_cast<double>(grids[o][0]) * grids[o][1] * grids[o][2] * lights;
    }
  }
  if (arrivals > MaxSceneDirectArrivals)
  {
    const double kept = this->FitDirectGrids(grids, lights);
    std::ostringstream percent;
    percent << std::setprecision(2) << 100.0 * kept / arrivals;
    vtkWarningWithObjectMacro(this->Filter,
      "The direct light's grids are coarsened to one texel size for the whole scene, "
        << percent.str() << " % of their texels: the scene's would hold "
        << static_cast<long long>(arrivals) << " texels x lights, more than "
        << static_cast<long long>(MaxSceneDirectArrivals) << ".");
  }
  std::size_t left = 0;
  for (std::size_t o = 0; o < this->Objects.size(); ++o)
  {
    if (grids[o][0] > 0)
    {
      const std::array<int, 3> res = grids[o];
      if (static_cast<double>(res[0]) * res[1] *
        res[2]<MinDirectTexels&& static_cast<double>(this->Scene.Lights.size()) * MinDirectTexels>
          MaxDirectArrivals)
      {
        ++left; // too many lights for a grid worth computing
        continue;
      }
      this->Objects[o]->EnableDirect(this->Direct.get(), res);
    }
  }
  if (left > 0)
  {
    vtkWarningWithObjectMacro(this->Filter,
      "" << this->Scene.Lights.size() << " lights: the direct light of " << left
         << " object(s) is estimated from the particles, not computed (texels x lights would "
            "exceed "
         << static_cast<long long>(MaxDirectArrivals) << ").");
  }
  return this->Agree(true);
}

double vtkBrumeRadianceTextures::FitDirectGrids(
  std::vector<std::array<int, 3>>& grids, double lights) const
{
  // Each object's extent, over which its own grid spans.
  std::vector<brume::Vec3> extents(grids.size());
  float largest = 0.f;
  for (std::size_t o = 0; o < grids.size(); ++o)
  {
    if (grids[o][0] > 0)
    {
      const brume::SurfaceChart& chart = this->Objects[o]->GetLayout().Chart;
      extents[o] = this->Scene.IsMedium(o)
        ? this->Scene.Media[o - this->Scene.Surfaces.size()].Bounds.Extent()
        : brume::Vec3(chart.Width, chart.Height, 0.f);
      largest = std::max(largest, MaxComponent(extents[o]));
    }
  }
  // A texel of `size` on every object, and no finer than its own grid: a
  // large ground keeps its texels, a small tile needs few.
  auto fitted = [&](double size, std::vector<std::array<int, 3>>* out)
  {
    double total = 0.0;
    for (std::size_t o = 0; o < grids.size(); ++o)
    {
      if (grids[o][0] <= 0)
      {
        continue;
      }
      std::array<int, 3> res = grids[o];
      for (int a = 0; a < 3; ++a)
      {
        if (extents[o][a] > 0.f)
        {
          res[a] = std::clamp(static_cast<int>(std::ceil(extents[o][a] / size)), 1, grids[o][a]);
        }
      }
      total += static_cast<double>(res[0]) * res[1] * res[2] * lights;
      if (out)
      {
        (*out)[o] = res;
      }
    }
    return total;
  };
  // The finest texel size within the budget (the count falls as the size
  // grows; one texel per object is the coarsest): bisection in log size.
  double coarse = std::max(1e-30, static_cast<double>(largest));
  double fine = coarse * 1e-6;
  for (int step = 0; step < 60; ++step)
  {
    const double size = std::sqrt(coarse * fine);
    (fitted(size, nullptr) > MaxSceneDirectArrivals ? fine : coarse) = size;
  }
  return fitted(coarse, &grids);
}

struct vtkBrumeRadianceTextures::KeptDirect
{
  std::shared_ptr<const brume::RayCaster> Caster;
  std::vector<brume::Light> Lights;
  struct Medium
  {
    brume::Box Bounds;
    brume::Vec3 SigmaT;
    bool Homogeneous = true;
    // The grid the rays marched, without keeping its samples: its identity
    // (a grid sampled again in its own memory, after an edit of its
    // function, has another), their memory's owner, its cells, slots and
    // constants.
    bool HasGrid = false;
    std::uint64_t Identity = 0;
    std::weak_ptr<float> Samples;
    const float* SampleData = nullptr; // compared, never read
    std::size_t SampleCount = 0;
    std::array<int, 3> Dims{ 0, 0, 0 };
    brume::Box Box;
    std::vector<std::int32_t> Slots;
    std::vector<float> Constants;
  };
  std::vector<Medium> Media;
  struct Object
  {
    std::array<int, 3> Dims{ 0, 0, 0 };
    std::array<int, 3> Resolution{ 0, 0, 0 };
    std::vector<float> Arrivals; // empty: none computed
  };
  std::vector<Object> Objects;
};

namespace
{
bool SameBox(const brume::Box& a, const brume::Box& b)
{
  for (int c = 0; c < 3; ++c)
  {
    if (a.lower[c] != b.lower[c] || a.upper[c] != b.upper[c])
    {
      return false;
    }
  }
  return true;
}

bool SameVec(const brume::Vec3& a, const brume::Vec3& b)
{
  return a.x == b.x && a.y == b.y && a.z == b.z;
}

// Everything a light's shadow rays and arrivals read.
bool SameLight(const brume::Light& a, const brume::Light& b)
{
  return a.Type == b.Type && SameVec(a.Position, b.Position) && SameVec(a.Direction, b.Direction) &&
    SameVec(a.Intensity, b.Intensity) && a.ConeAngle == b.ConeAngle &&
    SameVec(a.BeamCenter, b.BeamCenter) && a.BeamRadius == b.BeamRadius &&
    SameVec(a.AimCenter, b.AimCenter) && a.AimRadius == b.AimRadius &&
    a.AimFraction == b.AimFraction;
}
}

std::shared_ptr<vtkBrumeRadianceTextures::KeptDirect> vtkBrumeRadianceTextures::ReleaseDirect()
{
  if (!this->Direct || this->Distributed())
  {
    return nullptr;
  }
  auto kept = std::make_shared<KeptDirect>();
  kept->Caster = this->Caster;
  kept->Lights = this->Scene.Lights;
  const std::size_t surfaces = this->Scene.Surfaces.size();
  for (std::size_t m = 0; m < this->Scene.Media.size(); ++m)
  {
    const brume::Medium& medium = this->Scene.Media[m];
    KeptDirect::Medium key;
    key.Bounds = medium.Bounds;
    key.SigmaT = medium.SigmaT();
    key.Homogeneous = medium.IsHomogeneous();
    if (surfaces + m < this->Objects.size())
    {
      const brume::BrickedGrid& grid = this->Objects[surfaces + m]->GetNative().GetDensity();
      key.HasGrid = !grid.Empty();
      key.Identity = grid.GetIdentity();
      key.Samples = grid.GetSamples().Share();
      key.SampleData = grid.GetSamples().Data();
      key.SampleCount = grid.GetSamples().Size();
      key.Dims = grid.GetDims();
      key.Box = grid.GetBox();
      key.Slots = grid.GetSlots();
      key.Constants = grid.GetConstants();
    }
    kept->Media.push_back(std::move(key));
  }
  for (auto& object : this->Objects)
  {
    KeptDirect::Object key;
    const brume::DirectTexture& direct = object->GetDirect();
    if (direct.IsEnabled() && direct.HasArrivals())
    {
      key.Dims = direct.GetDims();
      key.Resolution = object->GetLayout().Resolution;
      key.Arrivals = direct.GetArrivals();
    }
    kept->Objects.push_back(std::move(key));
  }
  return kept;
}

bool vtkBrumeRadianceTextures::DirectKeptHolds() const
{
  // The same surfaces (the caster found by their geometry), lights and
  // media's extinction: every shadow ray is the same.
  const KeptDirect* kept = this->PreviousDirect.get();
  if (!kept || this->Distributed() || !this->Caster || kept->Caster != this->Caster ||
    kept->Lights.size() != this->Scene.Lights.size() ||
    kept->Media.size() != this->Scene.Media.size() || kept->Objects.size() != this->Objects.size())
  {
    return false;
  }
  for (std::size_t l = 0; l < kept->Lights.size(); ++l)
  {
    if (!SameLight(kept->Lights[l], this->Scene.Lights[l]))
    {
      return false;
    }
  }
  const std::size_t surfaces = this->Scene.Surfaces.size();
  for (std::size_t m = 0; m < kept->Media.size(); ++m)
  {
    const brume::Medium& medium = this->Scene.Media[m];
    const KeptDirect::Medium& key = kept->Media[m];
    if (!SameBox(key.Bounds, medium.Bounds) || !SameVec(key.SigmaT, medium.SigmaT()) ||
      key.Homogeneous != medium.IsHomogeneous())
    {
      return false;
    }
    // A heterogeneous medium's rays march its grid: the same grid (the one
    // kept after an edit that left its function as it was), not an equal one.
    if (!medium.IsHomogeneous())
    {
      const brume::BrickedGrid& grid = this->Objects[surfaces + m]->GetNative().GetDensity();
      const std::shared_ptr<float>& samples = grid.GetSamples().Share();
      const bool sameOwner =
        !samples.owner_before(key.Samples) && !key.Samples.owner_before(samples);
      if (grid.Empty() || !key.HasGrid || grid.GetIdentity() != key.Identity || !sameOwner ||
        samples.get() != key.SampleData || grid.GetSamples().Size() != key.SampleCount ||
        grid.GetDims() != key.Dims || !SameBox(grid.GetBox(), key.Box) ||
        grid.GetSlots() != key.Slots || grid.GetConstants() != key.Constants)
      {
        return false;
      }
    }
  }
  return true;
}

const std::vector<float>* vtkBrumeRadianceTextures::KeptArrivals(std::size_t o) const
{
  const KeptDirect::Object& key = this->PreviousDirect->Objects[o];
  const brume::ObjectRadiance& object = *this->Objects[o];
  const bool medium = this->Scene.IsMedium(o);
  if (key.Arrivals.empty() || key.Dims != object.GetDirect().GetDims() ||
    key.Resolution != object.GetLayout().Resolution ||
    (medium &&
      !SameBox(this->PreviousDirect->Media[o - this->Scene.Surfaces.size()].Bounds,
        this->Scene.Media[o - this->Scene.Surfaces.size()].Bounds)))
  {
    return nullptr;
  }
  return &key.Arrivals;
}

void vtkBrumeRadianceTextures::ComputeDirect(vtkBrumeReconstructionWork& work)
{
  if (!this->Direct)
  {
    this->PreviousDirect.reset();
    return;
  }
  const bool holds = this->DirectKeptHolds();
  // Shadow rays march the media's grids of density means, made with the
  // textures.
  const std::size_t surfaces = this->Scene.Surfaces.size();
  for (std::size_t o = surfaces; o < this->Objects.size(); ++o)
  {
    const brume::ObjectRadiance& medium = *this->Objects[o];
    if (!medium.GetNative().GetDensity().Empty())
    {
      this->Direct->SetMediumGrid(
        o - surfaces, &medium.GetNative().GetDensity(), vtkBrumeSMP::ParallelFor());
    }
  }
  // Objects of few texels x lights are computed side by side, each on one
  // thread (a scene of 65,000 tiles spent its time handing each tile's few
  // texels to every thread); larger ones in turn, on every thread. An
  // object's light does not depend on how its texels are shared out. A
  // distributed run gathers each object's shares in turn, on every process.
  const brume::ParallelFor parallelFor = vtkBrumeSMP::ParallelFor();
  const std::size_t lights = this->Scene.Lights.size();
  // The arrivals of the textures replaced, where they hold for this scene.
  std::vector<const std::vector<float>*> kept(this->Objects.size(), nullptr);
  for (std::size_t o = 0; holds && o < this->Objects.size(); ++o)
  {
    kept[o] = this->KeptArrivals(o);
  }
  std::vector<std::size_t> small;
  for (std::size_t o = 0; o < this->Objects.size(); ++o)
  {
    brume::ObjectRadiance& object = *this->Objects[o];
    if (!object.GetDirect().IsEnabled())
    {
      continue;
    }
    work.DirectArrivalsKept += kept[o] ? 1 : 0;
    const auto& dims = object.GetDirect().GetDims();
    const std::size_t arrivals = static_cast<std::size_t>(dims[0]) * dims[1] * dims[2] * lights;
    if (!this->Distributed() && arrivals < SmallDirectArrivals)
    {
      small.push_back(o);
    }
    else
    {
      object.ComputeDirect(parallelFor, kept[o]);
    }
  }
  vtkSMPTools::For(0, static_cast<vtkIdType>(small.size()),
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType k = begin; k < end; ++k)
      {
        const std::size_t o = small[static_cast<std::size_t>(k)];
        this->Objects[o]->ComputeDirect(brume::SerialFor(), kept[o]);
      }
    });
  this->PreviousDirect.reset();
}
