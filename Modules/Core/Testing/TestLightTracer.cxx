// SPDX-License-Identifier: BSD-3-Clause
// Known answers of the light tracer that need no reference table.
#include "brume/LightTracer.h"
#include "brume/Random.h"
#include "brume/Sampling.h"

#include "TestScenes.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace brume;
using brume::testing::ClosedBox;

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
// Sunlight straight down (unit irradiance, beam radius `beam` centred above
// the origin) on a ground 2 * `half` wide at y = -1 of reflectance
// `reflectance`, with one box medium in it.
Scene SunOverGround(float half, float reflectance, const Box& bounds, const Vec3& sigmaA,
  const Vec3& sigmaS, float beam)
{
  Scene scene;
  Surface ground = Quad("ground", half, -1.f, false);
  ground.Mat.Reflectance = Vec3(reflectance);
  scene.Surfaces = { ground };
  Medium medium;
  medium.Name = "medium";
  medium.Bounds = bounds;
  medium.SigmaA = sigmaA;
  medium.SigmaS = sigmaS;
  scene.Media = { medium };
  Light sun;
  sun.Type = LightType::Directional;
  sun.Direction = Vec3(0.f, -1.f, 0.f);
  sun.Intensity = Vec3(1.f);
  sun.BeamRadius = beam;
  sun.BeamCenter = Vec3(0.f, 3.f, 0.f);
  scene.Lights = { sun };
  return scene;
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
  light.Mat.Reflectance = Vec3(0.f);
  light.Mat.Emission = Vec3(2.f, 1.f, 0.5f);
  Surface floor = Quad("floor", 1e4f, 0.f, false);
  floor.Mat.Reflectance = Vec3(0.f);
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
  light.Mat.Reflectance = Vec3(0.f);
  light.Mat.Emission = Vec3(1.f);
  Surface floor = Quad("floor", 1e5f, 0.f, false);
  floor.Mat.Reflectance = Vec3(0.f);
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

namespace
{

TraceCounters TraceAll(const Scene& scene, std::uint64_t n, const TraceSettings& settings,
  std::vector<Hit>& hits, std::vector<ParticleExit>* exits = nullptr)
{
  const RayCaster caster(scene);
  const LightTracer tracer(scene, caster, settings);
  TraceCounters counters;
  for (std::uint64_t i = 0; i < n; ++i)
  {
    ParticleExit exit;
    tracer.TraceParticle(i, n, hits, counters, &exit);
    if (exits)
    {
      exits->push_back(exit);
    }
  }
  return counters;
}

double Relative(double a, double b)
{
  return std::abs(a - b) / std::max(std::abs(a), std::abs(b));
}
}

TEST(LightTracer, EnergyIsConservedInAClosedScene)
{
  // Walls and medium halve the flux at every interaction: without Russian
  // roulette, every particle's stored flux is the same geometric series.
  Material half;
  half.Reflectance = Vec3(0.5f);
  Scene scene;
  scene.Surfaces = ClosedBox(half);
  Surface light = Quad("light", 0.2f, 0.9f, true);
  light.Mat.Reflectance = Vec3(0.5f);
  light.Mat.Emission = Vec3(3.f);
  scene.Surfaces.push_back(light);
  Medium fog;
  fog.Name = "fog";
  fog.Bounds = { Vec3(-0.5f), Vec3(0.5f) };
  fog.SigmaA = Vec3(0.7f);
  fog.SigmaS = Vec3(0.7f);
  fog.G = 0.5f;
  scene.Media = { fog };
  ASSERT_EQ(scene.Validate(), "");

  const std::uint64_t n = 20000;
  const int depth = 30;
  TraceSettings settings;
  settings.MaxDepth = depth;
  settings.RouletteDepth = depth + 1; // off
  std::vector<Hit> hits;
  const TraceCounters c = TraceAll(scene, n, settings, hits);
  const double phi = Pi * 3.0 * 0.4 * 0.4; // pi L_e A
  double stored = 0.0;
  for (const Hit& h : hits)
  {
    stored += h.Flux[0];
  }
  // sum_k<depth 0.5^k of the emitted power; nothing escapes a closed box.
  EXPECT_LT(Relative(stored, phi * (2.0 - 2.0 * std::pow(0.5, depth))), 1e-6);
  EXPECT_EQ(hits.size(), n * depth);
  for (int ch = 0; ch < 3; ++ch)
  {
    EXPECT_EQ(c.Escaped[ch], 0.0);
    EXPECT_LT(Relative(c.Emitted[ch], phi), 1e-6);
    EXPECT_LT(Relative(c.Emitted[ch],
                c.Absorbed[ch] + c.Escaped[ch] + c.Truncated[ch] + c.EstimatorNet[ch]),
      1e-9);
    EXPECT_LT(Relative(c.Truncated[ch], phi * std::pow(0.5, depth)), 1e-6);
  }

  // With Russian roulette the balance still closes, and the roulette's net
  // effect vanishes in expectation (it is small against the emitted power).
  hits.clear();
  settings.MaxDepth = 1024;
  settings.RouletteDepth = 2;
  const TraceCounters r = TraceAll(scene, n, settings, hits);
  for (int ch = 0; ch < 3; ++ch)
  {
    EXPECT_LT(Relative(r.Emitted[ch],
                r.Absorbed[ch] + r.Escaped[ch] + r.Truncated[ch] + r.EstimatorNet[ch]),
      1e-9);
    EXPECT_LT(std::abs(r.EstimatorNet[ch]) / r.Emitted[ch], 0.02);
    EXPECT_EQ(r.Escaped[ch], 0.0);
  }
}

TEST(LightTracer, PointSpotAndDirectionalLightsCarryTheirPower)
{
  Material black;
  black.Reflectance = Vec3(0.f);
  struct Case
  {
    Light L;
    double Power;
  };
  Light point;
  point.Type = LightType::Point;
  point.Intensity = Vec3(2.f);
  Light spot;
  spot.Type = LightType::Spot;
  spot.Intensity = Vec3(2.f);
  spot.ConeAngle = 30.f;
  spot.Direction = Normalize(Vec3(1.f, -1.f, 0.f));
  Light beam;
  beam.Type = LightType::Directional;
  beam.Intensity = Vec3(2.f);
  beam.BeamCenter = Vec3(0.f, 0.5f, 0.f);
  beam.BeamRadius = 0.3f;
  beam.Direction = Vec3(0.f, -1.f, 0.f);
  const double cone = 2 * Pi * (1 - std::cos(30.0 * Pi / 180.0)) * 2.0;
  for (const Case& c :
    { Case{ point, 4 * Pi * 2.0 }, Case{ spot, cone }, Case{ beam, Pi * 0.09 * 2.0 } })
  {
    Scene scene;
    scene.Surfaces = ClosedBox(black);
    scene.Lights = { c.L };
    ASSERT_EQ(scene.Validate(), "");
    std::vector<Hit> hits;
    const std::uint64_t n = 5000;
    TraceAll(scene, n, TraceSettings(), hits);
    ASSERT_EQ(hits.size(), n);
    double total = 0.0;
    for (const Hit& h : hits)
    {
      total += h.Flux[1];
      EXPECT_EQ(h.Emitter, scene.LightEmitterId(0));
      const Vec3 d(h.Direction[0], h.Direction[1], h.Direction[2]);
      if (c.L.Type == LightType::Spot)
      {
        EXPECT_GE(Dot(d, c.L.Direction), std::cos(30.f * Pi / 180.f) - 1e-5f);
      }
      if (c.L.Type == LightType::Directional)
      {
        EXPECT_NEAR(h.Position[1], -1.f, 1e-4f);
        EXPECT_LE(std::hypot(h.Position[0], h.Position[2]), 0.3f + 1e-4f);
      }
    }
    EXPECT_LT(Relative(total, c.Power), 1e-5);
  }
}

namespace
{
// Fraction of a collimated beam's power leaving through the bottom of an
// absorbing medium without interaction, with its binomial standard error.
void TransmittedFraction(
  const Medium& medium, float top, double& fraction, double& stderr, std::uint64_t n = 100000)
{
  Scene scene;
  scene.Media = { medium };
  Light beam;
  beam.Type = LightType::Directional;
  beam.Direction = Vec3(0.f, -1.f, 0.f);
  beam.BeamCenter = Vec3(0.05f, top, -0.03f);
  beam.BeamRadius = 0.01f;
  scene.Lights = { beam };
  ASSERT_EQ(scene.Validate(), "");
  std::vector<Hit> hits;
  std::vector<ParticleExit> exits;
  TraceSettings settings;
  TraceAll(scene, n, settings, hits, &exits);
  double through = 0;
  for (const ParticleExit& e : exits)
  {
    through += (e.Escaped && e.Depth == 0) ? 1.0 : 0.0;
  }
  fraction = through / n;
  stderr = std::sqrt(fraction * (1 - fraction) / n);
}
}

TEST(LightTracer, BeerLambertThroughAHeterogeneousGrid)
{
  // Density ramps linearly 0 -> 2 from y = 0 to y = 1 (point data, 3 x 5 x 3
  // points): the optical depth of a vertical ray is 1.
  std::vector<float> values;
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 3; ++i)
        values.push_back(2.f * j / 4.f);
  Medium ramp;
  ramp.Name = "ramp";
  ramp.SigmaA = Vec3(1.f);
  ramp.SigmaS = Vec3(0.f);
  ramp.SetDensity(std::make_shared<GridDensity>(Box{ { -0.5f, 0.f, -0.5f }, { 0.5f, 1.f, 0.5f } },
    std::array<int, 3>{ 3, 5, 3 }, values, false));
  double f = 0, se = 0;
  TransmittedFraction(ramp, 2.f, f, se);
  EXPECT_NEAR(f, std::exp(-1.0), 4 * se);

  // Cell data, constant per cell: layers of density 0, 1, 3 of thickness 1/3.
  Medium layers;
  layers.Name = "layers";
  layers.SigmaA = Vec3(1.5f);
  layers.SigmaS = Vec3(0.f);
  layers.SetDensity(std::make_shared<GridDensity>(Box{ { -0.5f, 0.f, -0.5f }, { 0.5f, 1.f, 0.5f } },
    std::array<int, 3>{ 1, 3, 1 }, std::vector<float>{ 0.f, 1.f, 3.f }, true));
  TransmittedFraction(layers, 2.f, f, se);
  EXPECT_NEAR(f, std::exp(-1.5 * (1.0 + 3.0) / 3.0), 4 * se);
}

