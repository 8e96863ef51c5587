// SPDX-License-Identifier: BSD-3-Clause
// Phase 1 of Jimenez & Pueyo (2003), section 2: Monte Carlo light tracing.
//
// Particles leave the emitters (emissive triangles, point, spot and
// directional lights) in proportion to their power, travel through the scene,
// reflect on surfaces (BRDF sampling) and collide in media (delta tracking
// with block majorants and spectral-tracking weights, exact for homogeneous
// colourless media; Henyey-Greenstein phase sampling). Every interaction is
// stored as a Hit carrying the flux that arrived there.
#ifndef brume_LightTracer_h
#define brume_LightTracer_h

#include "brume/RayCaster.h"
#include "brume/Scene.h"

#include <cstdint>
#include <string>
#include <vector>

namespace brume
{

class Random;

/// One stored particle interaction: 48 bytes.
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
  /// Emitter: the emissive surface's object id, or Scene::LightEmitterId(k).
  std::uint16_t Emitter;
  /// Number of interactions before this one (0: straight from the light), saturating at 255.
  std::uint8_t Depth;
  /// Where an aimed light emitted the particle (Light::SampleEmission: 0
  /// unaimed, 1 outside the aimed disk, 2 inside it).
  std::uint8_t Aim;
  std::uint8_t Padding[2];
  /// Surface hits: the triangle (index in Surface::Triangles); media: 0.
  std::uint32_t Triangle;
};
static_assert(sizeof(Hit) == 48, "Hit layout changed: update the documentation");

struct TraceSettings
{
  std::uint64_t Seed = 0;
  /// Interactions after which a particle is stopped (its flux is tallied as truncated).
  int MaxDepth = 1024;
  /// Interactions after which Russian roulette may end a particle; a value
  /// above MaxDepth turns Russian roulette off.
  int RouletteDepth = 3;
  /**
   * Under an aimed light (AimAtMedia), a particle emitted outside the aimed
   * disk carries EmissionWeight(1) / EmissionWeight(2) times an aimed one's
   * flux; where such a particle's next segment crosses a medium's box before
   * a surface stops it (the sun's light reflected by the ground into a
   * cloud), it splits into that many particles of an aimed one's weight
   * (SplitHeavyParticle), so that the medium's light is not carried by a few
   * heavy particles. Unbiased; off, aimed runs are as before.
   */
  bool SplitHeavyParticles = true;
};

/// The most particles one heavy particle splits into (SplitHeavyParticles):
/// where the weights' ratio is larger, the children carry more than an aimed
/// particle's weight.
constexpr int MaxSplit = 256;

/// The random stream of child `child` of particle `index` when it splits:
/// particle indices stay below 2^40 (runs hold at most 10^10 particles), so
/// the children's streams are distinct from every particle's and each other's.
inline std::uint64_t ChildStream(std::uint64_t index, int child)
{
  return index + (static_cast<std::uint64_t>(child + 1) << 40u);
}

/// Per-run tallies, summed over particles in double precision.
struct TraceCounters
{
  std::uint64_t Rays = 0;
  std::uint64_t Hits = 0;
  /// Flux (W per channel) emitted, absorbed by surfaces and media, escaped to
  /// infinity, left in particles stopped at MaxDepth, and removed minus added
  /// by the unbiased estimators (Russian roulette, spectral tracking), which
  /// is zero in expectation. Emitted = the sum of the others, per run.
  double Emitted[3] = { 0, 0, 0 };
  double Absorbed[3] = { 0, 0, 0 };
  double Escaped[3] = { 0, 0, 0 };
  double Truncated[3] = { 0, 0, 0 };
  double EstimatorNet[3] = { 0, 0, 0 };

  void Add(const TraceCounters& o);
};

/// How a particle left the scene (for validation against transport codes).
/// A particle that split (TraceSettings::SplitHeavyParticles) left through
/// its children: Children is their number, and the rest is left unset.
struct ParticleExit
{
  bool Escaped = false;
  Vec3 Flux;
  Vec3 Direction;
  int Depth = 0;
  int Children = 0;
};

/// Optional log of the rays a particle casts (for benchmarks).
struct RayLog
{
  std::vector<float> OriginsAndDirections; // 6 floats per ray
};

