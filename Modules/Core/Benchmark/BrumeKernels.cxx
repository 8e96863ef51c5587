// SPDX-License-Identifier: BSD-3-Clause
// Google Benchmark of the core's hot kernels, each on inputs of the built-in
// scene's size: free-flight sampling (homogeneous and heterogeneous media),
// Henyey-Greenstein sampling, light tracing of one block of particles,
// histogram binning with exact sums, the summed-area table, the adaptive
// texel estimate, and a whole object's texture built from its hits.
//
//   build/bin/brume-kernels                       # every kernel
//   build/bin/brume-kernels --benchmark_filter=SummedArea
//   build/bin/brume-kernels --benchmark_format=json > kernels.json
//
// Figures are per item (a ray, a sample, a particle, a hit, a cell or a
// texel): items_per_second in the output.
#include "brume/DensityEstimation.h"
#include "brume/ExactHistogram.h"
#include "brume/LightTracer.h"
#include "brume/Medium.h"
#include "brume/Parallel.h"
#include "brume/RayCaster.h"
#include "brume/Reconstruction.h"
#include "brume/Sampling.h"
#include "brume/Scene.h"
#include "brume/SummedAreaTable.h"

#include "TestScenes.h" // HitStore: hits as the pipeline holds them

#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <numeric>
#include <vector>

