// SPDX-License-Identifier: BSD-3-Clause
#include "brume/DensityEstimation.h"

#include <algorithm>

namespace brume
{

Region GrowRegion(const SummedAreaTable& weights, const std::array<int, 3>& histogramDims,
  const std::array<int, 3>& texel, const AdaptiveRegionSettings& settings)
{
  constexpr int MaxChannels = 16;
  double sum[MaxChannels];
  Region r;
  for (int a = 0; a < 3; ++a)
  {
    r.Lo[a] = std::min(texel[a] * settings.Refinement[a], histogramDims[a] - 1);
    r.Hi[a] = std::min(r.Lo[a] + settings.Refinement[a], histogramDims[a]);
  }
  // Only axes with more than one cell grow (a 2D histogram stays 2D).
  const bool grows[3] = { histogramDims[0] > 1, histogramDims[1] > 1, histogramDims[2] > 1 };
  const int maxGrowth = *std::max_element(histogramDims.begin(), histogramDims.end());
  for (int growth = 0;; ++growth)
  {
    weights.RegionSum(r.Lo, r.Hi, sum);
    bool covers = true;
    for (int a = 0; a < 3; ++a)
    {
      covers = covers && r.Lo[a] == 0 && r.Hi[a] == histogramDims[a];
    }
    if (sum[settings.WeightChannel] >= settings.Threshold || covers || growth >= maxGrowth)
    {
      r.Growth = growth;
      return r;
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
