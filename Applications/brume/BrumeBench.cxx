// SPDX-License-Identifier: BSD-3-Clause
// `brume bench`: phase 1 against Embree, then the other phases' figures
// (BrumeBenchPhases.cxx) and whole commands (BrumeBenchCommands.cxx).
#include "BrumeBench.h"

#include "vtkBrumeDefaultSceneSource.h"
#include "vtkBrumeLightTracer.h"
#include "vtkBrumeSceneConversion.h"
#include "vtkNew.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"

#include "brume/LightTracer.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

using namespace BrumeBench;

namespace
{
// A field of /proc/self/status in kB (VmRSS, VmHWM), or -1.
long long StatusKiB(const std::string& field)
{
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
  {
    if (line.compare(0, field.size() + 1, field + ":") == 0)
    {
      return std::stoll(line.substr(field.size() + 1));
    }
  }
  return -1;
}

// Resets the peak resident size (Linux >= 4.0); false when unsupported.
bool ResetPeakMemory()
{
  std::ofstream clear("/proc/self/clear_refs");
  clear << "5";
  return static_cast<bool>(clear);
}
}

namespace
{
// Phase 1's figures beside the report's.
struct Traced
{
  double Seconds, Hits, Rays;
};

// Phase 1 through the VTK filter, hits stored in its output: the time,
// the memory per hit, and tracing again with the last output's memory.
Traced BenchTracer(
  vtkBrumeLightTracer* tracer, long long particles, std::uint64_t seed, Report& report)
{
  tracer->SetNumberOfParticles(particles);
  tracer->SetSeed(seed);
  const long long rssBefore = StatusKiB("VmRSS");
  const bool peakReset = ResetPeakMemory();
  auto start = std::chrono::steady_clock::now();
  tracer->Update();
  const double traceTime = Seconds(start);
  const long long peak = StatusKiB("VmHWM");
  const auto hits = static_cast<double>(tracer->GetOutput()->GetNumberOfPoints());
  const auto rays = static_cast<double>(tracer->GetLastRayCount());
  std::printf(
    "particle tracing   %8.3f s  %7.2f M particles/s  %7.2f M hits/s  (%.0f hits, %.0f rays)\n",
    traceTime, particles / traceTime * 1e-6, hits / traceTime * 1e-6, hits, rays);
  report.Add("particle_tracing", traceTime, "s", "<= 0.30", "hits kept");
  report.Add("hits", hits, "hits");
  if (peakReset && rssBefore > 0 && peak > 0)
  {
    std::printf("peak memory        %8.1f bytes per stored hit (resident-set growth while tracing; "
                "the output arrays take 45)\n",
      1024.0 * static_cast<double>(peak - rssBefore) / hits);
    report.Add("memory_per_hit", 1024.0 * static_cast<double>(peak - rssBefore) / hits, "B",
      "<= 32", "peak resident-set growth while tracing");
  }
  // Tracing again in the same process (another seed, as after an edit in a
  // pipeline): the hits are written where the last output's were, without
  // first touching fresh memory. The bench's own seed is traced once more
  // for the phases after this.
  const auto given = static_cast<vtkIdType>(seed); // at most 2^63 - 1
  tracer->SetSeed(given > 0 ? given - 1 : given + 1);
  start = std::chrono::steady_clock::now();
  tracer->Update();
  const double againTime = Seconds(start);
  const double reusedMB = static_cast<double>(tracer->GetLastReusedBytes()) / 1e6;
  tracer->SetSeed(seed);
  tracer->Update();
  std::printf("tracing again      %8.3f s  (another seed in the same process: its hits written "
              "where the last run's were, %.0f MB)\n",
    againTime, reusedMB);
  report.Add(
    "particle_tracing_again", againTime, "s", "", "another seed, the last output's memory reused");

  return { traceTime, hits, rays };
}

// The same rays, cast alone through Embree, and the transport without
// storing hits: the bounds of the tracer's throughput.
void BenchEmbree(vtkPartitionedDataSetCollection* defaultScene, long long particles,
  std::uint64_t seed, const Traced& traced, Report& report)
{
  const double traceTime = traced.Seconds, hits = traced.Hits, rays = traced.Rays;
  brume::Scene scene;
  vtkBrumeSceneConversion::ToScene(defaultScene, scene);
  const brume::RayCaster caster(scene);
  brume::TraceSettings settings;
  settings.Seed = seed;
  const brume::LightTracer core(scene, caster, settings);
  constexpr auto Block = static_cast<long long>(brume::LightTracer::ParticlesPerBlock);
  const long long blocks = (particles + Block - 1) / Block;
  // The same blocks of particles as the filter, hits dropped as they come.
  auto traceBlocks = [&](std::vector<brume::RayLog>* logs)
  {
    vtkSMPTools::For(0, blocks,
      [&](vtkIdType begin, vtkIdType end)
      {
        std::vector<brume::Hit> scratch;
        brume::TraceCounters counters;
        for (vtkIdType b = begin; b < end; ++b)
        {
          core.TraceParticles(static_cast<std::uint64_t>(b * Block),
            static_cast<std::uint64_t>(std::min((b + 1) * Block, particles)),
            static_cast<std::uint64_t>(particles), scratch, counters, logs ? &(*logs)[b] : nullptr,
            false);
        }
      });
  };
  // The transport alone.
  auto start = std::chrono::steady_clock::now();
  traceBlocks(nullptr);
  const double transportTime = Seconds(start);
  std::printf("transport only     %8.3f s  (same particles, hits not kept: the rest of the tracing "
              "time is storing %.0f hits)\n",
    transportTime, hits);
  report.Add("transport_only", transportTime, "s", "", "the tracing's limit: hits not kept");

  std::vector<brume::RayLog> logs(static_cast<std::size_t>(blocks));
  traceBlocks(&logs);
  std::vector<double> found(static_cast<std::size_t>(blocks), 0.0);
  start = std::chrono::steady_clock::now();
  vtkSMPTools::For(0, blocks,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType b = begin; b < end; ++b)
      {
        const std::vector<float>& r = logs[b].OriginsAndDirections;
        brume::SurfaceHit hit;
        double n = 0;
        for (std::size_t k = 0; k + 5 < r.size(); k += 6)
        {
          n += caster.Intersect({ r[k], r[k + 1], r[k + 2] }, { r[k + 3], r[k + 4], r[k + 5] }, 0.f,
                 std::numeric_limits<float>::infinity(), hit)
            ? 1.0
            : 0.0;
        }
        found[b] = n;
      }
    });
  const double rawTime = Seconds(start);
  double rawRays = 0;
  for (const auto& log : logs)
  {
    rawRays += static_cast<double>(log.OriginsAndDirections.size() / 6);
  }
  std::printf("raw Embree         %8.3f s  %7.2f M rays/s  (the same %.0f rays, closest hit)\n",
    rawTime, rawRays / rawTime * 1e-6, rawRays);
  std::printf("tracer/raw ray throughput ratio: %.3f (tracer %.2f M rays/s)\n",
    (rays / traceTime) / (rawRays / rawTime), rays / traceTime * 1e-6);
  report.Add("raw_embree", rawTime, "s", "", "the same rays, closest hit");
  report.Add(
    "tracer_over_embree_throughput", (rays / traceTime) / (rawRays / rawTime), "ratio", ">= 0.4");
  // What the tracer's ratio would be were storing its hits free.
  const double transportRatio = (rays / transportTime) / (rawRays / rawTime);
  std::printf("transport/raw ray throughput ratio: %.3f (hits not kept: the bound of the tracer's "
              "ratio)\n",
    transportRatio);
  report.Add("transport_over_embree_throughput", transportRatio, "ratio", "",
    "hits not kept: the bound of the tracer's ratio");
}
}