TEST(LightTracer, SparseMajorantsSkipEmptySpace)
{
  // A 64^3 grid that is empty but for one 4^3 cube of density 2.
  const int n = 64;
  std::vector<float> values(n * n * n, 0.f);
  for (int k = 32; k < 36; ++k)
    for (int j = 32; j < 36; ++j)
      for (int i = 32; i < 36; ++i)
        values[(k * n + j) * n + i] = 2.f;
  auto density = std::make_shared<GridDensity>(
    Box{ Vec3(0.f), Vec3(1.f) }, std::array<int, 3>{ n, n, n }, values, true);
  // Only the one block holding the cube has a majorant (of 8^3 blocks).
  EXPECT_EQ(density->NumberOfOccupiedBlocks(), 1u);
  EXPECT_EQ(density->GetMajorants().GlobalMax(), 2.f);
  Medium sparse;
  sparse.Name = "sparse";
  sparse.SigmaA = Vec3(1.f);
  sparse.SigmaS = Vec3(0.f);
  sparse.SetDensity(density);
  // Beside the cube (the beam at x = 0.05) nothing is in the way: every
  // particle passes, however many empty blocks it crosses.
  double f = 0, se = 0;
  TransmittedFraction(sparse, 2.f, f, se);
  EXPECT_EQ(f, 1.0);
}

