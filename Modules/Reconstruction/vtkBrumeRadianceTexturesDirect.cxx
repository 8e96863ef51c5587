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
#include <iomanip>
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
    if (!medium.GetNative().GetDensity().Empty())
    {
      this->Direct->SetMediumGrid(o - surfaces, &medium.GetNative().GetDensity());
    }
  }
  // Objects of few texels x lights are computed side by side, each on one
  // thread (a scene of 65,000 tiles spent its time handing each tile's few
  // texels to every thread); larger ones in turn, on every thread. An
  // object's light does not depend on how its texels are shared out. A
  // distributed run gathers each object's shares in turn, on every process.
  const brume::ParallelFor parallelFor = vtkBrumeSMP::ParallelFor();
  const std::size_t lights = this->Scene.Lights.size();
  std::vector<brume::ObjectRadiance*> small;
  for (auto& object : this->Objects)
  {
    if (!object->GetDirect().IsEnabled())
    {
      continue;
    }
    const auto& dims = object->GetDirect().GetDims();
    const std::size_t arrivals = static_cast<std::size_t>(dims[0]) * dims[1] * dims[2] * lights;
    if (!this->Distributed() && arrivals < SmallDirectArrivals)
    {
      small.push_back(object.get());
    }
    else
    {
      object->ComputeDirect(parallelFor);
    }
  }
  vtkSMPTools::For(0, static_cast<vtkIdType>(small.size()),
    [&small](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType k = begin; k < end; ++k)
      {
        small[k]->ComputeDirect(brume::SerialFor());
      }
    });
}
