// SPDX-License-Identifier: BSD-3-Clause
// BRDF sampling against its density (chi-square) and energy conservation.
#include "brume/Material.h"
#include "brume/Sampling.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace brume;

namespace
{
Material Phong(float diffuse, float specular, float exponent)
{
  Material m;
  m.Type = MaterialType::Phong;
  m.Reflectance = Vec3(diffuse);
  m.Specular = Vec3(specular);
  m.Exponent = exponent;
  return m;
}

// Directions over the hemisphere about n = +z, binned in (cos theta, phi).
struct Bins
{
  int NTheta = 16, NPhi = 32;
  int Index(const Vec3& w) const
  {
    const int i = std::min(NTheta - 1, static_cast<int>(w.z * NTheta));
    double phi = std::atan2(w.y, w.x);
    phi = phi < 0 ? phi + 2 * M_PI : phi;
    const int j = std::min(NPhi - 1, static_cast<int>(phi / (2 * M_PI) * NPhi));
    return i * NPhi + j;
  }
};

void ExpectSamplesFollowPdf(const Material& m, const Vec3& wi)
{
  const Vec3 n(0, 0, 1);
  const Bins bins;
  const int samples = 400000;
  std::vector<double> observed(bins.NTheta * bins.NPhi, 0.0), expected(observed.size(), 0.0);
  Random rng(17, 5);
  int below = 0;
  for (int s = 0; s < samples; ++s)
  {
    Vec3 wo, weight;
    if (!SampleBrdf(m, n, wi, rng, wo, weight))
    {
      ++below; // sampled under the horizon: the pdf there is not counted
      continue;
    }
    ASSERT_GT(wo.z, 0.f);
    observed[bins.Index(wo)] += 1.0;
  }
  // Expected counts: the pdf integrated over each bin (midpoint rule, 48 x 48
  // points per bin: fine enough for a lobe of exponent 200 near the pole).
  const int sub = 48;
  double total = 0.0;
  for (int i = 0; i < bins.NTheta; ++i)
    for (int j = 0; j < bins.NPhi; ++j)
    {
      double p = 0.0;
      for (int a = 0; a < sub; ++a)
        for (int b = 0; b < sub; ++b)
        {
          const double c = (i + (a + 0.5) / sub) / bins.NTheta;
          const double phi = 2 * M_PI * (j + (b + 0.5) / sub) / bins.NPhi;
          const double st = std::sqrt(1 - c * c);
          const Vec3 wo(static_cast<float>(st * std::cos(phi)),
            static_cast<float>(st * std::sin(phi)), static_cast<float>(c));
          p += BrdfPdf(m, n, wi, wo);
        }
      // d(omega) = d(cos theta) d(phi)
      p *= (1.0 / bins.NTheta) * (2 * M_PI / bins.NPhi) / (sub * sub);
      expected[i * bins.NPhi + j] = p * samples;
      total += p;
    }
  // The fraction sampled below the horizon is what the pdf misses.
  EXPECT_NEAR(static_cast<double>(below) / samples, 1.0 - total, 0.01);
  double chi2 = 0.0;
  int dof = -1;
  double pooledO = 0, pooledE = 0;
  for (std::size_t k = 0; k < observed.size(); ++k)
  {
    pooledO += observed[k];
    pooledE += expected[k];
    if (pooledE >= 20.0)
    {
      chi2 += (pooledO - pooledE) * (pooledO - pooledE) / pooledE;
      ++dof;
      pooledO = pooledE = 0;
    }
  }
  EXPECT_LT(chi2, dof + 5.0 * std::sqrt(2.0 * dof))
    << "chi-square " << chi2 << " with " << dof << " dof";
}

// Directional albedo two ways: the mean sampling weight, and
// uniform-hemisphere quadrature. They must agree within four standard
// errors of their difference (the quadrature of a sharp lobe is the noisy
// one), and the weights must not exceed the albedo bound.
void ExpectConsistentAlbedo(const Material& m, const Vec3& wi, double bound)
{
  const Vec3 n(0, 0, 1);
  Random rng(3, 3);
  const int samples = 400000;
  double weights = 0.0, weights2 = 0.0, quadrature = 0.0, quadrature2 = 0.0;
  for (int s = 0; s < samples; ++s)
  {
    Vec3 wo, weight;
    if (SampleBrdf(m, n, wi, rng, wo, weight))
    {
      weights += weight.x;
      weights2 += static_cast<double>(weight.x) * weight.x;
    }
    // Uniform hemisphere: pdf 1/(2 pi).
    Vec3 u = SampleUniformSphere(rng.NextFloat(), rng.NextFloat());
    u.z = std::abs(u.z);
    const double q = EvaluateBrdf(m, n, wi, u).x * u.z * 2 * M_PI;
    quadrature += q;
    quadrature2 += q * q;
  }
  const double N = samples;
  weights /= N;
  quadrature /= N;
  const double varianceOfMeans =
    (weights2 / N - weights * weights) / N + (quadrature2 / N - quadrature * quadrature) / N;
  EXPECT_NEAR(weights, quadrature, 4.0 * std::sqrt(varianceOfMeans));
  EXPECT_LE(weights, bound + 4.0 * std::sqrt(varianceOfMeans)); // energy conservation
}
}

