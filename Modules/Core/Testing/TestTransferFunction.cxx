// SPDX-License-Identifier: BSD-3-Clause
// Media defined by a scalar field and an opacity transfer function: the
// extinction VTK's compositing stands for, classified after interpolation,
// block majorants that follow the function, and unbiased free flights.
#include "brume/Medium.h"
#include "brume/Random.h"
#include "brume/TransferFunction.h"
#include "brume/VdbDensity.h"

#include "BrumeVdbWriter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <iostream>

using namespace brume;

namespace
{
using Nodes = std::vector<OpacityTransferFunction::Node>;

// A scalar that is x over the unit cube, on n^3 points.
std::shared_ptr<GridDensity> RampInX(
  int n, GridDensity::Interpolation interpolation = GridDensity::Interpolation::Linear)
{
  std::vector<float> values;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        values.push_back(static_cast<float>(i) / static_cast<float>(n - 1));
  return std::make_shared<GridDensity>(
    Box{ Vec3(0.f), Vec3(1.f) }, std::array<int, 3>{ n, n, n }, values, false, interpolation);
}

Medium Absorber(std::shared_ptr<const DensityField> density)
{
  Medium m;
  m.Name = "classified";
  m.SigmaA = Vec3(1.f); // sigma_t is the function's extinction
  m.SigmaS = Vec3(0.f);
  m.SetDensity(std::move(density));
  return m;
}

// The fraction of n free flights along o + t d, t in [0, length], that
// reach the end, and its standard error.
void Uncollided(const Medium& medium, const Vec3& o, const Vec3& d, float length, double& fraction,
  double& stderr, std::uint64_t n = 200000)
{
  const std::vector<Medium> media{ medium };
  MediumTracker tracker;
  std::uint64_t through = 0;
  for (std::uint64_t i = 0; i < n; ++i)
  {
    Random rng(7, i);
    Vec3 weight(1.f);
    float t = 0.f;
    through += SampleCollision(media, o, d, length, rng, weight, t, &tracker) ? 0 : 1;
  }
  fraction = static_cast<double>(through) / static_cast<double>(n);
  stderr = std::sqrt(fraction * (1.0 - fraction) / static_cast<double>(n));
}

// Optical depth along the segment by the midpoint rule (2^16 steps).
double Quadrature(const Medium& medium, const Vec3& o, const Vec3& d, float length)
{
  const int steps = 1 << 16;
  double depth = 0.0;
  for (int i = 0; i < steps; ++i)
  {
    const float t = length * (static_cast<float>(i) + 0.5f) / static_cast<float>(steps);
    depth += medium.SigmaTAt(o + d * t).x;
  }
  return depth * length / steps;
}
}

// A density whose majorant blocks are given: each block's value is half
// its majorant, its regions marked empty where every block is 0 or not.
class BlockDensity : public DensityField
{
public:
  BlockDensity(std::array<int, 3> blocks, std::vector<float> max, bool mark)
  {
    this->Bounds = Box{ Vec3(0.f), Vec3(1.f) };
    this->Majorants.Bounds = this->Bounds;
    this->Majorants.Dims = blocks;
    this->Majorants.Max = std::move(max);
    if (mark)
    {
      this->Majorants.MarkEmptyRegions();
    }
  }
  float Evaluate(const Vec3& p) const override
  {
    const MajorantGrid& g = this->Majorants;
    int b[3];
    for (int a = 0; a < 3; ++a)
    {
      b[a] = std::clamp(static_cast<int>(p[a] * static_cast<float>(g.Dims[a])), 0, g.Dims[a] - 1);
    }
    return 0.5f * g.At(b[0], b[1], b[2]);
  }
};

TEST(TransferFunction, EmptyRegionsAreSteppedThroughAlike)
{
  // 40^3 blocks (5^3 regions of 8^3), two occupied blocks in opposite
  // corners: every region but theirs is empty, and the trackers collide at
  // the same distances, bit for bit, whether the regions are marked or not.
  const std::array<int, 3> dims{ 40, 40, 40 };
  std::vector<float> max(40 * 40 * 40, 0.f);
  max[(3 * 40 + 2) * 40 + 1] = 30.f;
  max[(37 * 40 + 38) * 40 + 39] = 60.f;
  auto marked = std::make_shared<BlockDensity>(dims, max, true);
  auto plain = std::make_shared<BlockDensity>(dims, max, false);
  const MajorantGrid& g = marked->GetMajorants();
  ASSERT_EQ(g.RegionDims, (std::array<int, 3>{ 5, 5, 5 }));
  EXPECT_EQ(std::count(g.EmptyRegions.begin(), g.EmptyRegions.end(), 1), 123);
  const int occupied[3] = { 1, 2, 3 }, farCorner[3] = { 39, 38, 37 }, empty[3] = { 20, 20, 20 };
  EXPECT_FALSE(g.InEmptyRegion(occupied));
  EXPECT_FALSE(g.InEmptyRegion(farCorner));
  EXPECT_TRUE(g.InEmptyRegion(empty));
  EXPECT_TRUE(plain->GetMajorants().EmptyRegions.empty());
  Medium a = Absorber(marked), b = Absorber(plain);
  a.SigmaS = b.SigmaS = Vec3(1.f);
  const std::vector<Medium> withRegions{ a }, without{ b };
  MediumTracker ta, tb;
  int collided = 0;
  for (std::uint64_t i = 0; i < 20000; ++i)
  {
    // Rays from the first occupied block toward the other, and across.
    Random pick(11, i);
    const Vec3 o(0.04f + 0.01f * pick.NextFloat(), 0.06f, 0.09f);
    const Vec3 to(0.975f, 0.95f + 0.02f * pick.NextFloat(), 0.1f + 0.85f * pick.NextFloat());
    const Vec3 d = Normalize(to - o);
    Random ra(5, i), rb(5, i);
    Vec3 wa(1.f), wb(1.f);
    float tA = -1.f, tB = -1.f;
    const Medium* hitA = SampleCollision(withRegions, o, d, 2.f, ra, wa, tA, &ta);
    const Medium* hitB = SampleCollision(without, o, d, 2.f, rb, wb, tB, &tb);
    ASSERT_EQ(hitA != nullptr, hitB != nullptr) << "ray " << i;
    if (hitA)
    {
      ASSERT_EQ(tA, tB) << "ray " << i;
      ++collided;
    }
    ASSERT_EQ(ra.NextUInt(), rb.NextUInt()) << "ray " << i << ": the same numbers drawn";
  }
  EXPECT_GT(collided, 1000);
}

