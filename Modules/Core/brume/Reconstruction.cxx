// SPDX-License-Identifier: BSD-3-Clause
#include "brume/Reconstruction.h"

#include "brume/Density.h"
#include "brume/Material.h"

#include <algorithm>
#include <cmath>

namespace brume
{

ObjectRadiance::ObjectRadiance(
  const Surface& surface, SurfaceChart chart, std::array<int, 2> resolution, int refinement)
  : Layout(surface, std::move(chart), resolution, refinement)
  , Binning(Layout)
  , Directional(Layout)
{
}

ObjectRadiance::ObjectRadiance(const Medium& medium, std::array<int, 3> resolution, int refinement)
  : Layout(medium, resolution, refinement)
  , Binning(Layout)
  , Directional(Layout)
{
}

void ObjectRadiance::FixView(const Vec3& eye)
{
  this->Binning.FixView(this->Layout, eye);
}

namespace
{
bool SameEye(const Vec3& a, const Vec3& b)
{
  return a.x == b.x && a.y == b.y && a.z == b.z;
}

std::string FixedViewError(const Vec3& fixed)
{
  return "the texture is binned toward the fixed viewpoint (" + std::to_string(fixed.x) + ", " +
    std::to_string(fixed.y) + ", " + std::to_string(fixed.z) +
    ") and keeps no hits to follow another";
}
}

std::string ObjectRadiance::Build(const HitArrays& hits, const std::uint32_t* index,
  std::size_t count, const Vec3& eye, double thresholdFlux, const ParallelFor& parallelFor,
  bool estimate)
{
  const std::string error =
    this->BuildHits(hits, index, count, eye, thresholdFlux, parallelFor, estimate);
  if (!error.empty() || !estimate)
  {
    return error;
  }
  return this->Finish(eye, parallelFor);
}

std::string ObjectRadiance::BuildHits(const HitArrays& hits, const std::uint32_t* index,
  std::size_t count, const Vec3& eye, double thresholdFlux, const ParallelFor& parallelFor,
  bool estimate)
{
  if (this->Binning.IsViewFixed() && !SameEye(eye, this->Binning.GetFixedEye()))
  {
    return FixedViewError(this->Binning.GetFixedEye());
  }
  return this->BuildHistograms(hits, index, count, thresholdFlux, parallelFor, estimate);
}

std::string ObjectRadiance::Finish(const Vec3& eye, const ParallelFor& parallelFor)
{
  this->SumHistograms(eye, parallelFor);
  const std::string saturation = this->EstimateTexture(parallelFor);
  this->ShareTexture(parallelFor);
  return saturation;
}

std::string ObjectRadiance::BuildHistograms(const HitArrays& hits, const std::uint32_t* index,
  std::size_t count, double thresholdFlux, const ParallelFor& parallelFor, bool estimate)
{
  this->Built = false;
  this->Estimated = false;
  this->Binning.Clear(!estimate);
  this->ThresholdFlux = thresholdFlux;
  const std::string error = this->Check(hits, index, count);
  if (!error.empty())
  {
    return error;
  }
  // The quantum of the exact sums: from the particle flux, or the largest
  // hit's, the same on every process.
  double flux = this->Settings.ParticleFlux;
  if (!(flux > 0.0))
  {
    for (std::size_t k = 0; k < count; ++k)
    {
      const float* f = hits.Flux + 3 * index[k];
      flux = std::max(
        { flux, static_cast<double>(f[0]), static_cast<double>(f[1]), static_cast<double>(f[2]) });
    }
  }
  int exponent = ExactHistogram::QuantumExponent(flux);
  HistogramReduction* reduction = this->Distributed.GetReduction();
  if (reduction && !(this->Settings.ParticleFlux > 0.0))
  {
    exponent = static_cast<int>(reduction->Max(exponent));
  }
  this->Binning.Start(this->Layout, exponent, this->Settings.LobeCast);
  this->Regions.clear();
  this->Directional.Clear();
  this->Binning.Bin(this->Layout, hits, index, count, this->Direct.GetLight(),
    this->Settings.RunShare, parallelFor, this->Settings.BinOnEveryThread);
  this->Built = true;
  return this->Binning.Saturation();
}

std::string ObjectRadiance::Add(const HitArrays& hits, const std::uint32_t* index,
  std::size_t count, double scale, const Vec3& eye, double thresholdFlux,
  const ParallelFor& parallelFor, bool estimate)
{
  if (!this->Built)
  {
    return "particles can only be added to a texture already built";
  }
  if (this->Distributed.GetReduction())
  {
    return "particles cannot be added to a texture summed across processes";
  }
  if (!(scale > 0.0) || !std::isfinite(scale))
  {
    return "the flux scale of the particles already binned must be positive and finite";
  }
  if (this->Binning.IsViewFixed() && !SameEye(eye, this->Binning.GetFixedEye()))
  {
    return FixedViewError(this->Binning.GetFixedEye());
  }
  const std::string error = this->Check(hits, index, count);
  if (!error.empty())
  {
    return error; // nothing changed
  }
  // The particles already binned were normalized by a smaller count: scale
  // them (exactly, when the count grows by a power of two), then bin the new.
  const int exponent = this->Settings.ParticleFlux > 0.0
    ? ExactHistogram::QuantumExponent(this->Settings.ParticleFlux)
    : this->Binning.GetSumsExponent() + static_cast<int>(std::lround(std::log2(scale)));
  this->Binning.Scale(scale, exponent, parallelFor);
  this->Binning.SetDeferred(!estimate);
  this->Binning.Bin(this->Layout, hits, index, count, this->Direct.GetLight(),
    this->Settings.RunShare, parallelFor, this->Settings.BinOnEveryThread);
  if (!estimate)
  {
    return this->Binning.Saturation();
  }
  this->ThresholdFlux = thresholdFlux;
  this->SumHistograms(eye, parallelFor);
  this->EstimateTexture(parallelFor);
  if (this->Directional.GetOrder() >= 0)
  {
    const std::string directional =
      this->BuildDirectional(this->Directional.GetOrder(), parallelFor);
    if (!directional.empty())
    {
      return directional;
    }
  }
  return this->Binning.Saturation();
}

std::string ObjectRadiance::Check(
  const HitArrays& hits, const std::uint32_t* index, std::size_t count) const
{
  const Medium* medium = this->Layout.MediumRef;
  const bool planar = !medium && this->Layout.Chart.Type == SurfaceChart::Kind::Planar;
  if (this->Direct.IsEnabled() && count > 0 && (!hits.Emitter || !hits.Depth))
  {
    return "the hits have no EmitterId and Depth arrays, which direct lighting needs";
  }
  if (!medium && !planar && !hits.Triangle && count > 0)
  {
    return "the hits have no TriangleId array, which a non-planar surface needs";
  }
  if (!medium && !planar)
  {
    for (std::size_t k = 0; k < count; ++k)
    {
      if (hits.Triangle[index[k]] >= this->Layout.Chart.TriangleUV.size())
      {
        return "a hit's TriangleId is beyond the surface's triangles";
      }
    }
  }
  return {};
}

void ObjectRadiance::SumHistograms(const Vec3& eye, const ParallelFor& parallelFor)
{
  this->Eye = eye;
  if (this->Binning.KeepsHits())
  {
    // The kept hits' incident flux, and their weighted flux toward the eye.
    this->Binning.MergePending(parallelFor);
    this->Binning.WeighKept(this->Layout, eye, true, parallelFor);
  }
  // One message for both histograms.
  this->Reduce(this->Binning.WeightSums(), &this->Binning.ValueSums());
}

void ObjectRadiance::Reduce(ExactHistogram& a, ExactHistogram* b)
{
  this->Binning.NoteSaturation(a.Saturated() || (b && b->Saturated()));
  this->Distributed.Reduce(a, b);
}

void ObjectRadiance::SampleMedium(const ParallelFor& parallelFor)
{
  const Medium* medium = this->Layout.MediumRef;
  if (!medium || !this->Extinction.empty())
  {
    return;
  }
  const std::size_t texels = this->Layout.Texels();
  const std::array<int, 3>& resolution = this->Layout.Resolution;
  // What every process's output needs of the medium itself: sigma_t per
  // voxel, and the density at its own resolution.
  const Box box = medium->Bounds;
  this->Extinction.resize(3 * texels);
  const Vec3 voxelSize = box.Extent() /
    Vec3(static_cast<float>(resolution[0]), static_cast<float>(resolution[1]),
      static_cast<float>(resolution[2]));
  const std::size_t nx = resolution[0], nxy = nx * resolution[1];
  parallelFor(0, texels,
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t t = begin; t < end; ++t)
      {
        // sigma_t times the density's mean over 2^3 points of the voxel.
        Vec3 sigmaT = medium->SigmaT();
        if (medium->Density)
        {
          const Vec3 corner(static_cast<float>(t % nx), static_cast<float>((t % nxy) / nx),
            static_cast<float>(t / nxy));
          float mean = 0.f;
          for (int k = 0; k < 8; ++k)
          {
            const Vec3 offset(
              0.25f + 0.5f * (k & 1), 0.25f + 0.5f * ((k >> 1) & 1), 0.25f + 0.5f * (k >> 2));
            mean += medium->Density->Evaluate(box.lower + (corner + offset) * voxelSize) / 8.f;
          }
          sigmaT = sigmaT * mean;
        }
        for (int c = 0; c < 3; ++c)
        {
          this->Extinction[3 * t + c] = sigmaT[c];
        }
      }
    });
  if (medium->Density && this->Native.Empty())
  {
    // The grid replaced is this object's to reuse: an edit's extinction is
    // sampled again in its memory.
    if (this->PreviousNative)
    {
      this->Native.Sample(
        *medium, this->Settings.NativeMemory, parallelFor, std::move(*this->PreviousNative));
    }
    else
    {
      this->Native.Sample(*medium, this->Settings.NativeMemory, parallelFor);
    }
    this->PreviousNative.reset();
  }
}

