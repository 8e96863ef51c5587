// SPDX-License-Identifier: BSD-3-Clause
#include "brume/Slab.h"

#include <algorithm>
#include <cmath>

namespace brume
{

void SlabTally::Add(const SlabTally& o)
{
  this->Particles += o.Particles;
  for (int i = 0; i < 3; ++i)
  {
    this->Sum[i] += o.Sum[i];
    this->Sum2[i] += o.Sum2[i];
  }
}

double SlabTally::StandardError(int i) const
{
  const double n = this->Particles;
  const double mean = this->Sum[i] / n;
  const double variance = std::max(0.0, this->Sum2[i] / n - mean * mean);
  return std::sqrt(variance / (n - 1.0));
}

SlabExperiment::SlabExperiment(const SlabSpec& spec, std::uint64_t seed)
{
  if (!(spec.OpticalThickness > 0.0) || !std::isfinite(spec.OpticalThickness) ||
    spec.OpticalThickness > 1e4)
  {
    this->Error = "the optical thickness must be in (0, 1e4]";
    return;
  }
  if (!(spec.Albedo >= 0.0 && spec.Albedo <= 1.0))
  {
    this->Error = "the albedo must be in [0, 1]";
    return;
  }
  // sigma_t = 1: the slab 0 <= y <= tau, laterally (practically) infinite.
  Medium slab;
  slab.Name = "slab";
  const float tau = static_cast<float>(spec.OpticalThickness);
  slab.Bounds = { { -1e7f, 0.f, -1e7f }, { 1e7f, tau, 1e7f } };
  slab.SigmaS = Vec3(static_cast<float>(spec.Albedo));
  slab.SigmaA = Vec3(static_cast<float>(1.0 - spec.Albedo));
  slab.G = static_cast<float>(spec.G);
  this->SlabScene.Media.push_back(slab);
  // A collimated pencil beam straight down onto the slab.
  Light beam;
  beam.Name = "beam";
  beam.Type = LightType::Directional;
  beam.Direction = { 0.f, -1.f, 0.f };
  beam.BeamCenter = { 0.f, tau + 1.f, 0.f };
  beam.BeamRadius = 1e-3f;
  beam.Intensity = Vec3(1.f);
  this->SlabScene.Lights.push_back(beam);
  this->Error = this->SlabScene.Validate();
  if (!this->Error.empty())
  {
    return;
  }
  this->Caster.reset(new RayCaster(this->SlabScene));
  TraceSettings settings;
  settings.Seed = seed;
  settings.MaxDepth = 10000000; // Russian roulette ends the random walks
  this->Tracer.reset(new LightTracer(this->SlabScene, *this->Caster, settings));
}

SlabExperiment::~SlabExperiment() = default;

void SlabExperiment::Trace(
  std::uint64_t begin, std::uint64_t end, std::uint64_t count, SlabTally& tally) const
{
  std::vector<Hit> hits;
  TraceCounters counters;
  const double incident = Average(this->Tracer->GetTotalPower()) / static_cast<double>(count);
  for (std::uint64_t i = begin; i < end; ++i)
  {
    hits.clear();
    ParticleExit exit;
    this->Tracer->TraceParticle(i, count, hits, counters, &exit);
    double share[3] = { 0, 0, 0 };
    if (exit.Escaped)
    {
      const double f = Average(exit.Flux) / incident;
      const int kind = exit.Direction.y > 0.f ? 0 : (exit.Depth > 0 ? 1 : 2);
      share[kind] = f;
    }
    tally.Particles += 1.0;
    for (int k = 0; k < 3; ++k)
    {
      tally.Sum[k] += share[k];
      tally.Sum2[k] += share[k] * share[k];
    }
  }
}

SlabTally SlabExperiment::Run(std::uint64_t count, const ParallelFor& parallelFor) const
{
  constexpr std::uint64_t Block = 4096;
  const std::uint64_t blocks = (count + Block - 1) / Block;
  std::vector<SlabTally> tallies(blocks);
  parallelFor(0, blocks,
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t b = begin; b < end; ++b)
      {
        this->Trace(b * Block, std::min<std::uint64_t>((b + 1) * Block, count), count, tallies[b]);
      }
    });
  SlabTally total;
  for (const SlabTally& t : tallies)
  {
    total.Add(t);
  }
  return total;
}

} // namespace brume