TEST(TransferFunction, OpacityPerUnitDistanceIsVtksCompositing)
{
  // alpha 0.5 per unit distance 2: a step of 2 lets half through, as VTK's
  // 1 - (1 - alpha)^(dt / unit) composites it.
  const OpacityTransferFunction f({ { 0.f, 0.f }, { 1.f, 0.5f } }, 2.f);
  EXPECT_FLOAT_EQ(f.Opacity(0.5f), 0.25f);
  EXPECT_FLOAT_EQ(std::exp(-2.f * f.Extinction(1.f)), 0.5f);
  const float dt = 0.3f;
  EXPECT_NEAR(1.f - std::exp(-dt * f.Extinction(0.5f)), 1.f - std::pow(0.75f, dt / 2.f), 1e-6f);
  // Clamped to the end values outside the range, as vtkPiecewiseFunction clamps.
  EXPECT_EQ(f.Opacity(-3.f), 0.f);
  EXPECT_EQ(f.Opacity(7.f), 0.5f);
  // Opaque is finite: one unit distance lets 10^-6 through (float's 1 - 10^-6).
  const OpacityTransferFunction opaque({ { 0.f, 1.f } }, 1.f);
  EXPECT_NEAR(std::exp(-opaque.Extinction(0.f)), 1e-6, 2e-8);
}

TEST(TransferFunction, TheTableIsWithinItsToleranceOfTheExactExtinction)
{
  // Bends, a step, an opacity near 1 and a range of 10^4: sampled densely,
  // the table is within TableTolerance of the exact extinction (relative),
  // below the largest over any range about it, and most of its cells are
  // read from the table.
  const std::vector<std::vector<OpacityTransferFunction::Node>> functions{
    { { 0.f, 0.f }, { 1.f, 0.5f } },
    { { 0.f, 0.f }, { 0.5f, 0.f }, { 0.5f, 0.4f }, { 0.8f, 0.6f }, { 1.f, 0.2f } },
    { { -3.f, 0.f }, { 2.f, 0.999f }, { 2.5f, 0.9999f }, { 4.f, 0.1f } },
    { { 40.f, 0.f }, { 150.f, 0.f }, { 200.f, 0.5f }, { 10000.f, 1.f } },
  };
  const double tolerance = OpacityTransferFunction::TableTolerance;
  for (const auto& nodes : functions)
  {
    const OpacityTransferFunction f(nodes, 0.05f);
    EXPECT_LE(f.GetTableError(), tolerance * 1.01);
    EXPECT_LT(f.NumberOfExactCells(), OpacityTransferFunction::TableCells / 10);
    const float lo = nodes.front().Scalar, hi = nodes.back().Scalar;
    double worst = 0.0;
    for (int i = -1000; i <= 201000; ++i)
    {
      const float s = lo + (hi - lo) * static_cast<float>(i) / 200000.f;
      const double exact = f.ExactExtinction(s);
      const float got = f.Extinction(s);
      ASSERT_LE(std::abs(got - exact), tolerance * exact + 1e-30) << s;
      const float width = (hi - lo) * static_cast<float>(i % 7) / 1000.f;
      ASSERT_LE(got, f.MaxExtinction(s, s)) << s;
      ASSERT_LE(got, f.MaxExtinction(s - width, s)) << s;
      ASSERT_LE(got, f.MaxExtinction(s, s + 2.f * width)) << s;
      worst = std::max(worst, exact > 0.0 ? std::abs(got - exact) / exact : 0.0);
    }
    std::cout << "largest relative difference " << worst << ", table's bound " << f.GetTableError()
              << ", " << f.NumberOfExactCells() << " exact cells\n";
  }
}