void ObjectRadiance::OfferNative(NativeMediumGrid&& previous)
{
  this->PreviousNative.reset(new NativeMediumGrid(std::move(previous)));
}

std::string ObjectRadiance::EstimateTexture(const ParallelFor& parallelFor)
{
  const bool first = !this->Estimated;
  const std::size_t texels = this->Layout.Texels();
  const std::array<int, 3>& resolution = this->Layout.Resolution;
  const Medium* medium = this->Layout.MediumRef;
  if (first)
  {
    this->SampleMedium(parallelFor);
  }
  this->Estimated = true;
  if (!this->Distributed.EstimatesHere())
  {
    // The owner's histograms hold the totals; this process's are partial.
    this->Binning.ClearSums();
    return this->Binning.Saturation();
  }
  this->WeightTable = SummedAreaTable(this->Binning.WeightSums());
  this->ValueTable = SummedAreaTable(this->Binning.ValueSums());
  // Regions (view independent), then once: the area or density table.
  this->Regions.resize(texels);
  // Each half's region grows to half the threshold, so that the two
  // regions hold about the threshold's hits together, as one region grown
  // over all hits would.
  AdaptiveRegionSettings settings;
  const int refinement = this->Layout.Refinement;
  settings.Refinement = { refinement, refinement, medium ? refinement : 1 };
  settings.Threshold = 0.5 * this->ThresholdFlux;
  const std::size_t nx = resolution[0], nxy = nx * resolution[1];
  parallelFor(0, texels,
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t t = begin; t < end; ++t)
      {
        const std::array<int, 3> texel{ static_cast<int>(t % nx), static_cast<int>((t % nxy) / nx),
          static_cast<int>(t / nxy) };
        this->Regions[t] = GrowRegionPair(this->WeightTable, this->Layout.Dims, texel, settings);
      }
    });
  if (medium && medium->Density && !this->Native.HasTables(medium->Bounds, this->Layout.Dims))
  {
    // Independent of the particles and the view: made once per object.
    this->Native.BuildTables(medium->Bounds, this->Layout.Dims, parallelFor);
  }
  else if (first && !medium)
  {
    this->BuildAreaTable();
  }
  if (medium && medium->Density && this->Layout.Scattering.HasVaryingAlbedo() &&
    !this->Native.HasAlbedoTable(medium->Bounds, this->Layout.Dims, medium->AlbedoFactor.get()))
  {
    // Independent of the particles and the view: made once per colour.
    this->Native.BuildAlbedoTable(medium->Bounds, this->Layout.Dims, *medium, parallelFor);
  }
  if (medium && medium->Density)
  {
    this->Matching = this->Native.Centroids(this->Regions, resolution, refinement, parallelFor);
  }
  this->Estimate(parallelFor);
  return this->Binning.Saturation();
}