TEST(LightTracer, SpectralTrackingGivesEachChannelItsTransmittance)
{
  // A homogeneous absorber with sigma_t = (1, 2, 4) and thickness 0.5: the
  // flux leaving the bottom is exp(-sigma_t / 2) of the emitted, per channel.
  Medium coloured;
  coloured.Name = "coloured";
  coloured.Bounds = { { -10.f, 0.f, -10.f }, { 10.f, 0.5f, 10.f } };
  coloured.SigmaA = Vec3(1.f, 2.f, 4.f);
  coloured.SigmaS = Vec3(0.f);
  Scene scene;
  scene.Media = { coloured };
  Light beam;
  beam.Type = LightType::Directional;
  beam.Direction = Vec3(0.f, -1.f, 0.f);
  beam.BeamCenter = Vec3(0.f, 1.f, 0.f);
  beam.BeamRadius = 0.01f;
  scene.Lights = { beam };
  ASSERT_EQ(scene.Validate(), "");
  const std::uint64_t n = 200000;
  std::vector<Hit> hits;
  std::vector<ParticleExit> exits;
  TraceSettings settings;
  settings.RouletteDepth = 1000; // weights only from spectral tracking
  const TraceCounters c = TraceAll(scene, n, settings, hits, &exits);
  for (int ch = 0; ch < 3; ++ch)
  {
    double sum = 0, sum2 = 0;
    const double perParticle = c.Emitted[ch] / n;
    for (const ParticleExit& e : exits)
    {
      const double x = e.Escaped ? e.Flux[ch] / perParticle : 0.0;
      sum += x;
      sum2 += x * x;
    }
    const double mean = sum / n, se = std::sqrt((sum2 / n - mean * mean) / n);
    EXPECT_NEAR(mean, std::exp(-coloured.SigmaA[ch] * 0.5), 4 * se) << "channel " << ch;
  }
}

