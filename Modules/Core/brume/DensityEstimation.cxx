// SPDX-License-Identifier: BSD-3-Clause
#include "brume/DensityEstimation.h"

#include <algorithm>

namespace brume
{

namespace
{
// The regions of `texel` that channels [first, first + N) of `weights` grow
// (GrowRegion()), in one pass: they grow alike until each stops.
template <int N>
void GrowRegions(const SummedAreaTable& weights, const std::array<int, 3>& histogramDims,
  const std::array<int, 3>& texel, const AdaptiveRegionSettings& settings, int first,
  Region* regions)
{
  Region r;
  for (int a = 0; a < 3; ++a)
  {
    r.Lo[a] = std::min(texel[a] * settings.Refinement[a], histogramDims[a] - 1);
    r.Hi[a] = std::min(r.Lo[a] + settings.Refinement[a], histogramDims[a]);
  }
  // Only axes with more than one cell grow (a 2D histogram stays 2D).
  const bool grows[3] = { histogramDims[0] > 1, histogramDims[1] > 1, histogramDims[2] > 1 };
  const int maxGrowth = *std::max_element(histogramDims.begin(), histogramDims.end());
  bool done[N];
  std::fill_n(done, N, false);
  int left = N;
  for (int growth = 0;; ++growth)
  {
    double weight[N];
    weights.RegionSum(r.Lo, r.Hi, weight, first, N);
    bool covers = true;
    for (int a = 0; a < 3; ++a)
    {
      covers = covers && r.Lo[a] == 0 && r.Hi[a] == histogramDims[a];
    }
    for (int k = 0; k < N; ++k)
    {
      if (!done[k] && (weight[k] >= settings.Threshold || covers || growth >= maxGrowth))
      {
        regions[k] = r;
        regions[k].Growth = growth;
        done[k] = true;
        --left;
      }
    }
    if (left == 0)
    {
      return;
    }
    // Centred growth where there is room on both sides; clipped growth on
    // every axis only where there is none.
    bool centred[3];
    bool anyCentred = false;
    for (int a = 0; a < 3; ++a)
    {
      centred[a] = grows[a] && r.Lo[a] > 0 && r.Hi[a] < histogramDims[a];
      anyCentred = anyCentred || centred[a];
    }
    for (int a = 0; a < 3; ++a)
    {
      if (anyCentred ? centred[a] : grows[a])
      {
        r.Lo[a] = std::max(r.Lo[a] - 1, 0);
        r.Hi[a] = std::min(r.Hi[a] + 1, histogramDims[a]);
      }
    }
  }
}
}

Region GrowRegion(const SummedAreaTable& weights, const std::array<int, 3>& histogramDims,
  const std::array<int, 3>& texel, const AdaptiveRegionSettings& settings)
{
  Region r;
  GrowRegions<1>(weights, histogramDims, texel, settings, settings.WeightChannel, &r);
  return r;
}

std::array<Region, 2> GrowRegionPair(const SummedAreaTable& weights,
  const std::array<int, 3>& histogramDims, const std::array<int, 3>& texel,
  const AdaptiveRegionSettings& settings)
{
  std::array<Region, 2> r;
  GrowRegions<2>(weights, histogramDims, texel, settings, settings.WeightChannel, r.data());
  return r;
}

RegionEstimate EstimateTexel(const SummedAreaTable& sat, const std::array<int, 3>& histogramDims,
  const std::array<int, 3>& texel, const AdaptiveRegionSettings& settings, double* perCell)
{
  constexpr int MaxChannels = 16;
  double sum[MaxChannels];
  const Region r = GrowRegion(sat, histogramDims, texel, settings);
  sat.RegionSum(r.Lo, r.Hi, sum);
  RegionEstimate estimate;
  estimate.Growth = r.Growth;
  estimate.Cells = r.Cells();
  const int nc = std::min(sat.GetNumberOfChannels(), MaxChannels);
  for (int c = 0; c < nc; ++c)
  {
    perCell[c] = sum[c] / static_cast<double>(estimate.Cells);
  }
  return estimate;
}

} // namespace brume
