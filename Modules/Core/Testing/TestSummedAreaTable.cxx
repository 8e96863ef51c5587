// SPDX-License-Identifier: BSD-3-Clause
// Summed-area table region sums against brute force (paper, eq. 2).
#include "brume/Random.h"
#include "brume/SummedAreaTable.h"

#include <gtest/gtest.h>

using namespace brume;

namespace
{
void CheckRegions(const std::array<int, 3>& dims, int channels, std::uint64_t seed)
{
  Histogram h(dims, channels);
  Random rng(seed, 0);
  for (std::size_t cell = 0; cell < h.GetNumberOfCells(); ++cell)
  {
    std::vector<double> v(channels);
    for (auto& x : v)
    {
      // Integer-valued counts: every sum is exact in double.
      x = static_cast<double>(rng.NextUInt() % 1000);
    }
    h.Add(cell, v.data());
  }
  const SummedAreaTable sat(h);
  for (int trial = 0; trial < 500; ++trial)
  {
    std::array<int, 3> lo{}, hi{};
    for (int a = 0; a < 3; ++a)
    {
      const int x = static_cast<int>(rng.NextUInt() % (dims[a] + 1));
      const int y = static_cast<int>(rng.NextUInt() % (dims[a] + 1));
      lo[a] = std::min(x, y);
      hi[a] = std::max(x, y);
    }
    std::vector<double> expected(channels, 0.0), got(channels);
    for (int k = lo[2]; k < hi[2]; ++k)
      for (int j = lo[1]; j < hi[1]; ++j)
        for (int i = lo[0]; i < hi[0]; ++i)
          for (int c = 0; c < channels; ++c)
            expected[c] += h.Get(h.Index(i, j, k))[c];
    sat.RegionSum(lo, hi, got.data());
    for (int c = 0; c < channels; ++c)
    {
      ASSERT_EQ(got[c], expected[c]) << "region [" << lo[0] << "," << hi[0] << ")x[" << lo[1] << ","
                                     << hi[1] << ")x[" << lo[2] << "," << hi[2] << ")";
    }
  }
}
}

TEST(SummedAreaTable, RegionSums2D)
{
  CheckRegions({ 37, 23, 1 }, 3, 1);
}

TEST(SummedAreaTable, RegionSums3D)
{
  CheckRegions({ 17, 9, 13 }, 4, 2);
}

TEST(SummedAreaTable, WholeAndEmptyRegions)
{
  Histogram h({ 4, 4, 4 }, 1);
  const double one = 1.0;
  for (std::size_t c = 0; c < h.GetNumberOfCells(); ++c)
  {
    h.Add(c, &one);
  }
  const SummedAreaTable sat(h);
  double s = -1.0;
  sat.RegionSum({ 0, 0, 0 }, { 4, 4, 4 }, &s);
  EXPECT_EQ(s, 64.0);
  sat.RegionSum({ 2, 2, 2 }, { 2, 4, 4 }, &s);
  EXPECT_EQ(s, 0.0);
}