TEST(LightTracer, AimedBeamDeliversTheSamePowerWithLessNoise)
{
  // Sunlight straight down over a black 4 x 4 ground, with a black box
  // 0.2 wide (sigma_a 200: nothing crosses it) in it. The box absorbs
  // E * 0.04 and the ground E * (16 - 0.04), whatever the aim; aimed, the
  // box gets most particles and its estimate's standard error shrinks.
  Scene scene = SunOverGround(
    2.f, 0.f, { { 0.4f, -0.1f, 0.2f }, { 0.6f, 0.1f, 0.4f } }, Vec3(200.f), Vec3(0.f), 3.f);
  ASSERT_EQ(scene.Validate(), "");

  // Unaimed, AimAtMedia leaves the light as it was; aimed, the disk holds
  // the box's projection, to within a pilot cell.
  const RayCaster caster(scene);
  AimAtMedia(scene, caster, 0.f);
  EXPECT_FALSE(scene.Lights[0].Aims());
  AimAtMedia(scene, caster, 0.5f);
  const Light& aimed = scene.Lights[0];
  ASSERT_TRUE(aimed.Aims());
  const float cell = 2.f * scene.Lights[0].BeamRadius / AimPilotRays;
  EXPECT_NEAR(aimed.AimRadius, 0.1f * std::sqrt(2.f), 2.f * cell);
  EXPECT_NEAR(aimed.AimCenter.x, 0.5f, cell);
  EXPECT_NEAR(aimed.AimCenter.z, 0.3f, cell);
  for (float x : { 0.4f, 0.6f })
  {
    for (float z : { 0.2f, 0.4f })
    {
      EXPECT_LE(std::hypot(x - aimed.AimCenter.x, z - aimed.AimCenter.z), aimed.AimRadius);
    }
  }
  EXPECT_EQ(aimed.EmissionWeight(0), 1.f);
  EXPECT_FLOAT_EQ(aimed.EmissionWeight(1), 2.f);
  EXPECT_FLOAT_EQ(
    aimed.EmissionWeight(2), 1.f / (0.5f + 0.5f * 9.f / (aimed.AimRadius * aimed.AimRadius)));

  struct Estimate
  {
    double Box = 0.0, BoxError = 0.0, Ground = 0.0, GroundError = 0.0;
  };
  const std::uint64_t n = 100000;
  auto estimate = [&](float fraction)
  {
    AimAtMedia(scene, caster, fraction);
    const auto hits = Trace(scene, n, 11);
    // One interaction per particle (both objects absorb everything): each
    // hit is one particle's contribution; the others contribute 0.
    double sum[2] = { 0, 0 }, squares[2] = { 0, 0 };
    for (const Hit& h : hits)
    {
      sum[h.Object] += h.Flux[1];
      squares[h.Object] += static_cast<double>(h.Flux[1]) * h.Flux[1];
      EXPECT_EQ(h.Aim, fraction > 0.f ? (h.Object == 1 ? 2 : h.Aim) : 0);
    }
    Estimate e;
    auto error = [&](int o)
    { return std::sqrt((squares[o] - sum[o] * sum[o] / n) * n / (n - 1.0)); };
    e.Ground = sum[0];
    e.GroundError = error(0);
    e.Box = sum[1];
    e.BoxError = error(1);
    return e;
  };
  const Estimate uniform = estimate(0.f), half = estimate(0.5f);
  for (const Estimate& e : { uniform, half })
  {
    EXPECT_NEAR(e.Box, 0.04, 4.0 * e.BoxError);
    EXPECT_NEAR(e.Ground, 16.0 - 0.04, 4.0 * e.GroundError);
  }
  EXPECT_LT(half.BoxError, uniform.BoxError / 5.0);
}

