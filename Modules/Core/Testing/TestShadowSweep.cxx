// SPDX-License-Identifier: BSD-3-Clause
// The swept shadow rays (brume/ShadowSweep.h) against each texel's own
// shadow ray (DirectLight::AddOpticalDepth from the texel to the light).
#include "brume/DirectLight.h"
#include "brume/RayCaster.h"
#include "brume/Sampling.h"
#include "brume/ShadowSweep.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <iostream>
#include <limits>
#include <memory>

using namespace brume;

namespace
{
constexpr int Points = 49; // the density's grid: 48 cells a side over [-1, 1]^3

// A medium over [-1, 1]^3 whose density is f at the grid's points.
Medium GridMedium(const std::function<float(const Vec3&)>& f, float sigmaT)
{
  std::vector<float> values;
  for (int k = 0; k < Points; ++k)
    for (int j = 0; j < Points; ++j)
      for (int i = 0; i < Points; ++i)
      {
        const Vec3 p = Vec3(-1.f) +
          Vec3(static_cast<float>(i), static_cast<float>(j), static_cast<float>(k)) *
            (2.f / (Points - 1));
        values.push_back(f(p));
      }
  Medium m;
  m.Name = "field";
  m.Bounds = { Vec3(-1.f), Vec3(1.f) };
  m.SigmaS = Vec3(0.8f * sigmaT);
  m.SigmaA = Vec3(0.2f * sigmaT);
  m.Density = std::make_shared<GridDensity>(
    m.Bounds, std::array<int, 3>{ Points, Points, Points }, std::move(values), false);
  return m;
}

Light Sun(const Vec3& direction)
{
  Light sun;
  sun.Type = LightType::Directional;
  sun.Direction = Normalize(direction);
  sun.BeamCenter = sun.Direction * -4.f;
  sun.BeamRadius = 8.f;
  sun.Intensity = Vec3(1.f);
  return sun;
}

Light Lamp(const Vec3& position)
{
  Light lamp;
  lamp.Type = LightType::Point;
  lamp.Position = position;
  lamp.Intensity = Vec3(1.f);
  return lamp;
}

// The largest difference in optical depth (red) between the sweep of light
// `k` over a grid of `texels`^3 over the medium and each texel's own ray.
double LargestDifference(const Scene& scene, std::size_t k, int texels, double* largestDepth)
{
  const RayCaster caster(scene);
  const DirectLight direct(scene, caster);
  const std::array<int, 3> dims{ texels, texels, texels };
  const Box& box = scene.Media[0].Bounds;
  ShadowSweep sweep;
  EXPECT_TRUE(sweep.Plan(direct, k, box, dims));
  const std::vector<float> swept = sweep.Depths({});
  double worst = 0.0;
  *largestDepth = 0.0;
  for (int z = 0; z < texels; ++z)
    for (int y = 0; y < texels; ++y)
      for (int x = 0; x < texels; ++x)
      {
        const Vec3 centre = box.lower +
          (Vec3(static_cast<float>(x), static_cast<float>(y), static_cast<float>(z)) + Vec3(0.5f)) *
            (box.Extent() / static_cast<float>(texels));
        LightArrival a;
        float distance = 0.f;
        EXPECT_TRUE(direct.ArriveUnattenuated(k, centre, Vec3(0.f), a, distance));
        double depth[3] = { 0.0, 0.0, 0.0 };
        direct.AddOpticalDepth(centre, -a.Direction, distance, depth);
        const std::size_t t = (static_cast<std::size_t>(z) * texels + y) * texels + x;
        worst = std::max(worst, std::abs(swept[3 * t] - depth[0]));
        *largestDepth = std::max(*largestDepth, depth[0]);
      }
  return worst;
}
}

TEST(ShadowSweep, ExactWhereTexelsLieOnTheRays)
{
  // Straight down through a density linear in x, y and z: the rays run through
  // the texel centres, and a midpoint march of a linear density is exact
  // however it is split, so the sweep equals the texels' own rays.
  Scene scene;
  scene.Media = { GridMedium(
    [](const Vec3& p) { return 1.5f + 0.5f * p.x - 0.3f * p.y + 0.4f * p.z; }, 2.f) };
  scene.Lights = { Sun(Vec3(0.f, -1.f, 0.f)) };
  ASSERT_EQ(scene.Validate(), "");
  double depth = 0.0;
  const double worst = LargestDifference(scene, 0, 16, &depth);
  EXPECT_GT(depth, 5.0);
  EXPECT_LT(worst, 1e-5 * depth);
}

TEST(ShadowSweep, WithinTheInterpolationBoundOfEachTexelsRay)
{
  // A Gaussian blob of peak c and width w under an oblique sun and a lamp
  // above it. A texel's depth is its four rays' interpolated bilinearly,
  // RaysPerTexel per texel side apart (h): at most h^2 / 8 times the depth's
  // second derivative across the rays on each axis, and the depth from a
  // point to the light is a partial line integral of the blob, whose second
  // derivative across the line is at most c sqrt(2 pi) / w. The two
  // marches (midpoint rules of steps up to half a grid cell, s) differ by at
  // most s^2 / 24 times the density's second derivative along the ray
  // (c / w^2) over the ray's length in the box (at most 2 sqrt(3)), each.
  const float c = 3.f, w = 0.35f;
  Scene scene;
  scene.Media = { GridMedium(
    [&](const Vec3& p) { return c * std::exp(-Dot(p, p) / (2.f * w * w)); }, 1.f) };
  scene.Lights = { Sun(Vec3(0.3f, -1.f, 0.45f)), Lamp(Vec3(0.4f, 3.f, -0.2f)) };
  ASSERT_EQ(scene.Validate(), "");
  const int texels = 24;
  const double h = 2.0 / texels / ShadowSweep::RaysPerTexel, s = 2.0 / (Points - 1) / 2.0;
  const double interpolation = h * h / 8.0 * 2.0 * c * std::sqrt(2.0 * Pi) / w;
  const double march = 2.0 * s * s / 24.0 * c / (w * w) * 2.0 * std::sqrt(3.0);
  for (std::size_t k = 0; k < 2; ++k)
  {
    double depth = 0.0;
    const double worst = LargestDifference(scene, k, texels, &depth);
    EXPECT_GT(depth, 1.5) << "light " << k;
    // The lamp's rays lie h apart only in the farthest plane, closer nearer it.
    EXPECT_LT(worst, interpolation + march) << "light " << k << ": largest depth " << depth;
  }
}

