// SPDX-License-Identifier: BSD-3-Clause
// Deterministic single scattering (brume/DirectLight.h) against analytic
// direct light, shadows and transmittance, and against the particles it
// replaces.
#include "TestScenes.h"
#include "brume/DirectLight.h"
#include "brume/LightTracer.h"
#include "brume/Reconstruction.h"
#include "brume/Sampling.h"
#include "brume/SphericalHarmonics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

using namespace brume;

namespace
{
using brume::testing::HitStore;

std::vector<Hit> Trace(const Scene& scene, std::uint64_t n, int maxDepth, std::uint64_t seed = 1)
{
  const RayCaster caster(scene);
  TraceSettings settings;
  settings.MaxDepth = maxDepth;
  settings.Seed = seed;
  const LightTracer tracer(scene, caster, settings);
  std::vector<Hit> hits;
  TraceCounters counters;
  tracer.TraceParticles(0, n, n, hits, counters);
  return hits;
}

Surface Square(const std::string& name, float half, float z, bool up, const Vec3& reflectance)
{
  // |x|, |y| <= half in the plane z, facing +z (up) or -z.
  Surface s;
  s.Name = name;
  s.Vertices = { { -half, -half, z }, { half, -half, z }, { half, half, z }, { -half, half, z } };
  s.Triangles = up ? std::vector<std::array<std::uint32_t, 3>>{ { 0, 1, 2 }, { 0, 2, 3 } }
                   : std::vector<std::array<std::uint32_t, 3>>{ { 0, 2, 1 }, { 0, 3, 2 } };
  s.Mat.Reflectance = reflectance;
  return s;
}

Light PointLight(const Vec3& position, float intensity)
{
  Light light;
  light.Type = LightType::Point;
  light.Position = position;
  light.Intensity = Vec3(intensity);
  return light;
}

// The hits of one object, in hit order.
std::vector<std::uint32_t> IndexOf(const HitStore& store, std::size_t object)
{
  std::vector<std::uint32_t> index;
  for (std::size_t i = 0; i < store.Object.size(); ++i)
  {
    if (store.Object[i] == object)
    {
      index.push_back(static_cast<std::uint32_t>(i));
    }
  }
  return index;
}

// The centre of output texel t of a grid over [0, 1]^3.
Vec3 Centre(std::size_t t, const std::array<int, 3>& dims)
{
  const std::size_t nx = dims[0], nxy = nx * dims[1];
  return Vec3((static_cast<float>(t % nx) + 0.5f) / static_cast<float>(dims[0]),
    (static_cast<float>((t % nxy) / nx) + 0.5f) / static_cast<float>(dims[1]),
    (static_cast<float>(t / nxy) + 0.5f) / static_cast<float>(dims[2]));
}
}