TEST(TransferFunction, TheMeanAlongALinearRunIsItsIntegral)
{
  // MeanExtinction(a, b) against a midpoint sum of ExactExtinction() over
  // 10^5 steps of [a, b] (whose own error is at most the largest jump over
  // 10^5): runs inside a cell, across many, over steps and points, past
  // either end, reversed, of one point's width; for a function of one
  // point (no table) too. Within the table's tolerance, and at most the
  // largest extinction over the run.
  const std::vector<std::vector<OpacityTransferFunction::Node>> functions{
    { { 0.f, 0.f }, { 50.f, 0.f }, { 120.f, 0.004f }, { 140.f, 0.f }, { 155.f, 0.f },
      { 160.f, 0.06f }, { 180.f, 0.12f }, { 200.f, 0.25f }, { 220.f, 0.5f }, { 240.f, 0.9f },
      { 255.f, 0.9f } },
    { { 0.f, 0.f }, { 0.5f, 0.f }, { 0.5f, 0.4f }, { 0.8f, 0.6f }, { 1.f, 0.2f } },
    { { -3.f, 0.f }, { 2.f, 0.999f }, { 2.5f, 0.9999f }, { 4.f, 0.1f } },
    { { 7.f, 0.3f } },
  };
  for (const auto& nodes : functions)
  {
    const OpacityTransferFunction f(nodes, 0.02f);
    const float lo = nodes.front().Scalar, hi = nodes.back().Scalar;
    const float span = std::max(hi - lo, 1.f);
    double jump = 0.0;
    for (const auto& n : nodes)
    {
      jump = std::max(jump, static_cast<double>(f.ExactExtinction(n.Scalar)));
    }
    std::vector<std::pair<float, float>> runs;
    for (const auto& n : nodes)
    {
      runs.push_back({ n.Scalar, n.Scalar - 0.37f * span });
      runs.push_back({ n.Scalar - 1e-3f * span, n.Scalar + 2e-3f * span });
      runs.push_back({ n.Scalar, n.Scalar + 0.05f * span });
    }
    for (int r = 0; r < 60; ++r)
    {
      const float a = lo - 0.1f * span + 1.2f * span * static_cast<float>((r * 37) % 61) / 61.f;
      const float width = span * static_cast<float>(r % 5 == 0 ? 1e-4 : (r % 7) / 6.0);
      runs.push_back({ a, a + width });
    }
    runs.push_back({ lo - span, hi + span });
    for (const auto& [a, b] : runs)
    {
      const float got = f.MeanExtinction(a, b);
      if (a == b)
      {
        EXPECT_EQ(got, f.Extinction(a));
        continue;
      }
      constexpr int Steps = 100000;
      double sum = 0.0;
      for (int i = 0; i < Steps; ++i)
      {
        sum += f.ExactExtinction(static_cast<float>(a + (b - a) * (i + 0.5) / Steps));
      }
      const double expected = sum / Steps;
      EXPECT_NEAR(got, expected,
        2.0 * OpacityTransferFunction::TableTolerance * expected + 2.0 * jump / Steps + 1e-6)
        << a << " to " << b;
      EXPECT_EQ(got, f.MeanExtinction(b, a)) << a << " to " << b;
      EXPECT_LE(got, f.MaxExtinction(std::min(a, b), std::max(a, b)) * (1.f + 1e-6f));
    }
  }
}

TEST(TransferFunction, ASheetOneVoxelThinIsIntegratedNotSampled)
{
  // Data/scenes/shells.json's sheets: a scalar of 240 on one plane of
  // points, 60 elsewhere, under the shells' opacity function. The native
  // cells' means across the sheet, against the same field integrated
  // densely: within 10^-3, where the mean of 4^3 samples is 20 % off. A
  // sheet whose plane is tilted across the axes, integrated along one axis
  // only: within 6 % of a mean of 128^3 samples, where 4^3 samples are
  // 15 % off (what is left: the 4 x 4 lines across the other two axes).
  const Nodes shells{ { 0.f, 0.f }, { 50.f, 0.f }, { 120.f, 0.004f }, { 140.f, 0.f },
    { 155.f, 0.f }, { 160.f, 0.06f }, { 180.f, 0.12f }, { 200.f, 0.25f }, { 220.f, 0.5f },
    { 240.f, 0.9f }, { 255.f, 0.9f } };
  const OpacityTransferFunction function(shells, 0.02f);
  constexpr int N = 12;
  for (const bool tilted : { false, true })
  {
    std::vector<float> values;
    for (int k = 0; k < N; ++k)
      for (int j = 0; j < N; ++j)
        for (int i = 0; i < N; ++i)
        {
          const bool sheet = tilted ? (2 * i + j + k) / 2 == 11 : i == 5;
          values.push_back(sheet ? 240.f : 60.f);
        }
    const Box bounds{ Vec3(0.f), Vec3(1.f) };
    auto scalars = std::make_shared<GridDensity>(
      bounds, std::array<int, 3>{ N, N, N }, values, false, GridDensity::Interpolation::Linear);
    const ClassifiedDensity classified(scalars, function);
    // Native cell (i, j, k) spans half a spacing about point (i, j, k).
    const float h = 1.f / static_cast<float>(N - 1);
    auto mean = [&](int i, int j, int k, int s)
    {
      double sum = 0.0;
      for (int z = 0; z < s; ++z)
        for (int y = 0; y < s; ++y)
          for (int x = 0; x < s; ++x)
          {
            const Vec3 p(h * (static_cast<float>(i) + (x + 0.5f) / static_cast<float>(s) - 0.5f),
              h * (static_cast<float>(j) + (y + 0.5f) / static_cast<float>(s) - 0.5f),
              h * (static_cast<float>(k) + (z + 0.5f) / static_cast<float>(s) - 0.5f));
            sum += classified.Evaluate(p);
          }
      return sum / (static_cast<double>(s) * s * s);
    };
    double worst = 0.0, worstSampled = 0.0;
    for (int i = 3; i <= 7; ++i)
    {
      const int j = 5, k = 6;
      const Box cell{ Vec3(h * (i - 0.5f), h * (j - 0.5f), h * (k - 0.5f)),
        Vec3(h * (i + 0.5f), h * (j + 0.5f), h * (k + 0.5f)) };
      const double got = classified.NativeMean(i, j, k, cell, bounds, 4);
      double expected = 0.0;
      if (tilted)
      {
        expected = mean(i, j, k, 128);
      }
      else
      {
        // The field varies along x only: 10^5 steps along x.
        constexpr int Steps = 100000;
        for (int x = 0; x < Steps; ++x)
        {
          expected += classified.Evaluate(
            Vec3(h * (static_cast<float>(i) + (x + 0.5f) / Steps - 0.5f), h * j, h * k));
        }
        expected /= Steps;
      }
      if (expected < 1.0)
      {
        continue; // cells the sheet does not reach
      }
      worst = std::max(worst, std::abs(got - expected) / expected);
      worstSampled = std::max(worstSampled, std::abs(mean(i, j, k, 4) - expected) / expected);
    }
    std::cout << (tilted ? "tilted" : "axis-aligned") << " sheet: largest relative error " << worst
              << " (4^3 samples: " << worstSampled << ")\n";
    EXPECT_LT(worst, tilted ? 6e-2 : 1e-3);
    EXPECT_GT(worstSampled, tilted ? 0.1 : 0.15);
  }
}

