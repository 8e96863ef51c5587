// SPDX-License-Identifier: BSD-3-Clause
#include "brume/Reconstruction.h"
#include "brume/ReconstructionWeights.h"

#include "brume/Material.h"
#include "brume/Reflection.h"
#include "brume/Sampling.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>

namespace brume
{

std::string GroupHitsByObject(
  const HitArrays& hits, std::size_t objects, ObjectHits& groups, const ParallelFor& parallelFor)
{
  // Ids out of range fall in one more group, reported below.
  auto objectOf = [&](std::size_t i) { return std::min<std::size_t>(hits.Object[i], objects); };
  StableGrouping grouping(hits.Count, objects + 1);
  const std::vector<std::size_t>& counts = grouping.Count(objectOf, parallelFor);
  if (counts[objects] > 0)
  {
    const std::size_t i =
      static_cast<std::size_t>(std::find_if(hits.Object, hits.Object + hits.Count,
                                 [&](std::uint16_t object) { return object >= objects; }) -
        hits.Object);
    return "a particle hit refers to object " + std::to_string(hits.Object[i]) +
      " but the scene has " + std::to_string(objects) + " objects";
  }
  groups.Offset = grouping.Starts();
  groups.Offset.pop_back(); // the out-of-range group, empty
  groups.Index.resize(hits.Count);
  grouping.Place(
    groups.Offset, objectOf,
    [&](std::size_t i, std::size_t position)
    { groups.Index[position] = static_cast<std::uint32_t>(i); },
    parallelFor);
  return {};
}

ObjectRadiance::ObjectRadiance(
  const Surface& surface, SurfaceChart chart, std::array<int, 2> resolution, int refinement)
  : SurfaceRef(&surface)
  , Chart(std::move(chart))
  , Resolution{ resolution[0], resolution[1], 1 }
  , Dims{ resolution[0] * refinement, resolution[1] * refinement, 1 }
  , Refinement(refinement)
  , ViewDependent(surface.IsViewDependent())
{
  this->TriangleNormals.reserve(surface.Triangles.size());
  for (const auto& tri : surface.Triangles)
  {
    this->TriangleNormals.push_back(Cross(surface.Vertices[tri[1]] - surface.Vertices[tri[0]],
      surface.Vertices[tri[2]] - surface.Vertices[tri[0]]));
  }
}

ObjectRadiance::ObjectRadiance(const Medium& medium, std::array<int, 3> resolution, int refinement)
  : MediumRef(&medium)
  , Resolution(resolution)
  , Dims{ resolution[0] * refinement, resolution[1] * refinement, resolution[2] * refinement }
  , Refinement(refinement)
  , ViewDependent(medium.G != 0.f)
  , CellVolume(static_cast<double>(medium.Bounds.Volume()) /
      (static_cast<double>(this->Dims[0]) * this->Dims[1] * this->Dims[2]))
  , AlbedoVaries(medium.HasVaryingAlbedo())
  , MediumAlbedo(AlbedoVaries ? Vec3(1.f) : medium.Albedo())
  , Peaks{ SplitForwardPeak(medium.G, ResolvedG), SplitForwardPeak(medium.G, DirectionalResolvedG) }
  , ExtinctionFactors{ Vec3(1.f) - MediumAlbedo * Peaks[0].Forward,
    Vec3(1.f) - MediumAlbedo * Peaks[1].Forward }
{
  // A varying albedo is applied where the radiance is drawn: the texture
  // holds the radiance of an albedo of 1 with the peak's factor left out.
  if (this->AlbedoVaries)
  {
    this->ExtinctionFactors[0] = this->ExtinctionFactors[1] = Vec3(1.f);
  }
}

Vec3 ObjectRadiance::SourceAt(
  const Vec3& albedo, const Vec3& texel, bool directional, Vec3& factor) const
{
  if (!this->AlbedoVaries)
  {
    factor = this->ExtinctionFactors[directional ? 1 : 0];
    return texel;
  }
  factor = Vec3(1.f) - albedo * this->Peaks[directional ? 1 : 0].Forward;
  Vec3 s;
  for (int c = 0; c < 3; ++c)
  {
    s[c] = factor[c] > 0.f ? albedo[c] * texel[c] / factor[c] : 0.f;
  }
  return s;
}

void ObjectRadiance::FixView(const Vec3& eye)
{
  this->ViewFixed = this->ViewDependent;
  this->FixedEye = eye;
  this->FixedNormals =
    this->ViewFixed && this->SurfaceRef ? this->UnitNormals() : std::vector<Vec3>();
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
  if (this->ViewFixed && !SameEye(eye, this->FixedEye))
  {
    return FixedViewError(this->FixedEye);
  }
  const std::string error =
    this->BuildHistograms(hits, index, count, thresholdFlux, parallelFor, estimate);
  if (!error.empty() || !estimate)
  {
    return error;
  }
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
  this->Pending.Clear();
  this->DeferMerge = !estimate;
  this->Kept.Clear();
  this->RangeStart.assign(Ranges + 1, 0);
  this->ThresholdFlux = thresholdFlux;
  const std::string error = this->Check(hits, index, count);
  if (!error.empty())
  {
    return error;
  }
  // The quantum of the exact sums: from the particle flux, or the largest
  // hit's, the same on every process.
  double flux = this->ParticleFlux;
  if (!(flux > 0.0))
  {
    for (std::size_t k = 0; k < count; ++k)
    {
      const float* f = hits.Flux + 3 * index[k];
      flux = std::max(
        { flux, static_cast<double>(f[0]), static_cast<double>(f[1]), static_cast<double>(f[2]) });
    }
  }
  this->SumsExponent = ExactHistogram::QuantumExponent(flux);
  if (this->Reduction && !(this->ParticleFlux > 0.0))
  {
    this->SumsExponent = static_cast<int>(this->Reduction->Max(this->SumsExponent));
  }
  // View-independent objects (and fixed views) keep exact sums (for
  // Add()); the others keep hits.
  this->WeightSums = this->KeepsHits() ? ExactHistogram() : this->NewSums(1);
  this->ValueSums = this->KeepsHits() ? ExactHistogram() : this->NewSums(3);
  this->SumsClamped = false;
  this->Regions.clear();
  this->Directional.clear();
  this->DirectionalOrder = -1;
  this->Bin(hits, index, count, parallelFor);
  this->Built = true;
  return this->Saturation();
}

std::string ObjectRadiance::Saturation() const
{
  if (this->SumsClamped)
  {
    return "a hit's weighted flux exceeds 2^" +
      std::to_string(ExactHistogram::MaxTermBits - ExactHistogram::FractionBits) +
      " times a particle's: the histograms' exact sums cannot hold it";
  }
  return {};
}

std::string ObjectRadiance::Add(const HitArrays& hits, const std::uint32_t* index,
  std::size_t count, double scale, const Vec3& eye, double thresholdFlux,
  const ParallelFor& parallelFor, bool estimate)
{
  if (!this->Built)
  {
    return "particles can only be added to a texture already built";
  }
  if (this->Reduction)
  {
    return "particles cannot be added to a texture summed across processes";
  }
  if (!(scale > 0.0) || !std::isfinite(scale))
  {
    return "the flux scale of the particles already binned must be positive and finite";
  }
  if (this->ViewFixed && !SameEye(eye, this->FixedEye))
  {
    return FixedViewError(this->FixedEye);
  }
  const std::string error = this->Check(hits, index, count);
  if (!error.empty())
  {
    return error; // nothing changed
  }
  // The particles already binned were normalized by a smaller count: scale
  // them (exactly, when the count grows by a power of two), then bin the new.
  if (this->KeepsHits())
  {
    const float s = static_cast<float>(scale);
    parallelFor(0, this->Kept.Size(),
      [&](std::size_t begin, std::size_t end)
      {
        for (std::size_t k = begin; k < end; ++k)
        {
          for (float& f : this->Kept.Hits[k].Flux)
          {
            f *= s;
          }
        }
      });
    for (KeptHit& h : this->Pending.Hits) // batches not yet merged (scale 1 in practice)
    {
      for (float& f : h.Flux)
      {
        f *= s;
      }
    }
  }
  else
  {
    // Exactly, as a change of quantum, when the scale is a power of two.
    this->WeightSums.Scale(scale);
    this->ValueSums.Scale(scale);
  }
  this->SumsExponent = this->ParticleFlux > 0.0
    ? ExactHistogram::QuantumExponent(this->ParticleFlux)
    : this->SumsExponent + static_cast<int>(std::lround(std::log2(scale)));
  this->DeferMerge = !estimate;
  this->Bin(hits, index, count, parallelFor);
  if (!estimate)
  {
    return this->Saturation();
  }
  this->ThresholdFlux = thresholdFlux;
  this->SumHistograms(eye, parallelFor);
  this->EstimateTexture(parallelFor);
  if (this->DirectionalOrder >= 0)
  {
    const std::string directional = this->BuildDirectional(this->DirectionalOrder, parallelFor);
    if (!directional.empty())
    {
      return directional;
    }
  }
  return this->Saturation();
}

std::string ObjectRadiance::Check(
  const HitArrays& hits, const std::uint32_t* index, std::size_t count) const
{
  const bool planar = !this->MediumRef && this->Chart.Type == SurfaceChart::Kind::Planar;
  if (this->Direct && count > 0 && (!hits.Emitter || !hits.Depth))
  {
    return "the hits have no EmitterId and Depth arrays, which direct lighting needs";
  }
  if (!this->MediumRef && !planar && !hits.Triangle && count > 0)
  {
    return "the hits have no TriangleId array, which a non-planar surface needs";
  }
  if (!this->MediumRef && !planar)
  {
    for (std::size_t k = 0; k < count; ++k)
    {
      if (hits.Triangle[index[k]] >= this->Chart.TriangleUV.size())
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
  if (this->KeepsHits())
  {
    // The kept hits' incident flux, and their weighted flux toward the eye.
    if (!this->Pending.Empty())
    {
      this->MergePending(parallelFor);
    }
    this->DeferMerge = false;
    this->WeighCells(eye, parallelFor, true);
  }
  // One message for both histograms.
  this->Reduce(this->WeightSums, &this->ValueSums);
}

std::size_t ObjectRadiance::Texels() const
{
  return static_cast<std::size_t>(this->Resolution[0]) * this->Resolution[1] * this->Resolution[2];
}

std::string ObjectRadiance::EstimateTexture(const ParallelFor& parallelFor)
{
  const bool first = !this->Estimated;
  const std::size_t texels = this->Texels();
  if (first && this->MediumRef)
  {
    // What every process's output needs of the medium itself: sigma_t per
    // voxel, and the density at its own resolution.
    const Box box = this->MediumRef->Bounds;
    this->Extinction.resize(3 * texels);
    const Vec3 voxelSize = box.Extent() /
      Vec3(static_cast<float>(this->Resolution[0]), static_cast<float>(this->Resolution[1]),
        static_cast<float>(this->Resolution[2]));
    const std::size_t nx = this->Resolution[0], nxy = nx * this->Resolution[1];
    parallelFor(0, texels,
      [&](std::size_t begin, std::size_t end)
      {
        for (std::size_t t = begin; t < end; ++t)
        {
          // sigma_t times the density's mean over 2^3 points of the voxel.
          Vec3 sigmaT = this->MediumRef->SigmaT();
          if (this->MediumRef->Density)
          {
            const Vec3 corner(static_cast<float>(t % nx), static_cast<float>((t % nxy) / nx),
              static_cast<float>(t / nxy));
            float mean = 0.f;
            for (int k = 0; k < 8; ++k)
            {
              const Vec3 offset(
                0.25f + 0.5f * (k & 1), 0.25f + 0.5f * ((k >> 1) & 1), 0.25f + 0.5f * (k >> 2));
              mean +=
                this->MediumRef->Density->Evaluate(box.lower + (corner + offset) * voxelSize) / 8.f;
            }
            sigmaT = sigmaT * mean;
          }
          for (int c = 0; c < 3; ++c)
          {
            this->Extinction[3 * t + c] = sigmaT[c];
          }
        }
      });
    if (this->MediumRef->Density && this->NativeDensity.Empty())
    {
      // Independent of the particles and the view: made once per object.
      this->SampleNativeDensity(parallelFor);
    }
  }
  this->Estimated = true;
  if (!this->EstimatesHere())
  {
    // The owner's histograms hold the totals; this process's are partial.
    this->WeightSums = ExactHistogram();
    this->ValueSums = ExactHistogram();
    return this->Saturation();
  }
  this->WeightTable = SummedAreaTable(this->WeightSums);
  this->ValueTable = SummedAreaTable(this->ValueSums);
  // Regions (view independent), then once: the area or density table.
  this->Regions.resize(texels);
  AdaptiveRegionSettings settings;
  settings.Refinement = { this->Refinement, this->Refinement,
    this->MediumRef ? this->Refinement : 1 };
  settings.Threshold = this->ThresholdFlux;
  const std::size_t nx = this->Resolution[0], nxy = nx * this->Resolution[1];
  parallelFor(0, texels,
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t t = begin; t < end; ++t)
      {
        const std::array<int, 3> texel{ static_cast<int>(t % nx), static_cast<int>((t % nxy) / nx),
          static_cast<int>(t / nxy) };
        this->Regions[t] = GrowRegion(this->WeightTable, this->Dims, texel, settings);
      }
    });
  if (this->MediumRef && this->MediumRef->Density && this->DensityTable.GetNumberOfChannels() == 0)
  {
    // Independent of the particles and the view: made once per object.
    this->BuildDensityTable();
  }
  else if (first && !this->MediumRef)
  {
    this->BuildAreaTable();
  }
  if (this->MediumRef && this->MediumRef->Density)
  {
    this->FindCentroids(parallelFor);
  }
  this->Estimate(parallelFor);
  return this->Saturation();
}

std::string ObjectRadiance::UpdateView(const Vec3& eye, const ParallelFor& parallelFor)
{
  if (!this->ViewDependent)
  {
    return {};
  }
  if (this->ViewFixed)
  {
    // Its texture is toward the fixed eye already; no other can be made.
    return SameEye(eye, this->FixedEye) ? std::string() : FixedViewError(this->FixedEye);
  }
  this->Eye = eye;
  this->WeighCells(eye, parallelFor);
  this->Reduce(this->ValueSums);
  if (this->EstimatesHere())
  {
    this->ValueTable = SummedAreaTable(this->ValueSums);
    this->Estimate(parallelFor);
  }
  this->ShareTexture(parallelFor);
  return {};
}

void ObjectRadiance::WeighCells(const Vec3& eye, const ParallelFor& parallelFor, bool weights)
{
  this->ValueSums = this->NewSums(3);
  ExactHistogram& value = this->ValueSums;
  if (weights)
  {
    this->WeightSums = this->NewSums(1);
  }
  ExactHistogram& weight = this->WeightSums;
  // The kept hits' incident flux, with their weighted flux in the same pass
  // over them (exact sums: the order of the terms does not matter).
  auto addWeight = [&](const KeptHit& h, std::size_t k)
  {
    const double w[1] = { (static_cast<double>(h.Flux[0]) + h.Flux[1] + h.Flux[2]) / 3.0 *
      this->Kept.GrowthOf(k) };
    weight.AddNonNegative(h.Cell, w);
  };
  const Medium* medium = this->MediumRef;
  // Media: the remainder of the phase function once its peak is set apart.
  const HenyeyGreenstein phase(medium ? this->Peaks[0].G : 0.f);
  const float remainder = static_cast<float>(1.0 - this->Peaks[0].Forward);
  if (medium)
  {
    // Phase function from the direction of travel to the eye, in blocks
    // whose arithmetic the compiler vectorizes (square roots and divisions
    // are most of the cost).
    parallelFor(0, Ranges,
      [&](std::size_t begin, std::size_t end)
      {
        constexpr std::size_t Block = 16;
        float dx[Block], dy[Block], dz[Block], ux[Block], uy[Block], uz[Block], p[Block];
        const std::size_t last = this->RangeStart[end];
        for (std::size_t first = this->RangeStart[begin]; first < last; first += Block)
        {
          const std::size_t n = std::min(Block, last - first);
          for (std::size_t i = 0; i < Block; ++i)
          {
            const KeptHit& h = this->Kept.Hits[first + std::min(i, n - 1)];
            dx[i] = eye.x - h.Position[0];
            dy[i] = eye.y - h.Position[1];
            dz[i] = eye.z - h.Position[2];
            ux[i] = h.Direction[0];
            uy[i] = h.Direction[1];
            uz[i] = h.Direction[2];
          }
          for (std::size_t i = 0; i < Block; ++i)
          {
            const float cosine = (ux[i] * dx[i] + uy[i] * dy[i] + uz[i] * dz[i]) /
              std::sqrt(dx[i] * dx[i] + dy[i] * dy[i] + dz[i] * dz[i]);
            p[i] = remainder * phase.Evaluate(cosine);
          }
          for (std::size_t i = 0; i < n; ++i)
          {
            const KeptHit& h = this->Kept.Hits[first + i];
            const double v[3] = { static_cast<double>(p[i]) * h.Flux[0],
              static_cast<double>(p[i]) * h.Flux[1], static_cast<double>(p[i]) * h.Flux[2] };
            value.AddNonNegative(h.Cell, v);
            if (weights)
            {
              addWeight(h, first + i);
            }
          }
        }
      });
  }
  else
  {
    // The triangles' normals, once per update rather than per hit.
    const std::vector<Vec3> normals = this->UnitNormals();
    parallelFor(0, Ranges,
      [&](std::size_t begin, std::size_t end)
      {
        for (std::size_t k = this->RangeStart[begin]; k < this->RangeStart[end]; ++k)
        {
          const KeptHit& h = this->Kept.Hits[k];
          double v[3];
          this->WeighHit(
            eye, h.Position, h.Direction, h.Flux, this->Kept.TriangleOf(k), normals, v);
          value.AddNonNegative(h.Cell, v);
          if (weights)
          {
            addWeight(h, k);
          }
        }
      });
  }
}

void ObjectRadiance::BuildAreaTable()
{
  Histogram area(this->Dims, 1);
  AddChartAreas(*this->SurfaceRef, this->Chart, area);
  this->AreaTable = SummedAreaTable(area);
}

ExactHistogram ObjectRadiance::NewSums(int channels) const
{
  return ExactHistogram(this->Dims, channels, this->SumsExponent);
}

Histogram ObjectRadiance::GetWeightHistogram() const
{
  Histogram h;
  this->WeightSums.ToHistogram(h);
  return h;
}

Histogram ObjectRadiance::GetValueHistogram() const
{
  Histogram h;
  this->ValueSums.ToHistogram(h);
  return h;
}

void ObjectRadiance::ToRadiance(
  std::size_t t, const Region& r, const double* sum, float* out, bool directional) const
{
  const Vec3& factor = this->GetExtinctionFactor(directional);
  if (this->MediumRef->Density)
  {
    // Heterogeneous: the sigma_t-weighted mean over the region,
    // S = albedo * sum(p Phi) / integral of sigma_t over the region.
    double integral = 0.0; // of the density
    this->DensityTable.RegionSum(r.Lo, r.Hi, &integral);
    const Vec3 sigmaT = this->MediumRef->SigmaT();
    for (int c = 0; c < 3; ++c)
    {
      const double weight = integral * sigmaT[c];
      out[c] = integral > this->EmptyIntegral && weight > 0.0
        ? static_cast<float>(this->MediumAlbedo[c] * sum[c] / (weight * factor[c]))
        : 0.f;
    }
    return;
  }
  // J = albedo * sum(p Phi) / V; S = J / sigma_t.
  const double volume = static_cast<double>(r.Cells()) * this->CellVolume;
  for (int c = 0; c < 3; ++c)
  {
    const double sigmaT = this->Extinction[3 * t + c];
    out[c] = sigmaT > 0.0
      ? static_cast<float>(this->MediumAlbedo[c] * sum[c] / volume / (sigmaT * factor[c]))
      : 0.f;
  }
}

void ObjectRadiance::Estimate(const ParallelFor& parallelFor)
{
  const std::size_t texels = this->Regions.size();
  this->Radiance.resize(3 * texels);
  const Vec3 emission = this->SurfaceRef ? this->SurfaceRef->Mat.Emission : Vec3(0.f);
  parallelFor(0, texels,
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t t = begin; t < end; ++t)
      {
        const Region& r = this->Regions[t];
        double sum[3];
        this->ValueTable.RegionSum(r.Lo, r.Hi, sum);
        float* out = &this->Radiance[3 * t];
        if (this->MediumRef)
        {
          this->ToRadiance(t, r, sum, out, false);
        }
        else
        {
          // L_o = sum f_r Phi / A + L_e.
          double area = 0.0;
          this->AreaTable.RegionSum(r.Lo, r.Hi, &area);
          for (int c = 0; c < 3; ++c)
          {
            out[c] = static_cast<float>((area > 0.0 ? sum[c] / area : 0.0) + emission[c]);
          }
        }
      }
    });
  if (this->MediumRef && this->MatchingCentroids && !this->Matching.Empty())
  {
    this->Matching.Apply(this->Radiance, 3, parallelFor);
  }
  if (this->HasDirect())
  {
    this->CombineDirect(parallelFor);
  }
}

void ObjectRadiance::SetReflected(std::vector<float> radiance, const std::array<int, 3>& dims)
{
  this->Reflected = std::move(radiance);
  this->ReflectedDims = this->Reflected.empty() ? std::array<int, 3>{ 0, 0, 0 } : dims;
}

} // namespace brume