TEST(DirectLight, WallUnderAPointLightIsRhoIHOverPiR3WithAShadow)
{
  // A Lambertian wall 1 m under a point light, a small square occluder
  // half-way: the direct term is rho I h / (pi r^3) outside the occluder's
  // shadow (a square of half-width 0.4 centred below it) and zero inside.
  // Single bounce only: every particle hit is a first interaction, so the
  // output is the direct term alone.
  Scene scene;
  scene.Surfaces = { Square("wall", 1.f, 0.f, true, Vec3(0.5f, 0.25f, 0.75f)),
    Square("occluder", 0.2f, 0.5f, true, Vec3(0.f)) };
  scene.Lights = { PointLight({ 0.f, 0.f, 1.f }, 2.f) };
  ASSERT_EQ(scene.Validate(), "");
  const HitStore store(Trace(scene, 20000, 1));
  const RayCaster caster(scene);
  DirectLight direct(scene, caster);
  ObjectRadiance wall(scene.Surfaces[0], MakeChart(scene.Surfaces[0], nullptr), { 4, 4 }, 2);
  ASSERT_TRUE(brume::DirectTexture::Supports(wall.GetLayout()));
  wall.EnableDirect(&direct, { 64, 64, 1 });
  const auto index = IndexOf(store, 0);
  ASSERT_FALSE(index.empty());
  ASSERT_EQ(
    wall.Build(store.View(), index.data(), index.size(), { 0, 0, 5 }, 1e-3, SerialFor()), "");
  wall.ComputeDirect(SerialFor());
  ASSERT_TRUE(wall.GetDirect().HasArrivals());
  ASSERT_EQ(wall.GetOutput().Dims, (std::array<int, 3>{ 64, 64, 1 }));
  const auto& L = wall.GetOutput().Radiance;
  const auto& frame = wall.GetLayout().Chart.Frame;
  // The analytic direct term, zero in the occluder's shadow.
  auto analytic = [&](float u, float v, int c)
  {
    const Vec3 p = frame.Origin + frame.U * u + frame.V * v;
    if (std::abs(p.x) < 0.4f && std::abs(p.y) < 0.4f)
    {
      return 0.0;
    }
    const double r = Length(p - Vec3(0.f, 0.f, 1.f));
    return scene.Surfaces[0].Mat.Reflectance[c] / Pi * 2.0 * 1.0 / (r * r * r);
  };
  // Texels whose centre is lit while a neighbour's is not (or the reverse)
  // hold the mean over 4 x 4 points of the texel: the shadow's edge then
  // lies where it is once the texture is interpolated.
  constexpr int N = 64;
  auto lit = [&](int i, int j) { return analytic((i + 0.5f) / N, (j + 0.5f) / N, 0) > 0.0; };
  int shadowed = 0, edges = 0;
  for (int j = 0; j < N; ++j)
    for (int i = 0; i < N; ++i)
    {
      const bool here = lit(i, j);
      const bool edge = (i > 0 && lit(i - 1, j) != here) || (i + 1 < N && lit(i + 1, j) != here) ||
        (j > 0 && lit(i, j - 1) != here) || (j + 1 < N && lit(i, j + 1) != here);
      shadowed += here ? 0 : 1;
      edges += edge ? 1 : 0;
      const std::size_t t = static_cast<std::size_t>(j) * N + i;
      for (int c = 0; c < 3; ++c)
      {
        double expected = 0.0;
        if (edge)
        {
          for (int k = 0; k < 16; ++k)
          {
            expected +=
              analytic((i + (k % 4 + 0.5f) / 4.f) / N, (j + (k / 4 + 0.5f) / 4.f) / N, c) / 16.0;
          }
        }
        else
        {
          expected = analytic((i + 0.5f) / N, (j + 0.5f) / N, c);
        }
        // The particles' texture is empty: no texel may hold any of their light.
        EXPECT_NEAR(L[3 * t + c], expected, 1e-5 * std::max(expected, 1.0))
          << "texel " << i << "," << j << (edge ? " (edge)" : "");
      }
    }
  EXPECT_GT(edges, 100);
  EXPECT_GT(shadowed, 600);
}

TEST(DirectLight, PerTriangleMaterialsReflectTheirOwnDirectLight)
{
  // A wall of two triangles of different reflectances (a surface coloured
  // per cell), 1 m under a point light: each output texel reflects the
  // direct term rho I h / (pi r^3) by the reflectance of the triangle at
  // its centre. A mirror triangle leaves the direct light to the particles.
  Scene scene;
  scene.Surfaces = { Square("wall", 1.f, 0.f, true, Vec3(0.5f)) };
  const Vec3 below(0.8f, 0.2f, 0.1f), above(0.1f, 0.3f, 0.9f); // y < x, y > x
  scene.Surfaces[0].TriangleMaterials.assign(2, scene.Surfaces[0].Mat);
  scene.Surfaces[0].TriangleMaterials[0].Reflectance = below;
  scene.Surfaces[0].TriangleMaterials[1].Reflectance = above;
  scene.Lights = { PointLight({ 0.f, 0.f, 1.f }, 2.f) };
  ASSERT_EQ(scene.Validate(), "");
  const HitStore store(Trace(scene, 20000, 1));
  const RayCaster caster(scene);
  DirectLight direct(scene, caster);
  ObjectRadiance wall(scene.Surfaces[0], MakeChart(scene.Surfaces[0], nullptr), { 4, 4 }, 2);
  ASSERT_TRUE(brume::DirectTexture::Supports(wall.GetLayout()));
  wall.EnableDirect(&direct, { 32, 32, 1 });
  const auto index = IndexOf(store, 0);
  ASSERT_EQ(
    wall.Build(store.View(), index.data(), index.size(), { 0, 0, 5 }, 1e-3, SerialFor()), "");
  wall.ComputeDirect(SerialFor());
  ASSERT_TRUE(wall.GetDirect().HasArrivals());
  const auto& L = wall.GetOutput().Radiance;
  const auto& frame = wall.GetLayout().Chart.Frame;
  constexpr int N = 32;
  int checked = 0;
  for (int j = 0; j < N; ++j)
    for (int i = 0; i < N; ++i)
    {
      const Vec3 p = frame.Origin + frame.U * ((i + 0.5f) / N) + frame.V * ((j + 0.5f) / N);
      if (std::abs(p.y - p.x) < 0.05f)
      {
        continue; // on the diagonal both triangles share
      }
      const Vec3& rho = p.y < p.x ? below : above;
      const double r = Length(p - Vec3(0.f, 0.f, 1.f));
      const std::size_t t = static_cast<std::size_t>(j) * N + i;
      for (int c = 0; c < 3; ++c)
      {
        const double expected = rho[c] / Pi * 2.0 / (r * r * r);
        EXPECT_NEAR(L[3 * t + c], expected, 1e-5 * std::max(expected, 1.0))
          << "texel " << i << "," << j;
      }
      ++checked;
    }
  EXPECT_GT(checked, 800);
  Scene mirrored = scene;
  mirrored.Surfaces[0].TriangleMaterials[1].Type = MaterialType::Mirror;
  mirrored.Surfaces[0].TriangleMaterials[1].Reflectance = Vec3(0.f);
  mirrored.Surfaces[0].TriangleMaterials[1].Specular = Vec3(0.9f);
  ASSERT_EQ(mirrored.Validate(), "");
  const ObjectRadiance mirror(
    mirrored.Surfaces[0], MakeChart(mirrored.Surfaces[0], nullptr), { 4, 4 }, 2);
  EXPECT_FALSE(brume::DirectTexture::Supports(mirror.GetLayout()));
}