TEST(TransferFunction, ManyScalarsAtOnceAreEachClassifiedAlike)
{
  // Extinctions() gives each scalar Extinction()'s float: in the table's
  // cells, in those evaluated exactly, at the function's points, outside
  // its range, and for a function of one point (no table).
  const std::vector<std::vector<OpacityTransferFunction::Node>> functions{
    { { 0.f, 0.f }, { 0.5f, 0.f }, { 0.5f, 0.4f }, { 0.8f, 0.6f }, { 1.f, 0.2f } },
    { { -3.f, 0.f }, { 2.f, 0.999f }, { 2.5f, 0.9999f }, { 4.f, 0.1f } },
    { { 7.f, 0.3f } },
  };
  for (const auto& nodes : functions)
  {
    const OpacityTransferFunction f(nodes, 0.05f);
    const float lo = nodes.front().Scalar - 1.f, hi = nodes.back().Scalar + 1.f;
    std::vector<float> scalars;
    for (int i = 0; i <= 20000; ++i)
    {
      scalars.push_back(lo + (hi - lo) * static_cast<float>(i) / 20000.f);
    }
    for (const auto& node : nodes)
    {
      scalars.push_back(node.Scalar);
    }
    std::vector<float> classified = scalars;
    f.Extinctions(classified.data(), static_cast<int>(classified.size()));
    int exact = 0;
    for (std::size_t i = 0; i < scalars.size(); ++i)
    {
      ASSERT_EQ(classified[i], f.Extinction(scalars[i])) << scalars[i];
      exact += classified[i] == f.ExactExtinction(scalars[i]) ? 1 : 0;
    }
    EXPECT_GT(exact, 0);
  }
}

TEST(TransferFunction, AnEditKeepsTheRangesItLeftAsTheyWere)
{
  // Where OpacityFunctionEdit says a range is the same, every scalar in it
  // classifies to the same floats before and after the edit (densely
  // sampled, the points themselves among them); where the edit changed
  // the function, it says so.
  const Nodes before{ { 0.f, 0.f }, { 50.f, 0.f }, { 120.f, 0.004f }, { 160.f, 0.06f },
    { 200.f, 0.25f }, { 240.f, 0.9f }, { 255.f, 0.9f } };
  struct Case
  {
    Nodes After;
    float ChangedLo, ChangedHi; // where the function differs
  };
  const std::vector<Case> cases{
    // A point's opacity raised.
    { { { 0.f, 0.f }, { 50.f, 0.f }, { 120.f, 0.004f }, { 160.f, 0.06f }, { 200.f, 0.4f },
        { 240.f, 0.9f }, { 255.f, 0.9f } },
      160.f, 240.f },
    // A point added.
    { { { 0.f, 0.f }, { 50.f, 0.f }, { 120.f, 0.004f }, { 160.f, 0.06f }, { 180.f, 0.2f },
        { 200.f, 0.25f }, { 240.f, 0.9f }, { 255.f, 0.9f } },
      160.f, 200.f },
    // A point moved.
    { { { 0.f, 0.f }, { 60.f, 0.f }, { 120.f, 0.004f }, { 160.f, 0.06f }, { 200.f, 0.25f },
        { 240.f, 0.9f }, { 255.f, 0.9f } },
      0.f, 120.f },
  };
  const OpacityTransferFunction f(before, 0.02f);
  // Unchanged: everything the same.
  const OpacityTransferFunction copy(before, 0.02f);
  EXPECT_TRUE(f.SameAs(copy));
  EXPECT_TRUE(OpacityFunctionEdit(f, copy).SameOver(-10.f, 300.f));
  EXPECT_FALSE(OpacityFunctionEdit(f, copy).SameOver(0.f, NAN));
  EXPECT_FALSE(OpacityFunctionEdit(f, OpacityTransferFunction(before, 0.03f)).SameOver(0.f, 1.f));
  for (const Case& c : cases)
  {
    const OpacityTransferFunction g(c.After, 0.02f);
    EXPECT_FALSE(f.SameAs(g));
    const OpacityFunctionEdit edit(f, g);
    int same = 0;
    for (int r = 0; r < 2000; ++r)
    {
      // Ranges of widths from 0 to 64 over [-5, 260], whole numbers among them.
      const float lo = r % 3 == 0 ? static_cast<float>(r % 261) : -5.f + 265.f * (r % 997) / 997.f;
      const float hi = lo + static_cast<float>((r * 7) % 65) * (r % 2 ? 1.f : 0.37f);
      if (!edit.SameOver(lo, hi))
      {
        continue;
      }
      ++same;
      EXPECT_TRUE(hi <= c.ChangedLo || lo >= c.ChangedHi) << lo << " " << hi;
      for (int i = 0; i <= 200; ++i)
      {
        const float s = i == 200 ? hi : lo + (hi - lo) * static_cast<float>(i) / 200.f;
        ASSERT_EQ(f.Extinction(s), g.Extinction(s)) << s << " in " << lo << " " << hi;
        ASSERT_EQ(f.ExactExtinction(s), g.ExactExtinction(s)) << s;
        // A cell's mean along a run within the range reads the range only.
        ASSERT_EQ(f.MeanExtinction(lo, s), g.MeanExtinction(lo, s)) << s;
        ASSERT_EQ(f.MeanExtinction(s, hi), g.MeanExtinction(s, hi)) << s;
      }
    }
    // Ranges clear of the edit were found the same.
    EXPECT_GT(same, 100);
    EXPECT_TRUE(edit.SameOver(c.ChangedHi + 1.f, c.ChangedHi + 2.f) || c.ChangedHi + 2.f > 255.f);
    EXPECT_FALSE(edit.SameOver(c.ChangedLo, c.ChangedHi));
  }
}

