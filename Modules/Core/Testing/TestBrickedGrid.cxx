// SPDX-License-Identifier: BSD-3-Clause
// The sparse grid of a medium's native density: the dense grid's values and
// interpolation, memory only where the values vary.
#include "brume/BrickedGrid.h"
#include "brume/Random.h"
#include "brume/Vec3.h"

#include "TestScenes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>

using namespace brume;
using brume::testing::Scrambled;

namespace
{
const auto Never = [](const std::array<int, 3>&, const std::array<int, 3>&) { return false; };

// Trilinear between cell centres of a dense x-fastest grid, clamped at the
// faces: what a cell-data 3D texture with linear filtering gives.
float DenseTrilinear(
  const std::vector<float>& v, const std::array<int, 3>& n, const Box& box, const Vec3& p)
{
  const Vec3 q = (p - box.lower) / box.Extent();
  const CellCentreWeights x(q.x, n[0]), y(q.y, n[1]), z(q.z, n[2]);
  auto at = [&](int i, int j, int k)
  { return v[(static_cast<std::size_t>(k) * n[1] + j) * n[0] + i]; };
  auto row = [&](int j, int k) { return at(x.I0, j, k) * (1.f - x.W) + at(x.I1, j, k) * x.W; };
  const float c0 = row(y.I0, z.I0) * (1.f - y.W) + row(y.I1, z.I0) * y.W;
  const float c1 = row(y.I0, z.I1) * (1.f - y.W) + row(y.I1, z.I1) * y.W;
  return c0 * (1.f - z.W) + c1 * z.W;
}
}

TEST(BrickedGrid, InterpolatesAsTheDenseGrid)
{
  // Sizes that are not multiples of the stride, and an axis of one cell.
  for (const std::array<int, 3>& n : { std::array<int, 3>{ 23, 9, 15 },
         std::array<int, 3>{ 8, 1, 2 }, std::array<int, 3>{ 1, 1, 1 } })
  {
    const Box box{ Vec3(-1.f, 0.f, 2.f), Vec3(3.f, 0.5f, 2.5f) };
    std::vector<float> dense(static_cast<std::size_t>(n[0]) * n[1] * n[2]);
    for (std::size_t c = 0; c < dense.size(); ++c)
    {
      dense[c] = static_cast<float>((c * 2654435761u) % 1000u) / 100.f;
    }
    auto value = [&](int i, int j, int k)
    { return dense[(static_cast<std::size_t>(k) * n[1] + j) * n[0] + i]; };
    const BrickedGrid grid = BrickedGrid::Sample(n, box, value, Never, SerialFor());
    EXPECT_EQ(grid.GetDims(), n);
    for (int k = 0; k < n[2]; ++k)
      for (int j = 0; j < n[1]; ++j)
        for (int i = 0; i < n[0]; ++i)
        {
          ASSERT_EQ(grid.At(i, j, k), value(i, j, k)) << i << " " << j << " " << k;
        }
    // Points everywhere, beyond the outer centres and on brick boundaries.
    Random random(7, 0);
    for (int s = 0; s < 20000; ++s)
    {
      Vec3 p;
      for (int a = 0; a < 3; ++a)
      {
        const float u = s < 10000 ? random.NextFloat()
                                  : (static_cast<float>(s % (n[a] + 1)) + 0.5f * (s % 2)) / n[a];
        p[a] = box.lower[a] + box.Extent()[a] * u;
      }
      const float expected = DenseTrilinear(dense, n, box, p);
      ASSERT_NEAR(grid.Interpolate(p), expected, 2e-6f * (1.f + std::abs(expected)))
        << p.x << " " << p.y << " " << p.z;
    }
  }
}