TEST(DirectLight, VertexReflectanceIsInterpolatedOverTheTriangles)
{
  // A wall whose vertices' reflectance goes from 0.1 (x = -1) to 0.9
  // (x = 1), 1 m under a point light: each output texel reflects the
  // direct term by the reflectance interpolated at its centre, linear in x.
  Scene scene;
  scene.Surfaces = { Square("wall", 1.f, 0.f, true, Vec3(0.5f)) };
  Surface& wall = scene.Surfaces[0];
  for (const Vec3& v : wall.Vertices)
  {
    wall.VertexReflectance.push_back(Vec3(v.x < 0.f ? 0.1f : 0.9f, 0.5f, 0.2f));
  }
  scene.Lights = { PointLight({ 0.f, 0.f, 1.f }, 2.f) };
  ASSERT_EQ(scene.Validate(), "");
  EXPECT_NEAR(wall.MaterialAt(0, Vec3(0.5f, -0.5f, 0.f)).Reflectance.x, 0.7f, 1e-6f);
  const HitStore store(Trace(scene, 20000, 1));
  const RayCaster caster(scene);
  DirectLight direct(scene, caster);
  ObjectRadiance radiance(wall, MakeChart(wall, nullptr), { 4, 4 }, 2);
  ASSERT_TRUE(brume::DirectTexture::Supports(radiance.GetLayout()));
  radiance.EnableDirect(&direct, { 32, 32, 1 });
  const auto index = IndexOf(store, 0);
  ASSERT_EQ(
    radiance.Build(store.View(), index.data(), index.size(), { 0, 0, 5 }, 1e-3, SerialFor()), "");
  radiance.ComputeDirect(SerialFor());
  const auto& L = radiance.GetOutput().Radiance;
  const auto& frame = radiance.GetLayout().Chart.Frame;
  constexpr int N = 32;
  for (int j = 0; j < N; ++j)
    for (int i = 0; i < N; ++i)
    {
      const Vec3 p = frame.Origin + frame.U * ((i + 0.5f) / N) + frame.V * ((j + 0.5f) / N);
      const double rho = 0.1 + 0.8 * (p.x + 1.0) / 2.0;
      const double r = Length(p - Vec3(0.f, 0.f, 1.f));
      const double expected = rho / Pi * 2.0 / (r * r * r);
      EXPECT_NEAR(L[3 * (static_cast<std::size_t>(j) * N + i)], expected, 1e-5 * expected)
        << "texel " << i << "," << j;
    }
  // As many reflectances as vertices, each a valid reflectance.
  Scene wrong = scene;
  wrong.Surfaces[0].VertexReflectance.pop_back();
  EXPECT_NE(wrong.Validate().find("3 vertex reflectances for 4 vertices"), std::string::npos);
  wrong = scene;
  wrong.Surfaces[0].VertexReflectance[1] = Vec3(1.5f, 0.f, 0.f);
  EXPECT_NE(
    wrong.Validate().find("vertex reflectance has a reflectance outside"), std::string::npos)
    << wrong.Validate();
}

