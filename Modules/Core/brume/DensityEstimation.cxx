// SPDX-License-Identifier: BSD-3-Clause
#include "brume/DensityEstimation.h"

#include <algorithm>

namespace brume
{

RegionEstimate EstimateTexel(const SummedAreaTable& sat, const std::array<int, 3>& histogramDims,
  const std::array<int, 3>& texel, const AdaptiveRegionSettings& settings, double* perCell)
{
  constexpr int MaxChannels = 16;
  double sum[MaxChannels];
  const int nc = std::min(sat.GetNumberOfChannels(), MaxChannels);
  std::array<int, 3> lo{}, hi{};
  for (int a = 0; a < 3; ++a)
  {
    lo[a] = texel[a] * settings.Refinement[a];
    hi[a] = std::min(lo[a] + settings.Refinement[a], histogramDims[a]);
  }
  // Only axes with more than one cell grow (a 2D histogram stays 2D).
  const bool grows[3] = { histogramDims[0] > 1, histogramDims[1] > 1, histogramDims[2] > 1 };
  const int maxGrowth = *std::max_element(histogramDims.begin(), histogramDims.end());
  RegionEstimate estimate;
  for (int growth = 0;; ++growth)
  {
    sat.RegionSum(lo, hi, sum);
    bool covers = true;
    for (int a = 0; a < 3; ++a)
    {
      covers = covers && lo[a] == 0 && hi[a] == histogramDims[a];
    }
    if (sum[settings.WeightChannel] >= settings.Threshold || covers || growth >= maxGrowth)
    {
      estimate.Growth = growth;
      break;
    }
    for (int a = 0; a < 3; ++a)
    {
      if (grows[a])
      {
        lo[a] = std::max(lo[a] - 1, 0);
        hi[a] = std::min(hi[a] + 1, histogramDims[a]);
      }
    }
  }
  estimate.Cells = 1;
  for (int a = 0; a < 3; ++a)
  {
    estimate.Cells *= hi[a] - lo[a];
  }
  for (int c = 0; c < nc; ++c)
  {
    perCell[c] = sum[c] / static_cast<double>(estimate.Cells);
  }
  return estimate;
}

} // namespace brume
