// SPDX-License-Identifier: BSD-3-Clause
// The sub-commands of `brume` other than render.
#ifndef BrumeCommands_h
#define BrumeCommands_h

#include <cstdint>
#include <optional>
#include <string>

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
  std::optional<long long> Particles; // unset: the light tracer's default
  std::uint64_t Seed = 0;
  /// Where to write the figures as JSON (none when empty).
  std::string Json;
  /// Points per axis of the render pass's volume, whose transfer-function
  /// edits are timed.
  int VolumePoints = 21;
};

/// `brume bench`: phase-1 throughput against Embree's raw throughput.
int RunBench(const BenchOptions& options);

struct ChartOptions
{
  std::string Output = "chart.png";
  std::string Csv = "chart.csv";
  std::string CacheDirectory;
  int Width = 128;
  int Height = 128;
  long long MinParticles = 10000;
  long long MaxParticles = 10000000;
  int MaxSamples = 1024;
  int ReferenceSamples = 16384;
  std::optional<double> Threshold; // unset: the scene file's render.threshold, else the default
  std::uint64_t Seed = 0;
  bool Sweep = false;
  int Supersample = 4;   // the pipeline's samples per pixel along each axis
  int ShOrder = 3;       // spherical-harmonics order of the SH rows
  std::string Scene;     // a scene file; empty: the built-in default scene
  std::string Medium;    // the medium the stability sweep edits; empty: the scene's first medium
  std::string Surface;   // the surface the sweep makes glossy/mirror; empty: chosen automatically
  std::string Parameter; // the sweep's only parameter; empty: every case
};

/// `brume chart`: error against time for the pipeline and the path tracer.
int RunChart(const ChartOptions& options);

#endif
