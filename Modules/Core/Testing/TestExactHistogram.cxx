// SPDX-License-Identifier: BSD-3-Clause
// Exact fixed-point sums: the same bits in any order and grouping, the
// documented bounds held at their worst case, and limbs that sum across
// processes without overflow.
#include "brume/ExactHistogram.h"
#include "brume/Random.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <thread>
#include <vector>

using namespace brume;

namespace
{
// Sums `a` and `b` limb by limb as an all-reduce over two processes would.
std::vector<std::int64_t> AddLimbs(std::vector<std::int64_t> a, const std::vector<std::int64_t>& b)
{
  for (std::size_t i = 0; i < a.size(); ++i)
  {
    a[i] += b[i];
  }
  return a;
}
}

TEST(ExactHistogram, QuantumIsAPowerOfTwoBelowTheParticleFlux)
{
  // particleFlux in [2^(e-1), 2^e): quantum 2^(e - 40).
  EXPECT_EQ(ExactHistogram::QuantumExponent(1.0), 1 - 40);
  EXPECT_EQ(ExactHistogram::QuantumExponent(0.75), 0 - 40);
  EXPECT_EQ(ExactHistogram::QuantumExponent(3e-7), -21 - 40);
  // Halving the flux halves the quantum: progressive runs stay exact.
  for (double f : { 1e-9, 0.3, 7.0, 1e6 })
  {
    EXPECT_EQ(ExactHistogram::QuantumExponent(f / 2), ExactHistogram::QuantumExponent(f) - 1) << f;
  }
}

TEST(ExactHistogram, SameBitsInAnyOrderAndGrouping)
{
  // 30,000 terms of very different sizes (1e-6 to 1e3 particle fluxes, some
  // negative, as spherical-harmonics projections are) over 7 cells: added
  // in order, in reverse, and as three merged parts, the sums are the same.
  const double particle = 2.5e-7;
  const int e = ExactHistogram::QuantumExponent(particle);
  Random random(3, 0);
  std::vector<std::pair<std::size_t, double>> terms;
  for (int k = 0; k < 30000; ++k)
  {
    const double size = particle * std::pow(10.0, -6.0 + 9.0 * random.NextDouble());
    terms.emplace_back(random.NextUInt() % 7, (k % 5 == 0 ? -1.0 : 1.0) * size);
  }
  auto exact = [&](const std::vector<std::size_t>& order, int parts)
  {
    std::vector<ExactHistogram> h(parts, ExactHistogram({ 7, 1, 1 }, 1, e));
    for (std::size_t k = 0; k < order.size(); ++k)
    {
      h[k % parts].Add(terms[order[k]].first, &terms[order[k]].second);
    }
    for (int p = 1; p < parts; ++p)
    {
      h[0].Merge(h[p]);
    }
    return h[0];
  };
  std::vector<std::size_t> forward(terms.size()), backward(terms.size());
  std::iota(forward.begin(), forward.end(), 0);
  std::iota(backward.rbegin(), backward.rend(), 0);
  const ExactHistogram a = exact(forward, 1), b = exact(backward, 1), c = exact(forward, 3);
  EXPECT_EQ(a.GetSums(), b.GetSums());
  EXPECT_EQ(a.GetSums(), c.GetSums());
  EXPECT_FALSE(a.Saturated());
  // Against long double sums: each term is rounded once by at most half a
  // quantum, 2^-41 of a particle's flux.
  std::vector<long double> reference(7, 0.0L);
  for (const auto& t : terms)
  {
    reference[t.first] += t.second;
  }
  Histogram doubles;
  a.ToHistogram(doubles);
  const double bound = 0.5 * std::ldexp(1.0, e) * static_cast<double>(terms.size());
  for (std::size_t cell = 0; cell < 7; ++cell)
  {
    EXPECT_NEAR(doubles.GetValues()[cell], static_cast<double>(reference[cell]), bound) << cell;
  }
}

TEST(ExactHistogram, ThreadsAddingToTheSameCellsKeepEveryBit)
{
  // AddNonNegative<true>: four threads adding at once into the same five
  // cells, terms large enough that the low words carry every few terms,
  // some negative and one NaN (Add()'s way, atomically too): the sums of
  // adding them all on one thread, and the clamp reported.
  const int e = ExactHistogram::QuantumExponent(1.0);
  const double quantum = std::ldexp(1.0, e);
  constexpr int Threads = 4, Terms = 100000;
  std::vector<std::array<double, 2>> terms(static_cast<std::size_t>(Threads) * Terms);
  Random random(11, 0);
  for (std::size_t k = 0; k < terms.size(); ++k)
  {
    for (double& t : terms[k])
    {
      t = quantum * std::ldexp(random.NextDouble(), 61) * (k % 9 == 0 ? -1.0 : 1.0);
    }
  }
  terms[12345][1] = std::nan("");
  ExactHistogram one({ 5, 1, 1 }, 2, e), shared({ 5, 1, 1 }, 2, e);
  for (std::size_t k = 0; k < terms.size(); ++k)
  {
    const double values[2] = { terms[k][0], terms[k][1] };
    one.AddNonNegative(k % 5, 0, values);
  }
  std::vector<std::thread> threads;
  for (int t = 0; t < Threads; ++t)
  {
    threads.emplace_back(
      [&, t]
      {
        for (std::size_t k = t; k < terms.size(); k += Threads)
        {
          const double values[2] = { terms[k][0], terms[k][1] };
          shared.AddNonNegative<true>(k % 5, 0, values);
        }
      });
  }
  for (std::thread& thread : threads)
  {
    thread.join();
  }
  EXPECT_EQ(shared.GetSums(), one.GetSums());
  EXPECT_TRUE(one.Saturated());
  EXPECT_TRUE(shared.Saturated());
  // The sums went past one word: the carries were counted.
  EXPECT_GT(one.MaxMagnitude(), static_cast<Int128>(1) << 64);
}