void ObjectRadiance::ShareTexture(const ParallelFor& parallelFor)
{
  if (!this->Distributed.SharesTexture())
  {
    return;
  }
  this->Radiance.resize(3 * this->Layout.Texels());
  this->Distributed.Broadcast(this->Radiance);
  if (!this->Distributed.EstimatesHere() && this->Direct.HasArrivals())
  {
    this->CombineDirect(parallelFor);
  }
}

std::string ObjectRadiance::UpdateView(const Vec3& eye, const ParallelFor& parallelFor)
{
  if (!this->Layout.ViewDependent)
  {
    return {};
  }
  if (this->Binning.IsViewFixed())
  {
    // Its texture is toward the fixed eye already; no other can be made.
    const Vec3& fixed = this->Binning.GetFixedEye();
    return SameEye(eye, fixed) ? std::string() : FixedViewError(fixed);
  }
  this->Eye = eye;
  this->Binning.WeighKept(this->Layout, eye, false, parallelFor);
  this->Reduce(this->Binning.ValueSums());
  if (this->Distributed.EstimatesHere())
  {
    this->ValueTable = SummedAreaTable(this->Binning.ValueSums());
    this->Estimate(parallelFor);
  }
  this->ShareTexture(parallelFor);
  return {};
}

void ObjectRadiance::BuildAreaTable()
{
  Histogram area(this->Layout.Dims, 1);
  AddChartAreas(*this->Layout.SurfaceRef, this->Layout.Chart, area);
  this->AreaTable = SummedAreaTable(area);
}

