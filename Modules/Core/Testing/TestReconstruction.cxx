// SPDX-License-Identifier: BSD-3-Clause
// Phase 2 against known answers: exact summed-area tables at large counts,
// density estimation of known distributions, and radiometry against analytic
// irradiance and single scattering.
#include "TestScenes.h"
#include "brume/LightTracer.h"
#include "brume/Random.h"
#include "brume/Reconstruction.h"
#include "brume/Sampling.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <memory>

using namespace brume;

namespace
{
using brume::testing::HitStore;
using brume::testing::Trace;

Surface Wall(float half, const Vec3& reflectance)
{
  // The square |x|, |y| <= half in the plane z = 0, facing +z.
  Surface s;
  s.Name = "wall";
  s.Vertices = { { -half, -half, 0 }, { half, -half, 0 }, { half, half, 0 }, { -half, half, 0 } };
  s.Triangles = { { 0, 1, 2 }, { 0, 2, 3 } };
  s.Mat.Reflectance = reflectance;
  return s;
}
}

TEST(Reconstruction, SummedAreaTableIsExactBeyond2To31Counts)
{
  // 64^3 cells of 9,000 to 11,000 counts: 2.6e9 in all, beyond 2^31.
  Histogram h({ 64, 64, 64 }, 1);
  Random rng(9, 9);
  std::vector<long long> counts(h.GetNumberOfCells());
  long long total = 0;
  for (std::size_t c = 0; c < counts.size(); ++c)
  {
    counts[c] = 9000 + static_cast<long long>(rng.NextUInt() % 2001);
    total += counts[c];
    const double v = static_cast<double>(counts[c]);
    h.Add(c, &v);
  }
  ASSERT_GT(total, 1LL << 31);
  const SummedAreaTable sat(h);
  double whole = 0.0;
  sat.RegionSum({ 0, 0, 0 }, { 64, 64, 64 }, &whole);
  EXPECT_EQ(static_cast<long long>(whole), total);
  // Small regions far from the origin: exact, no cancellation.
  for (int trial = 0; trial < 200; ++trial)
  {
    std::array<int, 3> lo, hi;
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = 32 + static_cast<int>(rng.NextUInt() % 30);
      hi[a] = lo[a] + 1 + static_cast<int>(rng.NextUInt() % 2);
    }
    long long expected = 0;
    for (int k = lo[2]; k < hi[2]; ++k)
      for (int j = lo[1]; j < hi[1]; ++j)
        for (int i = lo[0]; i < hi[0]; ++i)
          expected += counts[h.Index(i, j, k)];
    double got = 0.0;
    sat.RegionSum(lo, hi, &got);
    ASSERT_EQ(got, static_cast<double>(expected));
  }
}

TEST(Reconstruction, LinearGradientIsRecovered)
{
  // Density proportional to 1 + x on [0, 1]^2 (x the first coordinate).
  Histogram h({ 128, 128, 1 }, 1);
  Random rng(4, 4);
  const int n = 2000000;
  const double one = 1.0;
  for (int i = 0; i < n; ++i)
  {
    // Inverse CDF of (1 + x) / 1.5: x = sqrt(1 + 3u) - 1.
    const double x = std::sqrt(1.0 + 3.0 * rng.NextDouble()) - 1.0;
    const auto c = h.CellOf(x, rng.NextDouble(), 0.0);
    h.Add(h.Index(c[0], c[1], 0), &one);
  }
  const SummedAreaTable sat(h);
  AdaptiveRegionSettings settings;
  settings.Refinement = { 8, 8, 1 };
  settings.Threshold = 2000.0;
  for (int i = 0; i < 16; ++i)
  {
    double perCell = 0.0;
    const RegionEstimate r = EstimateTexel(sat, h.GetDimensions(), { i, 7, 0 }, settings, &perCell);
    const double x = (i + 0.5) / 16.0; // the region is symmetric about the texel centre
    const double expected = n * (1.0 + x) / 1.5 / (128.0 * 128.0);
    const double se = std::sqrt(expected * r.Cells) / r.Cells;
    EXPECT_NEAR(perCell, expected, 4.0 * se + 0.01 * expected) << "texel " << i;
  }
}

TEST(Reconstruction, ThresholdTradesVarianceForBias)
{
  // A peaked density (a Gaussian of sigma 0.05 at the centre of [0, 1]^2):
  // a larger threshold lowers the variance of flat regions but widens the
  // regions, which flattens (biases) the peak. Measured over 20 seeds.
  const int texels = 32, refinement = 4, n = 200000;
  std::printf("threshold  peak bias  flat rel. std.dev.\n");
  double previousStd = 1e30, previousBias = 0.0;
  for (double threshold : { 32.0, 256.0, 2048.0, 16384.0 })
  {
    double peakSum = 0.0, flatSum = 0.0, flatSum2 = 0.0;
    const int seeds = 20;
    double peakExpected = 0.0, flatExpected = 0.0;
    for (int seed = 0; seed < seeds; ++seed)
    {
      Histogram h({ texels * refinement, texels * refinement, 1 }, 1);
      Random rng(100 + seed, 1);
      const double one = 1.0;
      for (int i = 0; i < n; ++i)
      {
        double x, y;
        if (i % 2 == 0)
        {
          // Box-Muller around the centre.
          const double r = 0.05 * std::sqrt(-2.0 * std::log(1.0 - rng.NextDouble()));
          const double a = 2 * M_PI * rng.NextDouble();
          x = 0.5 + r * std::cos(a);
          y = 0.5 + r * std::sin(a);
        }
        else
        {
          x = rng.NextDouble();
          y = rng.NextDouble();
        }
        if (x < 0 || x >= 1 || y < 0 || y >= 1)
        {
          continue;
        }
        const auto c = h.CellOf(x, y, 0.0);
        h.Add(h.Index(c[0], c[1], 0), &one);
      }
      const SummedAreaTable sat(h);
      AdaptiveRegionSettings settings;
      settings.Refinement = { refinement, refinement, 1 };
      settings.Threshold = threshold;
      double peak = 0.0, flat = 0.0;
      EstimateTexel(sat, h.GetDimensions(), { texels / 2, texels / 2, 0 }, settings, &peak);
      EstimateTexel(sat, h.GetDimensions(), { 3, 3, 0 }, settings, &flat);
      const double cells = static_cast<double>(texels * refinement) * (texels * refinement);
      // Expected per cell: the uniform half plus the Gaussian's mean over the
      // peak texel, [0.5, 0.5 + 1/32]^2 (the Gaussian's centre at its corner).
      const double half = n / 2.0 / cells;
      const double side = 1.0 / texels;
      const double g = 0.5 * std::erf(side / (0.05 * std::sqrt(2.0)));
      peakExpected = half + n / 2.0 * g * g / (side * side) / cells;
      flatExpected = half;
      peakSum += peak;
      flatSum += flat;
      flatSum2 += flat * flat;
    }
    const double bias = peakSum / seeds / peakExpected - 1.0;
    const double mean = flatSum / seeds;
    const double std = std::sqrt(std::max(0.0, flatSum2 / seeds - mean * mean)) / flatExpected;
    std::printf("%9.0f  %9.3f  %18.4f\n", threshold, bias, std);
    // Variance falls and the peak's (negative) bias grows with the threshold.
    EXPECT_LT(std, previousStd * 1.05);
    EXPECT_LE(bias, previousBias + 0.02);
    if (threshold <= 2048.0)
    {
      EXPECT_LT(std::abs(bias), 0.03); // the peak texel holds that much alone
    }
    else
    {
      EXPECT_LT(bias, -0.05); // its region had to grow off the peak (measured -0.081)
    }
    previousStd = std;
    previousBias = bias;
  }
}