TEST(ExactHistogram, WorstCaseSumsStayExact)
{
  // The largest term, 2^62 - 1 quanta, and the sum of 2^64 of them (made by
  // merging a histogram with itself 64 times, as binning them would add):
  // (2^62 - 1) 2^64 < 2^127 is held exactly, and two processes' such sums
  // still reduce exactly through three limbs.
  const int e = ExactHistogram::QuantumExponent(1.0);
  ExactHistogram h({ 2, 1, 1 }, 1, e);
  const double largest =
    std::ldexp(1.0, e) * (std::ldexp(1.0, 62) - 1024.0); // a double below the bound
  h.Add(0, &largest);
  const double negative = -largest;
  h.Add(1, &negative);
  EXPECT_FALSE(h.Saturated());
  const Int128 term = h.GetSum(0);
  EXPECT_EQ(term, static_cast<Int128>(std::ldexp(1.0, 62) - 1024.0));
  for (int k = 0; k < 64; ++k)
  {
    h.Merge(h);
  }
  const Int128 expected = term * (static_cast<Int128>(1) << 64);
  EXPECT_EQ(h.GetSums()[0], expected);
  EXPECT_EQ(h.GetSums()[1], -expected);
  EXPECT_FALSE(ExactHistogram::FitsOneLimb(h.MaxMagnitude(), 2));
  std::vector<std::int64_t> limbs(6);
  h.ToLimbs(3, 0, 2, limbs.data());
  ExactHistogram total({ 2, 1, 1 }, 1, e);
  total.FromLimbs(3, AddLimbs(limbs, limbs).data(), 0, 2);
  EXPECT_EQ(total.GetSums()[0], 2 * expected);
  // Piece by piece, as a reduction goes: the second value alone.
  std::vector<std::int64_t> second(3);
  h.ToLimbs(3, 1, 1, second.data());
  EXPECT_TRUE(std::equal(second.begin(), second.end(), limbs.begin() + 3));
  ExactHistogram piece({ 2, 1, 1 }, 1, e);
  piece.FromLimbs(3, second.data(), 1, 1);
  EXPECT_EQ(piece.GetSums()[0], 0);
  EXPECT_EQ(piece.GetSums()[1], -expected);
  EXPECT_EQ(total.GetSums()[1], -2 * expected);
  EXPECT_DOUBLE_EQ(total.GetValue(0), std::ldexp(static_cast<double>(2 * expected), e));
  // A term beyond the bound is clamped and reported; so is NaN.
  ExactHistogram over({ 1, 1, 1 }, 1, e);
  const double beyond = std::ldexp(1.0, e + 62);
  over.Add(0, &beyond);
  EXPECT_TRUE(over.Saturated());
  ExactHistogram nan({ 1, 1, 1 }, 1, e);
  const double notANumber = std::nan("");
  nan.Add(0, &notANumber);
  EXPECT_TRUE(nan.Saturated());
  EXPECT_EQ(nan.GetSums()[0], 0);
}

TEST(ExactHistogram, OneLimbWhenTheSumsFit)
{
  // Sums below 2^62 / R travel as one 64-bit integer each and come back the
  // same; three limbs give the same totals.
  const int e = ExactHistogram::QuantumExponent(1.0);
  ExactHistogram h({ 3, 1, 1 }, 2, e);
  const double v[2] = { 12.25, -3.5 };
  for (std::size_t cell = 0; cell < 3; ++cell)
  {
    h.Add(cell, v);
  }
  ASSERT_TRUE(ExactHistogram::FitsOneLimb(h.MaxMagnitude(), 4));
  for (int limbs : { 1, 3 })
  {
    std::vector<std::int64_t> out(static_cast<std::size_t>(6 * limbs));
    h.ToLimbs(limbs, 0, 6, out.data());
    const auto summed = AddLimbs(AddLimbs(out, out), out); // three processes
    ExactHistogram total({ 3, 1, 1 }, 2, e);
    total.FromLimbs(limbs, summed.data(), 0, 6);
    for (std::size_t i = 0; i < 6; ++i)
    {
      EXPECT_EQ(total.GetSums()[i], 3 * h.GetSums()[i]) << limbs << " limbs, value " << i;
      EXPECT_EQ(total.GetValue(i), 3 * v[i % 2]);
    }
  }
}

TEST(ExactHistogram, ScalingByAPowerOfTwoIsExact)
{
  // Add()'s rescaling: a power of two moves the quantum, the integers stay;
  // terms added afterwards at the new quantum sum as if all were added at it.
  const int e = ExactHistogram::QuantumExponent(1.0);
  ExactHistogram h({ 1, 1, 1 }, 1, e);
  const double first = 0.3;
  h.Add(0, &first);
  h.Scale(0.5);
  EXPECT_EQ(h.GetExponent(), e - 1);
  const double second = 0.15;
  h.Add(0, &second);
  ExactHistogram all({ 1, 1, 1 }, 1, e - 1);
  all.Add(0, &second);
  all.Add(0, &second);
  EXPECT_EQ(h.GetSums(), all.GetSums());
  // Another factor rounds each sum once.
  h.Scale(0.3);
  EXPECT_NEAR(h.GetValue(0), 0.3 * 0.3, std::ldexp(1.0, e - 1));
}