TEST(DirectLight, ThinMediumSourceIsTheAnalyticSingleScattering)
{
  // A point light at the centre of a homogeneous anisotropic medium,
  // single scattering only: S_1(x) = albedo p(w_l . w_o) I exp(-sigma_t r) / r^2
  // at every output voxel's centre.
  Medium fog;
  fog.Name = "fog";
  fog.Bounds = { Vec3(-1.f), Vec3(1.f) };
  fog.SigmaS = Vec3(0.3f, 0.2f, 0.1f);
  fog.SigmaA = Vec3(0.05f);
  fog.G = 0.6f;
  Scene scene;
  scene.Media = { fog };
  scene.Lights = { PointLight(Vec3(0.01f, 0.02f, 0.03f), 1.f) };
  ASSERT_EQ(scene.Validate(), "");
  const HitStore store(Trace(scene, 20000, 1));
  const RayCaster caster(scene);
  DirectLight direct(scene, caster);
  ObjectRadiance medium(scene.Media[0], { 4, 4, 4 }, 1);
  medium.EnableDirect(&direct, { 16, 16, 16 });
  const auto index = IndexOf(store, 0);
  const Vec3 eye(0.3f, 0.5f, 5.f);
  ASSERT_EQ(medium.Build(store.View(), index.data(), index.size(), eye, 1e-3, SerialFor()), "");
  medium.ComputeDirect(SerialFor());
  const HenyeyGreenstein phase(fog.G);
  const auto& S = medium.GetOutput().Radiance;
  const Vec3 albedo = fog.Albedo(), sigmaT = fog.SigmaT();
  for (std::size_t t = 0; t < 16 * 16 * 16; ++t)
  {
    const Vec3 p = Vec3(-1.f) + Centre(t, { 16, 16, 16 }) * 2.f;
    const Vec3 d = p - scene.Lights[0].Position;
    const double r = Length(d);
    const double cosine = Dot(d / static_cast<float>(r), Normalize(eye - p));
    for (int c = 0; c < 3; ++c)
    {
      const double expected =
        albedo[c] * phase.Evaluate(static_cast<float>(cosine)) * std::exp(-sigmaT[c] * r) / (r * r);
      EXPECT_NEAR(S[3 * t + c], expected, 1e-4 * expected) << "voxel " << t << " channel " << c;
    }
  }
  // The view changes the phase function's angle, not the shadow rays.
  const Vec3 other(-4.f, 1.f, 0.5f);
  medium.UpdateView(other, SerialFor());
  const Vec3 p = Vec3(-1.f) + Centre(0, { 16, 16, 16 }) * 2.f;
  const Vec3 d = p - scene.Lights[0].Position;
  const double r = Length(d);
  const double expected = albedo[0] *
    phase.Evaluate(Dot(d / static_cast<float>(r), Normalize(other - p))) *
    std::exp(-sigmaT[0] * r) / (r * r);
  EXPECT_NEAR(medium.GetOutput().Radiance[0], expected, 1e-4 * expected);
}