TEST(Reconstruction, DiffuseWallUnderAPointLightShowsRhoEOverPi)
{
  // A point light of intensity I at height h above a Lambertian wall:
  // E = I h / r^3 and L = rho E / pi.
  Scene scene;
  scene.Surfaces = { Wall(1.f, Vec3(0.5f, 0.25f, 0.75f)) };
  Light light;
  light.Type = LightType::Point;
  light.Position = { 0.f, 0.f, 1.f };
  light.Intensity = Vec3(2.f);
  scene.Lights = { light };
  ASSERT_EQ(scene.Validate(), "");
  TraceSettings settings;
  settings.MaxDepth = 1;
  Vec3 power;
  const std::uint64_t particles = 2000000;
  const HitStore store(Trace(scene, particles, settings, &power));
  const int res = 8;
  ObjectRadiance wall(scene.Surfaces[0], MakeChart(scene.Surfaces[0], nullptr), { res, res }, 2);
  std::vector<std::uint32_t> index(store.Object.size());
  for (std::size_t i = 0; i < index.size(); ++i)
  {
    index[i] = static_cast<std::uint32_t>(i);
  }
  // A tiny threshold: every texel keeps its own square.
  ASSERT_EQ(
    wall.Build(store.View(), index.data(), index.size(), { 0, 0, 5 }, 1e-12, SerialFor()), "");
  const auto& L = wall.GetTexture().Radiance;
  const auto& frame = wall.GetLayout().Chart.Frame;
  for (int j = 0; j < res; ++j)
    for (int i = 0; i < res; ++i)
    {
      // The analytic radiance averaged over the texel (8 x 8 points).
      double e = 0.0;
      for (int b = 0; b < 8; ++b)
        for (int a = 0; a < 8; ++a)
        {
          const Vec3 p = frame.Origin + frame.U * ((i + (a + 0.5f) / 8.f) / res) +
            frame.V * ((j + (b + 0.5f) / 8.f) / res);
          const double r = Length(p - light.Position);
          e += 2.0 * 1.0 / (r * r * r) / 64.0;
        }
      // Hits in the texel: about E A / (Phi / N); their count sets the error.
      const double texelArea = 4.0 / (res * res);
      const double expectedHits = e * texelArea / (power.x / particles);
      const double relative = 4.0 / std::sqrt(expectedHits);
      for (int c = 0; c < 3; ++c)
      {
        const double expected = scene.Surfaces[0].Mat.Reflectance[c] / Pi * e;
        EXPECT_NEAR(L[3 * (j * res + i) + c], expected, relative * expected)
          << "texel " << i << "," << j << " channel " << c;
      }
    }
}

TEST(Reconstruction, ThinMediumSingleScatteringMatchesTheAnalyticSource)
{
  // A point light at the centre of a homogeneous medium, single scattering
  // only (MaxDepth 1): J(x) = sigma_s p(w_in . w_o) I exp(-sigma_t r) / r^2,
  // w_in from the light to x, w_o from x to the eye.
  Medium fog;
  fog.Name = "fog";
  fog.Bounds = { Vec3(-1.f), Vec3(1.f) };
  fog.SigmaS = Vec3(0.3f);
  fog.SigmaA = Vec3(0.f);
  fog.G = 0.6f;
  Scene scene;
  scene.Media = { fog };
  Light light;
  light.Type = LightType::Point;
  light.Position = Vec3(0.f);
  light.Intensity = Vec3(1.f);
  scene.Lights = { light };
  ASSERT_EQ(scene.Validate(), "");
  TraceSettings settings;
  settings.MaxDepth = 1;
  const HitStore store(Trace(scene, 3000000, settings));
  const int res = 8;
  ObjectRadiance medium(scene.Media[0], { res, res, res }, 1);
  std::vector<std::uint32_t> index(store.Object.size());
  for (std::size_t i = 0; i < index.size(); ++i)
  {
    index[i] = static_cast<std::uint32_t>(i);
  }
  const Vec3 eye(0.3f, 0.5f, 5.f);
  ASSERT_EQ(medium.Build(store.View(), index.data(), index.size(), eye, 1e-12, SerialFor()), "");
  ASSERT_TRUE(medium.GetLayout().ViewDependent);
  const HenyeyGreenstein phase(fog.G);
  // Compare sums of J over groups of voxels (shells, facing or not the eye).
  double got[6] = { 0 }, expected[6] = { 0 };
  const float voxel = 2.f / res;
  for (int k = 0; k < res; ++k)
    for (int j = 0; j < res; ++j)
      for (int i = 0; i < res; ++i)
      {
        const Vec3 centre = Vec3(-1.f) + Vec3(i + 0.5f, j + 0.5f, k + 0.5f) * voxel;
        const float rc = Length(centre);
        if (rc < 0.5f)
        {
          continue; // near the light the 1/r^2 varies too fast within a voxel
        }
        const int group =
          (rc < 0.9f ? 0 : (rc < 1.3f ? 2 : 4)) + (Dot(centre, eye - centre) > 0.f ? 1 : 0);
        const std::size_t v = (static_cast<std::size_t>(k) * res + j) * res + i;
        got[group] += medium.GetTexture().Radiance[3 * v] *
          medium.GetTexture().Extinction[3 * v]; // J = S sigma_t
        double j0 = 0.0;
        for (int s = 0; s < 64; ++s)
        {
          const Vec3 p = centre +
            Vec3((s % 4 + 0.5f) / 4.f - 0.5f, ((s / 4) % 4 + 0.5f) / 4.f - 0.5f,
              (s / 16 + 0.5f) / 4.f - 0.5f) *
              voxel;
          const double r = Length(p);
          j0 += 0.3 * phase.Evaluate(Dot(p / static_cast<float>(r), Normalize(eye - p))) *
            std::exp(-0.3 * r) / (r * r) / 64.0;
        }
        expected[group] += j0;
      }
  for (int g = 0; g < 6; ++g)
  {
    EXPECT_NEAR(got[g], expected[g], 0.03 * expected[g]) << "group " << g;
  }
}