TEST(TransferFunction, StepsAndMaximaOverRanges)
{
  // A step at s = 0.5 (two points at the same scalar) and a peak at 0.8.
  const OpacityTransferFunction f(
    { { 0.f, 0.f }, { 0.5f, 0.f }, { 0.5f, 0.4f }, { 0.8f, 0.6f }, { 1.f, 0.2f } }, 1.f);
  EXPECT_EQ(f.Opacity(0.49f), 0.f);
  EXPECT_FLOAT_EQ(f.Opacity(0.5f), 0.4f); // a scalar at a step takes the later point
  EXPECT_EQ(f.MaxExtinction(0.f, 0.45f), 0.f);
  EXPECT_FLOAT_EQ(f.MaxExtinction(0.f, 0.5f), -std::log1p(-0.4f));
  EXPECT_FLOAT_EQ(f.MaxExtinction(0.6f, 0.9f), -std::log1p(-0.6f)); // the peak inside
  EXPECT_FLOAT_EQ(f.MaxExtinction(0.9f, 0.95f), f.Extinction(0.9f));
}

TEST(TransferFunction, BadFunctionsAreRefused)
{
  EXPECT_NE(OpacityTransferFunction::Validate({}, 1.0), "");
  EXPECT_NE(OpacityTransferFunction::Validate({ { 0.f, -0.1f } }, 1.0), "");
  EXPECT_NE(OpacityTransferFunction::Validate({ { 0.f, 1.5f } }, 1.0), "");
  EXPECT_NE(OpacityTransferFunction::Validate({ { 0.f, NAN } }, 1.0), "");
  EXPECT_NE(OpacityTransferFunction::Validate({ { INFINITY, 0.5f } }, 1.0), "");
  EXPECT_NE(OpacityTransferFunction::Validate({ { 1.f, 0.5f }, { 0.f, 0.5f } }, 1.0), "");
  EXPECT_NE(OpacityTransferFunction::Validate({ { 0.f, 0.5f } }, 0.0), "");
  EXPECT_NE(OpacityTransferFunction::Validate({ { 0.f, 0.5f } }, NAN), "");
  EXPECT_EQ(OpacityTransferFunction::Validate({ { 0.f, 0.f }, { 0.f, 1.f } }, 1.0), "");
}

TEST(TransferFunction, ConstantFunctionIsTheHomogeneousMedium)
{
  const float alpha = 0.3f, unit = 0.5f;
  const float sigma = -std::log(1.f - alpha) / unit;
  const Medium classified = Absorber(std::make_shared<ClassifiedDensity>(
    RampInX(9), OpacityTransferFunction({ { 0.f, alpha } }, unit)));
  Medium homogeneous = Absorber(nullptr);
  homogeneous.Bounds = { Vec3(0.f), Vec3(1.f) };
  homogeneous.SigmaA = Vec3(sigma);
  const Vec3 o(-0.5f, 0.3f, 0.6f), d = Normalize(Vec3(1.f, 0.2f, -0.1f));
  double f = 0, se = 0, h = 0, hse = 0;
  Uncollided(classified, o, d, 3.f, f, se);
  Uncollided(homogeneous, o, d, 3.f, h, hse);
  const float length = 1.f / d.x; // the ray crosses the cube from x = 0 to x = 1
  EXPECT_NEAR(f, std::exp(-sigma * length), 4 * se);
  EXPECT_NEAR(f, h, 4 * std::hypot(se, hse));
  EXPECT_FLOAT_EQ(classified.SigmaTAt(Vec3(0.2f, 0.7f, 0.4f)).x, sigma);
}

TEST(TransferFunction, TwoLevelStepIsClassifiedAfterInterpolation)
{
  // s = x on 5 points along x, a step of the function at s = 0.6 (between
  // the points at 0.5 and 0.75): classified after interpolation, the
  // extinction steps exactly at x = 0.6, and the transmittance across the
  // cube is the product of the two levels' transmittances.
  const float low = 0.2f, high = 0.7f;
  const OpacityTransferFunction f(
    { { 0.f, low }, { 0.6f, low }, { 0.6f, high }, { 1.f, high } }, 1.f);
  const Medium m = Absorber(std::make_shared<ClassifiedDensity>(RampInX(5), f));
  const double expected = std::pow(1.0 - low, 0.6) * std::pow(1.0 - high, 0.4);
  double fraction = 0, se = 0;
  Uncollided(m, Vec3(-0.1f, 0.4f, 0.5f), Vec3(1.f, 0.f, 0.f), 1.2f, fraction, se);
  EXPECT_NEAR(fraction, expected, 4 * se);
  EXPECT_FLOAT_EQ(m.SigmaTAt(Vec3(0.599f, 0.5f, 0.5f)).x, -std::log1p(-low));
  EXPECT_FLOAT_EQ(m.SigmaTAt(Vec3(0.601f, 0.5f, 0.5f)).x, -std::log1p(-high));

  // Nearest interpolation steps at the point halfway between 0.5 and 0.75.
  const Medium nearest = Absorber(
    std::make_shared<ClassifiedDensity>(RampInX(5, GridDensity::Interpolation::Nearest), f));
  EXPECT_FLOAT_EQ(nearest.SigmaTAt(Vec3(0.62f, 0.5f, 0.5f)).x, -std::log1p(-low));
  EXPECT_FLOAT_EQ(nearest.SigmaTAt(Vec3(0.63f, 0.5f, 0.5f)).x, -std::log1p(-high));
  Uncollided(nearest, Vec3(-0.1f, 0.4f, 0.5f), Vec3(1.f, 0.f, 0.f), 1.2f, fraction, se);
  EXPECT_NEAR(fraction, std::pow(1.0 - low, 0.625) * std::pow(1.0 - high, 0.375), 4 * se);
}

