// SPDX-License-Identifier: BSD-3-Clause
// The reference path tracer against known answers.
#include "brume/PathTracer.h"
#include "brume/Random.h"
#include "brume/Sampling.h"

#include "TestScenes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

using namespace brume;
using brume::testing::ClosedBox;

namespace
{
// The furnace: walls emitting L_e = 1 and reflecting rho = 0.5 all round.
Scene Furnace()
{
  Material wall;
  wall.Reflectance = Vec3(0.5f);
  wall.Emission = Vec3(1.f);
  Scene scene;
  scene.Surfaces = ClosedBox(wall);
  return scene;
}

// A camera inside the furnace, off its centre, n x n pixels.
PinholeCamera InsideTheFurnace(int n)
{
  PinholeCamera camera;
  camera.Position = { 0.1f, 0.2f, 0.3f };
  camera.FocalPoint = { 0.f, 0.f, -1.f };
  camera.Width = camera.Height = n;
  camera.ViewAngle = 90.f;
  return camera;
}
}

TEST(PathTracer, FurnaceRadianceIsEverywhereTheSteadyState)
{
  // A scattering medium of albedo 1 inside the furnace: the radiance is
  // L_e / (1 - rho) = 2 everywhere.
  Scene scene = Furnace();
  Medium fog;
  fog.Name = "fog";
  fog.Bounds = { Vec3(-0.6f), Vec3(0.6f) };
  fog.SigmaS = Vec3(1.5f);
  fog.SigmaA = Vec3(0.f);
  fog.G = 0.5f;
  scene.Media = { fog };
  ASSERT_EQ(scene.Validate(), "");
  const RayCaster caster(scene);
  PathSettings settings;
  settings.SamplesPerPixel = 64;
  const PathTracer tracer(scene, caster, settings);
  const PinholeCamera camera = InsideTheFurnace(16);
  std::vector<float> mean(3 * 256), variance(3 * 256);
  tracer.RenderRows(camera, 0, 16, mean.data(), variance.data());
  double sum = 0.0, var = 0.0;
  for (int p = 0; p < 256; ++p)
  {
    ASSERT_TRUE(std::isfinite(mean[3 * p]));
    EXPECT_NEAR(mean[3 * p], 2.0, 5.0 * std::sqrt(variance[3 * p]) + 1e-6) << "pixel " << p;
    sum += mean[3 * p];
    var += variance[3 * p];
  }
  EXPECT_NEAR(sum / 256, 2.0, 4.0 * std::sqrt(var) / 256);
}

TEST(PathTracer, PathsStoppedAfterKVerticesCarryKReflections)
{
  // The furnace's walls without the medium: a path stopped after k
  // vertices sees L_e (1 + rho + ... + rho^k). Its last vertex's light
  // sample takes the whole weight (no BRDF-sampled ray follows to meet the
  // emitter, as multiple importance sampling would otherwise count on).
  const Scene scene = Furnace();
  ASSERT_EQ(scene.Validate(), "");
  const RayCaster caster(scene);
  const PinholeCamera camera = InsideTheFurnace(8);
  for (int k = 1; k <= 3; ++k)
  {
    PathSettings settings;
    settings.SamplesPerPixel = 64;
    settings.MaxDepth = k;
    settings.RouletteDepth = k + 1; // no roulette: every path runs its k vertices
    const PathTracer tracer(scene, caster, settings);
    std::vector<float> mean(3 * 64), variance(3 * 64);
    tracer.RenderRows(camera, 0, 8, mean.data(), variance.data());
    double sum = 0.0, var = 0.0;
    for (int p = 0; p < 64; ++p)
    {
      sum += mean[3 * p];
      var += variance[3 * p];
    }
    const double expected = 2.0 - std::pow(0.5, k); // 1 + 1/2 + ... + 1/2^k
    EXPECT_NEAR(sum / 64, expected, 4.0 * std::sqrt(var) / 64 + 1e-6) << k << " vertices";
  }
}