TEST(Reconstruction, IncrementalViewUpdateEqualsAFullBuild)
{
  Medium fog;
  fog.Name = "fog";
  fog.Bounds = { Vec3(-1.f), Vec3(1.f) };
  fog.G = 0.8f;
  Scene scene;
  scene.Media = { fog };
  Light light;
  light.Type = LightType::Point;
  light.Position = Vec3(0.2f, 0.1f, 0.f);
  scene.Lights = { light };
  const HitStore store(Trace(scene, 100000, TraceSettings()));
  std::vector<std::uint32_t> index(store.Object.size());
  for (std::size_t i = 0; i < index.size(); ++i)
  {
    index[i] = static_cast<std::uint32_t>(i);
  }
  ObjectRadiance incremental(scene.Media[0], { 6, 6, 6 }, 2), full(scene.Media[0], { 6, 6, 6 }, 2);
  const double threshold = 1e-3;
  ASSERT_EQ(incremental.Build(
              store.View(), index.data(), index.size(), { 0, 0, 5 }, threshold, SerialFor()),
    "");
  const std::vector<float> before = incremental.GetTexture().Radiance;
  incremental.UpdateView({ 0.2f, 0.f, 5.f }, SerialFor());
  ASSERT_EQ(full.Build(
              store.View(), index.data(), index.size(), { 0.2f, 0.f, 5.f }, threshold, SerialFor()),
    "");
  EXPECT_EQ(incremental.GetTexture().Radiance, full.GetTexture().Radiance);
  EXPECT_NE(incremental.GetTexture().Radiance, before);
}

TEST(Reconstruction, AtlasOfACurvedSurfaceKeepsTheReflectedPower)
{
  // A closed octahedron (not planar, no texture coordinates) around a point
  // light: every particle lands on it once; the texture must integrate to
  // the reflected power, L = rho E / pi, integral of pi L dA = rho Phi.
  Surface octahedron;
  octahedron.Name = "octahedron";
  octahedron.Vertices = { { 1, 0, 0 }, { -1, 0, 0 }, { 0, 1, 0 }, { 0, -1, 0 }, { 0, 0, 1 },
    { 0, 0, -1 } };
  // Wound inward: the light inside sees the front side of every face.
  octahedron.Triangles = { { 0, 4, 2 }, { 2, 4, 1 }, { 1, 4, 3 }, { 3, 4, 0 }, { 2, 5, 0 },
    { 1, 5, 2 }, { 3, 5, 1 }, { 0, 5, 3 } };
  octahedron.Mat.Reflectance = Vec3(0.5f);
  Scene scene;
  scene.Surfaces = { octahedron };
  Light light;
  light.Type = LightType::Point;
  light.Position = Vec3(0.1f, 0.05f, -0.02f);
  scene.Lights = { light };
  ASSERT_EQ(scene.Validate(), "");
  TraceSettings settings;
  settings.MaxDepth = 1;
  Vec3 power;
  const HitStore store(Trace(scene, 400000, settings, &power));
  const SurfaceChart chart = MakeChart(octahedron, nullptr);
  ASSERT_EQ(chart.Type, SurfaceChart::Kind::Atlas);
  const int res = 48;
  ObjectRadiance radiance(octahedron, chart, { res, res }, 2);
  std::vector<std::uint32_t> index(store.Object.size());
  for (std::size_t i = 0; i < index.size(); ++i)
  {
    index[i] = static_cast<std::uint32_t>(i);
  }
  ASSERT_EQ(
    radiance.Build(store.View(), index.data(), index.size(), { 0, 0, 5 }, 1e-12, SerialFor()), "");
  // Integrate pi L over the surface: each triangle's texels, by their (u, v)
  // area inside the triangle times the world/texture area ratio.
  double integral = 0.0;
  const auto& L = radiance.GetTexture().Radiance;
  for (std::size_t t = 0; t < octahedron.Triangles.size(); ++t)
  {
    const auto& uv = chart.TriangleUV[t];
    const double uvArea =
      0.5 * std::abs((uv[2] - uv[0]) * (uv[5] - uv[1]) - (uv[4] - uv[0]) * (uv[3] - uv[1]));
    const double worldArea = std::sqrt(3.0) / 2.0; // equilateral of side sqrt(2)
    const int samples = 200;
    for (int b = 0; b < samples; ++b)
      for (int a = 0; a < samples - b; ++a)
      {
        const double s = (a + 0.33) / samples, q = (b + 0.33) / samples;
        const double u = uv[0] + s * (uv[2] - uv[0]) + q * (uv[4] - uv[0]);
        const double v = uv[1] + s * (uv[3] - uv[1]) + q * (uv[5] - uv[1]);
        const int i = std::min(res - 1, static_cast<int>(u * res));
        const int j = std::min(res - 1, static_cast<int>(v * res));
        integral += Pi * L[3 * (j * res + i)] * worldArea / (samples * samples / 2.0);
      }
    (void)uvArea;
  }
  EXPECT_NEAR(integral, 0.5 * power.x, 0.03 * 0.5 * power.x);
}

// A heterogeneous medium in two resolutions: the source radiance is the
// sigma_t-weighted mean over a region (RADIOMETRY.md, "Two resolutions in
// one medium"), so a region that spills into the empty half of the box
// keeps the dense half's value instead of being diluted by the empty
// volume; and sigma_t is kept at the density's own resolution.
TEST(Reconstruction, HeterogeneousMediumIsNormalizedByTheExtinctionIntegral)
{
  // The box [0, 1]^3, density 1 on x < 1/2 and 0 beyond (4 x 1 x 1 cells).
  Medium smoke;
  smoke.Name = "smoke";
  smoke.SigmaS = Vec3(2.f);
  smoke.SigmaA = Vec3(0.5f);
  smoke.G = 0.f;
  smoke.SetDensity(std::make_shared<GridDensity>(Box{ Vec3(0.f), Vec3(1.f) },
    std::array<int, 3>{ 4, 1, 1 }, std::vector<float>{ 1.f, 1.f, 0.f, 0.f }, true));
  // Hits on a regular lattice of the dense half, each of flux phi.
  const int n = 10;
  const float phi = 1e-3f;
  HitStore store;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
      {
        const float p[3] = { (i + 0.5f) * 0.5f / n, (j + 0.5f) / n, (k + 0.5f) / n };
        store.Position.insert(store.Position.end(), p, p + 3);
        store.Direction.insert(store.Direction.end(), { 0.f, 0.f, 1.f });
        store.Flux.insert(store.Flux.end(), { phi, phi, phi });
        store.Object.push_back(0);
        store.Triangle.push_back(0);
      }
  std::vector<std::uint32_t> index(store.Object.size());
  for (std::size_t i = 0; i < index.size(); ++i)
  {
    index[i] = static_cast<std::uint32_t>(i);
  }
  // Two texels along x; a threshold above the total flux grows every region
  // to the whole box, half of it empty.
  ObjectRadiance radiance(smoke, { 2, 1, 1 }, 2);
  const double total = static_cast<double>(n) * n * n * phi;
  ASSERT_EQ(radiance.Build(store.View(), index.data(), index.size(), Vec3(0.f, 0.f, 5.f),
              2.0 * total, SerialFor()),
    "");
  // S = albedo sum(p phi) / integral of sigma_t = (sigma_s/sigma_t) total / (4 pi sigma_t / 2).
  const double sigmaT = 2.5, albedo = 2.0 / 2.5;
  const double expected = albedo * total / (4.0 * Pi) / (sigmaT * 0.5);
  for (int t = 0; t < 2; ++t)
  {
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_NEAR(radiance.GetTexture().Radiance[3 * t + c], expected, 1e-5 * expected)
        << "texel " << t << ", channel " << c;
    }
  }
  // The density at its own resolution: 4 x 1 x 1 cells.
  EXPECT_EQ(radiance.GetNative().GetResolution(), (std::array<int, 3>{ 4, 1, 1 }));
  ASSERT_FALSE(radiance.GetNative().GetDensity().Empty());
  for (int cell = 0; cell < 4; ++cell)
  {
    EXPECT_FLOAT_EQ(radiance.GetNative().GetDensity().At(cell, 0, 0), cell < 2 ? 1.f : 0.f);
  }
  // A homogeneous medium has no second grid.
  Medium fog = smoke;
  fog.SetDensity(nullptr);
  ObjectRadiance homogeneous(fog, { 2, 1, 1 }, 2);
  ASSERT_EQ(homogeneous.Build(store.View(), index.data(), index.size(), Vec3(0.f, 0.f, 5.f),
              2.0 * total, SerialFor()),
    "");
  EXPECT_TRUE(homogeneous.GetNative().GetDensity().Empty());
}