void ObjectRadiance::ToRadiance(
  std::size_t t, const Region& r, const double* sum, float* out, bool directional) const
{
  const MediumScattering& scattering = this->Layout.Scattering;
  const Vec3& factor = scattering.GetExtinctionFactor(directional);
  const Vec3& albedo = scattering.GetAlbedo();
  const Medium& medium = *this->Layout.MediumRef;
  if (medium.Density)
  {
    // Heterogeneous: the sigma_t-weighted mean over the region,
    // S = albedo * sum(p Phi) / integral of sigma_t over the region.
    // Where the albedo a(x) varies, each hit's term carries its albedo
    // (HitBinning) and the integral is of sigma_t a: a renderer's a(x) S
    // then scatters over the region what its hits did.
    const double integral = this->Native.RegionIntegral(r); // of the density
    double weighted[3] = { integral, integral, integral };
    if (scattering.HasVaryingAlbedo())
    {
      this->Native.RegionAlbedoIntegral(r, weighted);
    }
    const Vec3 sigmaT = medium.SigmaT();
    for (int c = 0; c < 3; ++c)
    {
      const double weight = weighted[c] * sigmaT[c];
      out[c] = integral > this->Native.GetEmptyIntegral() && weight > 0.0
        ? static_cast<float>(albedo[c] * sum[c] / (weight * factor[c]))
        : 0.f;
    }
    return;
  }
  // J = albedo * sum(p Phi) / V; S = J / sigma_t.
  const double volume = static_cast<double>(r.Cells()) * this->Layout.CellVolume;
  for (int c = 0; c < 3; ++c)
  {
    const double sigmaT = this->Extinction[3 * t + c];
    out[c] =
      sigmaT > 0.0 ? static_cast<float>(albedo[c] * sum[c] / volume / (sigmaT * factor[c])) : 0.f;
  }
}