TEST(BrickedGrid, StoresOnlyTheBricksWhereValuesVary)
{
  // A ball of 5 cells' radius in a 64^3 box whose left half holds 1: the
  // majorants say the right half is 0 away from the ball.
  const std::array<int, 3> n{ 64, 64, 64 };
  const Box box{ Vec3(0.f), Vec3(64.f) };
  auto value = [](int i, int j, int k)
  {
    const float dx = static_cast<float>(i) - 48.f, dy = static_cast<float>(j) - 32.f,
                dz = static_cast<float>(k) - 32.f;
    return i < 16 ? 1.f : (dx * dx + dy * dy + dz * dz < 25.f ? 2.f : 0.f);
  };
  std::atomic<int> evaluated{ 0 };
  auto counted = [&](int i, int j, int k)
  {
    ++evaluated;
    return value(i, j, k);
  };
  auto zeroOver = [](const std::array<int, 3>& lo, const std::array<int, 3>& hi)
  {
    // Bricks away from the slab and the ball's box.
    const bool slab = lo[0] < 16;
    const bool ball =
      hi[0] >= 43 && lo[0] <= 53 && hi[1] >= 27 && lo[1] <= 37 && hi[2] >= 27 && lo[2] <= 37;
    return !slab && !ball;
  };
  const BrickedGrid grid = BrickedGrid::Sample(n, box, counted, zeroOver, SerialFor());
  ASSERT_EQ(grid.GetBrickDims(), (std::array<int, 3>{ 9, 9, 9 }));
  // Stored: the bricks whose 8^3 samples are not all equal (the slab's
  // face, the ball's bricks); evaluated: only those zeroOver leaves.
  std::size_t varying = 0, candidates = 0;
  for (int bk = 0; bk < 9; ++bk)
    for (int bj = 0; bj < 9; ++bj)
      for (int bi = 0; bi < 9; ++bi)
      {
        const std::array<int, 3> lo{ 7 * bi, 7 * bj, 7 * bk };
        const std::array<int, 3> hi{ std::min(lo[0] + 7, 63), std::min(lo[1] + 7, 63),
          std::min(lo[2] + 7, 63) };
        candidates += zeroOver(lo, hi) ? 0 : 1;
        bool same = true;
        for (int k = lo[2]; k <= hi[2]; ++k)
          for (int j = lo[1]; j <= hi[1]; ++j)
            for (int i = lo[0]; i <= hi[0]; ++i)
              same = same && value(i, j, k) == value(lo[0], lo[1], lo[2]);
        varying += same ? 0 : 1;
      }
  EXPECT_EQ(grid.NumberOfStoredBricks(), varying);
  EXPECT_GE(varying, 81u + 8u); // the slab's face, at least 2^3 around the ball
  EXPECT_LT(varying, 729u / 5);
  EXPECT_EQ(grid.GetSamples().Size(), grid.NumberOfStoredBricks() * 512u);
  EXPECT_EQ(grid.GetMemorySize(), 729u * 8u + grid.GetSamples().Size() * 4u);
  EXPECT_EQ(static_cast<std::size_t>(evaluated.load()), candidates * 512u);
  EXPECT_LT(candidates, 729u / 2);
  for (int k = 0; k < n[2]; k += 3)
    for (int j = 0; j < n[1]; j += 5)
      for (int i = 0; i < n[0]; ++i)
      {
        ASSERT_EQ(grid.At(i, j, k), value(i, j, k)) << i << " " << j << " " << k;
      }
  // The cells the callback visits: every cell of every brick not 0.
  double sum = 0.0;
  std::size_t visited = 0;
  grid.ForEachNonZeroCell(
    [&](int i, int j, int k, float v)
    {
      EXPECT_EQ(v, value(i, j, k));
      sum += v;
      ++visited;
    });
  double expected = 0.0;
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i)
        expected += value(i, j, k);
  EXPECT_EQ(sum, expected);
  EXPECT_LT(visited, static_cast<std::size_t>(n[0]) * n[1] * n[2] / 2);
}

TEST(BrickedGrid, SameWhateverTheThreadsAndTheBox)
{
  // The same ball in a box twice as wide, moved by a whole number of
  // bricks: the same stored bricks and samples; any split of the work
  // gives the same bytes.
  auto ball = [](int ox)
  {
    return [ox](int i, int j, int k)
    {
      const float dx = static_cast<float>(i - ox) - 10.f, dy = static_cast<float>(j) - 10.f,
                  dz = static_cast<float>(k) - 10.f;
      return std::max(0.f, 36.f - (dx * dx + dy * dy + dz * dz));
    };
  };
  auto zeroFar = [](int ox)
  {
    return [ox](const std::array<int, 3>& lo, const std::array<int, 3>& hi) {
      return hi[0] < ox + 4 || lo[0] > ox + 16 || hi[1] < 4 || hi[2] < 4 || lo[1] > 16 ||
        lo[2] > 16;
    };
  };
  const BrickedGrid small = BrickedGrid::Sample(
    { 22, 22, 22 }, Box{ Vec3(0.f), Vec3(22.f) }, ball(0), zeroFar(0), SerialFor());
  const BrickedGrid wide = BrickedGrid::Sample({ 22 + 70, 22, 22 },
    Box{ Vec3(0.f), Vec3(92.f, 22.f, 22.f) }, ball(70), zeroFar(70), Scrambled);
  EXPECT_EQ(small.NumberOfStoredBricks(), wide.NumberOfStoredBricks());
  EXPECT_EQ(small.GetSamples(), wide.GetSamples());
  EXPECT_GT(wide.NumberOfBricks(), 3 * small.NumberOfBricks());
  const BrickedGrid serial = BrickedGrid::Sample({ 22 + 70, 22, 22 },
    Box{ Vec3(0.f), Vec3(92.f, 22.f, 22.f) }, ball(70), zeroFar(70), SerialFor());
  EXPECT_EQ(serial.GetSamples(), wide.GetSamples());
  EXPECT_EQ(serial.GetSlots(), wide.GetSlots());
  EXPECT_EQ(serial.GetConstants(), wide.GetConstants());
}