TEST(Reconstruction, LargeHistogramsBinByRangesOfCellsToTheSameSums)
{
  // A wall and an isotropic medium with histograms beyond the caches (over
  // 2 MB: 512 x 512 and 64^3 cells) are binned range of cells by range; the
  // sums must be those of the hits added one by one (doubles, in hit order:
  // the same up to their rounding), and nothing may be lost: a 4 x 4 wall's
  // histogram takes the hits in hit order.
  const std::uint64_t particles = 200000;
  Medium fog;
  fog.Name = "fog";
  fog.Bounds = { Vec3(-1.f), Vec3(1.f) };
  fog.SigmaS = Vec3(0.5f);
  fog.SigmaA = Vec3(0.1f);
  fog.G = 0.f; // view independent: binned in place
  Scene scene;
  scene.Surfaces = brume::testing::ClosedBox(Material());
  for (Surface& s : scene.Surfaces)
  {
    s.Mat.Reflectance = Vec3(0.5f, 0.25f, 0.75f);
  }
  scene.Media = { fog };
  Light light;
  light.Type = LightType::Point;
  light.Position = Vec3(0.2f, 0.1f, -0.3f);
  light.Intensity = Vec3(1.f);
  scene.Lights = { light };
  ASSERT_EQ(scene.Validate(), "");
  const HitStore store(Trace(scene, particles, TraceSettings()));
  const HitArrays hits = store.View();
  std::vector<std::uint32_t> wallHits, fogHits;
  for (std::size_t i = 0; i < store.Object.size(); ++i)
  {
    if (store.Object[i] == 0)
    {
      wallHits.push_back(static_cast<std::uint32_t>(i));
    }
    else if (store.Object[i] == 6)
    {
      fogHits.push_back(static_cast<std::uint32_t>(i));
    }
  }
  ASSERT_GT(wallHits.size(), 10000u);
  ASSERT_GT(fogHits.size(), 10000u);

  // Expected sums in doubles, with the cell found as the binning does.
  auto expect = [&](const std::vector<std::uint32_t>& index, const std::array<int, 3>& dims,
                  auto cellOf, auto value, std::vector<double>& w, std::vector<double>& v)
  {
    const std::size_t cells = static_cast<std::size_t>(dims[0]) * dims[1] * dims[2];
    w.assign(cells, 0.0);
    v.assign(3 * cells, 0.0);
    for (const std::uint32_t i : index)
    {
      const float* f = &store.Flux[3 * i];
      const std::size_t c = cellOf(i);
      w[c] += (static_cast<double>(f[0]) + f[1] + f[2]) / 3.0;
      for (int k = 0; k < 3; ++k)
      {
        v[3 * c + k] += value(k) * static_cast<double>(f[k]);
      }
    }
  };
  auto compare = [](const Histogram& got, const std::vector<double>& expected, const char* what)
  {
    ASSERT_EQ(got.GetValues().size(), expected.size()) << what;
    double total = 0.0, largest = 0.0;
    for (std::size_t c = 0; c < expected.size(); ++c)
    {
      total += expected[c];
      largest = std::max(largest, std::abs(got.GetValues()[c] - expected[c]));
    }
    ASSERT_GT(total, 0.0) << what;
    EXPECT_LT(largest, 1e-12 * total) << what;
  };
  auto cellIndex = [](double q, int n)
  { return std::clamp(static_cast<int>(std::floor(q * n)), 0, n - 1); };

  // The medium: 64^3 cells (texture 32^3, refinement 2).
  ObjectRadiance medium(scene.Media[0], { 32, 32, 32 }, 2);
  ASSERT_EQ(
    medium.Build(hits, fogHits.data(), fogHits.size(), Vec3(0.f, 0.f, 5.f), 1e-12, SerialFor()),
    "");
  std::vector<double> w, v;
  expect(
    fogHits, { 64, 64, 64 },
    [&](std::uint32_t i)
    {
      int c[3];
      for (int a = 0; a < 3; ++a)
      {
        c[a] = cellIndex((store.Position[3 * i + a] + 1.0f) / 2.0f, 64);
      }
      return (static_cast<std::size_t>(c[2]) * 64 + c[1]) * 64 + c[0];
    },
    [](int) { return static_cast<double>(Inv4Pi); }, w, v);
  compare(medium.GetBinning().GetWeightHistogram(), w, "medium weights");
  compare(medium.GetBinning().GetValueHistogram(), v, "medium values");

  // The wall (the box's face y = -1, seen from inside): 512 x 512 cells,
  // then 4 x 4 (the in-order path), hits from the front side only.
  const Surface& wall = scene.Surfaces[0];
  const SurfaceChart chart = MakeChart(wall, nullptr);
  ASSERT_EQ(chart.Type, SurfaceChart::Kind::Planar);
  const Vec3 normal =
    Normalize(Cross(wall.Vertices[wall.Triangles[0][1]] - wall.Vertices[wall.Triangles[0][0]],
      wall.Vertices[wall.Triangles[0][2]] - wall.Vertices[wall.Triangles[0][0]]));
  std::vector<std::uint32_t> front;
  for (const std::uint32_t i : wallHits)
  {
    if (Dot(normal,
          Vec3(store.Direction[3 * i], store.Direction[3 * i + 1], store.Direction[3 * i + 2])) <
      0.f)
    {
      front.push_back(i);
    }
  }
  for (const int res : { 256, 2 })
  {
    ObjectRadiance radiance(wall, chart, { res, res }, 2);
    ASSERT_EQ(radiance.Build(
                hits, wallHits.data(), wallHits.size(), Vec3(0.f, 0.f, 5.f), 1e-12, SerialFor()),
      "");
    const int n = 2 * res;
    const float uu = Dot(chart.Frame.U, chart.Frame.U), vv = Dot(chart.Frame.V, chart.Frame.V);
    expect(
      front, { n, n, 1 },
      [&](std::uint32_t i)
      {
        const Vec3 d =
          Vec3(store.Position[3 * i], store.Position[3 * i + 1], store.Position[3 * i + 2]) -
          chart.Frame.Origin;
        return static_cast<std::size_t>(cellIndex(Dot(d, chart.Frame.V) / vv, n)) * n +
          cellIndex(Dot(d, chart.Frame.U) / uu, n);
      },
      [&](int k) { return static_cast<double>(wall.Mat.Reflectance[k] * InvPi); }, w, v);
    compare(radiance.GetBinning().GetWeightHistogram(), w,
      res > 2 ? "large wall weights" : "small wall weights");
    compare(radiance.GetBinning().GetValueHistogram(), v,
      res > 2 ? "large wall values" : "small wall values");
  }
}

