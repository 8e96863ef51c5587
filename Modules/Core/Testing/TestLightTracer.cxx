// SPDX-License-Identifier: BSD-3-Clause
// Known answers of the light tracer that need no reference table.
#include "brume/LightTracer.h"
#include "brume/Sampling.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace brume;

namespace
{
Surface Quad(const std::string& name, float half, float y, bool facingDown)
{
  Surface s;
  s.Name = name;
  s.Vertices = { { -half, y, -half }, { half, y, -half }, { half, y, half }, { -half, y, half } };
  if (facingDown)
  {
    s.Triangles = { { 0, 1, 2 }, { 0, 2, 3 } };
  }
  else
  {
    s.Triangles = { { 0, 2, 1 }, { 0, 3, 2 } };
  }
  return s;
}

std::vector<Hit> Trace(const Scene& scene, std::uint64_t n, std::uint64_t seed = 1)
{
  const RayCaster caster(scene);
  TraceSettings settings;
  settings.Seed = seed;
  const LightTracer tracer(scene, caster, settings);
  std::vector<Hit> hits;
  TraceCounters counters;
  for (std::uint64_t i = 0; i < n; ++i)
  {
    tracer.TraceParticle(i, n, hits, counters);
  }
  return hits;
}
}

TEST(LightTracer, DefaultSceneIsValidAndHasTheSpecifiedPower)
{
  const Scene scene = MakeDefaultScene();
  EXPECT_EQ(scene.Validate(), "");
  const RayCaster caster(scene);
  ASSERT_EQ(caster.GetError(), "");
  const LightTracer tracer(scene, caster, TraceSettings());
  // Phi = pi * L_e * A = pi * 15 * 0.5^2.
  EXPECT_NEAR(tracer.GetTotalPower().x, Pi * 15.f * 0.25f, 1e-4f);
}

TEST(LightTracer, ParticlesCarryTheLightsPower)
{
  // An emitter above a huge black plane: every particle lands on it once.
  Scene scene;
  Surface light = Quad("light", 0.5f, 1.f, true);
  light.Reflectance = Vec3(0.f);
  light.Emission = Vec3(2.f, 1.f, 0.5f);
  Surface floor = Quad("floor", 1e4f, 0.f, false);
  floor.Reflectance = Vec3(0.f);
  scene.Surfaces = { light, floor };
  ASSERT_EQ(scene.Validate(), "");
  const std::uint64_t n = 20000;
  const auto hits = Trace(scene, n);
  Vec3 total(0.f);
  int onFloor = 0;
  for (const Hit& h : hits)
  {
    EXPECT_EQ(h.Depth, 0);
    EXPECT_EQ(h.Emitter, 0);
    if (h.Object == 1)
    {
      ++onFloor;
      total += Vec3(h.Flux[0], h.Flux[1], h.Flux[2]);
    }
  }
  // A cosine lobe from 1 m misses a 10 km plane with probability ~1e-8.
  EXPECT_EQ(onFloor, static_cast<int>(n));
  EXPECT_NEAR(total.x, Pi * 2.f, 1e-3f);
  EXPECT_NEAR(total.y, Pi * 1.f, 1e-3f);
  EXPECT_NEAR(total.z, Pi * 0.5f, 1e-3f);
}

TEST(LightTracer, UnscatteredPowerThroughAnAbsorbingSlabFollowsBeerLambert)
{
  // Light facing down onto a black floor through a purely absorbing layer
  // 0 < y < 0.5 that extends far sideways. Cosine-weighted emission: the
  // transmitted fraction is E3-like: 2 * int_0^1 mu exp(-tau/mu) dmu.
  Scene scene;
  Surface light = Quad("light", 0.01f, 1.f, true);
  light.Reflectance = Vec3(0.f);
  light.Emission = Vec3(1.f);
  Surface floor = Quad("floor", 1e5f, 0.f, false);
  floor.Reflectance = Vec3(0.f);
  scene.Surfaces = { light, floor };
  Medium absorber;
  absorber.Name = "absorber";
  absorber.Bounds = { { -1e5f, 1e-3f, -1e5f }, { 1e5f, 0.501f, 1e5f } };
  absorber.SigmaA = Vec3(2.f);
  absorber.SigmaS = Vec3(0.f);
  scene.Media = { absorber };
  ASSERT_EQ(scene.Validate(), "");
  const std::uint64_t n = 200000;
  const auto hits = Trace(scene, n, 3);
  int reached = 0;
  for (const Hit& h : hits)
  {
    reached += h.Object == 1 ? 1 : 0;
  }
  const double tau = 2.0 * 0.5;
  double expected = 0.0; // 2 int_0^1 mu exp(-tau/mu) dmu by the midpoint rule
  const int m = 200000;
  for (int i = 0; i < m; ++i)
  {
    const double mu = (i + 0.5) / m;
    expected += 2.0 * mu * std::exp(-tau / mu) / m;
  }
  const double fraction = static_cast<double>(reached) / n;
  const double stderr = std::sqrt(expected * (1.0 - expected) / n);
  EXPECT_NEAR(fraction, expected, 4.0 * stderr);
}