TEST(BrickedGrid, ConstantRunsAreWhatInterpolationGives)
{
  // The slab and the ball of StoresOnlyTheBricksWhereValuesVary, over a
  // box of another size: a ray's samples that ConstantSamples() counts in
  // a brick of one value interpolate to that value, every one of them.
  const std::array<int, 3> n{ 64, 64, 64 };
  const Box box{ Vec3(-1.f, 0.f, 2.f), Vec3(1.f, 3.f, 2.5f) };
  auto value = [](int i, int j, int k)
  {
    const float dx = static_cast<float>(i) - 48.f, dy = static_cast<float>(j) - 32.f,
                dz = static_cast<float>(k) - 32.f;
    return i < 16 ? 1.f : (dx * dx + dy * dy + dz * dz < 25.f ? 2.f : 0.f);
  };
  const BrickedGrid grid = BrickedGrid::Sample(n, box, value, Never, SerialFor());
  Random random(3, 0);
  long counted = 0, longest = 0;
  for (int ray = 0; ray < 2000; ++ray)
  {
    // From anywhere in the box (and a little beyond), steps of 0.1 to 3 cells.
    Vec3 p, d;
    for (int a = 0; a < 3; ++a)
    {
      p[a] = box.lower[a] + box.Extent()[a] * (1.2f * random.NextFloat() - 0.1f);
      d[a] = 2.f * random.NextFloat() - 1.f;
    }
    const Vec3 step = d * (box.Extent().x / 64.f) * (0.1f + 2.9f * random.NextFloat());
    float constant = -1.f;
    const int run = grid.ConstantSamples(p, step, 500, constant);
    ASSERT_LE(run, 500);
    for (int k = 0; k < run; ++k)
    {
      const Vec3 q = p + step * static_cast<float>(k);
      ASSERT_EQ(grid.Interpolate(q), constant) << ray << " sample " << k << " of " << run;
    }
    counted += run;
    longest = std::max<long>(longest, run);
  }
  EXPECT_GT(counted, 10000); // most of the box is bricks of one value (14,752 counted)
  EXPECT_GT(longest, 20);
}

TEST(BrickedGrid, MarchSumsWhatInterpolationGivesAtEachPoint)
{
  // Blocks of ten cells, each of one value (1 or 2) or varying: a shadow
  // ray's midpoint march (SumAlong) is the sum of Interpolate() at its
  // points, to the bit, through constant bricks, stored ones and the faces
  // between them, and stops where Interpolate()'s sum first passes its stop.
  const std::array<int, 3> n{ 64, 48, 40 };
  const Box box{ Vec3(-1.f, 0.f, 2.f), Vec3(1.f, 3.f, 2.5f) };
  auto value = [](int i, int j, int k)
  {
    const int block = (i / 10 + j / 10 + k / 10) % 3;
    return block == 0 ? 0.1f * static_cast<float>(i % 5 + j % 3) : static_cast<float>(block);
  };
  const BrickedGrid grid = BrickedGrid::Sample(n, box, value, Never, SerialFor());
  ASSERT_GT(grid.NumberOfStoredBricks(), 0u);
  ASSERT_LT(grid.NumberOfStoredBricks(), grid.NumberOfBricks());
  Random random(5, 0);
  int stopped = 0;
  for (int ray = 0; ray < 1000; ++ray)
  {
    Vec3 x, d;
    for (int a = 0; a < 3; ++a)
    {
      x[a] = box.lower[a] + box.Extent()[a] * (1.2f * random.NextFloat() - 0.1f);
      d[a] = 2.f * random.NextFloat() - 1.f;
    }
    d = d / Length(d);
    const float t0 = 0.1f * random.NextFloat();
    const float h = (box.Extent().x / 64.f) * (0.25f + random.NextFloat());
    const int samples = 1 + static_cast<int>(random.NextFloat() * 300.f);
    const double stop = ray % 2 ? 0.0 : 40.0 * random.NextFloat();
    double expected = 0.0;
    for (int i = 0; i < samples; ++i)
    {
      expected += grid.Interpolate(x + d * (t0 + (static_cast<float>(i) + 0.5f) * h));
      if (stop > 0.0 && expected > stop)
      {
        ++stopped;
        break;
      }
    }
    ASSERT_EQ(grid.SumAlong(x, d, t0, h, samples, stop), expected) << "ray " << ray;
  }
  EXPECT_GT(stopped, 50);
}

