// SPDX-License-Identifier: BSD-3-Clause
// Adaptive nearest-neighbour density estimation over a summed-area table
// (paper, section 3 and Figure 1).
//
// A texture texel covers a block of Refinement cells of the (finer)
// histogram. Its region starts as that block and grows by one cell on every
// side (clipped to the histogram) until the accumulated weight reaches the
// threshold; the estimate is the region's sum divided by the region's own
// number of cells, so the caller divides by one cell's area or volume.
#ifndef brume_DensityEstimation_h
#define brume_DensityEstimation_h

#include "brume/SummedAreaTable.h"

#include <array>

namespace brume
{

struct AdaptiveRegionSettings
{
  /// Histogram cells per texel along each axis (1 along unused axes).
  std::array<int, 3> Refinement{ 1, 1, 1 };
  /// Weight the region must accumulate before it stops growing.
  double Threshold = 0.0;
  /// SAT channel holding the weight that drives the growth.
  int WeightChannel = 0;
};

struct RegionEstimate
{
  /// Number of histogram cells in the final region.
  long long Cells = 0;
  /// Cells the region grew by on each side.
  int Growth = 0;
};

/// A region of histogram cells [Lo, Hi) on every axis.
struct Region
{
  std::array<int, 3> Lo{ 0, 0, 0 };
  std::array<int, 3> Hi{ 0, 0, 0 };
  int Growth = 0;
  long long Cells() const
  {
    return static_cast<long long>(Hi[0] - Lo[0]) * (Hi[1] - Lo[1]) * (Hi[2] - Lo[2]);
  }
};

/**
 * The adaptive region of texel `texel`: its own cells, grown by one cell on
 * every side (clipped) until channel `settings.WeightChannel` of `weights`
 * reaches the threshold or the region covers the histogram.
 */
Region GrowRegion(const SummedAreaTable& weights, const std::array<int, 3>& histogramDims,
  const std::array<int, 3>& texel, const AdaptiveRegionSettings& settings);

/**
 * Estimates texel `texel` from `sat` (built on a histogram of dimensions
 * `histogramDims`). Writes, for every channel, the region's sum divided by
 * its number of cells into `perCell`.
 */
RegionEstimate EstimateTexel(const SummedAreaTable& sat, const std::array<int, 3>& histogramDims,
  const std::array<int, 3>& texel, const AdaptiveRegionSettings& settings, double* perCell);

} // namespace brume

#endif
