// SPDX-License-Identifier: BSD-3-Clause
// Directional radiance of anisotropic media: the spherical-harmonics
// projection of the light each voxel receives (see brume/Reconstruction.h).
#include "brume/Reconstruction.h"

#include "brume/SphericalHarmonics.h"

#include <algorithm>

namespace brume
{

std::string ObjectRadiance::BuildDirectional(int order, const ParallelFor& parallelFor)
{
  if (!this->MediumRef || !this->ViewDependent)
  {
    return "directional radiance is made for anisotropic media only";
  }
  if (!this->Estimated)
  {
    return "directional radiance needs a texture already built";
  }
  if (this->ViewFixed)
  {
    return "directional radiance needs the hits, which an object whose view is fixed does not keep";
  }
  if (order < 0 || order > MaxShOrder)
  {
    return "the spherical-harmonics order must be in [0, " + std::to_string(MaxShOrder) + "]";
  }
  const int nk = ShCoefficients(order);
  const std::size_t texels = this->Texels();
  this->Directional.assign(texels * nk * 3, 0.f);
  const bool here = this->EstimatesHere();
  this->DirectionalOrder = order;
  // A few coefficients per pass bound the memory: each pass bins
  // Y_k(w_p) Phi_p into a histogram, sums every region from its table and
  // normalizes the sums as the per-view textures are.
  constexpr int PerPass = 4;
  for (int k0 = 0; k0 < nk; k0 += PerPass)
  {
    const int kn = std::min(PerPass, nk - k0);
    ExactHistogram sums = this->NewSums(3 * kn);
    parallelFor(0, Ranges,
      [&](std::size_t begin, std::size_t end)
      {
        float y[ShCoefficients(MaxShOrder)];
        double v[3 * PerPass];
        // The light in-scattered by the phase function's remainder.
        const double remainder = 1.0 - this->Peaks[1].Forward;
        for (std::size_t k = this->RangeStart[begin]; k < this->RangeStart[end]; ++k)
        {
          const KeptHit& h = this->Kept.Hits[k];
          EvaluateSh(order, Vec3(h.Direction[0], h.Direction[1], h.Direction[2]), y);
          for (int j = 0; j < kn; ++j)
          {
            for (int c = 0; c < 3; ++c)
            {
              v[3 * j + c] = remainder * y[k0 + j] * h.Flux[c];
            }
          }
          sums.Add(h.Cell, v);
        }
      });
    this->Reduce(sums);
    if (!here)
    {
      continue; // the owner's sums alone are the totals
    }
    const SummedAreaTable table(sums);
    parallelFor(0, texels,
      [&](std::size_t begin, std::size_t end)
      {
        double sum[3 * PerPass];
        for (std::size_t t = begin; t < end; ++t)
        {
          const Region& r = this->Regions[t];
          table.RegionSum(r.Lo, r.Hi, sum);
          for (int j = 0; j < kn; ++j)
          {
            this->ToRadiance(t, r, sum + 3 * j, &this->Directional[(t * nk + k0 + j) * 3], true);
          }
        }
      });
  }
  if (here && this->MatchingCentroids && !this->Matching.Empty())
  {
    // As the per-view textures: each region's coefficients belong to its
    // centroid (the direct light, computed per voxel, is added after).
    this->Matching.Apply(this->Directional, 3 * nk, parallelFor);
  }
  if (here && this->HasDirect())
  {
    this->AddDirectToDirectional(order);
  }
  if (this->Reduction && this->Owner >= 0 && this->Reduction->NumberOfProcesses() > 1)
  {
    this->Reduction->Broadcast(this->Directional, this->Owner);
  }
  return {};
}

void ObjectRadiance::EvaluateDirectional(const Vec3& eye, std::vector<float>& radiance) const
{
  const std::size_t texels = this->Texels();
  radiance.assign(3 * texels, 0.f);
  if (this->DirectionalOrder < 0 || !this->MediumRef)
  {
    return;
  }
  const int nk = ShCoefficients(this->DirectionalOrder);
  const Box box = this->MediumRef->Bounds;
  const Vec3 voxel = box.Extent() /
    Vec3(static_cast<float>(this->Resolution[0]), static_cast<float>(this->Resolution[1]),
      static_cast<float>(this->Resolution[2]));
  const std::size_t nx = this->Resolution[0], nxy = nx * this->Resolution[1];
  for (std::size_t t = 0; t < texels; ++t)
  {
    const Vec3 centre = box.lower +
      (Vec3(static_cast<float>(t % nx), static_cast<float>((t % nxy) / nx),
         static_cast<float>(t / nxy)) +
        Vec3(0.5f)) *
        voxel;
    const Vec3 toEye = Normalize(eye - centre);
    for (int c = 0; c < 3; ++c)
    {
      radiance[3 * t + c] = std::max(0.f,
        EvaluateHgFromSh(
          this->DirectionalOrder, this->Peaks[1].G, &this->Directional[t * nk * 3 + c], 3, toEye));
    }
  }
}

} // namespace brume