TEST(BrickedGrid, ResampledInPlaceIsTheGridSampledAfresh)
{
  // Values a function of a field, then of the field edited: sampled again
  // in the first grid's memory (bricks kept where `keep` says), or, where a
  // copy shares that memory, elsewhere; every cell is what SampleBricks()
  // gives with the edited values, and the copy keeps the first values.
  const std::array<int, 3> n{ 40, 33, 27 };
  const Box box{ Vec3(0.f), Vec3(1.f) };
  auto field = [](int i, int j, int k, int edit) -> float
  {
    // Bricks constant at first (i < 14) vary after the edit and the reverse
    // (j >= 20); the rest changes only in the first layer of bricks.
    if (i < 14)
    {
      return edit ? 0.1f * static_cast<float>(j) : 3.f;
    }
    if (j >= 20)
    {
      return edit ? 5.f : static_cast<float>(i + j);
    }
    return static_cast<float>(i * j + k) + (edit && k < 7 && k % 2 == 0 ? 0.5f : 0.f);
  };
  auto bricksOf = [&](int edit)
  {
    return [&, edit](const std::array<int, 3>& lower, float* out)
    {
      for (int k = 0; k < BrickedGrid::Size; ++k)
        for (int j = 0; j < BrickedGrid::Size; ++j)
          for (int i = 0; i < BrickedGrid::Size; ++i)
          {
            *out++ = field(std::min(lower[0] + i, n[0] - 1), std::min(lower[1] + j, n[1] - 1),
              std::min(lower[2] + k, n[2] - 1), edit);
          }
    };
  };
  const std::vector<char> candidate = BrickedGrid::Candidates(n, Never, SerialFor());
  const BrickedGrid fresh = BrickedGrid::SampleBricks(n, box, bricksOf(1), candidate, SerialFor());
  // Bricks whose values the edit left as they were are kept, unwritten.
  std::vector<char> keep(candidate.size(), 0);
  const BrickedGrid first = BrickedGrid::SampleBricks(n, box, bricksOf(0), candidate, SerialFor());
  for (std::size_t b = 0; b < keep.size(); ++b)
  {
    float a[BrickedGrid::BrickSamples], c[BrickedGrid::BrickSamples];
    first.CopyBrick(b, a);
    fresh.CopyBrick(b, c);
    keep[b] = std::equal(a, a + BrickedGrid::BrickSamples, c) ? 1 : 0;
  }
  EXPECT_GT(std::count(keep.begin(), keep.end(), 1), 0);
  EXPECT_LT(std::count(keep.begin(), keep.end(), 1), static_cast<long>(keep.size()));
  auto same = [&](const BrickedGrid& g, const BrickedGrid& h)
  {
    for (int k = 0; k < n[2]; ++k)
      for (int j = 0; j < n[1]; ++j)
        for (int i = 0; i < n[0]; ++i)
        {
          if (g.At(i, j, k) != h.At(i, j, k))
          {
            return false;
          }
        }
    return true;
  };
  for (const bool shared : { false, true })
  {
    BrickedGrid grid = BrickedGrid::SampleBricks(n, box, bricksOf(0), candidate, SerialFor());
    const std::uint64_t identity = grid.GetIdentity();
    BrickedGrid copy;
    if (shared)
    {
      copy = grid;
      EXPECT_FALSE(grid.SoleOwner());
    }
    else
    {
      EXPECT_TRUE(grid.SoleOwner());
    }
    const BrickedGrid edited =
      BrickedGrid::ResampleInPlace(std::move(grid), keep, bricksOf(1), candidate, SerialFor());
    EXPECT_TRUE(grid.Empty());
    EXPECT_TRUE(same(edited, fresh)) << (shared ? "shared" : "own");
    EXPECT_NE(edited.GetIdentity(), identity);
    EXPECT_EQ(edited.NumberOfStoredBricks(), fresh.NumberOfStoredBricks());
    EXPECT_TRUE(edited.HasSamples());
    if (shared)
    {
      EXPECT_TRUE(same(copy, first));
      EXPECT_EQ(copy.GetIdentity(), identity);
    }
  }
}
