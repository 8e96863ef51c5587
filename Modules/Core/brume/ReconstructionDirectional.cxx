// SPDX-License-Identifier: BSD-3-Clause
// Directional radiance of anisotropic media: the spherical-harmonics
// projection of the light each voxel receives (brume/DirectionalRadiance.h).
#include "brume/Reconstruction.h"

#include "brume/SphericalHarmonics.h"

#include <algorithm>

namespace brume
{

std::string ObjectRadiance::BuildDirectional(int order, const ParallelFor& parallelFor)
{
  if (!this->Layout.MediumRef || !this->Layout.ViewDependent)
  {
    return "directional radiance is made for anisotropic media only";
  }
  if (!this->Estimated)
  {
    return "directional radiance needs a texture already built";
  }
  if (this->Binning.IsViewFixed())
  {
    return "directional radiance needs the hits, which an object whose view is fixed does not keep";
  }
  if (order < 0 || order > MaxShOrder)
  {
    return "the spherical-harmonics order must be in [0, " + std::to_string(MaxShOrder) + "]";
  }
  const int nk = ShCoefficients(order);
  const std::size_t texels = this->Layout.Texels();
  std::vector<float>& directional = this->Directional.Start(order, texels * nk * 3);
  const bool here = this->Distributed.EstimatesHere();
  const KeptHitStore& store = this->Binning.GetStore();
  const KeptHits& kept = store.GetHits();
  // A few coefficients per pass bound the memory: each pass bins
  // Y_k(w_p) Phi_p into a histogram, sums every region from its table and
  // normalizes the sums as the per-view textures are.
  constexpr int PerPass = 4;
  for (int k0 = 0; k0 < nk; k0 += PerPass)
  {
    const int kn = std::min(PerPass, nk - k0);
    // Each hit in its half's channels (HitHalf()), as the per-view sums.
    ExactHistogram sums = this->Binning.NewSums(this->Layout.Dims, 6 * kn);
    parallelFor(0, KeptHitStore::Ranges,
      [&](std::size_t begin, std::size_t end)
      {
        float y[ShCoefficients(MaxShOrder)];
        double v[3 * PerPass];
        // The light in-scattered by the phase function's remainder.
        const double remainder = 1.0 - this->Layout.Scattering.GetPeak(true).Forward;
        for (std::size_t k = store.RangeStart(begin); k < store.RangeStart(end); ++k)
        {
          const KeptHit& h = kept.Hits[k];
          EvaluateSh(order, Vec3(h.Direction[0], h.Direction[1], h.Direction[2]), y);
          const int half = HitHalf(h.Position);
          for (int j = 0; j < kn; ++j)
          {
            for (int c = 0; c < 3; ++c)
            {
              v[3 * j + c] = remainder * y[k0 + j] * h.Flux[c];
            }
          }
          sums.Add(h.Cell, 3 * kn * half, v, 3 * kn);
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
          for (int j = 0; j < kn; ++j)
          {
            std::fill_n(&directional[(t * nk + k0 + j) * 3], 3, 0.f);
          }
          // Each half's region averages the other half's hits (Estimate()).
          for (int h = 0; h < 2; ++h)
          {
            const Region& r = this->Regions[t][h];
            table.RegionSum(r.Lo, r.Hi, sum, 3 * kn * (1 - h), 3 * kn);
            for (int j = 0; j < kn; ++j)
            {
              float half[3];
              this->ToRadiance(t, r, sum + 3 * j, half, true);
              for (int c = 0; c < 3; ++c)
              {
                directional[(t * nk + k0 + j) * 3 + c] += half[c];
              }
            }
          }
        }
      });
  }
  if (here && this->Settings.CentroidMatching && !this->Matching.Empty())
  {
    // As the per-view textures: each region's coefficients belong to its
    // centroid (the direct light, computed per voxel, is added after).
    this->Matching.Apply(directional, 3 * nk, parallelFor);
  }
  if (here && this->Direct.HasArrivals())
  {
    this->Direct.AddToDirectional(this->Layout, order, directional);
  }
  this->Distributed.Broadcast(directional);
  return {};
}

} // namespace brume
