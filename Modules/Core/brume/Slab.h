// SPDX-License-Identifier: BSD-3-Clause
// Validation against transport codes: a collimated beam at normal incidence
// on a laterally infinite, index-matched slab (the set-up of adding-doubling
// and MCML tables).
#ifndef brume_Slab_h
#define brume_Slab_h

#include "brume/LightTracer.h"
#include "brume/Parallel.h"

#include <cstdint>
#include <memory>

namespace brume
{

struct SlabSpec
{
  double Albedo = 0.9;
  double OpticalThickness = 1.0;
  double G = 0.0;
};

/// Sums over particles of each particle's share of the incident power.
struct SlabTally
{
  double Particles = 0;
  double Sum[3] = { 0, 0, 0 }; // R_diffuse, T_diffuse, T_unscattered
  double Sum2[3] = { 0, 0, 0 };
  void Add(const SlabTally& o);
  /// Mean (fraction of the incident power) and its standard error.
  double Mean(int i) const { return this->Sum[i] / this->Particles; }
  double StandardError(int i) const;
};

/// Traces particles through a slab with the Brume light tracer.
class SlabExperiment
{
public:
  /// Empty `GetError()` when the specification is valid.
  SlabExperiment(const SlabSpec& spec, std::uint64_t seed);
  ~SlabExperiment();
  const std::string& GetError() const { return this->Error; }

  /// Traces particles [begin, end) of `count` into `tally`.
  void Trace(std::uint64_t begin, std::uint64_t end, std::uint64_t count, SlabTally& tally) const;

  /// Traces `count` particles in fixed blocks (possibly in parallel) and
  /// sums the blocks in order: the same figures for any thread count.
  SlabTally Run(std::uint64_t count, const ParallelFor& parallelFor) const;

private:
  std::string Error;
  Scene SlabScene;
  std::unique_ptr<RayCaster> Caster;
  std::unique_ptr<LightTracer> Tracer;
};

} // namespace brume

#endif