TEST(DirectLight, TransmittanceMarchesTheDensityGrid)
{
  // A slab of density 2 between x = 0 and 0.5 in a box [-1, 1]^3, given as
  // the grid of cell means the reconstruction passes (interpolated between
  // cell centres: the ramps across its faces integrate as the step does),
  // sigma_t 1.5: a segment crossing it along x has optical depth 1.5.
  Medium slab;
  slab.Name = "slab";
  slab.SigmaA = Vec3(0.5f, 1.f, 1.5f);
  slab.SigmaS = Vec3(1.f, 0.5f, 0.f);
  std::vector<float> values(16 * 4 * 4, 0.f);
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 8; i < 12; ++i)
      {
        values[(k * 4 + j) * 16 + i] = 2.f;
      }
  slab.SetDensity(std::make_shared<GridDensity>(
    Box{ Vec3(-1.f), Vec3(1.f) }, std::array<int, 3>{ 16, 4, 4 }, values, true));
  const BrickedGrid grid = BrickedGrid::Sample(
    { 16, 4, 4 }, Box{ Vec3(-1.f), Vec3(1.f) },
    [&](int i, int j, int k) { return values[(k * 4 + j) * 16 + i]; },
    [](const std::array<int, 3>&, const std::array<int, 3>&) { return false; }, SerialFor());
  // A ramp, density x + 1, as point values (trilinear): what the field
  // itself gives when no grid is set; its integral from -0.9 to 0.9 is 1.8.
  Medium ramp;
  ramp.Name = "ramp";
  ramp.SigmaA = Vec3(0.f);
  ramp.SigmaS = Vec3(0.5f);
  ramp.SetDensity(
    std::make_shared<GridDensity>(Box{ Vec3(-1.f), Vec3(1.f) }, std::array<int, 3>{ 3, 2, 2 },
      std::vector<float>{ 0, 1, 2, 0, 1, 2, 0, 1, 2, 0, 1, 2 }, false));
  // The slab eight times as dense: three optical depths a cell, so that
  // the march takes half cells (at most one optical depth a step).
  Medium dense = slab;
  dense.Name = "dense slab";
  dense.SigmaA = slab.SigmaA * 8.f;
  dense.SigmaS = slab.SigmaS * 8.f;
  struct Case
  {
    const Medium* M;
    bool Grid;
    double Depth, Step; // the step in cells
  };
  for (const Case& c : { Case{ &slab, true, 1.5 * 2.0 * 0.5, 1.0 },
         Case{ &dense, true, 12.0 * 2.0 * 0.5, 0.5 }, Case{ &ramp, false, 0.5 * 1.8, 0.5 } })
  {
    Scene scene;
    scene.Media = { *c.M };
    scene.Lights = { PointLight(Vec3(0.f), 1.f) };
    ASSERT_EQ(scene.Validate(), "");
    const RayCaster caster(scene);
    DirectLight direct(scene, caster);
    if (c.Grid)
    {
      direct.SetMediumGrid(0, &grid);
    }
    const Vec3 T = direct.Transmittance(Vec3(-0.9f, 0.1f, -0.2f), Vec3(1.f, 0.f, 0.f), 1.8f);
    for (int channel = 0; channel < 3; ++channel)
    {
      // The midpoint rule misses the interpolation's kinks between cell
      // centres by O(step^2): 0.1 % of the depth here at half-cell steps,
      // four times that at one-cell steps.
      const double tolerance = 4e-3 * c.Step * c.Step;
      EXPECT_NEAR(T[channel], std::exp(-c.Depth), tolerance * c.Depth * std::exp(-c.Depth))
        << c.M->Name << " channel " << channel;
    }
  }
  // Segments that miss the slab see nothing.
  Scene scene;
  scene.Media = { slab };
  scene.Lights = { PointLight(Vec3(0.f), 1.f) };
  const RayCaster caster(scene);
  DirectLight direct(scene, caster);
  direct.SetMediumGrid(0, &grid);
  EXPECT_NEAR(direct.Transmittance(Vec3(-0.9f, 0.f, 0.f), Vec3(1.f, 0.f, 0.f), 0.5f).x, 1.f, 1e-6);
}

TEST(DirectLight, DirectionalBeamAndSpotConeBoundTheLight)
{
  Scene scene;
  scene.Surfaces = { Square("floor", 4.f, 0.f, true, Vec3(0.5f)) };
  Light sun;
  sun.Type = LightType::Directional;
  sun.Direction = Vec3(0.f, 0.f, -1.f);
  sun.Intensity = Vec3(3.f);
  sun.BeamCenter = Vec3(0.f, 0.f, 2.f);
  sun.BeamRadius = 1.f;
  Light spot;
  spot.Type = LightType::Spot;
  spot.Position = Vec3(2.f, 0.f, 1.f);
  spot.Direction = Vec3(0.f, 0.f, -1.f);
  spot.ConeAngle = 45.f;
  spot.Intensity = Vec3(1.f);
  scene.Lights = { sun, spot };
  ASSERT_EQ(scene.Validate(), "");
  const RayCaster caster(scene);
  DirectLight direct(scene, caster);
  const Vec3 lift(0.f, 0.f, 1e-4f);
  LightArrival a;
  ASSERT_TRUE(direct.Arrive(0, Vec3(0.5f, 0.5f, 0.f), lift, a));
  EXPECT_NEAR(a.Irradiance.x, 3.f, 1e-6f);
  EXPECT_FLOAT_EQ(a.Direction.z, -1.f);
  EXPECT_FALSE(direct.Arrive(0, Vec3(0.8f, 0.8f, 0.f), lift, a)); // outside the beam
  EXPECT_FALSE(direct.Arrive(0, Vec3(0.f, 0.f, 3.f), lift, a));   // upstream of the disk
  ASSERT_TRUE(direct.Arrive(1, Vec3(2.5f, 0.f, 0.f), lift, a));   // inside the cone
  EXPECT_NEAR(a.Irradiance.x, 1.f / 1.25f, 1e-4f);
  EXPECT_FALSE(direct.Arrive(1, Vec3(3.2f, 0.f, 0.f), lift, a)); // outside the cone
  // Particles of both lights: each first interaction is left to this class.
  EXPECT_TRUE(direct.IsFirstInteraction(static_cast<std::uint16_t>(scene.LightEmitterId(0)), 0));
  EXPECT_TRUE(direct.IsFirstInteraction(static_cast<std::uint16_t>(scene.LightEmitterId(1)), 0));
  EXPECT_FALSE(direct.IsFirstInteraction(static_cast<std::uint16_t>(scene.LightEmitterId(1)), 1));
  EXPECT_FALSE(direct.IsFirstInteraction(0, 0)); // an emissive surface's particles
}

