// SPDX-License-Identifier: BSD-3-Clause
// Adaptive nearest-neighbour density estimation over a summed-area table
// (paper, section 3 and Figure 1).
//
// A texture texel covers a block of Refinement cells of the (finer)
// histogram. Its region starts as that block and grows by one cell on both
// sides of every axis until the accumulated weight reaches the threshold;
// the estimate is the region's sum divided by the region's own number of
// cells, so the caller divides by one cell's area or volume.
//
// The region stays centred on its texel: an axis whose region has reached
// the histogram's edge on one side stops growing, and the others go on.
// A region clipped on one side only would average the texel with cells
// beyond it on the other, so wherever the radiance falls or rises toward
// an object's edge (a wall beside an open side, a medium's face) the edge
// texels would take the inner cells' value. Centred, the region's mean is
// the texel's value to first order. Only when no axis can grow on both
// sides before the threshold is reached (a corner) does it grow clipped.
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
 * both sides of every axis that has room on both, until channel
 * `settings.WeightChannel` of `weights` reaches the threshold or the region
 * covers the histogram. When no axis has room on both sides, every axis
 * grows clipped to the histogram.
 */
Region GrowRegion(const SummedAreaTable& weights, const std::array<int, 3>& histogramDims,
  const std::array<int, 3>& texel, const AdaptiveRegionSettings& settings);

/**
 * GrowRegion() for channels `settings.WeightChannel` and the next one at
 * once (the two halves of brume::HitBinning's sums): the regions grow alike
 * until each has reached the threshold, reading the table once a step.
 */
std::array<Region, 2> GrowRegionPair(const SummedAreaTable& weights,
  const std::array<int, 3>& histogramDims, const std::array<int, 3>& texel,
  const AdaptiveRegionSettings& settings);

/**
 * Estimates texel `texel` from `sat` (built on a histogram of dimensions
 * `histogramDims`). Writes, for every channel, the region's sum divided by
 * its number of cells into `perCell`.
 */
RegionEstimate EstimateTexel(const SummedAreaTable& sat, const std::array<int, 3>& histogramDims,
  const std::array<int, 3>& texel, const AdaptiveRegionSettings& settings, double* perCell);

} // namespace brume

#endif
