// SPDX-License-Identifier: BSD-3-Clause
// Adaptive nearest-neighbour density estimation (paper, section 3, Figure 1).
#include "brume/DensityEstimation.h"
#include "brume/Random.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>

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

TEST(DensityEstimation, RegionsGrownOnTheOtherHalfAreUnbiased)
{
  // Uniform hits, a texel holding about the threshold's number of them (the
  // resolution brume::ChooseResolution picks): a region grown on the hits it
  // averages stops where they happen to be dense and reads them too bright
  // (about 1/k for k hits); one grown on an independent half of the hits
  // and averaging the other half does not. Each trial is an independent
  // set of hits, so the trials' spread gives the standard error of their
  // mean. Each half is a Poisson process of its own (its count too), as the
  // hits of independent particles on an object are.
  const int texels = 16, refinement = 2, cells = texels * refinement;
  const double threshold = 16.0;
  const double hits = threshold * texels * texels; // expected, both halves
  const double expected = hits / (cells * cells);
  AdaptiveRegionSettings own;
  own.Refinement = { refinement, refinement, 1 };
  own.Threshold = threshold;
  own.WeightChannel = 2; // both halves
  AdaptiveRegionSettings split = own;
  split.Threshold = 0.5 * threshold;
  split.WeightChannel = 0; // half 0, then half 1
  const int trials = 1000;
  double sumOwn = 0.0, sumOwn2 = 0.0, sumSplit = 0.0, sumSplit2 = 0.0;
  for (int trial = 0; trial < trials; ++trial)
  {
    // Channels: half 0, half 1, both.
    Histogram h({ cells, cells, 1 }, 3);
    Random rng(77, static_cast<std::uint64_t>(trial));
    for (int half = 0; half < 2; ++half)
    {
      // Arrivals of a unit-rate process up to hits / 2.
      for (double time = -std::log(1.0 - rng.NextDouble()); time < 0.5 * hits;
           time -= std::log(1.0 - rng.NextDouble()))
      {
        const auto c = h.CellOf(rng.NextDouble(), rng.NextDouble(), 0.0);
        double one[3] = { 0.0, 0.0, 1.0 };
        one[half] = 1.0;
        h.Add(h.Index(c[0], c[1], 0), one);
      }
    }
    const SummedAreaTable sat(h);
    double meanOwn = 0.0, meanSplit = 0.0;
    for (int j = 0; j < texels; ++j)
    {
      for (int i = 0; i < texels; ++i)
      {
        const Region r = GrowRegion(sat, h.GetDimensions(), { i, j, 0 }, own);
        double sum[3];
        sat.RegionSum(r.Lo, r.Hi, sum);
        meanOwn += sum[2] / static_cast<double>(r.Cells());
        const std::array<Region, 2> pair = GrowRegionPair(sat, h.GetDimensions(), { i, j, 0 }, split);
        for (int half = 0; half < 2; ++half)
        {
          sat.RegionSum(pair[half].Lo, pair[half].Hi, sum);
          meanSplit += sum[1 - half] / static_cast<double>(pair[half].Cells());
        }
      }
    }
    meanOwn /= texels * texels * expected;
    meanSplit /= texels * texels * expected;
    sumOwn += meanOwn;
    sumOwn2 += meanOwn * meanOwn;
    sumSplit += meanSplit;
    sumSplit2 += meanSplit * meanSplit;
  }
  const double own1 = sumOwn / trials, split1 = sumSplit / trials;
  const double ownError = std::sqrt((sumOwn2 / trials - own1 * own1) / (trials - 1));
  const double splitError = std::sqrt((sumSplit2 / trials - split1 * split1) / (trials - 1));
  std::printf("mean over expected: own regions %.4f +- %.4f, split %.4f +- %.4f\n", own1,
    ownError, split1, splitError);
  EXPECT_GT(own1 - 1.0, 5.0 * ownError); // the bias the split removes
  EXPECT_NEAR(split1, 1.0, 4.0 * splitError);
}