TEST(Material, PhongSamplingFollowsItsDensity)
{
  const Vec3 wi = Normalize(Vec3(0.5f, 0.f, 1.f));
  {
    SCOPED_TRACE("mixed lobes, e = 20");
    ExpectSamplesFollowPdf(Phong(0.3f, 0.6f, 20.f), wi);
  }
  {
    SCOPED_TRACE("specular only, e = 200");
    ExpectSamplesFollowPdf(Phong(0.0f, 0.9f, 200.f), Normalize(Vec3(0.f, 0.2f, 1.f)));
  }
  {
    SCOPED_TRACE("diffuse only");
    ExpectSamplesFollowPdf(Phong(0.7f, 0.0f, 10.f), wi);
  }
}

TEST(Material, LambertianSamplingFollowsItsDensity)
{
  Material m;
  ExpectSamplesFollowPdf(m, Normalize(Vec3(1.f, 1.f, 1.f)));
}

TEST(Material, PhongConservesEnergyAndWeightsMatchTheBrdf)
{
  for (float theta : { 0.f, 0.6f, 1.2f, 1.5f })
  {
    SCOPED_TRACE(testing::Message() << "incidence " << theta);
    const Vec3 wi(std::sin(theta), 0.f, std::cos(theta));
    ExpectConsistentAlbedo(Phong(0.2f, 0.8f, 50.f), wi, 1.0);
    ExpectConsistentAlbedo(Phong(0.5f, 0.5f, 5.f), wi, 1.0);
  }
}

TEST(Material, MirrorReflectsExactly)
{
  Material m;
  m.Type = MaterialType::Mirror;
  m.Reflectance = Vec3(0.f);
  m.Specular = Vec3(0.9f, 0.8f, 0.7f);
  Random rng(1, 1);
  const Vec3 wi = Normalize(Vec3(0.3f, -0.4f, 0.8f));
  Vec3 wo, weight;
  ASSERT_TRUE(SampleBrdf(m, Vec3(0, 0, 1), wi, rng, wo, weight));
  EXPECT_NEAR(wo.x, -wi.x, 1e-6f);
  EXPECT_NEAR(wo.y, -wi.y, 1e-6f);
  EXPECT_NEAR(wo.z, wi.z, 1e-6f);
  EXPECT_EQ(weight.y, 0.8f);
}

TEST(Material, ValidationRejectsUnphysicalMaterials)
{
  EXPECT_EQ(Phong(0.5f, 0.5f, 10.f).Validate(), "");
  EXPECT_NE(Phong(0.6f, 0.5f, 10.f).Validate(), "");
  EXPECT_NE(Phong(0.5f, 0.2f, 0.f).Validate(), "");
  EXPECT_NE(Phong(-0.1f, 0.2f, 1.f).Validate(), "");
  Material nan;
  nan.Emission = Vec3(NAN, 0.f, 0.f);
  EXPECT_NE(nan.Validate(), "");
}
