// SPDX-License-Identifier: BSD-3-Clause
// Chi-square tests of the direction samplers against their densities.
#include "brume/Random.h"
#include "brume/Sampling.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

using namespace brume;

namespace
{
// Pearson's statistic of observed counts against expected probabilities.
// Bins with small expectations are pooled so the chi-square law applies.
struct ChiSquare
{
  double Statistic = 0.0;
  int DegreesOfFreedom = -1;
};

ChiSquare Pearson(
  const std::vector<double>& observed, const std::vector<double>& probability, double samples)
{
  ChiSquare r;
  double pooledObs = 0.0, pooledExp = 0.0;
  for (std::size_t i = 0; i < observed.size(); ++i)
  {
    pooledObs += observed[i];
    pooledExp += probability[i] * samples;
    if (pooledExp >= 20.0)
    {
      r.Statistic += (pooledObs - pooledExp) * (pooledObs - pooledExp) / pooledExp;
      ++r.DegreesOfFreedom;
      pooledObs = pooledExp = 0.0;
    }
  }
  if (pooledExp > 0.0)
  {
    r.Statistic += (pooledObs - pooledExp) * (pooledObs - pooledExp) / pooledExp;
    ++r.DegreesOfFreedom;
  }
  return r;
}

// Rejects at about 5 standard deviations of the chi-square law (p < 1e-6):
// a correct sampler with a fixed seed passes, a wrong density fails by far.
void ExpectChiSquareAccepts(const ChiSquare& r)
{
  const double k = r.DegreesOfFreedom;
  EXPECT_LT(r.Statistic, k + 5.0 * std::sqrt(2.0 * k)) << "chi-square with " << k << " dof";
}

// Probability of each of `bins` equal cos(theta) bins in [-1, 1] for a density
// p(cos theta) per steradian, by Simpson integration (times 2 pi for phi).
std::vector<double> CosineBinProbabilities(int bins, const std::function<double(double)>& pdf)
{
  std::vector<double> prob(bins);
  const int sub = 200;
  for (int b = 0; b < bins; ++b)
  {
    const double a = -1.0 + 2.0 * b / bins, h = (2.0 / bins) / sub;
    double s = 0.0;
    for (int i = 0; i <= sub; ++i)
    {
      const double w = (i == 0 || i == sub) ? 1.0 : (i % 2 ? 4.0 : 2.0);
      s += w * pdf(a + i * h);
    }
    prob[b] = 2.0 * M_PI * s * h / 3.0;
  }
  return prob;
}

ChiSquare SampleHenyeyGreenstein(float g, int samples, int bins)
{
  const HenyeyGreenstein hg(g);
  Random rng(7, 3);
  std::vector<double> counts(bins, 0.0);
  for (int i = 0; i < samples; ++i)
  {
    // A random incoming direction: the sampled angle is measured from it.
    const Vec3 wi = SampleUniformSphere(rng.NextFloat(), rng.NextFloat());
    const Vec3 wo = hg.Sample(wi, rng.NextFloat(), rng.NextFloat());
    const double c = std::max(-1.0, std::min(1.0, static_cast<double>(Dot(wi, wo))));
    const int b = std::min(bins - 1, static_cast<int>((c + 1.0) * 0.5 * bins));
    counts[b] += 1.0;
  }
  const auto prob =
    CosineBinProbabilities(bins, [&](double c) { return hg.Evaluate(static_cast<float>(c)); });
  return Pearson(counts, prob, samples);
}
}

TEST(Sampling, HenyeyGreensteinIsNormalized)
{
  for (float g : { -0.95f, -0.5f, 0.f, 0.3f, 0.7f, 0.95f })
  {
    const auto prob = CosineBinProbabilities(
      400, [&](double c) { return HenyeyGreenstein(g).Evaluate(static_cast<float>(c)); });
    double total = 0.0;
    for (double p : prob)
    {
      total += p;
    }
    EXPECT_NEAR(total, 1.0, 2e-3) << "g = " << g;
  }
}

TEST(Sampling, HenyeyGreensteinMeanCosineIsG)
{
  for (float g : { -0.7f, 0.f, 0.7f, 0.95f })
  {
    const HenyeyGreenstein hg(g);
    Random rng(11, 0);
    double sum = 0.0;
    const int n = 400000;
    for (int i = 0; i < n; ++i)
    {
      sum += hg.SampleCosTheta(rng.NextFloat());
    }
    // Standard error of the mean cosine is below sqrt(1/n).
    EXPECT_NEAR(sum / n, g, 5.0 / std::sqrt(static_cast<double>(n))) << "g = " << g;
  }
}

TEST(Sampling, HenyeyGreensteinChiSquare)
{
  for (float g : { -0.95f, -0.7f, -0.3f, 0.f, 0.3f, 0.7f, 0.95f })
  {
    SCOPED_TRACE(testing::Message() << "g = " << g);
    ExpectChiSquareAccepts(SampleHenyeyGreenstein(g, 200000, 100));
  }
}

TEST(Sampling, ChiSquareRejectsAWrongAsymmetry)
{
  // The test has power: samples of g = 0.7 against the density of g = 0.65.
  const HenyeyGreenstein sampler(0.7f), wrong(0.65f);
  Random rng(5, 1);
  const int bins = 100, samples = 200000;
  std::vector<double> counts(bins, 0.0);
  for (int i = 0; i < samples; ++i)
  {
    const double c = sampler.SampleCosTheta(rng.NextFloat());
    counts[std::min(bins - 1, static_cast<int>((c + 1.0) * 0.5 * bins))] += 1.0;
  }
  const auto prob =
    CosineBinProbabilities(bins, [&](double c) { return wrong.Evaluate(static_cast<float>(c)); });
  const ChiSquare r = Pearson(counts, prob, samples);
  EXPECT_GT(r.Statistic, r.DegreesOfFreedom + 5.0 * std::sqrt(2.0 * r.DegreesOfFreedom));
}