TEST(DirectLight, AgreesWithTheParticlesItReplaces)
{
  // A floor, a ceiling and a fog layer between them under a spot light, all
  // bounces: each object's mean radiance with the direct light computed
  // agrees with the mean estimated from every hit, within four standard
  // errors of the latter (measured over four independent batches).
  Scene scene;
  scene.Surfaces = { Square("floor", 1.f, 0.f, true, Vec3(0.6f)),
    Square("ceiling", 1.f, 2.f, false, Vec3(0.4f, 0.5f, 0.6f)) };
  Medium fog;
  fog.Name = "fog";
  fog.Bounds = { Vec3(-1.f, -1.f, 0.f), Vec3(1.f, 1.f, 1.5f) };
  fog.SigmaS = Vec3(0.4f);
  fog.SigmaA = Vec3(0.1f);
  fog.G = 0.f;
  scene.Media = { fog };
  Light spot;
  spot.Type = LightType::Spot;
  spot.Position = Vec3(0.f, 0.f, 1.9f);
  spot.Direction = Vec3(0.f, 0.f, -1.f);
  spot.ConeAngle = 30.f;
  spot.Intensity = Vec3(1.f);
  scene.Lights = { spot };
  ASSERT_EQ(scene.Validate(), "");
  const RayCaster caster(scene);
  DirectLight direct(scene, caster);
  const Vec3 eye(0.2f, -3.f, 1.f);
  const double threshold = 1e-12; // every texel its own cells: no blur to compare
  constexpr int Batches = 4;
  std::vector<HitStore> batches;
  for (int b = 0; b < Batches; ++b)
  {
    batches.emplace_back(Trace(scene, 100000, 64, 10 + b));
  }
  for (std::size_t o = 0; o < scene.NumberOfObjects(); ++o)
  {
    const bool surface = o < scene.Surfaces.size();
    auto make = [&]()
    {
      return surface
        ? std::make_unique<ObjectRadiance>(
            scene.Surfaces[o], MakeChart(scene.Surfaces[o], nullptr), std::array<int, 2>{ 8, 8 }, 2)
        : std::make_unique<ObjectRadiance>(scene.Media[0], std::array<int, 3>{ 8, 8, 8 }, 1);
    };
    auto mean = [](const std::vector<float>& v)
    {
      double sum = 0.0;
      for (float x : v)
      {
        sum += x;
      }
      return sum / static_cast<double>(v.size());
    };
    double plain[Batches], split[Batches];
    for (int b = 0; b < Batches; ++b)
    {
      auto p = make(), s = make();
      s->EnableDirect(&direct, { 32, 32, surface ? 1 : 32 });
      const auto index = IndexOf(batches[b], o);
      ASSERT_EQ(
        p->Build(batches[b].View(), index.data(), index.size(), eye, threshold, SerialFor()), "");
      ASSERT_EQ(
        s->Build(batches[b].View(), index.data(), index.size(), eye, threshold, SerialFor()), "");
      s->ComputeDirect(SerialFor());
      plain[b] = mean(p->GetTexture().Radiance);
      split[b] = mean(s->GetOutput().Radiance);
    }
    double a = 0.0, b = 0.0, a2 = 0.0;
    for (int k = 0; k < Batches; ++k)
    {
      a += plain[k] / Batches;
      b += split[k] / Batches;
      a2 += plain[k] * plain[k] / Batches;
    }
    const double standardError = std::sqrt(std::max(0.0, a2 - a * a) / (Batches - 1));
    EXPECT_NEAR(b, a, 4.0 * standardError + 1e-3 * a)
      << "object " << o << ": standard error " << standardError;
  }
}

