// SPDX-License-Identifier: BSD-3-Clause
// Phase 1 of Jimenez & Pueyo (2003), section 2: Monte Carlo light tracing.
//
// Particles leave the emitters with a share of their power, travel through the
// scene, collide with surfaces (Lambertian BRDF sampling) and media (exact
// free-flight sampling in homogeneous media, Henyey-Greenstein phase
// sampling). Every interaction is stored as a Hit carrying the flux that
// arrived there.
#ifndef brume_LightTracer_h
#define brume_LightTracer_h

#include "brume/RayCaster.h"
#include "brume/Scene.h"

#include <cstdint>
#include <string>
#include <vector>

namespace brume
{

/// One stored particle interaction: 44 bytes.
struct Hit
{
  /// World-space position of the interaction.
  float Position[3];
  /// Unit direction of travel of the particle when it arrived.
  float Direction[3];
  /// Flux (W per channel) carried by the particle when it arrived, before the
  /// surface reflectance or the medium albedo is applied.
  float Flux[3];
  /// Scene object id (surfaces first, then media).
  std::uint16_t Object;
  /// Object id of the emitting surface.
  std::uint16_t Emitter;
  /// Number of interactions before this one (0: straight from the light).
  std::uint8_t Depth;
  std::uint8_t Padding[3];
};
static_assert(sizeof(Hit) == 44, "Hit layout changed: update the documentation");

struct TraceSettings
{
  std::uint64_t Seed = 0;
  /// Interactions after which a particle is stopped.
  int MaxDepth = 64;
  /// Interactions after which Russian roulette may end a particle.
  int RouletteDepth = 3;
};

struct TraceCounters
{
  std::uint64_t Rays = 0;
  std::uint64_t Hits = 0;
  void Add(const TraceCounters& o)
  {
    this->Rays += o.Rays;
    this->Hits += o.Hits;
  }
};

class LightTracer
{
public:
  /// The scene must have passed Scene::Validate() and outlive the tracer.
  LightTracer(const Scene& scene, const RayCaster& caster, const TraceSettings& settings);

  /// Total emitted power per channel (W): sum of pi * L_e * A over emitters.
  Vec3 GetTotalPower() const { return this->TotalPower; }

  /// Traces particle `index` of `count` and appends its hits to `hits`.
  /// Deterministic: depends only on (seed, index, count).
  void TraceParticle(std::uint64_t index, std::uint64_t count, std::vector<Hit>& hits,
    TraceCounters& counters) const;

private:
  struct EmitterTriangle
  {
    std::uint32_t Surface;
    std::uint32_t Triangle;
    Vec3 Normal; // unit, front side of emission
    Vec3 Radiance;
    double Area;
  };

  const Scene& SceneRef;
  const RayCaster& Caster;
  TraceSettings Settings;
  std::vector<EmitterTriangle> Emitters;
  std::vector<double> EmitterCdf;
  Vec3 TotalPower;
};

} // namespace brume

#endif