TEST(TransferFunction, FreeFlightsAreUnbiasedAlongFixedRays)
{
  // A smooth scalar (a Gaussian blob on 17^3 points) through a function
  // with a ramp, a plateau and a peak: uncollided fractions along oblique
  // rays against the quadrature of the same classified field.
  const int n = 17;
  std::vector<float> values;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
      {
        const float x = i / 16.f - 0.5f, y = j / 16.f - 0.45f, z = k / 16.f - 0.55f;
        values.push_back(std::exp(-6.f * (x * x + y * y + z * z)) * 100.f);
      }
  auto scalars = std::make_shared<GridDensity>(
    Box{ Vec3(0.f), Vec3(1.f) }, std::array<int, 3>{ n, n, n }, values, false);
  const OpacityTransferFunction f(
    { { 30.f, 0.f }, { 60.f, 0.5f }, { 75.f, 0.5f }, { 90.f, 0.9f }, { 95.f, 0.1f } }, 0.25f);
  const Medium m = Absorber(std::make_shared<ClassifiedDensity>(scalars, f));
  ASSERT_EQ(m.Validate(), "");
  const Vec3 origins[] = { { -0.2f, 0.1f, 0.3f }, { 0.5f, -0.3f, 0.4f }, { 1.2f, 0.9f, 0.2f } };
  const Vec3 targets[] = { { 1.1f, 0.8f, 0.6f }, { 0.45f, 1.2f, 0.55f }, { -0.1f, 0.1f, 0.9f } };
  for (int r = 0; r < 3; ++r)
  {
    const Vec3 d = Normalize(targets[r] - origins[r]);
    const float length = Length(targets[r] - origins[r]);
    double fraction = 0, se = 0;
    Uncollided(m, origins[r], d, length, fraction, se);
    const double depth = Quadrature(m, origins[r], d, length);
    EXPECT_GT(depth, 0.3) << "ray " << r; // each ray crosses the classified blob
    EXPECT_NEAR(fraction, std::exp(-depth), 4 * se) << "ray " << r;
  }
}

TEST(TransferFunction, MajorantsFollowTheFunctionNotTheField)
{
  // s = x on 65^3 points, opacity only for s in [0.9, 1]: only the last
  // column of 8^3 blocks (cells with x >= 7/8) may collide, though the
  // field is positive everywhere.
  const auto scalars = RampInX(65);
  const OpacityTransferFunction f({ { 0.9f, 0.f }, { 0.95f, 0.8f }, { 1.f, 0.f } }, 1.f);
  const ClassifiedDensity classified(scalars, f);
  EXPECT_EQ(scalars->NumberOfOccupiedBlocks(), 512u);
  EXPECT_EQ(classified.NumberOfOccupiedBlocks(), 64u);
  EXPECT_FLOAT_EQ(classified.GetMajorants().GlobalMax(), -std::log1p(-0.8f));
  // Every block's majorant bounds the field inside it (sampled densely).
  const MajorantGrid& g = classified.GetMajorants();
  Random rng(3, 0);
  for (int i = 0; i < 100000; ++i)
  {
    const Vec3 p(rng.NextFloat(), rng.NextFloat(), rng.NextFloat());
    int b[3];
    for (int a = 0; a < 3; ++a)
    {
      b[a] = std::min(g.Dims[a] - 1,
        static_cast<int>((p[a] - g.Bounds.lower[a]) / g.Bounds.Extent()[a] * g.Dims[a]));
    }
    ASSERT_LE(classified.Evaluate(p), g.At(b[0], b[1], b[2]) * (1.f + 1e-6f)) << i;
  }
  // Occupancy counts the values the function makes non-zero: s = i / 64 in (0.9, 1).
  EXPECT_NEAR(classified.OccupiedFraction(), 6.0 / 65.0, 1e-9);
}

TEST(TransferFunction, BendsWhereAPointLiesInsideTheScalarsRange)
{
  // s = x on 9 points: a region of x in [0.5, 0.6] is defined by the
  // points at 0.5 and 0.625, so a point of the function at 0.55 lies inside
  // its range, one at 0.3 or exactly at 0.5 does not.
  const OpacityTransferFunction inside({ { 0.f, 0.f }, { 0.55f, 0.9f }, { 1.f, 0.f } }, 1.f);
  const OpacityTransferFunction outside({ { 0.3f, 0.f }, { 0.5f, 0.9f } }, 1.f);
  const Box region{ Vec3(0.5f, 0.2f, 0.2f), Vec3(0.6f, 0.3f, 0.3f) };
  EXPECT_TRUE(ClassifiedDensity(RampInX(9), inside).BendsWithin(region));
  EXPECT_FALSE(ClassifiedDensity(RampInX(9), outside).BendsWithin(region));
}

