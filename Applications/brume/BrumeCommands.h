// SPDX-License-Identifier: BSD-3-Clause
// The sub-commands of `brume` other than render.
#ifndef BrumeCommands_h
#define BrumeCommands_h

#include <cstdint>

struct SlabOptions
{
  double Albedo = -1.0;
  double OpticalThickness = -1.0;
  double G = 0.0;
  long long Particles = 1000000;
  std::uint64_t Seed = 0;
};

/// `brume validate slab`: prints the CSV header and the values.
int RunValidateSlab(const SlabOptions& options);

struct BenchOptions
{
  long long Particles = 1000000;
  std::uint64_t Seed = 0;
};

/// `brume bench`: phase-1 throughput against Embree's raw throughput.
int RunBench(const BenchOptions& options);

#endif
