// SPDX-License-Identifier: BSD-3-Clause
#include "brume/Histogram.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace brume;

TEST(Histogram, BinsByNormalizedCoordinates)
{
  const Histogram h({ 4, 2, 8 }, 1);
  EXPECT_EQ(h.CellOf(0.0, 0.0, 0.0), (std::array<int, 3>{ 0, 0, 0 }));
  EXPECT_EQ(h.CellOf(0.2499, 0.4999, 0.1249), (std::array<int, 3>{ 0, 0, 0 }));
  EXPECT_EQ(h.CellOf(0.25, 0.5, 0.125), (std::array<int, 3>{ 1, 1, 1 }));
  // The upper border belongs to the last cell, outside points are clamped.
  EXPECT_EQ(h.CellOf(1.0, 1.0, 1.0), (std::array<int, 3>{ 3, 1, 7 }));
  EXPECT_EQ(h.CellOf(-0.5, 7.0, 0.99), (std::array<int, 3>{ 0, 1, 7 }));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(h.CellOf(nan, 0.3, 0.3), (std::array<int, 3>{ 0, 0, 2 }));
}

TEST(Histogram, AccumulatesEveryChannel)
{
  Histogram h({ 3, 3, 1 }, 2);
  const double a[2] = { 1.0, 0.5 };
  h.Add(h.Index(2, 1, 0), a);
  h.Add(h.Index(2, 1, 0), a);
  EXPECT_EQ(h.Get(h.Index(2, 1, 0))[0], 2.0);
  EXPECT_EQ(h.Get(h.Index(2, 1, 0))[1], 1.0);
  EXPECT_EQ(h.Get(h.Index(1, 2, 0))[0], 0.0);
  EXPECT_EQ(h.Index(2, 1, 0), 5u);
}