TEST(TransferFunction, OpenVdbScalarsAreClassifiedToo)
{
  // A signed scalar in an OpenVDB grid (voxels of 0.1 m over x in [0, 3.2],
  // y and z in [0, 1.6]): s = 5 x - 8, in [-8, 8], background -20 outside
  // the active voxels. Opacity 0 below s = -2, `low` up to the step at
  // s = 0 (x = 1.6), `high` from there.
  const std::string path =
    (std::filesystem::temp_directory_path() / "brume-classified-scalars.vdb").string();
  vdbwriter::Grid grid;
  grid.Name = "signed";
  grid.Background = -20.f;
  grid.VoxelSize = 0.1;
  grid.Upper = { 32, 16, 16 };
  grid.Value = [](int i, int, int) { return 0.5f * static_cast<float>(i) - 8.f; };
  vdbwriter::Write(path, { grid });
  std::string error;
  EXPECT_EQ(VdbDensity::Load(path, "signed", error), nullptr); // negative: not a density
  auto scalars = VdbDensity::LoadScalars(path, "signed", error);
  ASSERT_NE(scalars, nullptr) << error;
  const float low = 0.3f, high = 0.7f;
  const OpacityTransferFunction f(
    { { -2.f, 0.f }, { -1.9f, low }, { -0.001f, low }, { 0.f, high }, { 8.f, high } }, 1.f);
  auto classified = std::make_shared<ClassifiedDensity>(scalars, f);
  const Medium m = Absorber(classified);
  ASSERT_EQ(m.Validate(), "");
  // Along x from 1.0 to 2.2 (s from -3 to 3): nothing up to x = 1.2, a
  // ramp to x = 1.22, `low` to 1.6, `high` to 2.2.
  const Vec3 o(1.f, 0.8f, 0.8f), d(1.f, 0.f, 0.f);
  double fraction = 0, se = 0;
  Uncollided(m, o, d, 1.2f, fraction, se);
  const double depth = Quadrature(m, o, d, 1.2f);
  EXPECT_NEAR(fraction, std::exp(-depth), 4 * se);
  EXPECT_NEAR(depth, -std::log1p(-low) * 0.38 - std::log1p(-high) * 0.6, 0.01);
  // The first column of blocks (s at most -4.5 and the background there)
  // holds no medium; the function's largest extinction is reached.
  const MajorantGrid& g = classified->GetMajorants();
  EXPECT_FLOAT_EQ(g.GlobalMax(), -std::log1p(-high));
  for (int k = 0; k < g.Dims[2]; ++k)
    for (int j = 0; j < g.Dims[1]; ++j)
    {
      EXPECT_EQ(g.At(0, j, k), 0.f) << j << " " << k;
      EXPECT_GT(g.At(1, j, k), 0.f) << j << " " << k;
    }
  std::filesystem::remove(path);
}

TEST(TransferFunction, ColourIsLinearBetweenPointsAndClampedBeyond)
{
  const ColorTransferFunction f({ { 0.f, Vec3(1.f, 0.f, 0.f) }, { 1.f, Vec3(0.f, 0.5f, 1.f) },
    { 1.f, Vec3(0.2f, 0.2f, 0.2f) } });
  const Vec3 mid = f.Color(0.25f);
  EXPECT_FLOAT_EQ(mid.x, 0.75f);
  EXPECT_FLOAT_EQ(mid.y, 0.125f);
  EXPECT_FLOAT_EQ(mid.z, 0.25f);
  EXPECT_FLOAT_EQ(f.Color(-3.f).x, 1.f);
  // At two points' scalar, the later point's; beyond, the last colour.
  EXPECT_FLOAT_EQ(f.Color(1.f).x, 0.2f);
  EXPECT_FLOAT_EQ(f.Color(7.f).z, 0.2f);

  EXPECT_NE(ColorTransferFunction::Validate({}), "");
  EXPECT_NE(ColorTransferFunction::Validate({ { 0.f, Vec3(1.2f, 0.f, 0.f) } }), "");
  EXPECT_NE(ColorTransferFunction::Validate({ { 0.f, Vec3(0.f, -0.1f, 0.f) } }), "");
  EXPECT_NE(ColorTransferFunction::Validate({ { 0.f, Vec3(0.f, 0.f, NAN) } }), "");
  EXPECT_NE(ColorTransferFunction::Validate({ { NAN, Vec3(0.5f) } }), "");
  EXPECT_NE(ColorTransferFunction::Validate({ { 1.f, Vec3(0.5f) }, { 0.f, Vec3(0.5f) } }), "");
  EXPECT_EQ(ColorTransferFunction::Validate({ { 0.f, Vec3(0.f) }, { 0.f, Vec3(1.f) } }), "");
}

TEST(TransferFunction, AlbedoIsTheColourAfterInterpolationTimesTheMediumAlbedo)
{
  // s = x on 5 points, the colour stepping from red to blue at s = 0.6
  // (between the points at 0.5 and 0.75): the albedo steps exactly there,
  // scaled by the medium's own albedo; sigma_t is the opacity's alone.
  const auto scalars = RampInX(5);
  Medium m;
  m.SigmaS = Vec3(0.8f, 0.9f, 1.f);
  m.SigmaA = Vec3(1.f) - m.SigmaS;
  m.SetDensity(
    std::make_shared<ClassifiedDensity>(scalars, OpacityTransferFunction({ { 0.f, 0.5f } }, 1.f)));
  EXPECT_FALSE(m.HasVaryingAlbedo());
  m.AlbedoFactor = std::make_shared<ClassifiedAlbedo>(scalars,
    ColorTransferFunction({ { 0.6f, Vec3(1.f, 0.f, 0.f) }, { 0.6f, Vec3(0.f, 0.f, 1.f) } }));
  EXPECT_TRUE(m.HasVaryingAlbedo());
  const Vec3 red = m.AlbedoAt(Vec3(0.599f, 0.3f, 0.8f));
  const Vec3 blue = m.AlbedoAt(Vec3(0.601f, 0.3f, 0.8f));
  EXPECT_FLOAT_EQ(red.x, 0.8f);
  EXPECT_FLOAT_EQ(red.z, 0.f);
  EXPECT_FLOAT_EQ(blue.x, 0.f);
  EXPECT_FLOAT_EQ(blue.z, 1.f);
  EXPECT_FLOAT_EQ(m.SigmaTAt(Vec3(0.599f, 0.3f, 0.8f)).x, m.SigmaTAt(Vec3(0.601f, 0.3f, 0.8f)).x);
}