TEST(Reconstruction, HitsOnAndBeyondTheCellBoundariesBinWhereFloorPutsThem)
{
  // A medium's box [0, 1]^3 in 4 x 4 x 4 histogram cells (texture 2^3,
  // refinement 2): a hit's cell along each axis is floor(4 q) clamped to
  // [0, 3], on the faces between cells (q = 0.25: cell 1), on the box's
  // lower and upper faces (q = 0: cell 0, q = 1: cell 3), just below and
  // above them and far beyond (clamped), and at the largest float below a
  // face (the cell before it).
  Medium fog;
  fog.Name = "fog";
  fog.Bounds = { Vec3(0.f), Vec3(1.f) };
  fog.SigmaS = Vec3(0.5f);
  fog.G = 0.f;
  ASSERT_EQ(fog.Validate(), "");
  const float below = std::nextafter(0.5f, 0.f);
  const std::vector<std::array<float, 4>> cases = {
    // x, y, z, and the expected cell along each (all three the same).
    { 0.f, 0.f, 0.f, 0 },
    { 0.25f, 0.25f, 0.25f, 1 },
    { 0.5f, 0.5f, 0.5f, 2 },
    { below, below, below, 1 },
    { 0.75f, 0.75f, 0.75f, 3 },
    { 1.f, 1.f, 1.f, 3 },
    { -1e-7f, -1e-7f, -1e-7f, 0 },
    { 1.0000001f, 1.0000001f, 1.0000001f, 3 },
    { -1e30f, -1e30f, -1e30f, 0 },
    { 1e30f, 1e30f, 1e30f, 3 },
  };
  for (const auto& c : cases)
  {
    HitStore store;
    // The hit of interest, then one in cell (0, 0, 3) to tell the axes apart.
    store.Position = { c[0], c[1], c[2], 0.1f, 0.1f, 0.9f };
    store.Direction = { 0.f, 0.f, 1.f, 0.f, 0.f, 1.f };
    store.Flux = { 1.f, 1.f, 1.f, 2.f, 2.f, 2.f };
    store.Object = { 0, 0 };
    store.Triangle = { 0, 0 };
    store.Emitter = { 0, 0 };
    store.Depth = { 1, 1 };
    const std::uint32_t index[2] = { 0, 1 };
    ObjectRadiance medium(fog, { 2, 2, 2 }, 2);
    ASSERT_EQ(medium.Build(store.View(), index, 2, Vec3(0.f, 0.f, 5.f), 1e-12, SerialFor()), "");
    const Histogram weights = medium.GetBinning().GetWeightHistogram();
    ASSERT_EQ(weights.GetValues().size(), 64u);
    const auto cell = static_cast<std::size_t>(c[3]);
    const std::size_t expected = (cell * 4 + cell) * 4 + cell;
    const std::size_t other = (3 * 4 + 0) * 4 + 0;
    for (std::size_t k = 0; k < 64; ++k)
    {
      const double want = (k == expected ? 1.0 : 0.0) + (k == other ? 2.0 : 0.0);
      EXPECT_DOUBLE_EQ(weights.GetValues()[k], want) << "hit at " << c[0] << ", cell " << k;
    }
  }
}

TEST(Reconstruction, ADenseMediumsVoxelsAreCutToItsMeanFreePath)
{
  // Voxels of 1/4 m, the densest 2: voxels per mean free path 0.5 sigma_t.
  std::vector<float> values(64, 0.f);
  values[5] = 2.f;
  values[6] = 1.f;
  Medium medium;
  medium.SigmaA = Vec3(0.f);
  medium.SigmaS = Vec3(1.f);
  // Particles' texels finer than the voxels (7 for 4 along y).
  const std::array<int, 3> fine{ 4, 7, 4 }, coarse{ 4, 4, 3 };
  EXPECT_EQ(MediumVoxelRefinement(medium, fine), 1); // homogeneous
  medium.SetDensity(std::make_shared<GridDensity>(
    Box{ Vec3(0.f), Vec3(1.f) }, std::array<int, 3>{ 4, 4, 4 }, values, true));
  EXPECT_EQ(MediumVoxelRefinement(medium, fine), 1); // a voxel is half a mean free path
  medium.SigmaS = Vec3(2.9f, 1.f, 1.f);              // 1.45 voxels a mean free path: rounded to 1
  EXPECT_EQ(MediumVoxelRefinement(medium, fine), 1);
  medium.SigmaS = Vec3(1.f, 3.1f, 1.f); // the densest channel's: 1.55, cut in two
  EXPECT_EQ(MediumVoxelRefinement(medium, fine), 2);
  medium.SigmaS = Vec3(100.f);
  EXPECT_EQ(MediumVoxelRefinement(medium, fine), MaxVoxelRefinement);
  // Not finer than the particles resolve: texels of a voxel or more keep it whole.
  EXPECT_EQ(MediumVoxelRefinement(medium, coarse), 1);
}

TEST(Reconstruction, DenseMediaCountTheirTexelsWhereTheyAre)
{
  // A unit box, a quarter of whose 4^3 cells hold density 2.
  std::vector<float> values(64, 0.f);
  for (int c = 0; c < 16; ++c)
  {
    values[static_cast<std::size_t>(4 * c)] = 2.f;
  }
  auto density = std::make_shared<GridDensity>(
    Box{ Vec3(0.f), Vec3(1.f) }, std::array<int, 3>{ 4, 4, 4 }, values, true);
  EXPECT_DOUBLE_EQ(density->OccupiedFraction(), 0.25);
  EXPECT_DOUBLE_EQ(density->MeanOccupiedDensity(), 2.0);

  Medium medium;
  medium.SigmaA = Vec3(0.f);
  medium.G = 0.f;
  const std::size_t hits = 64000;
  const double threshold = 100.0;
  const double boxEdge = std::cbrt(threshold / static_cast<double>(hits));
  // Homogeneous: the threshold, whatever its density.
  medium.SigmaS = Vec3(100.f);
  EXPECT_EQ(MediumHitsPerTexel(medium, hits, threshold), threshold);
  medium.SetDensity(density);
  // Dense (a mean free path of 1/200 m): texels counted over the occupied quarter.
  EXPECT_DOUBLE_EQ(MediumHitsPerTexel(medium, hits, threshold), 0.25 * threshold);
  // Thin (5 m): the box's texels.
  medium.SigmaS = Vec3(0.1f);
  EXPECT_DOUBLE_EQ(MediumHitsPerTexel(medium, hits, threshold), threshold);
  // In between: texels of the mean free path's size, 0.8 of the box's edge.
  medium.SigmaS = Vec3(static_cast<float>(1.0 / (0.8 * boxEdge) / 2.0));
  const double sigmaT = medium.SigmaT()[0] * 2.0;
  const double ratio = 1.0 / sigmaT / boxEdge;
  EXPECT_NEAR(ratio, 0.8, 1e-6);
  EXPECT_NEAR(MediumHitsPerTexel(medium, hits, threshold), threshold * ratio * ratio * ratio,
    1e-9 * threshold);
  // Forward scattering lengthens the transport mean free path: back to the box's texels
  // at g = 0.9 (0.8 / 0.1 = 8 box edges).
  medium.G = 0.9f;
  EXPECT_DOUBLE_EQ(MediumHitsPerTexel(medium, hits, threshold), threshold);
  // No hits: the threshold (ChooseResolution keeps its minimum).
  EXPECT_EQ(MediumHitsPerTexel(medium, 0, threshold), threshold);
}