int RunBench(const BenchOptions& given)
{
  // The budget: the one given, else the light tracer's default (whose
  // figures the targets are stated for).
  const long long defaultParticles = vtkNew<vtkBrumeLightTracer>()->GetNumberOfParticles();
  BenchOptions options = given;
  options.Particles = given.Particles.value_or(defaultParticles);
  const long long particles = *options.Particles;
  Report report(particles == defaultParticles);
  if (!options.Json.empty())
  {
    // Told before the minutes of measuring, not after.
    const auto directory = std::filesystem::absolute(options.Json).parent_path();
    std::error_code error;
    if (!std::filesystem::is_directory(directory, error))
    {
      std::fprintf(stderr, "brume bench: cannot write %s: no directory %s\n", options.Json.c_str(),
        directory.string().c_str());
      return 1;
    }
  }
  std::printf("brume bench: built-in scene, %lld particles, %d threads (vtkSMPTools %s)\n",
    particles, vtkSMPTools::GetEstimatedNumberOfThreads(), vtkSMPTools::GetBackend());

  vtkNew<vtkBrumeDefaultSceneSource> source;
  source->Update();

  vtkNew<vtkBrumeLightTracer> tracer;
  tracer->SetInputConnection(source->GetOutputPort());
  const Traced traced = BenchTracer(tracer, particles, options.Seed, report);
  BenchEmbree(source->GetOutput(), particles, options.Seed, traced, report);
  const double update = BenchReconstruction(source, tracer, report);
  BenchRendering(source, tracer, update, report);
  BenchMirror(source->GetOutput(), static_cast<vtkIdType>(particles), options.Seed, report);
  BenchPass(particles, options.VolumePoints, report);
  // A command that fails is said, its figures left out, the others kept.
  const bool commands = BenchWholeCommands(options, report);
  report.PrintSummary();
  if (!options.Json.empty())
  {
    const nlohmann::json run = { { "particles", particles }, { "seed", options.Seed },
      { "threads", vtkSMPTools::GetEstimatedNumberOfThreads() },
      { "smp_backend", vtkSMPTools::GetBackend() } };
    return report.WriteJson(options.Json, run) && commands ? 0 : 1;
  }
  return commands ? 0 : 1;
}