TEST(TransferFunction, CellAlbedosReadABrickAtOnceAsOneCellAtATime)
{
  // Point values of all kinds (between points, on a point, beyond both
  // ends, jumping between pairs of points from one value to the next): a
  // block of cells' factors read at once (CellAlbedo::AtCells()) are each
  // cell's own (AtCell()), which is the field at the cell's centre.
  const std::array<int, 3> dims{ 9, 7, 5 };
  std::vector<float> values(static_cast<std::size_t>(dims[0]) * dims[1] * dims[2]);
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    values[i] = -0.3f + 1.6f * static_cast<float>((i * 37) % 101) / 100.f;
  }
  values[5] = 0.25f; // on a point
  auto scalars =
    std::make_shared<const GridDensity>(Box{ Vec3(0.f), Vec3(1.f) }, dims, values, false);
  Medium m;
  m.SetDensity(
    std::make_shared<ClassifiedDensity>(scalars, OpacityTransferFunction({ { 0.f, 0.5f } }, 1.f)));
  const ColorTransferFunction colours(
    { { 0.f, Vec3(1.f, 0.f, 0.f) }, { 0.25f, Vec3(0.f, 1.f, 0.5f) },
      { 0.25f, Vec3(0.2f, 0.3f, 1.f) }, { 0.9f, Vec3(0.6f, 0.1f, 0.f) } });
  m.AlbedoFactor = std::make_shared<ClassifiedAlbedo>(scalars, colours);
  ASSERT_TRUE(m.AlbedoFactor->SharesNativeCells(*m.Density));
  const CellAlbedo cells(m);
  const std::array<int, 3> lower{ 1, 2, 0 }, count{ 8, 4, 5 };
  std::vector<Vec3> batch(static_cast<std::size_t>(count[0]) * count[1] * count[2]);
  std::vector<float> scratch;
  cells.AtCells(lower, count, scratch, batch.data());
  std::size_t n = 0;
  for (int k = lower[2]; k < lower[2] + count[2]; ++k)
    for (int j = lower[1]; j < lower[1] + count[1]; ++j)
      for (int i = lower[0]; i < lower[0] + count[0]; ++i, ++n)
      {
        const Vec3 one = cells.AtCell(i, j, k);
        const Vec3 own =
          colours.Color(values[(static_cast<std::size_t>(k) * dims[1] + j) * dims[0] + i]);
        const Vec3 centre = m.AlbedoFactor->Evaluate(cells.Centre(i, j, k));
        for (int c = 0; c < 3; ++c)
        {
          EXPECT_EQ(batch[n][c], one[c]) << i << " " << j << " " << k;
          EXPECT_EQ(one[c], own[c]);
          EXPECT_NEAR(one[c], centre[c], 1e-5f);
        }
      }
  // Colours of other scalars (another grid's cells) are read at the
  // centres, one cell at a time.
  auto coarser = std::make_shared<const GridDensity>(
    Box{ Vec3(0.f), Vec3(1.f) }, std::array<int, 3>{ 2, 2, 2 }, std::vector<float>(8, 0.5f), false);
  m.AlbedoFactor = std::make_shared<ClassifiedAlbedo>(coarser, colours);
  EXPECT_FALSE(m.AlbedoFactor->SharesNativeCells(*m.Density));
  const CellAlbedo other(m);
  other.AtCells(lower, count, scratch, batch.data());
  EXPECT_EQ(batch[3].y, m.AlbedoFactor->Evaluate(other.Centre(4, 2, 0)).y);
}

TEST(TransferFunction, AnEditKeepsTheOccupancyOfChunksItLeftAsTheyWere)
{
  // Floats that are not whole numbers, rising with z: each chunk of
  // 65,536 values (eight slices) spans its own range. An edit of the
  // function's point at 40 leaves it as it was below 20: the two chunks
  // there keep their occupancy, the others are counted again, and the
  // totals are those of the edited function counted afresh, to the bit.
  const std::array<int, 3> dims{ 128, 64, 64 };
  std::vector<float> values(static_cast<std::size_t>(dims[0]) * dims[1] * dims[2]);
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    const std::size_t z = i / (static_cast<std::size_t>(dims[0]) * dims[1]);
    values[i] = static_cast<float>(z) + 0.25f + 0.5f * static_cast<float>(i % 3) / 3.f;
  }
  auto grid = std::make_shared<const GridDensity>(Box{ Vec3(0.f), Vec3(1.f) }, dims, values, false);
  ASSERT_TRUE(grid->GetValueCounts(SerialFor()).Counts.empty()); // not whole numbers
  const OpacityTransferFunction before(
    Nodes{ { 0.f, 0.f }, { 20.f, 0.3f }, { 40.f, 0.5f }, { 70.f, 0.8f } }, 0.1f);
  const OpacityTransferFunction after(
    Nodes{ { 0.f, 0.f }, { 20.f, 0.3f }, { 40.f, 0.65f }, { 70.f, 0.8f } }, 0.1f);
  const ClassifiedDensity first(grid, before);
  const ClassifiedDensity edited(grid, after, SerialFor(), &first);
  const ClassifiedDensity afresh(grid, after);
  EXPECT_EQ(first.GetNumberOfKeptChunks(), 0u);
  EXPECT_EQ(edited.GetNumberOfKeptChunks(), 2u);
  EXPECT_EQ(edited.OccupiedFraction(), afresh.OccupiedFraction());
  EXPECT_EQ(edited.MeanOccupiedDensity(), afresh.MeanOccupiedDensity());
  EXPECT_NE(edited.MeanOccupiedDensity(), first.MeanOccupiedDensity());
  // The same edit back: the same two chunks kept, the first's totals.
  const ClassifiedDensity back(grid, before, SerialFor(), &edited);
  EXPECT_EQ(back.GetNumberOfKeptChunks(), 2u);
  EXPECT_EQ(back.MeanOccupiedDensity(), first.MeanOccupiedDensity());
  // Another grid's previous function keeps nothing.
  auto other =
    std::make_shared<const GridDensity>(Box{ Vec3(0.f), Vec3(1.f) }, dims, values, false);
  const ClassifiedDensity elsewhere(other, after, SerialFor(), &first);
  EXPECT_EQ(elsewhere.GetNumberOfKeptChunks(), 0u);
  EXPECT_EQ(elsewhere.MeanOccupiedDensity(), afresh.MeanOccupiedDensity());
}