TEST(ShadowSweep, NotWhereALampIsAmongThePlanes)
{
  // A lamp inside the grid's span along every axis has no side to sweep from.
  Scene scene;
  scene.Media = { GridMedium([](const Vec3&) { return 1.f; }, 1.f) };
  scene.Lights = { Lamp(Vec3(0.1f, 0.2f, -0.3f)), Lamp(Vec3(0.1f, 3.f, -0.3f)) };
  ASSERT_EQ(scene.Validate(), "");
  const RayCaster caster(scene);
  const DirectLight direct(scene, caster);
  ShadowSweep sweep;
  EXPECT_FALSE(sweep.Plan(direct, 0, scene.Media[0].Bounds, { 16, 16, 16 }));
  EXPECT_TRUE(sweep.Plan(direct, 1, scene.Media[0].Bounds, { 16, 16, 16 }));
  EXPECT_EQ(sweep.NumberOfPlanes(), 16);
  EXPECT_LE(static_cast<double>(sweep.NumberOfRays()),
    ShadowSweep::MaxRayFactor * 16 * 16 * ShadowSweep::RaysPerTexel * ShadowSweep::RaysPerTexel);
}

TEST(ShadowSweep, ALampNearTheGridIsSweptInRunsOfPlanes)
{
  // A lamp close above the grid: rays through the farthest plane's texels,
  // h apart there, would lie far closer than needed near the lamp (and a
  // lamp just beyond the first plane's texels would need 2 x 64 times the
  // grid's rays). Each run of planes, from one to the farthest at most
  // twice as far from the lamp, casts its own rays, starting from the
  // depths of the run before interpolated where they cross its last plane:
  // within the interpolation bound of the test above once per run, with
  // at most MaxRayFactor times a plane's rays a run, and marching less
  // than the texels' own rays would.
  const float c = 3.f, w = 0.35f;
  Scene scene;
  scene.Media = { GridMedium(
    [&](const Vec3& p) { return c * std::exp(-Dot(p, p) / (2.f * w * w)); }, 1.f) };
  scene.Lights = { Lamp(Vec3(0.3f, 1.25f, -0.2f)), Lamp(Vec3(0.1f, 1.001f, -0.3f)) };
  ASSERT_EQ(scene.Validate(), "");
  const int texels = 24;
  const double h = 2.0 / texels / ShadowSweep::RaysPerTexel, s = 2.0 / (Points - 1) / 2.0;
  const double interpolation = h * h / 8.0 * 2.0 * c * std::sqrt(2.0 * Pi) / w;
  const double march = 2.0 * s * s / 24.0 * c / (w * w) * 2.0 * std::sqrt(3.0);
  const RayCaster caster(scene);
  const DirectLight direct(scene, caster);
  const double onePlane =
    static_cast<double>(texels) * texels * ShadowSweep::RaysPerTexel * ShadowSweep::RaysPerTexel;
  for (std::size_t k = 0; k < 2; ++k)
  {
    ShadowSweep sweep;
    ASSERT_TRUE(sweep.Plan(direct, k, scene.Media[0].Bounds, { texels, texels, texels }));
    const std::size_t runs = sweep.NumberOfRuns();
    EXPECT_GT(runs, k == 0 ? 1u : 4u);
    EXPECT_LE(
      static_cast<double>(sweep.NumberOfRays()), ShadowSweep::MaxRayFactor * onePlane * runs);
    // The texels' own rays: from each texel to where it leaves the box.
    double perTexel = 0.0;
    const Box& box = scene.Media[0].Bounds;
    for (int t = 0; t < texels * texels * texels; ++t)
    {
      const Vec3 centre = box.lower +
        (Vec3(static_cast<float>(t % texels), static_cast<float>((t / texels) % texels),
           static_cast<float>(t / (texels * texels))) +
          Vec3(0.5f)) *
          (box.Extent() / static_cast<float>(texels));
      float t0 = 0.f, t1 = std::numeric_limits<float>::max();
      if (box.Intersect(centre, -direct.DirectionAt(k, centre), t0, t1))
      {
        perTexel += t1 - t0;
      }
    }
    EXPECT_LT(sweep.MarchLength(), 0.5 * perTexel) << "light " << k;
    double depth = 0.0;
    const double worst = LargestDifference(scene, k, texels, &depth);
    std::cout << "light " << k << ": " << runs << " runs, " << sweep.NumberOfRays()
              << " rays, march " << sweep.MarchLength() << " against " << perTexel
              << " per texel; largest difference " << worst << " (bound "
              << static_cast<double>(runs) * interpolation + march << "), largest depth " << depth
              << "\n";
    EXPECT_GT(depth, 1.5) << "light " << k;
    EXPECT_LT(worst, static_cast<double>(runs) * interpolation + march) << "light " << k;
  }
}