TEST(Reconstruction, MediaTexelsFollowWhereTheHitsAre)
{
  // A unit box: its pilot grid is 16^3 near-cubic cells; a flat box's
  // cells stay near-cubic too.
  const Box box{ Vec3(0.f), Vec3(1.f) };
  EXPECT_EQ(PilotGridResolution(box), (std::array<int, 3>{ 16, 16, 16 }));
  const std::array<int, 3> flat = PilotGridResolution(Box{ Vec3(0.f), Vec3(4.f, 1.f, 1.f) });
  EXPECT_NEAR(4.0 * flat[1] / flat[0], 1.0, 0.2);

  // Hits spread over a part of the box, as positions of a HitArrays.
  auto concentrationOf = [&](int n, float xMax, float yMax)
  {
    Random rng(3, 4);
    std::vector<float> positions(3 * static_cast<std::size_t>(n));
    std::vector<std::uint32_t> index(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i)
    {
      positions[3 * i] = xMax * rng.NextFloat();
      positions[3 * i + 1] = yMax * rng.NextFloat();
      positions[3 * i + 2] = rng.NextFloat();
      index[i] = static_cast<std::uint32_t>(i);
    }
    HitArrays hits;
    hits.Position = positions.data();
    hits.Count = static_cast<std::size_t>(n);
    std::vector<std::int64_t> counts, threaded;
    CountHitsOverPilotGrid(hits, index.data(), index.size(), box, counts);
    EXPECT_EQ(counts.size(), 4096u);
    // Counted in chunks on threads (ranges handed out last first): the same.
    CountHitsOverPilotGrid(
      hits, index.data(), index.size(), box, threaded, brume::testing::ThreadedFor(3, 5));
    EXPECT_EQ(threaded, counts);
    std::int64_t total = 0;
    for (const std::int64_t c : counts)
    {
      total += c;
    }
    EXPECT_EQ(total, n);
    return HitConcentration(counts);
  };
  // Evenly spread: 1, few hits or many (sum n(n - 1) is unbiased for Poisson counts).
  EXPECT_NEAR(concentrationOf(200000, 1.f, 1.f), 1.0, 0.01);
  EXPECT_NEAR(concentrationOf(3000, 1.f, 1.f), 1.0, 0.06);
  // A quarter of the box: 4 (its texel count is multiplied by 4).
  EXPECT_NEAR(concentrationOf(200000, 0.5f, 0.5f), 4.0, 0.05);
  // A sixteenth: past the cap.
  EXPECT_EQ(concentrationOf(200000, 0.25f, 0.25f), MaxHitConcentration);

  // Equal counts in every cell, or no hits at all: 1.
  EXPECT_EQ(HitConcentration(std::vector<std::int64_t>(4096, 5)), 1.0);
  EXPECT_EQ(HitConcentration(std::vector<std::int64_t>(4096, 0)), 1.0);
  // All of them in one of two cells: 2 (n(n - 1) / n^2 times 2 cells, just under).
  EXPECT_NEAR(HitConcentration({ 1000, 0 }), 2.0, 0.01);
  // Hits on the box's far faces count in its edge cells.
  const float corner[3] = { 1.f, 1.f, 1.f };
  const std::uint32_t zero = 0;
  HitArrays one;
  one.Position = corner;
  one.Count = 1;
  std::vector<std::int64_t> counts;
  CountHitsOverPilotGrid(one, &zero, 1, box, counts);
  EXPECT_EQ(counts.back(), 1);
}

TEST(Reconstruction, SurfaceTexelsFollowWhereTheScatteredLightIs)
{
  // A 4 x 1 plane: its pilot grid has near-square cells, about 4,096.
  PlanarFrame frame;
  frame.Origin = Vec3(0.f);
  frame.U = Vec3(4.f, 0.f, 0.f);
  frame.V = Vec3(0.f, 0.f, 1.f);
  frame.Normal = Vec3(0.f, 1.f, 0.f);
  const std::array<int, 3> res = PilotGridResolution(frame);
  EXPECT_EQ(res[2], 1);
  EXPECT_NEAR(4.0 * res[1] / res[0], 1.0, 0.1);
  EXPECT_NEAR(res[0] * res[1], 4096, 300);
  // Hits over [0, uMax) x [0, 1) of the frame; every other one a particle's
  // first interaction after the delta light of emitter 7 (the direct
  // light's), spread over the whole plane wherever the others are.
  auto concentrationOf = [&](int n, float uMax, std::size_t deltaLights)
  {
    Random rng(5, 6);
    std::vector<float> positions(3 * static_cast<std::size_t>(n));
    std::vector<std::uint32_t> index(static_cast<std::size_t>(n));
    std::vector<std::uint16_t> emitter(static_cast<std::size_t>(n));
    std::vector<std::uint8_t> depth(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i)
    {
      const bool direct = i % 2 == 1;
      positions[3 * i] = 4.f * (direct ? 1.f : uMax) * rng.NextFloat();
      positions[3 * i + 1] = 0.f;
      positions[3 * i + 2] = rng.NextFloat();
      emitter[i] = direct ? 7 : 2;
      depth[i] = direct ? 0 : 1;
      index[i] = static_cast<std::uint32_t>(i);
    }
    HitArrays hits;
    hits.Position = positions.data();
    hits.Emitter = emitter.data();
    hits.Depth = depth.data();
    hits.Count = static_cast<std::size_t>(n);
    std::vector<std::int64_t> counts;
    CountHitsOverPilotGrid(hits, index.data(), index.size(), frame, 7, deltaLights, counts);
    EXPECT_EQ(counts.size(), static_cast<std::size_t>(res[0] * res[1]));
    return HitConcentration(counts);
  };
  // The scattered light over a quarter of the plane: 4 once the direct
  // light's hits are left out. Counted with them, the density is 2.5 n on
  // the quarter and 0.5 n elsewhere: (0.25 * 2.5^2 + 0.75 * 0.5^2) = 1.75.
  EXPECT_NEAR(concentrationOf(400000, 0.25f, 1), 4.0, 0.1);
  EXPECT_NEAR(concentrationOf(400000, 0.25f, 0), 1.75, 0.05);
  // Evenly lit: 1.
  EXPECT_NEAR(concentrationOf(400000, 1.f, 1), 1.0, 0.02);
}