namespace
{
// A fog over [-1, 1]^3 (sigma_s 0.3, g 0.3: view dependent, so that the
// directional mode applies) under a sun whose beam lights every voxel.
Scene SunlitFog()
{
  Medium fog;
  fog.Name = "fog";
  fog.Bounds = { Vec3(-1.f), Vec3(1.f) };
  fog.SigmaS = Vec3(0.3f);
  fog.SigmaA = Vec3(0.f);
  fog.G = 0.3f;
  Scene scene;
  scene.Media = { fog };
  Light sun;
  sun.Type = LightType::Directional;
  sun.Direction = Normalize(Vec3(0.3f, -1.f, 0.2f));
  sun.BeamCenter = Vec3(0.f, 3.f, 0.f);
  sun.BeamRadius = 4.f; // every voxel lit: no beam edge to average over
  sun.Intensity = Vec3(2.f);
  scene.Lights = { sun };
  return scene;
}

// The largest difference, over the `texels` voxels, between the fog's
// order-3 directional radiance toward `eye` (red), its direct light
// computed on `output` voxels, and expected(direct, voxel centre).
template <typename Expected>
double WorstDirectional(const std::array<int, 3>& texels, const std::array<int, 3>& output,
  const Vec3& eye, Expected expected)
{
  const Scene scene = SunlitFog();
  EXPECT_EQ(scene.Validate(), "");
  const RayCaster caster(scene);
  DirectLight direct(scene, caster);
  const HitStore store(Trace(scene, 20000, 1));
  ObjectRadiance medium(scene.Media[0], texels, 1);
  medium.EnableDirect(&direct, output);
  const auto index = IndexOf(store, 0);
  EXPECT_EQ(medium.Build(store.View(), index.data(), index.size(), eye, 1e-3, SerialFor()), "");
  medium.ComputeDirect(SerialFor());
  EXPECT_EQ(medium.BuildDirectional(3, SerialFor()), "");
  std::vector<float> evaluated;
  medium.GetDirectional().Evaluate(eye, evaluated);
  const std::size_t voxels = static_cast<std::size_t>(texels[0]) * texels[1] * texels[2];
  EXPECT_EQ(evaluated.size(), 3 * voxels);
  double worst = evaluated.size() == 3 * voxels ? 0.0 : 1e30;
  for (std::size_t v = 0; v < voxels && worst < 1e30; ++v)
  {
    const Vec3 centre = Vec3(-1.f) + Centre(v, texels) * 2.f;
    worst = std::max(worst, std::abs(evaluated[3 * v] - expected(direct, centre)));
  }
  return worst;
}

// The order-3 projection of an HG lobe of g = 0.3 drops the terms l >= 4,
// at most sum g^l (2l + 1) / (4 pi) per unit of irradiance.
double TruncatedBands()
{
  double truncation = 0.0;
  for (int l = 4; l < 60; ++l)
  {
    truncation += std::pow(0.3, l) * (2 * l + 1) / (4.0 * Pi);
  }
  return truncation;
}
}

TEST(DirectLight, DirectionalMediaProjectTheDirectLight)
{
  // g = 0: the projection of S_1 holds it exactly (the l = 0 term), so the
  // directional evaluation is the mean of the output voxels in each voxel:
  // per voxel, the mean over its 2^3 output voxels of S_1 toward the eye
  // from the voxel's centre.
  const Vec3 eye(0.f, 0.f, 6.f);
  const HenyeyGreenstein phase(0.3f);
  const double worst = WorstDirectional({ 4, 4, 4 }, { 8, 8, 8 }, eye,
    [&](const DirectLight& direct, const Vec3& centre)
    {
      double expected = 0.0;
      for (std::size_t t = 0; t < 512; ++t)
      {
        const Vec3 p = Vec3(-1.f) + Centre(t, { 8, 8, 8 }) * 2.f;
        LightArrival a;
        if (std::abs(p.x - centre.x) < 0.25f && std::abs(p.y - centre.y) < 0.25f &&
          std::abs(p.z - centre.z) < 0.25f && direct.Arrive(0, p, Vec3(0.f), a))
        {
          expected +=
            phase.Evaluate(Dot(a.Direction, Normalize(eye - centre))) * a.Irradiance.x / 8.0;
        }
      }
      return expected; // albedo 1
    });
  EXPECT_LT(worst, TruncatedBands() * 2.0 + 1e-5) << "largest difference " << worst;
}