TEST(LightTracer, AimedPointsBeyondTheBeamCarryNothing)
{
  // A disk aimed half outside the beam: its points beyond the beam get
  // weight 0, the others their class's, and the weights' mean over the
  // beam's area is 1 (the light's power is unchanged).
  Light sun;
  sun.Type = LightType::Directional;
  sun.Direction = Vec3(0.f, -1.f, 0.f);
  sun.BeamRadius = 1.f;
  sun.BeamCenter = Vec3(0.f);
  sun.AimCenter = Vec3(1.f, 0.f, 0.f);
  sun.AimRadius = 0.25f;
  sun.AimFraction = 0.4f;
  ASSERT_EQ(sun.Validate(), "");
  Random rng(3, 0);
  const int n = 400000;
  double total = 0.0;
  int beyond = 0;
  for (int i = 0; i < n; ++i)
  {
    Vec3 origin, direction;
    std::uint8_t aim = 0;
    const float w = sun.SampleEmission(rng, origin, direction, aim);
    const bool inBeam = Length(origin - sun.BeamCenter) <= sun.BeamRadius;
    if (!inBeam)
    {
      EXPECT_EQ(w, 0.f);
      ++beyond;
    }
    else
    {
      EXPECT_EQ(w, sun.EmissionWeight(aim));
    }
    total += w;
  }
  EXPECT_GT(beyond, 0);
  // Each weight is at most 1 / (1 - 0.4): a bound on the standard error.
  EXPECT_NEAR(total / n, 1.0, 4.0 * (1.0 / 0.6) / std::sqrt(double(n)));
  sun.AimFraction = 1.f;
  EXPECT_NE(sun.Validate(), "");
}

