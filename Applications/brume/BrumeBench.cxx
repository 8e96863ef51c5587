// SPDX-License-Identifier: BSD-3-Clause
#include "BrumeCommands.h"

#include "vtkBrumeDefaultSceneSource.h"
#include "vtkBrumeLightTracer.h"
#include "vtkNew.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"

#include "brume/LightTracer.h"

#include "vtkBrumeSceneConversion.h"

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

namespace
{
double Seconds(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

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

int RunBench(const BenchOptions& options)
{
  const auto particles = options.Particles;
  std::printf("brume bench: built-in scene, %lld particles, %d threads (vtkSMPTools %s)\n",
    particles, vtkSMPTools::GetEstimatedNumberOfThreads(), vtkSMPTools::GetBackend());

  vtkNew<vtkBrumeDefaultSceneSource> source;
  source->Update();

  // Phase 1 through the VTK filter, hits stored in its output.
  vtkNew<vtkBrumeLightTracer> tracer;
  tracer->SetInputConnection(source->GetOutputPort());
  tracer->SetNumberOfParticles(particles);
  tracer->SetSeed(options.Seed);
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
  if (peakReset && rssBefore > 0 && peak > 0)
  {
    std::printf("peak memory        %8.1f bytes per stored hit (resident-set growth while tracing; "
                "the output arrays take 41)\n",
      1024.0 * static_cast<double>(peak - rssBefore) / hits);
  }

  // The same rays, cast alone through Embree.
  brume::Scene scene;
  vtkBrumeSceneConversion::ToScene(source->GetOutput(), scene);
  const brume::RayCaster caster(scene);
  brume::TraceSettings settings;
  settings.Seed = options.Seed;
  const brume::LightTracer core(scene, caster, settings);
  constexpr long long Block = 4096;
  const long long blocks = (particles + Block - 1) / Block;
  // The transport alone: the same particles, hits dropped as they come.
  start = std::chrono::steady_clock::now();
  vtkSMPTools::For(0, blocks,
    [&](vtkIdType begin, vtkIdType end)
    {
      std::vector<brume::Hit> scratch;
      brume::TraceCounters counters;
      for (vtkIdType b = begin; b < end; ++b)
      {
        for (long long i = b * Block; i < std::min((b + 1) * Block, particles); ++i)
        {
          scratch.clear();
          core.TraceParticle(static_cast<std::uint64_t>(i), static_cast<std::uint64_t>(particles),
            scratch, counters);
        }
      }
    });
  const double transportTime = Seconds(start);
  std::printf("transport only     %8.3f s  (same particles, hits not kept: the rest of the tracing "
              "time is storing %.0f hits)\n",
    transportTime, hits);

  std::vector<brume::RayLog> logs(static_cast<std::size_t>(blocks));
  vtkSMPTools::For(0, blocks,
    [&](vtkIdType begin, vtkIdType end)
    {
      std::vector<brume::Hit> scratch;
      brume::TraceCounters counters;
      for (vtkIdType b = begin; b < end; ++b)
      {
        for (long long i = b * Block; i < std::min((b + 1) * Block, particles); ++i)
        {
          scratch.clear();
          core.TraceParticle(static_cast<std::uint64_t>(i), static_cast<std::uint64_t>(particles),
            scratch, counters, nullptr, &logs[b]);
        }
      }
    });
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
  return 0;
}