namespace
{
// A closed box of Phong walls (view dependent) around a cube of anisotropic
// fog, lit by a point light: every object keeps its hits unless its view is fixed.
Scene GlossyFogScene()
{
  Material phong;
  phong.Type = MaterialType::Phong;
  phong.Reflectance = Vec3(0.4f, 0.5f, 0.3f);
  phong.Specular = Vec3(0.3f);
  phong.Exponent = 12.f;
  Scene scene;
  scene.Surfaces = brume::testing::ClosedBox(phong);
  Medium fog;
  fog.Name = "fog";
  fog.Bounds = { Vec3(-0.5f), Vec3(0.5f) };
  fog.G = 0.85f; // a peak set apart: the remainder's phase function weighs the hits
  scene.Media = { fog };
  Light light;
  light.Type = LightType::Point;
  light.Position = Vec3(0.2f, 0.7f, 0.1f);
  scene.Lights = { light };
  return scene;
}

// 60,000 particles of GlossyFogScene(), their hits grouped by object, an
// eye, the particle flux and a threshold of 64 particles.
struct GlossyFogRun
{
  static constexpr std::uint64_t Particles = 60000;
  Scene Setting = GlossyFogScene();
  Vec3 Power;
  HitStore Store{ Trace(Setting, Particles, TraceSettings(), &Power) };
  ObjectHits Groups;
  std::string GroupError = GroupHitsByObject(Store.View(), Setting.NumberOfObjects(), Groups);
  Vec3 Eye{ 0.3f, -0.2f, 0.9f };
  double ParticleFlux = (Power.x + Power.y + Power.z) / 3.0 / static_cast<double>(Particles);
  double Threshold = 64.0 * ParticleFlux;
};

std::vector<std::unique_ptr<ObjectRadiance>> GlossyFogObjects(const Scene& scene)
{
  std::vector<std::unique_ptr<ObjectRadiance>> objects;
  for (const Surface& s : scene.Surfaces)
  {
    objects.emplace_back(new ObjectRadiance(s, MakeChart(s, nullptr), { 12, 12 }, 2));
  }
  objects.emplace_back(new ObjectRadiance(scene.Media[0], { 8, 8, 8 }, 2));
  return objects;
}
}

TEST(Reconstruction, AFixedViewBinsToTheTexturesOfKeptHitsBitForBit)
{
  // What a fixed view bins as the hits come must be what kept hits give
  // toward the same eye, bit for bit: in one build, and in batches whose
  // last estimates (the hits of the earlier ones no longer held).
  const GlossyFogRun run;
  const Scene& scene = run.Setting;
  ASSERT_EQ(scene.Validate(), "");
  ASSERT_EQ(run.GroupError, "");
  const HitArrays hits = run.Store.View();
  const ObjectHits& groups = run.Groups;
  const Vec3 eye = run.Eye;
  const double particleFlux = run.ParticleFlux, threshold = run.Threshold;
  const auto kept = GlossyFogObjects(scene);
  const auto fixed = GlossyFogObjects(scene);
  const auto batched = GlossyFogObjects(scene);
  // Batches: the first half of the hits, then the second (hit order).
  for (std::size_t o = 0; o < kept.size(); ++o)
  {
    ASSERT_TRUE(kept[o]->GetLayout().ViewDependent) << o;
    const std::uint32_t* index = groups.Index.data() + groups.Offset[o];
    const std::size_t count = groups.Offset[o + 1] - groups.Offset[o];
    ASSERT_GT(count, 1000u) << o;
    for (auto* set : { &kept, &fixed, &batched })
    {
      (*set)[o]->Options().ParticleFlux = particleFlux;
    }
    fixed[o]->FixView(eye);
    batched[o]->FixView(eye);
    EXPECT_TRUE(fixed[o]->GetBinning().IsViewFixed());
    EXPECT_FALSE(fixed[o]->GetBinning().KeepsHits());
    EXPECT_TRUE(kept[o]->GetBinning().KeepsHits());
    ASSERT_EQ(kept[o]->Build(hits, index, count, eye, threshold, SerialFor()), "");
    ASSERT_EQ(fixed[o]->Build(hits, index, count, eye, threshold, SerialFor()), "");
    const std::size_t half = count / 2;
    ASSERT_EQ(batched[o]->Build(hits, index, half, eye, threshold, SerialFor(), false), "");
    ASSERT_EQ(batched[o]->Add(hits, index + half, count - half, 1.0, eye, threshold,
                brume::testing::ThreadedFor(2, 7)),
      "");
    EXPECT_EQ(fixed[o]->GetTexture().Radiance, kept[o]->GetTexture().Radiance) << o;
    EXPECT_EQ(batched[o]->GetTexture().Radiance, kept[o]->GetTexture().Radiance) << o;
    EXPECT_EQ(fixed[o]->GetTexture().Extinction, kept[o]->GetTexture().Extinction) << o;
  }
  // The texture is the eye's: another eye's differs (the test can fail).
  ASSERT_EQ(kept.back()->UpdateView(Vec3(-0.9f, 0.1f, 0.2f), SerialFor()), "");
  EXPECT_NE(kept.back()->GetTexture().Radiance, fixed.back()->GetTexture().Radiance);
}

TEST(Reconstruction, AnObjectBinnedOnEveryThreadHasTheSumsOfOneThread)
{
  // ObjectOptions::BinOnEveryThread: the hits split between threads that
  // add atomically into the same exact sums give the bits of one thread's
  // pass in hit order, whatever the split (fixed views: binned in place).
  const GlossyFogRun run;
  ASSERT_EQ(run.GroupError, "");
  const HitArrays hits = run.Store.View();
  const ObjectHits& groups = run.Groups;
  const auto one = GlossyFogObjects(run.Setting);
  const auto every = GlossyFogObjects(run.Setting);
  for (std::size_t o = 0; o < one.size(); ++o)
  {
    const std::uint32_t* index = groups.Index.data() + groups.Offset[o];
    const std::size_t count = groups.Offset[o + 1] - groups.Offset[o];
    ASSERT_GT(count, 1000u) << o;
    for (auto* set : { &one, &every })
    {
      (*set)[o]->Options().ParticleFlux = run.ParticleFlux;
      (*set)[o]->FixView(run.Eye);
    }
    every[o]->Options().BinOnEveryThread = true;
    ASSERT_EQ(one[o]->Build(hits, index, count, run.Eye, run.Threshold, SerialFor()), "");
    for (const ParallelFor& parallelFor :
      { brume::testing::ThreadedFor(3, 7), brume::testing::ThreadedFor(4, 1000) })
    {
      ASSERT_EQ(every[o]->BuildHits(hits, index, count, run.Eye, run.Threshold, parallelFor), "");
      // What was binned, then what is estimated from it (on one thread).
      EXPECT_EQ(every[o]->GetBinning().GetWeightHistogram().GetValues(),
        one[o]->GetBinning().GetWeightHistogram().GetValues())
        << o;
      EXPECT_EQ(every[o]->GetBinning().GetValueHistogram().GetValues(),
        one[o]->GetBinning().GetValueHistogram().GetValues())
        << o;
      ASSERT_EQ(every[o]->Finish(run.Eye, SerialFor()), "");
      EXPECT_EQ(every[o]->GetTexture().Radiance, one[o]->GetTexture().Radiance) << o;
    }
  }
  // The sums hold every hit: half of them bin to other sums (the test can fail).
  const std::size_t count = groups.Offset[1] - groups.Offset[0];
  ASSERT_EQ(every[0]->BuildHits(hits, groups.Index.data(), count / 2, run.Eye, run.Threshold,
              brume::testing::ThreadedFor(3, 7)),
    "");
  EXPECT_NE(every[0]->GetBinning().GetWeightHistogram().GetValues(),
    one[0]->GetBinning().GetWeightHistogram().GetValues());
}