/**
 * Aims every directional light at the scene's media: `fraction` of its
 * particles (Light::AimFraction) leave the disk of its emitting plane from
 * which the beam reaches a medium, the others the whole beam. Which part
 * reaches one is found by pilot rays, AimPilotRays across the beam's
 * diameter: those that cross a medium's box over more than a thousandth of
 * its diagonal before any surface stops them (a cloud's box above the
 * ground, the window through which the sun enters a hazy room, not the
 * walls around it). The disk holds the cells of those rays and their
 * neighbours (the edge of what reaches may lie in one); it is used where it
 * covers at most MaxAimedBeamShare of the beam's area. Other
 * lights, fraction 0 and beams whose every part reaches a medium are left
 * unaimed. A beam covering a kilometre-wide ground, or a house with one
 * window, sends most particles where only the direct light (computed, not
 * estimated) and a little reflected light are; aimed, the medium gets the
 * particles, every flux weighted so that the light is unchanged.
 */
void AimAtMedia(Scene& scene, const RayCaster& caster, float fraction);
constexpr int AimPilotRays = 128;
constexpr float MaxAimedBeamShare = 0.25f;

class LightTracer
{
public:
  /// The scene must have passed Scene::Validate() and outlive the tracer.
  LightTracer(const Scene& scene, const RayCaster& caster, const TraceSettings& settings);

  /// Total emitted power per channel (W).
  Vec3 GetTotalPower() const { return this->TotalPower; }

  /// Traces particle `index` of `count` and appends its hits to `hits`.
  /// Deterministic: depends only on (seed, index, count).
  void TraceParticle(std::uint64_t index, std::uint64_t count, std::vector<Hit>& hits,
    TraceCounters& counters, ParticleExit* exit = nullptr, RayLog* rays = nullptr) const;

  /**
   * Particles [first, end) of a run of `count`, in order: the loop every
   * caller runs over a block of particles. With `keepHits` false the hits
   * are dropped as they come (what tracing costs without storing them).
   */
  void TraceParticles(std::uint64_t first, std::uint64_t end, std::uint64_t count,
    std::vector<Hit>& hits, TraceCounters& counters, RayLog* rays = nullptr,
    bool keepHits = true) const;

  /// Particles per block: callers split a run into blocks of this many, which
  /// (not threads) own the order of the hits.
  static constexpr std::uint64_t ParticlesPerBlock = 4096;

private:
  // An emissive triangle or a light, chosen in proportion to its power.
  struct Emitter
  {
    int Light = -1; // index in Scene::Lights, or -1 for a triangle
    std::uint32_t Surface = 0;
    std::uint32_t Triangle = 0;
    Vec3 Normal;
    Vec3 Power;
    std::uint16_t Id = 0;
  };

  /// Chooses an emitter in proportion to its power and samples where and
  /// in which direction the particle leaves it, with its flux.
  const Emitter& Emit(Random& rng, std::uint64_t count, Vec3& flux, Vec3& origin, Vec3& direction,
    std::uint8_t& aim) const;

  /// Where a particle is on its walk: what it carries, where it goes, and
  /// the flux Russian roulette compares with.
  struct Walker
  {
    Vec3 Flux, Origin, Direction;
    int Depth = 0;
    std::uint8_t Aim = 0;
    float InitialFlux = 0.f;
  };

  /// Follows a particle of `emitter` from `w` until it is absorbed, escapes
  /// or stops, storing its hits; a heavy particle splits
  /// (TraceSettings::SplitHeavyParticles), its children walked in turn.
  void Walk(std::uint64_t index, Random& rng, const Emitter& emitter, Walker w,
    std::vector<Hit>& hits, TraceCounters& counters, ParticleExit* exit, RayLog* rays) const;

  /// A heavy particle `w` of `aimedLight` heading into a medium, split into
  /// aimed particles that walk on (Walk's heavy-particle case).
  void Split(std::uint64_t index, Random& rng, const Emitter& emitter, const Light& aimedLight,
    const Walker& w, std::vector<Hit>& hits, TraceCounters& counters, ParticleExit* exit,
    RayLog* rays) const;
  /// Whether the segment o + t d, t in [0, tEnd], crosses a medium's box.
  bool CrossesMedium(const Vec3& o, const Vec3& d, float tEnd) const;
  /// Russian roulette after interaction w.Depth; false when the particle ends.
  bool Roulette(Walker& w, Random& rng, TraceCounters& counters) const;

  const Scene& SceneRef;
  const RayCaster& Caster;
  TraceSettings Settings;
  std::vector<Emitter> Emitters;
  std::vector<double> EmitterCdf;
  Vec3 TotalPower;
};

} // namespace brume

#endif