TEST(PathTracer, ThinMediumMatchesSingleScatteringQuadrature)
{
  // A point light in an optically thin medium (tau ~ 0.02: multiple
  // scattering below 1 %), seen along one ray that misses the light.
  Medium fog;
  fog.Name = "fog";
  fog.Bounds = { Vec3(-1.f), Vec3(1.f) };
  fog.SigmaS = Vec3(0.01f);
  fog.SigmaA = Vec3(0.f);
  fog.G = 0.4f;
  Scene scene;
  scene.Media = { fog };
  Light light;
  light.Type = LightType::Point;
  light.Position = { 0.f, 0.3f, 0.f };
  light.Intensity = Vec3(1.f);
  scene.Lights = { light };
  ASSERT_EQ(scene.Validate(), "");
  const RayCaster caster(scene);
  PathSettings settings;
  settings.SamplesPerPixel = 1000000; // paths collide with probability ~tau: many are needed
  const PathTracer tracer(scene, caster, settings);
  PinholeCamera camera;
  camera.Position = { 0.f, 0.f, 3.f };
  camera.FocalPoint = { 0.f, 0.f, 0.f };
  camera.ViewAngle = 0.001f; // one pixel, one ray
  camera.Width = camera.Height = 1;
  float mean[3], variance[3];
  tracer.RenderRows(camera, 0, 1, mean, variance);
  // L = int sigma_s p(cos) I exp(-sigma_t (r + path in the medium)) / r^2 ds, z from 1 to -1.
  const HenyeyGreenstein phase(fog.G);
  double expected = 0.0;
  const int n = 200000;
  for (int i = 0; i < n; ++i)
  {
    const double z = 1.0 - 2.0 * (i + 0.5) / n;
    const Vec3 x(0.f, 0.f, static_cast<float>(z));
    const Vec3 toLight = light.Position - x;
    const double r = Length(toLight);
    // Travel from the light to x, then from x toward the camera (+z).
    const double cosTheta = Dot(Normalize(-toLight), Vec3(0.f, 0.f, 1.f));
    const double inMedium = r + (1.0 - z);
    expected += 0.01 * phase.Evaluate(static_cast<float>(cosTheta)) * std::exp(-0.01 * inMedium) /
      (r * r) * (2.0 / n);
  }
  EXPECT_NEAR(mean[0], expected, 0.02 * expected + 4.0 * std::sqrt(variance[0]));
  EXPECT_LT(std::sqrt(variance[0]), 0.01 * expected); // the test has the precision it claims
}

TEST(PathTracer, SlabReflectanceAndTransmittanceMatchAddingDoubling)
{
  // The adjoint of the slab experiment: with a collimated beam of unit
  // irradiance from above, R = pi E[L_up] over cosine-distributed directions
  // seen from above, T_diffuse likewise from below. Skips without ../shared.
  std::ifstream csv(std::string(BRUME_SOURCE_DIR) + "/../shared/reference/slab_collimated.csv");
  if (!csv)
  {
    GTEST_SKIP() << "no ../shared/reference/slab_collimated.csv here";
  }
  std::string line;
  std::getline(csv, line);
  std::vector<std::vector<double>> rows;
  while (std::getline(csv, line))
  {
    std::vector<double> v;
    std::stringstream fields(line);
    std::string f;
    while (std::getline(fields, f, ','))
    {
      v.push_back(std::atof(f.c_str()));
    }
    rows.push_back(v);
  }
  for (int row : { 1, 4, 12, 20 })
  {
    const auto& v = rows[row - 1];
    const float albedo = static_cast<float>(v[0]), tau = static_cast<float>(v[1]);
    Medium slab;
    slab.Name = "slab";
    slab.Bounds = { { -1e7f, 0.f, -1e7f }, { 1e7f, tau, 1e7f } };
    slab.SigmaS = Vec3(albedo);
    slab.SigmaA = Vec3(1.f - albedo);
    slab.G = static_cast<float>(v[2]);
    Scene scene;
    scene.Media = { slab };
    Light beam;
    beam.Type = LightType::Directional;
    beam.Direction = { 0.f, -1.f, 0.f };
    beam.BeamCenter = { 0.f, tau + 1.f, 0.f };
    beam.BeamRadius = 1e6f;
    beam.Intensity = Vec3(1.f);
    scene.Lights = { beam };
    ASSERT_EQ(scene.Validate(), "");
    const RayCaster caster(scene);
    PathSettings settings;
    settings.MaxDepth = 100000;
    const PathTracer tracer(scene, caster, settings);
    // Forward scattering (g = 0.9) makes next-event estimation toward the
    // collimated beam noisy: those rows need more samples for 0.002.
    const int n = v[2] > 0.5 ? 2000000 : 200000;
    for (int side = 0; side < 2; ++side) // 0: reflection, 1: diffuse transmission
    {
      double sum = 0.0, sum2 = 0.0;
      Random rng(31 + side, static_cast<std::uint64_t>(row));
      for (int i = 0; i < n; ++i)
      {
        // A cosine-distributed direction leaving the slab (up, or down).
        Vec3 w = SampleCosineHemisphere(rng.NextFloat(), rng.NextFloat());
        const Vec3 out = side == 0 ? Vec3(w.x, w.z, w.y) : Vec3(w.x, -w.z, w.y);
        const Vec3 origin = side == 0 ? Vec3(0.f, tau + 0.5f, 0.f) : Vec3(0.f, -0.5f, 0.f);
        const double l = Pi * tracer.Trace(origin, -out, rng).x;
        sum += l;
        sum2 += l * l;
      }
      const double mean = sum / n, se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / (n - 1));
      const double reference = v[3 + side];
      EXPECT_NEAR(mean, reference, 4.0 * se + 1e-9)
        << (side == 0 ? "R_diffuse" : "T_diffuse") << " of row " << row << " (stderr " << se << ")";
      EXPECT_NEAR(mean, reference, 0.002);
    }
  }
}
