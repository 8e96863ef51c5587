// SPDX-License-Identifier: BSD-3-Clause
// Adaptive nearest-neighbour density estimation (paper, section 3, Figure 1).
#include "brume/DensityEstimation.h"
#include "brume/Random.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace brume;

TEST(DensityEstimation, UniformParticlesGiveAFlatTexture)
{
  // 64x64 histogram, 16x16 texture, unit-weight particles spread uniformly.
  Histogram h({ 64, 64, 1 }, 1);
  Random rng(1, 2);
  const int n = 400000;
  const double one = 1.0;
  for (int i = 0; i < n; ++i)
  {
    const auto c = h.CellOf(rng.NextDouble(), rng.NextDouble(), 0.0);
    h.Add(h.Index(c[0], c[1], 0), &one);
  }
  const SummedAreaTable sat(h);
  AdaptiveRegionSettings settings;
  settings.Refinement = { 4, 4, 1 };
  settings.Threshold = 1000.0;
  const double expectedPerCell = static_cast<double>(n) / (64 * 64);
  double worstZ = 0.0;
  for (int j = 0; j < 16; ++j)
  {
    for (int i = 0; i < 16; ++i)
    {
      double perCell = 0.0;
      const RegionEstimate r =
        EstimateTexel(sat, h.GetDimensions(), { i, j, 0 }, settings, &perCell);
      // Poisson counts: the region's total has standard deviation sqrt(total).
      const double total = perCell * r.Cells;
      const double z = (total - expectedPerCell * r.Cells) / std::sqrt(expectedPerCell * r.Cells);
      worstZ = std::max(worstZ, std::abs(z));
      EXPECT_GE(total, settings.Threshold);
    }
  }
  // 256 texels: |z| beyond 4.5 has probability below 0.2 % in all.
  EXPECT_LT(worstZ, 4.5);
}

TEST(DensityEstimation, RegionGrowsUntilTheThreshold)
{
  // A single cell holds all the weight: texels far from it grow until they reach it.
  Histogram h({ 32, 32, 1 }, 2);
  const double v[2] = { 8.0, 1.0 };
  h.Add(h.Index(20, 10, 0), v);
  const SummedAreaTable sat(h);
  AdaptiveRegionSettings settings;
  settings.Refinement = { 2, 2, 1 };
  settings.Threshold = 0.5;
  settings.WeightChannel = 1;
  double perCell[2];
  // Texel (10, 5) covers cells [20, 22) x [10, 12): no growth.
  RegionEstimate r = EstimateTexel(sat, h.GetDimensions(), { 10, 5, 0 }, settings, perCell);
  EXPECT_EQ(r.Growth, 0);
  EXPECT_EQ(r.Cells, 4);
  EXPECT_DOUBLE_EQ(perCell[0], 2.0);
  // Texel (2, 5) covers [4, 6) x [10, 12). Centred, it grows on both axes
  // until x reaches 0 (growth 4: [0, 10) x [6, 16)), then on y alone until y
  // reaches 0 too (growth 10: [0, 10) x [0, 22)); with no axis left that can
  // grow on both sides it grows clipped, until x reaches the weight at 20
  // (growth 21: [0, 21) x [0, 32)).
  r = EstimateTexel(sat, h.GetDimensions(), { 2, 5, 0 }, settings, perCell);
  EXPECT_EQ(r.Growth, 21);
  EXPECT_EQ(r.Cells, 21 * 32);
  EXPECT_DOUBLE_EQ(perCell[0], 8.0 / (21 * 32));
}

TEST(DensityEstimation, EdgeTexelsStayCentredWhereTheRadianceFalls)
{
  // Weight rising linearly away from the left edge, 1 + i in column i (as
  // the light on a wall rises away from an open side). Texel 0 covers
  // columns [0, 2), mean 1.5. Its region can no longer grow leftward, so it
  // grows along y only and keeps that mean; grown clipped to the right as
  // well, it would take the brighter columns beyond it (2.5 at growth 2).
  Histogram h({ 32, 32, 1 }, 1);
  for (int j = 0; j < 32; ++j)
  {
    for (int i = 0; i < 32; ++i)
    {
      const double v = 1.0 + i;
      h.Add(h.Index(i, j, 0), &v);
    }
  }
  const SummedAreaTable sat(h);
  AdaptiveRegionSettings settings;
  settings.Refinement = { 2, 2, 1 };
  settings.Threshold = 30.0;
  double perCell = 0.0;
  const RegionEstimate edge =
    EstimateTexel(sat, h.GetDimensions(), { 0, 8, 0 }, settings, &perCell);
  EXPECT_EQ(edge.Growth, 4); // [0, 2) x [12, 22): 20 cells of 1.5
  EXPECT_EQ(edge.Cells, 2 * 10);
  EXPECT_DOUBLE_EQ(perCell, 1.5);
  // An interior texel grows on both axes and keeps its own mean too.
  const RegionEstimate inner =
    EstimateTexel(sat, h.GetDimensions(), { 2, 8, 0 }, settings, &perCell);
  EXPECT_EQ(inner.Growth, 1); // [3, 7) x [15, 19)
  EXPECT_DOUBLE_EQ(perCell, 5.5);
  // A corner texel has no axis with room on both sides: it grows clipped.
  const RegionEstimate corner =
    EstimateTexel(sat, h.GetDimensions(), { 0, 0, 0 }, settings, &perCell);
  EXPECT_EQ(corner.Growth, 2); // [0, 4) x [0, 4)
  EXPECT_DOUBLE_EQ(perCell, 2.5);
}

TEST(DensityEstimation, ThreeDimensionalRegions)
{
  Histogram h({ 8, 8, 8 }, 1);
  const double one = 1.0;
  for (std::size_t c = 0; c < h.GetNumberOfCells(); ++c)
  {
    h.Add(c, &one);
  }
  const SummedAreaTable sat(h);
  AdaptiveRegionSettings settings;
  settings.Refinement = { 2, 2, 2 };
  settings.Threshold = 64.0;
  double perCell = 0.0;
  // 8 cells in the block, grows once to 4x4x4 = 64 cells (interior texel).
  const RegionEstimate r = EstimateTexel(sat, h.GetDimensions(), { 1, 1, 1 }, settings, &perCell);
  EXPECT_EQ(r.Growth, 1);
  EXPECT_EQ(r.Cells, 64);
  EXPECT_DOUBLE_EQ(perCell, 1.0);
}
