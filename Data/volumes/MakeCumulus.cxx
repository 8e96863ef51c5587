// SPDX-License-Identifier: BSD-3-Clause
// Writes Data/scenes/cumulus.json's volume: a procedural cumulus cloud as a
// sparse OpenVDB float grid named "density" (values in [0, 1], one-metre
// voxels, only the voxels with density active), its base 60 m up.
//
//   MakeCumulus OUTPUT.vdb
//
// The shape is a union of spheres with a flat base, its surface broken up by
// four octaves of value noise (a hash of the lattice point, smoothstep
// interpolated): deterministic, the same file on every machine.
#include "BrumeValueNoise.h"
#include "BrumeVdbWriter.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>

namespace
{
using BrumeValueNoise::Noise;
using BrumeValueNoise::Smooth;

// Four octaves, in [0, 1).
double Fbm(double x, double y, double z)
{
  double sum = 0.0, amplitude = 0.5, total = 0.0;
  for (int octave = 0; octave < 4; ++octave)
  {
    sum += amplitude * Noise(x, y, z);
    total += amplitude;
    x *= 2.03;
    y *= 2.03;
    z *= 2.03;
    amplitude *= 0.5;
  }
  return sum / total;
}

// The cloud's density at (x, y, z) metres, the base at y = 0.
double Density(double x, double y, double z)
{
  struct Sphere
  {
    double X, Y, Z, R;
  };
  static const std::array<Sphere, 6> puffs = { { { 0, 8, 0, 30 }, { -28, 2, 6, 22 },
    { 26, 4, -4, 24 }, { 8, 24, 4, 20 }, { -12, 18, -10, 17 }, { 40, -2, 8, 14 } } };
  double shape = -1e30;
  for (const Sphere& s : puffs)
  {
    const double d =
      std::sqrt((x - s.X) * (x - s.X) + (y - s.Y) * (y - s.Y) + (z - s.Z) * (z - s.Z));
    shape = std::max(shape, 1.0 - d / s.R);
  }
  if (shape < -0.3)
  {
    return 0.0; // beyond the noise's reach
  }
  const double base = std::clamp(y / 6.0, 0.0, 1.0); // a flat, soft base
  const double d = shape + 0.45 * (Fbm(x / 14.0, y / 14.0, z / 14.0) - 0.5);
  return Smooth(std::clamp(d / 0.2, 0.0, 1.0)) * base;
}
}

int main(int argc, char* argv[])
{
  if (argc != 2)
  {
    std::fprintf(stderr, "usage: MakeCumulus OUTPUT.vdb\n");
    return 2;
  }
  try
  {
    brume::vdbwriter::Grid grid;
    grid.FogVolume = true;
    // One-metre voxels; the base 60 m above the ground.
    grid.Translation = { 0.0, 60.0, 0.0 };
    grid.Lower = { -70, -2, -50 };
    grid.Upper = { 70, 50, 50 };
    grid.Value = [](int i, int j, int k)
    {
      const double v = Density(i, j, k);
      return v > 1e-3 ? static_cast<float>(v) : std::nanf("");
    };
    grid.Prune = true;
    const auto active = brume::vdbwriter::Write(argv[1], { grid });
    std::printf(
      "%s: %llu active voxels\n", argv[1], static_cast<unsigned long long>(active.front()));
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "MakeCumulus: %s\n", e.what());
    return 1;
  }
  return 0;
}
