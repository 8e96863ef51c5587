// SPDX-License-Identifier: BSD-3-Clause
// The texture whose trilinear interpolation meets each texel's estimate at
// its region's centroid.
#include "brume/CentroidMatching.h"
#include "brume/Random.h"
#include "brume/Vec3.h"

#include "TestScenes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

using namespace brume;
using brume::testing::Scrambled;

namespace
{
std::size_t Texels(const std::array<int, 3>& n)
{
  return static_cast<std::size_t>(n[0]) * n[1] * n[2];
}

// Every texel's centre, and offsets uniform in [-spread, spread] on each
// axis for the texels `inside` says.
template <typename Inside>
std::vector<float> Centroids(const std::array<int, 3>& n, float spread, Inside inside)
{
  Random rng(7, 0);
  std::vector<float> c(3 * Texels(n));
  for (std::size_t t = 0; t < Texels(n); ++t)
  {
    const int ijk[3] = { static_cast<int>(t % n[0]), static_cast<int>((t / n[0]) % n[1]),
      static_cast<int>(t / (static_cast<std::size_t>(n[0]) * n[1])) };
    for (int a = 0; a < 3; ++a)
    {
      const float offset = (2.f * rng.NextFloat() - 1.f) * spread;
      c[3 * t + a] = static_cast<float>(ijk[a]) + (inside(ijk) ? offset : 0.f);
    }
  }
  return c;
}

// A field that varies linearly, positive over the grids used here (at most 3.5).
double Linear(double x, double y, double z)
{
  return 2.0 + 0.11 * x - 0.07 * y + 0.05 * z;
}

// One that crosses 0 over them, within [-0.5, 0.5].
double Signed(double x, double y, double z)
{
  return 0.3 - 0.06 * x + 0.02 * y - 0.01 * z;
}
}

TEST(CentroidMatching, CentredEstimatesStayAsTheyAre)
{
  const std::array<int, 3> n{ 6, 5, 4 };
  const auto centroids = Centroids(n, 0.f, [](const int*) { return false; });
  const CentroidMatching matching(n, centroids, SerialFor());
  EXPECT_EQ(matching.NumberOfMovingTexels(), 0u);
  Random rng(3, 0);
  std::vector<float> values(3 * Texels(n));
  for (float& v : values)
  {
    v = rng.NextFloat();
  }
  const std::vector<float> estimates = values;
  EXPECT_EQ(matching.Apply(values, 3, SerialFor()), 0.0);
  EXPECT_EQ(values, estimates);
}

TEST(CentroidMatching, LinearFieldAtItsCentroidsIsRecoveredAtTheCentres)
{
  // Estimates exact at centroids drawn toward the grid's middle, as a
  // cloud's edge draws them inward: by 0.45 texel on each axis next to the
  // faces, less toward the middle (the faces' own texels centred, where
  // interpolation clamps). Taken as belonging to the centres they are off
  // by up to 0.45 texel of the gradient; the texture must be exact at the
  // centres, to the iterations' convergence.
  const std::array<int, 3> n{ 12, 10, 9 };
  std::vector<float> centroids(3 * Texels(n));
  for (std::size_t t = 0; t < Texels(n); ++t)
  {
    const int ijk[3] = { static_cast<int>(t % n[0]), static_cast<int>((t / n[0]) % n[1]),
      static_cast<int>(t / (n[0] * n[1])) };
    bool face = false;
    for (int a = 0; a < 3; ++a)
    {
      face = face || ijk[a] == 0 || ijk[a] == n[a] - 1;
    }
    for (int a = 0; a < 3; ++a)
    {
      const float middle = 0.5f * static_cast<float>(n[a] - 1);
      const float towards = (middle - static_cast<float>(ijk[a])) / (middle - 1.f);
      centroids[3 * t + a] = static_cast<float>(ijk[a]) + (face ? 0.f : 0.45f * towards);
    }
  }
  const CentroidMatching matching(n, centroids, SerialFor());
  EXPECT_GT(matching.NumberOfMovingTexels(), Texels(n) / 2);
  // Two channels: a source (positive) and a signed quantity crossing 0
  // (a spherical-harmonics coefficient), errors relative to the largest
  // magnitude of each.
  std::vector<float> values(2 * Texels(n));
  for (std::size_t t = 0; t < Texels(n); ++t)
  {
    const float* c = &centroids[3 * t];
    values[2 * t] = static_cast<float>(Linear(c[0], c[1], c[2]));
    values[2 * t + 1] = static_cast<float>(Signed(c[0], c[1], c[2]));
  }
  double before = 0.0, after = 0.0;
  auto worst = [&](double& error)
  {
    for (std::size_t t = 0; t < Texels(n); ++t)
    {
      const double x = static_cast<double>(t % n[0]), y = static_cast<double>((t / n[0]) % n[1]),
                   z = static_cast<double>(t / (n[0] * n[1]));
      error = std::max(error, std::abs(values[2 * t] - Linear(x, y, z)) / 3.5);
      error = std::max(error, std::abs(values[2 * t + 1] - Signed(x, y, z)) / 0.5);
    }
  };
  worst(before);
  const double residual = matching.Apply(values, 2, SerialFor());
  worst(after);
  std::printf("before %g after %g residual %g\n", before, after, residual);
  EXPECT_GT(before, 0.02);
  EXPECT_LT(after, 1e-4);
  EXPECT_LT(residual, 1e-5);
}