TEST(LightTracer, HeavyParticlesSplitIntoAimedOnesWithoutBias)
{
  // Sunlight straight down on a white ground with a scattering cloud above
  // it, aimed at the cloud: the particles emitted beside the aimed disk
  // weigh w1 / w2 aimed ones and reach the cloud only after the ground
  // reflects them. Split where they head into the cloud, they bring the
  // cloud the same light (unbiased: the per-particle means agree) from
  // many particles instead of a few heavy ones (a smaller standard error).
  Scene scene = SunOverGround(
    2.f, 0.8f, { { 0.3f, -0.8f, 0.1f }, { 0.7f, -0.4f, 0.5f } }, Vec3(0.5f), Vec3(10.f), 2.f);
  ASSERT_EQ(scene.Validate(), "");
  const RayCaster caster(scene);
  AimAtMedia(scene, caster, 0.5f);
  const Light& aimed = scene.Lights[0];
  ASSERT_TRUE(aimed.Aims());
  const double ratio = aimed.EmissionWeight(1) / aimed.EmissionWeight(2);
  ASSERT_GT(ratio, 10.0);
  ASSERT_LT(ratio, MaxSplit);

  struct Run
  {
    double Mean = 0.0, Error = 0.0, Children = 0.0, ChildrenSquares = 0.0;
    std::uint64_t Splits = 0, HeavyHitsInCloud = 0;
    TraceCounters Counters;
  };
  const std::uint64_t n = 100000;
  auto run = [&](bool split)
  {
    TraceSettings settings;
    settings.Seed = 5;
    settings.SplitHeavyParticles = split;
    const LightTracer tracer(scene, caster, settings);
    Run r;
    double sum = 0.0, squares = 0.0;
    std::vector<Hit> hits;
    for (std::uint64_t i = 0; i < n; ++i)
    {
      hits.clear();
      ParticleExit exit;
      tracer.TraceParticle(i, n, hits, r.Counters, &exit);
      // The light the ground reflects into the cloud: the cloud's hits of
      // particles that met the ground first (the hit before any split).
      double x = 0.0;
      for (const Hit& h : hits)
      {
        if (h.Object == 1 && hits.front().Object == 0)
        {
          x += h.Flux[1];
          r.HeavyHitsInCloud += h.Aim == 1 ? 1 : 0;
        }
      }
      sum += x;
      squares += x * x;
      if (exit.Children > 0)
      {
        ++r.Splits;
        r.Children += exit.Children;
        r.ChildrenSquares += static_cast<double>(exit.Children) * exit.Children;
      }
    }
    r.Mean = sum / n;
    r.Error = std::sqrt((squares / n - r.Mean * r.Mean) / (n - 1.0));
    return r;
  };
  const Run whole = run(false), split = run(true);
  EXPECT_GT(whole.HeavyHitsInCloud, 0u);
  EXPECT_EQ(split.HeavyHitsInCloud, 0u);
  EXPECT_EQ(whole.Splits, 0u);
  ASSERT_GT(split.Splits, 100u);
  EXPECT_GT(whole.Mean, 0.0);
  EXPECT_NEAR(split.Mean, whole.Mean, 4.0 * std::hypot(split.Error, whole.Error));
  EXPECT_LT(split.Error, 0.8 * whole.Error);
  // floor(r) or floor(r) + 1 children, r on average.
  const double mean = split.Children / split.Splits;
  const double spread = std::sqrt(split.ChildrenSquares / split.Splits - mean * mean);
  EXPECT_LE(spread, 0.5 + 1e-9);
  EXPECT_NEAR(mean, ratio, 4.0 * 0.5 / std::sqrt(static_cast<double>(split.Splits)));
  // The split's flux change is the estimators' (zero in expectation): the
  // run's balance stays exact.
  for (const TraceCounters& c : { whole.Counters, split.Counters })
  {
    for (int ch = 0; ch < 3; ++ch)
    {
      const double out = c.Absorbed[ch] + c.Escaped[ch] + c.Truncated[ch] + c.EstimatorNet[ch];
      EXPECT_LT(Relative(c.Emitted[ch], out), 1e-9);
    }
  }
  std::printf("cloud's light per particle: whole %.6g +- %.2g, split %.6g +- %.2g; "
              "%llu splits into %.2f (r = %.2f)\n",
    whole.Mean, whole.Error, split.Mean, split.Error, static_cast<unsigned long long>(split.Splits),
    mean, ratio);
}