TEST(Reconstruction, KeptHitsInBatchesKeepTheirTrianglesAndGrowthScales)
{
  // Kept hits hold a surface's triangle and, once a light was aimed, each
  // hit's growth scale beside them: batches (held, then merged) must give
  // the textures of one build, also when the first batch's hits have no
  // aim classes and the second's do (the first batch's scales are then 1),
  // and toward a fixed eye the same bits.
  const GlossyFogRun run;
  const Scene& scene = run.Setting;
  ASSERT_EQ(scene.Validate(), "");
  ASSERT_EQ(run.GroupError, "");
  const HitStore& store = run.Store;
  const ObjectHits& groups = run.Groups;
  // Aim classes: none for the first half of every object's hits (class 0,
  // scale 1), then classes 1 and 2 (scales 0.5 and 3) by turns.
  std::vector<std::uint8_t> aim(store.Object.size(), 0);
  for (std::size_t o = 0; o + 1 < groups.Offset.size(); ++o)
  {
    const std::size_t count = groups.Offset[o + 1] - groups.Offset[o];
    for (std::size_t k = count / 2; k < count; ++k)
    {
      aim[groups.Index[groups.Offset[o] + k]] = static_cast<std::uint8_t>(1 + k % 2);
    }
  }
  std::vector<double> scales(3 * 65536);
  for (std::size_t e = 0; e < 65536; ++e)
  {
    scales[3 * e] = 1.0;
    scales[3 * e + 1] = 0.5;
    scales[3 * e + 2] = 3.0;
  }
  HitArrays aimed = store.View();
  aimed.Aim = aim.data();
  aimed.GrowthScales = scales.data();
  const HitArrays unaimed = store.View();
  const Vec3 eye = run.Eye;
  const double particleFlux = run.ParticleFlux, threshold = run.Threshold;
  const auto once = GlossyFogObjects(scene);
  const auto batched = GlossyFogObjects(scene);
  const auto fixed = GlossyFogObjects(scene);
  const auto plain = GlossyFogObjects(scene);
  for (std::size_t o = 0; o < once.size(); ++o)
  {
    const std::uint32_t* index = groups.Index.data() + groups.Offset[o];
    const std::size_t count = groups.Offset[o + 1] - groups.Offset[o];
    const std::size_t half = count / 2;
    for (auto* set : { &once, &batched, &fixed, &plain })
    {
      (*set)[o]->Options().ParticleFlux = particleFlux;
    }
    fixed[o]->FixView(eye);
    ASSERT_EQ(once[o]->Build(aimed, index, count, eye, threshold, SerialFor()), "");
    ASSERT_EQ(plain[o]->Build(unaimed, index, count, eye, threshold, SerialFor()), "");
    for (auto* set : { &batched, &fixed })
    {
      ASSERT_EQ((*set)[o]->Build(unaimed, index, half, eye, threshold, SerialFor(), false), "");
      ASSERT_EQ((*set)[o]->Add(aimed, index + half, count - half, 1.0, eye, threshold,
                  brume::testing::ThreadedFor(2, 7)),
        "");
    }
    EXPECT_EQ(batched[o]->GetTexture().Radiance, once[o]->GetTexture().Radiance) << o;
    EXPECT_EQ(fixed[o]->GetTexture().Radiance, once[o]->GetTexture().Radiance) << o;
    // The regions grow by the weights, which hold the scales (the test can
    // fail: without them, other weights).
    EXPECT_EQ(batched[o]->GetBinning().GetWeightHistogram().GetValues(),
      once[o]->GetBinning().GetWeightHistogram().GetValues())
      << o;
    EXPECT_EQ(fixed[o]->GetBinning().GetWeightHistogram().GetValues(),
      once[o]->GetBinning().GetWeightHistogram().GetValues())
      << o;
    EXPECT_NE(plain[o]->GetBinning().GetWeightHistogram().GetValues(),
      once[o]->GetBinning().GetWeightHistogram().GetValues())
      << o;
    // Turned, the batches' kept hits re-weigh as one build's.
    const Vec3 turned(-0.9f, 0.1f, 0.2f);
    ASSERT_EQ(once[o]->UpdateView(turned, SerialFor()), "");
    ASSERT_EQ(batched[o]->UpdateView(turned, brume::testing::ThreadedFor(3, 5)), "");
    EXPECT_EQ(batched[o]->GetTexture().Radiance, once[o]->GetTexture().Radiance) << o;
  }
}

TEST(Reconstruction, AFixedViewRefusesAnotherEye)
{
  const Scene scene = GlossyFogScene();
  const HitStore store(Trace(scene, 5000, TraceSettings()));
  const HitArrays hits = store.View();
  ObjectHits groups;
  ASSERT_EQ(GroupHitsByObject(hits, scene.NumberOfObjects(), groups), "");
  const std::size_t fog = scene.Surfaces.size();
  const std::uint32_t* index = groups.Index.data() + groups.Offset[fog];
  const std::size_t count = groups.Offset[fog + 1] - groups.Offset[fog];
  ObjectRadiance medium(scene.Media[0], { 4, 4, 4 }, 2);
  const Vec3 eye(0.f, 0.f, 0.9f), other(0.5f, 0.f, 0.9f);
  medium.FixView(eye);
  EXPECT_NE(medium.Build(hits, index, count, other, 1e-3, SerialFor()).find("fixed viewpoint"),
    std::string::npos);
  ASSERT_EQ(medium.Build(hits, index, count, eye, 1e-3, SerialFor()), "");
  const std::vector<float> texture = medium.GetTexture().Radiance;
  EXPECT_EQ(medium.UpdateView(eye, SerialFor()), "");
  EXPECT_NE(medium.UpdateView(other, SerialFor()).find("keeps no hits"), std::string::npos);
  EXPECT_NE(medium.Add(hits, index, count, 0.5, other, 1e-3, SerialFor()), "");
  EXPECT_NE(medium.BuildDirectional(2, SerialFor()), "");
  EXPECT_EQ(medium.GetTexture().Radiance, texture) << "a refused call leaves the texture as it was";
  // A view-independent object is not fixed.
  ObjectRadiance wall(scene.Surfaces[0], MakeChart(scene.Surfaces[0], nullptr), { 4, 4 }, 2);
  Scene diffuse = scene;
  diffuse.Surfaces[0].Mat = Material();
  ObjectRadiance lambertian(
    diffuse.Surfaces[0], MakeChart(diffuse.Surfaces[0], nullptr), { 4, 4 }, 2);
  lambertian.FixView(eye);
  EXPECT_FALSE(lambertian.GetBinning().IsViewFixed());
  wall.FixView(eye);
  EXPECT_TRUE(wall.GetBinning().IsViewFixed());
}