TEST(CentroidMatching, NoNewExtremes)
{
  // Noisy estimates at scattered centroids, zeros among them: every value
  // stays in [0, the largest estimate of its 27 texels].
  const std::array<int, 3> n{ 9, 8, 7 };
  const auto centroids = Centroids(n, 0.49f, [](const int*) { return true; });
  const CentroidMatching matching(n, centroids, SerialFor());
  Random rng(5, 0);
  std::vector<float> values(3 * Texels(n));
  for (float& v : values)
  {
    v = rng.NextFloat() < 0.2f ? 0.f : rng.NextFloat();
  }
  const std::vector<float> estimates = values;
  matching.Apply(values, 3, SerialFor());
  for (std::size_t t = 0; t < Texels(n); ++t)
  {
    const int x = static_cast<int>(t % n[0]), y = static_cast<int>((t / n[0]) % n[1]),
              z = static_cast<int>(t / (n[0] * n[1]));
    for (int c = 0; c < 3; ++c)
    {
      float bound = 0.f;
      for (int k = std::max(z - 1, 0); k <= std::min(z + 1, n[2] - 1); ++k)
        for (int j = std::max(y - 1, 0); j <= std::min(y + 1, n[1] - 1); ++j)
          for (int i = std::max(x - 1, 0); i <= std::min(x + 1, n[0] - 1); ++i)
          {
            bound = std::max(bound, estimates[3 * ((k * n[1] + j) * n[0] + i) + c]);
          }
      ASSERT_GE(values[3 * t + c], 0.f);
      ASSERT_LE(values[3 * t + c], bound);
    }
  }
}

TEST(CentroidMatching, TheSameWhateverTheSplit)
{
  // Enough moving texels for the iterations to run in parallel.
  const std::array<int, 3> n{ 20, 18, 16 };
  const auto centroids = Centroids(n, 0.4f, [](const int*) { return true; });
  const CentroidMatching serial(n, centroids, SerialFor());
  const CentroidMatching scrambled(n, centroids, Scrambled);
  ASSERT_GE(serial.NumberOfMovingTexels(), CentroidMatching::ParallelColumns);
  Random rng(9, 0);
  std::vector<float> a(3 * Texels(n));
  for (float& v : a)
  {
    v = 0.5f + rng.NextFloat();
  }
  std::vector<float> b = a;
  EXPECT_EQ(serial.Apply(a, 3, SerialFor()), scrambled.Apply(b, 3, Scrambled));
  EXPECT_EQ(a, b);
}

TEST(CentroidMatching, CentroidsOutsideTheirCellSetNoEquation)
{
  // Texel 0 lies beside a thin structure at texel 2 and its region grew
  // into it: its centroid is two texels away, its estimate (3) a mean over
  // a far wider region than texel 2's own (1). It must not pull texel 2,
  // nor be pulled itself; a centroid just inside its cell still moves the
  // texels it interpolates.
  const std::array<int, 3> n{ 5, 1, 1 };
  std::vector<float> centroids = Centroids(n, 0.f, [](const int*) { return false; });
  centroids[0] = 2.f;
  std::vector<float> values{ 3.f, 1.f, 1.f, 3.f, 3.f };
  const std::vector<float> estimates = values;
  const CentroidMatching far(n, centroids, SerialFor());
  EXPECT_EQ(far.NumberOfMovingTexels(), 0u);
  EXPECT_EQ(far.Apply(values, 1, SerialFor()), 0.0);
  EXPECT_EQ(values, estimates);

  centroids[0] = 0.49f;
  const CentroidMatching inside(n, centroids, SerialFor());
  EXPECT_EQ(inside.NumberOfMovingTexels(), 2u);
}

TEST(CentroidMatching, CentroidsBeyondTheGridAreClamped)
{
  // A region grown past the grid's faces, or a centroid that is not a
  // number: interpolation clamps as the renderer's does, nothing breaks.
  const std::array<int, 3> n{ 3, 3, 3 };
  std::vector<float> centroids = Centroids(n, 0.f, [](const int*) { return false; });
  centroids[0] = -7.f;
  centroids[4] = 12.f;
  centroids[8] = std::nanf("");
  const CentroidMatching matching(n, centroids, SerialFor());
  std::vector<float> values(Texels(n), 1.f);
  matching.Apply(values, 1, SerialFor());
  for (const float v : values)
  {
    EXPECT_FLOAT_EQ(v, 1.f);
  }
}

TEST(CentroidMatching, SizesThatDoNotMatchAreRefused)
{
  const std::array<int, 3> n{ 2, 2, 2 };
  EXPECT_THROW(CentroidMatching(n, std::vector<float>(5), SerialFor()), std::invalid_argument);
  const CentroidMatching matching(
    n, Centroids(n, 0.f, [](const int*) { return false; }), SerialFor());
  std::vector<float> values(7);
  EXPECT_THROW(matching.Apply(values, 1, SerialFor()), std::invalid_argument);
  values.resize(8 * 5);
  EXPECT_THROW(matching.Apply(values, 4, SerialFor()), std::invalid_argument);
  EXPECT_THROW(matching.Apply(values, 0, SerialFor()), std::invalid_argument);
}
