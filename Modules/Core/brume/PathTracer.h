// SPDX-License-Identifier: BSD-3-Clause
// The reference renderer: an unbiased volumetric path tracer over the same
// scene, ray caster, media, phase functions and BRDFs as the light tracer.
//
// Camera paths are traced from a pinhole camera: delta tracking (with
// spectral-tracking weights) through the media, BRDF and Henyey-Greenstein
// sampling, next-event estimation toward every kind of light (emissive
// triangles chosen by power, point, spot and directional lights) with
// transmittance by ratio tracking, multiple importance sampling (power
// heuristic) between light and BRDF/phase sampling for area lights, and
// Russian roulette. Each sample's random stream depends only on (seed,
// pixel, sample): images are identical for any thread count.
#ifndef brume_PathTracer_h
#define brume_PathTracer_h

#include "brume/Camera.h"
#include "brume/RayCaster.h"
#include "brume/Scene.h"

#include <cstdint>
#include <vector>

namespace brume
{

struct PathSettings
{
  std::uint64_t Seed = 0;
  int SamplesPerPixel = 16;
  int MaxDepth = 1024;
  int RouletteDepth = 3;
};

class PathTracer
{
public:
  /// The scene must have passed Scene::Validate() and outlive the tracer.
  PathTracer(const Scene& scene, const RayCaster& caster, const PathSettings& settings);

  /// One radiance sample of pixel (x, y).
  Vec3 Sample(const PinholeCamera& camera, int x, int y, int sample) const;

  /// Radiance arriving at `origin` from the direction -`direction` (one sample).
  Vec3 Trace(const Vec3& origin, const Vec3& direction, Random& rng) const
  {
    return this->Radiance(origin, direction, rng);
  }

  /// Mean radiance and variance of the mean (RGB) of rows [y0, y1).
  void RenderRows(const PinholeCamera& camera, int y0, int y1, float* mean, float* variance) const;

private:
  struct LightSample
  {
    Vec3 Direction; // from the shaded point toward the light
    float Distance; // to the light (infinite for none)
    Vec3 Radiance;  // arriving radiance (area) or irradiance-like term (delta lights)
    float Pdf;      // solid-angle density (area lights) or selection probability (delta)
    bool Delta;
  };
  bool SampleLight(const Vec3& p, Random& rng, LightSample& s) const;
  /// Solid-angle density of reaching the emissive triangle `t` of surface
  /// `s` at distance `distance` with cosine `cosLight` by light sampling.
  float LightPdf(std::uint32_t s, std::uint32_t t, float distance, float cosLight) const;
  Vec3 Radiance(Vec3 origin, Vec3 direction, Random& rng) const;

  struct Emitter
  {
    int Light = -1;
    std::uint32_t Surface = 0, Triangle = 0;
    Vec3 Normal;
    float Area = 0.f;
    double Probability = 0.0;
  };
  const Scene& SceneRef;
  const RayCaster& Caster;
  PathSettings Settings;
  std::vector<Emitter> Emitters;
  std::vector<double> EmitterCdf;
  // Selection probability of each emissive triangle, per surface.
  std::vector<std::vector<float>> TriangleProbability;
};

} // namespace brume

#endif