namespace
{
using namespace brume;

// Rays from points on a sphere of radius 2 around the default fog's cube
// toward points inside it, as particles entering the medium.
struct Rays
{
  std::vector<Vec3> Origin, Direction;
  explicit Rays(std::size_t n)
  {
    Random rng(1, 0);
    for (std::size_t i = 0; i < n; ++i)
    {
      const Vec3 o = SampleUniformSphere(rng.NextFloat(), rng.NextFloat()) * 2.f;
      const Vec3 target(rng.NextFloat() - 0.5f, rng.NextFloat() - 0.5f, rng.NextFloat() - 0.5f);
      this->Origin.push_back(o);
      this->Direction.push_back(Normalize(target - o));
    }
  }
};

Medium DefaultFog()
{
  return MakeDefaultScene().Media.at(0);
}

// A cloud-like density: a ball of smooth noise, empty outside radius 0.5,
// on a 64^3 grid over the fog's cube (most majorant blocks empty or thin).
Medium Cloud()
{
  Medium m = DefaultFog();
  const int n = 64;
  std::vector<float> values(static_cast<std::size_t>(n) * n * n);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
      {
        const float x = (i + 0.5f) / n - 0.5f, y = (j + 0.5f) / n - 0.5f, z = (k + 0.5f) / n - 0.5f;
        const float r = std::sqrt(x * x + y * y + z * z);
        const float noise =
          0.5f + 0.5f * std::sin(23.f * x) * std::sin(19.f * y) * std::sin(17.f * z);
        values[(static_cast<std::size_t>(k) * n + j) * n + i] = r < 0.5f ? 4.f * noise : 0.f;
      }
  m.SetDensity(std::make_shared<GridDensity>(
    m.Bounds, std::array<int, 3>{ n, n, n }, std::move(values), true));
  return m;
}

void FreeFlight(benchmark::State& state, const Medium& medium)
{
  const std::vector<Medium> media{ medium };
  const Rays rays(4096);
  std::vector<MediumTracker> trackers(1);
  Random rng(7, 0);
  std::size_t r = 0;
  for (auto _ : state)
  {
    Vec3 weight(1.f);
    float t = 0.f;
    benchmark::DoNotOptimize(SampleCollision(
      media, rays.Origin[r], rays.Direction[r], 10.f, rng, weight, t, trackers.data()));
    benchmark::DoNotOptimize(t);
    r = (r + 1) % rays.Origin.size();
  }
  state.SetItemsProcessed(state.iterations());
}

void BM_FreeFlightHomogeneous(benchmark::State& state)
{
  FreeFlight(state, DefaultFog());
}
BENCHMARK(BM_FreeFlightHomogeneous);

void BM_FreeFlightHeterogeneous(benchmark::State& state)
{
  FreeFlight(state, Cloud());
}
BENCHMARK(BM_FreeFlightHeterogeneous);

void BM_HenyeyGreensteinSample(benchmark::State& state)
{
  const HenyeyGreenstein phase(0.7f);
  Random rng(3, 0);
  Vec3 w(0.f, 0.f, 1.f);
  for (auto _ : state)
  {
    w = phase.Sample(w, rng.NextFloat(), rng.NextFloat());
    benchmark::DoNotOptimize(w);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_HenyeyGreensteinSample);

// One block of the light tracer (LightTracer::ParticlesPerBlock particles of
// the default scene, hits kept), as the VTK filter traces it per thread.
void BM_LightTracerBlock(benchmark::State& state)
{
  const Scene scene = MakeDefaultScene();
  const RayCaster caster(scene);
  const LightTracer tracer(scene, caster, TraceSettings());
  constexpr std::uint64_t Block = LightTracer::ParticlesPerBlock;
  std::vector<Hit> hits;
  std::uint64_t first = 0;
  for (auto _ : state)
  {
    hits.clear();
    TraceCounters counters;
    tracer.TraceParticles(first, first + Block, 1000000, hits, counters);
    benchmark::DoNotOptimize(hits.data());
    first = (first + Block) % 1000000;
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(Block));
}
BENCHMARK(BM_LightTracerBlock)->Unit(benchmark::kMillisecond);

// Exact (fixed-point) binning of 2^20 weighted hits into a 64^3 histogram of
// 4 channels (weight and RGB), cells in random order: cache misses included.
void BM_HistogramBinning(benchmark::State& state)
{
  const std::array<int, 3> dims{ 64, 64, 64 };
  const std::size_t cells = 64 * 64 * 64;
  std::vector<std::uint32_t> cellOf(1u << 20);
  std::vector<double> values(4 * cellOf.size());
  Random rng(5, 0);
  for (std::size_t i = 0; i < cellOf.size(); ++i)
  {
    cellOf[i] = static_cast<std::uint32_t>(rng.NextDouble() * cells);
    for (int c = 0; c < 4; ++c)
    {
      values[4 * i + c] = 1e-6 * rng.NextDouble();
    }
  }
  ExactHistogram histogram(dims, 4, ExactHistogram::QuantumExponent(1e-6));
  for (auto _ : state)
  {
    for (std::size_t i = 0; i < cellOf.size(); ++i)
    {
      histogram.Add(cellOf[i], &values[4 * i]);
    }
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(cellOf.size()));
}
BENCHMARK(BM_HistogramBinning)->Unit(benchmark::kMillisecond);

Histogram SparseHistogram(const std::array<int, 3>& dims, int channels)
{
  Histogram h(dims, channels);
  Random rng(11, 0);
  for (double& v : h.GetValues())
  {
    v = rng.NextFloat() < 0.2f ? rng.NextDouble() : 0.0;
  }
  return h;
}

// The summed-area table of a 64^3 histogram of 4 channels.
void BM_SummedAreaTableBuild(benchmark::State& state)
{
  const Histogram h = SparseHistogram({ 64, 64, 64 }, 4);
  for (auto _ : state)
  {
    const SummedAreaTable sat(h);
    benchmark::DoNotOptimize(&sat);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(h.GetNumberOfCells()));
}
BENCHMARK(BM_SummedAreaTableBuild)->Unit(benchmark::kMillisecond);

// Every texel of a 32^3 texture over that histogram (2 cells per texel per
// axis), regions grown until they hold a weight of 2 (a few cells' worth).
void BM_EstimateTexel(benchmark::State& state)
{
  const std::array<int, 3> dims{ 64, 64, 64 };
  const SummedAreaTable sat(SparseHistogram(dims, 4));
  AdaptiveRegionSettings settings;
  settings.Refinement = { 2, 2, 2 };
  settings.Threshold = 2.0;
  double perCell[4];
  for (auto _ : state)
  {
    for (int k = 0; k < 32; ++k)
      for (int j = 0; j < 32; ++j)
        for (int i = 0; i < 32; ++i)
        {
          benchmark::DoNotOptimize(EstimateTexel(sat, dims, { i, j, k }, settings, perCell));
        }
  }
  state.SetItemsProcessed(state.iterations() * 32 * 32 * 32);
}
BENCHMARK(BM_EstimateTexel)->Unit(benchmark::kMillisecond);

// A whole view-independent texture from its hits: the default scene's back
// wall (binning, table, regions, estimates) from 10^5 particles' hits, on
// the calling thread.
void BM_SurfaceTextureBuild(benchmark::State& state)
{
  const Scene scene = MakeDefaultScene();
  const RayCaster caster(scene);
  const LightTracer tracer(scene, caster, TraceSettings());
  std::vector<Hit> hits;
  TraceCounters counters;
  tracer.TraceParticles(0, 100000, 100000, hits, counters);
  std::size_t wall = 0;
  while (scene.Surfaces[wall].Name != "back")
  {
    ++wall;
  }
  const testing::HitStore store(hits);
  const HitArrays arrays = store.View();
  std::vector<std::uint32_t> index;
  for (std::size_t i = 0; i < hits.size(); ++i)
  {
    if (hits[i].Object == wall)
    {
      index.push_back(static_cast<std::uint32_t>(i));
    }
  }
  const Surface& surface = scene.Surfaces[wall];
  const Vec3 extent(2.f, 2.f, 0.f);
  const auto resolution = ChooseResolution(extent, index.size(), 8.0, 4, 1024);
  for (auto _ : state)
  {
    ObjectRadiance radiance(
      surface, MakeChart(surface, nullptr), { resolution[0], resolution[1] }, 4);
    const std::string error =
      radiance.Build(arrays, index.data(), index.size(), { 0, 0, 4 }, 1e-4, SerialFor());
    if (!error.empty())
    {
      state.SkipWithError(error.c_str());
      break;
    }
    benchmark::DoNotOptimize(radiance.GetTexture().Radiance.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(index.size()));
}
BENCHMARK(BM_SurfaceTextureBuild)->Unit(benchmark::kMillisecond);
} // namespace

BENCHMARK_MAIN();