void ObjectRadiance::Estimate(const ParallelFor& parallelFor)
{
  const std::size_t texels = this->Regions.size();
  this->Radiance.resize(3 * texels);
  const Surface* surface = this->Layout.SurfaceRef;
  const Vec3 emission = surface ? surface->Mat.Emission : Vec3(0.f);
  parallelFor(0, texels,
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t t = begin; t < end; ++t)
      {
        // Each half's region averages the other half's hits; each half
        // holds half the flux in expectation, so the two estimates add up.
        double estimate[3] = { 0.0, 0.0, 0.0 };
        for (int h = 0; h < 2; ++h)
        {
          const Region& r = this->Regions[t][h];
          double other[3];
          this->ValueTable.RegionSum(r.Lo, r.Hi, other, 3 * (1 - h), 3);
          if (this->Layout.MediumRef)
          {
            float half[3];
            this->ToRadiance(t, r, other, half, false);
            for (int c = 0; c < 3; ++c)
            {
              estimate[c] += half[c];
            }
          }
          else
          {
            // L_o = sum f_r Phi / A + L_e.
            double area = 0.0;
            this->AreaTable.RegionSum(r.Lo, r.Hi, &area);
            for (int c = 0; c < 3; ++c)
            {
              estimate[c] += area > 0.0 ? other[c] / area : 0.0;
            }
          }
        }
        float* out = &this->Radiance[3 * t];
        for (int c = 0; c < 3; ++c)
        {
          out[c] = static_cast<float>(estimate[c] + emission[c]);
        }
      }
    });
  if (this->Layout.MediumRef && this->Settings.CentroidMatching && !this->Matching.Empty())
  {
    this->Matching.Apply(this->Radiance, 3, parallelFor);
  }
  if (this->Direct.HasArrivals())
  {
    this->CombineDirect(parallelFor);
  }
}

void ObjectRadiance::EnableDirect(const DirectLight* light, const std::array<int, 3>& resolution)
{
  this->Direct.Enable(this->Layout, light, resolution);
}

void ObjectRadiance::ComputeDirect(const ParallelFor& parallelFor)
{
  this->ComputeDirect(parallelFor, nullptr);
}

void ObjectRadiance::ComputeDirect(const ParallelFor& parallelFor, const std::vector<float>* kept)
{
  if (this->Direct.Compute(
        this->Layout, this->Radiance, this->Native, this->Distributed, parallelFor, kept))
  {
    this->CombineDirect(parallelFor);
    if (this->Directional.GetOrder() >= 0)
    {
      this->BuildDirectional(this->Directional.GetOrder(), parallelFor);
    }
  }
}

void ObjectRadiance::CombineDirect(const ParallelFor& parallelFor)
{
  this->Direct.Combine(this->Layout, this->Radiance, this->Eye, parallelFor);
}

void ObjectRadiance::SetReflected(std::vector<float> radiance, const std::array<int, 3>& dims)
{
  this->Reflected = std::move(radiance);
  this->ReflectedDims = this->Reflected.empty() ? std::array<int, 3>{ 0, 0, 0 } : dims;
}

KeptHits ObjectRadiance::ReleaseKeptMemory()
{
  return this->Binning.GetStore().ReleaseMemory();
}

void ObjectRadiance::ReuseKeptMemory(KeptHits&& memory, std::size_t hits)
{
  KeptHits given = std::move(memory);
  if (this->Binning.KeepsHits())
  {
    this->Binning.GetStore().ReuseMemory(std::move(given), hits);
  }
}

} // namespace brume