TEST(Sampling, ForwardPeakKeepsTheMeanCosine)
{
  // Beyond the resolved asymmetry, the peak and the remainder have HG(g)'s
  // mean cosine: Forward * 1 + (1 - Forward) * G = g.
  for (float g : { 0.75f, 0.9f, 0.99f, 0.999f })
  {
    const ForwardPeak peak = SplitForwardPeak(g, 0.7f);
    EXPECT_FLOAT_EQ(peak.G, 0.7f) << "g = " << g;
    EXPECT_GT(peak.Forward, 0.f) << "g = " << g;
    EXPECT_LT(peak.Forward, 1.f) << "g = " << g;
    EXPECT_NEAR(peak.Forward + (1.f - peak.Forward) * peak.G, g, 1e-6f) << "g = " << g;
    EXPECT_FLOAT_EQ(
      peak.Remainder(-0.3f), (1.f - peak.Forward) * HenyeyGreenstein(0.7f).Evaluate(-0.3f));
  }
  // Up to it, and backward, nothing is set apart.
  for (float g : { -0.99f, -0.5f, 0.f, 0.5f, 0.7f })
  {
    const ForwardPeak peak = SplitForwardPeak(g, 0.7f);
    EXPECT_EQ(peak.Forward, 0.f) << "g = " << g;
    EXPECT_EQ(peak.G, g) << "g = " << g;
  }
}

TEST(Sampling, TruncatedForwardPeakIsHenyeyGreensteinBelowItsCap)
{
  // Beyond the cap, only what rises above it is set apart: the remainder is
  // HG(g) itself wherever HG(g) is below the cap (backward above all), and
  // the remainder and the peak together hold all the light.
  const float cap = HenyeyGreenstein(0.7f).Evaluate(1.f);
  for (float g : { 0.75f, 0.8f, 0.9f, 0.99f, 0.999f })
  {
    const ForwardPeak peak = TruncateForwardPeak(g, cap);
    const HenyeyGreenstein hg(g);
    EXPECT_GT(peak.Forward, 0.f) << "g = " << g;
    EXPECT_LT(peak.Forward, 1.f) << "g = " << g;
    double total = 0.0, largest = 0.0;
    const int steps = 200000;
    for (int i = 0; i < steps; ++i)
    {
      // The midpoint rule in cos(theta), finer toward the peak (cos = 1 - t^4).
      const double t0 = static_cast<double>(i) / steps, t1 = static_cast<double>(i + 1) / steps;
      const double c0 = 1.0 - 2.0 * std::pow(t0, 4.0), c1 = 1.0 - 2.0 * std::pow(t1, 4.0);
      const float mu = static_cast<float>(0.5 * (c0 + c1));
      const double r = peak.Remainder(mu);
      total += 2.0 * M_PI * r * (c0 - c1);
      largest = std::max(largest, r);
      if (hg.Evaluate(mu) < 0.99f * cap)
      {
        ASSERT_FLOAT_EQ(peak.Remainder(mu), hg.Evaluate(mu)) << "g = " << g << ", cos " << mu;
      }
    }
    EXPECT_NEAR(total + peak.Forward, 1.0, 1e-4) << "g = " << g;
    EXPECT_LE(largest, cap * (1.0 + 1e-6)) << "g = " << g;
  }
  // Where HG(g) never reaches the cap, and backward, nothing is set apart.
  for (float g : { -0.99f, -0.5f, 0.f, 0.5f, 0.7f })
  {
    const ForwardPeak peak = TruncateForwardPeak(g, cap);
    EXPECT_EQ(peak.Forward, 0.f) << "g = " << g;
    for (float mu : { -1.f, 0.f, 0.5f, 1.f })
    {
      EXPECT_EQ(peak.Remainder(mu), HenyeyGreenstein(g).Evaluate(mu)) << "g = " << g;
    }
  }
}

TEST(Sampling, CosineHemisphereChiSquare)
{
  Random rng(3, 9);
  const int bins = 50, samples = 200000;
  std::vector<double> counts(bins, 0.0);
  for (int i = 0; i < samples; ++i)
  {
    const Vec3 d = SampleCosineHemisphere(rng.NextFloat(), rng.NextFloat());
    ASSERT_GE(d.z, 0.f);
    EXPECT_NEAR(Length(d), 1.f, 1e-5f);
    counts[std::min(bins - 1, static_cast<int>((d.z + 1.0) * 0.5 * bins))] += 1.0;
  }
  const auto prob = CosineBinProbabilities(
    bins, [](double c) { return CosineHemispherePdf(static_cast<float>(c)); });
  ExpectChiSquareAccepts(Pearson(counts, prob, samples));
}

TEST(Sampling, RandomStreamsDependOnlyOnSeedAndIndex)
{
  Random a(42, 1000), b(42, 1000), c(42, 1001), d(43, 1000);
  bool differsC = false, differsD = false;
  for (int i = 0; i < 16; ++i)
  {
    const auto x = a.NextUInt();
    EXPECT_EQ(x, b.NextUInt());
    differsC = differsC || x != c.NextUInt();
    differsD = differsD || x != d.NextUInt();
  }
  EXPECT_TRUE(differsC);
  EXPECT_TRUE(differsD);
}