TEST(DirectLight, DirectionalMediaProjectTheDirectLightOfACoarserGrid)
{
  // The output grid is at most the field's own resolution while the
  // texture's follows the particles: here 3^3 output voxels under 6^3
  // texels, so that two texels in three along each axis hold no output
  // voxel's centre. Each takes the lobe of the output voxel holding its
  // own centre; none is left without its direct light (they were, and a
  // plume's SH image went 40 % dark where its texels outnumbered the
  // field's cells).
  const Vec3 eye(0.f, 0.f, 6.f);
  const HenyeyGreenstein phase(0.3f);
  const double worst = WorstDirectional({ 6, 6, 6 }, { 3, 3, 3 }, eye,
    [&](const DirectLight& direct, const Vec3& centre)
    {
      // The output voxel holding the texel's centre, and its own centre.
      Vec3 p;
      for (int a = 0; a < 3; ++a)
      {
        const int i = std::min(static_cast<int>((centre[a] + 1.f) / 2.f * 3.f), 2);
        p[a] = -1.f + (static_cast<float>(i) + 0.5f) * 2.f / 3.f;
      }
      LightArrival a;
      return direct.Arrive(0, p, Vec3(0.f), a)
        ? phase.Evaluate(Dot(a.Direction, Normalize(eye - centre))) * a.Irradiance.x
        : 0.0; // albedo 1
    });
  EXPECT_LT(worst, TruncatedBands() * 2.0 + 1e-5) << "largest difference " << worst;
}

TEST(DirectLight, ViewUpdatesAndAddedParticlesEqualAFullBuild)
{
  // With the direct light computed, a view update equals a build toward the
  // new eye, and adding the particles that double the count equals a build
  // with all of them (bitwise: the direct term does not depend on the
  // particles, the textures are the paths without it).
  Medium fog;
  fog.Name = "fog";
  fog.Bounds = { Vec3(-1.f), Vec3(1.f) };
  fog.SigmaS = Vec3(0.6f);
  fog.SigmaA = Vec3(0.1f);
  fog.G = 0.6f;
  Scene scene;
  scene.Media = { fog };
  scene.Lights = { PointLight(Vec3(0.2f, 0.1f, 0.f), 1.f) };
  ASSERT_EQ(scene.Validate(), "");
  const RayCaster caster(scene);
  DirectLight direct(scene, caster);
  const std::uint64_t n = 40000;
  // Particles [0, n) of a run of n, of 2n, and [n, 2n) of 2n.
  const RayCaster tracerCaster(scene);
  TraceSettings settings;
  settings.Seed = 5;
  const LightTracer tracer(scene, tracerCaster, settings);
  std::vector<Hit> first, all, second;
  TraceCounters counters;
  tracer.TraceParticles(0, n, n, first, counters);
  tracer.TraceParticles(0, 2 * n, 2 * n, all, counters);
  tracer.TraceParticles(n, 2 * n, 2 * n, second, counters);
  const HitStore a(first), b(all), c(second);
  const auto ia = IndexOf(a, 0), ib = IndexOf(b, 0), ic = IndexOf(c, 0);
  const double threshold = 1e-3;
  const Vec3 eye(0.f, 0.f, 5.f), other(0.3f, 0.2f, 5.f);
  ObjectRadiance progressive(scene.Media[0], { 6, 6, 6 }, 2), full(scene.Media[0], { 6, 6, 6 }, 2),
    turned(scene.Media[0], { 6, 6, 6 }, 2);
  for (ObjectRadiance* r : { &progressive, &full, &turned })
  {
    r->EnableDirect(&direct, { 12, 12, 12 });
  }
  ASSERT_EQ(progressive.Build(a.View(), ia.data(), ia.size(), eye, threshold, SerialFor()), "");
  progressive.ComputeDirect(SerialFor());
  const std::vector<float> before = progressive.GetOutput().Radiance;
  // Particles added: the direct term stays, the textures gain the new paths.
  ASSERT_EQ(progressive.Add(c.View(), ic.data(), ic.size(), 0.5, eye, threshold, SerialFor()), "");
  ASSERT_EQ(full.Build(b.View(), ib.data(), ib.size(), eye, threshold, SerialFor()), "");
  full.ComputeDirect(SerialFor());
  EXPECT_EQ(progressive.GetOutput().Radiance, full.GetOutput().Radiance);
  EXPECT_NE(progressive.GetOutput().Radiance, before);
  // A new eye: the update equals a build toward it.
  progressive.UpdateView(other, SerialFor());
  ASSERT_EQ(turned.Build(b.View(), ib.data(), ib.size(), other, threshold, SerialFor()), "");
  turned.ComputeDirect(SerialFor());
  EXPECT_EQ(progressive.GetOutput().Radiance, turned.GetOutput().Radiance);
}
