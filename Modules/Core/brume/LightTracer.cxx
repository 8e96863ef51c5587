// SPDX-License-Identifier: BSD-3-Clause
#include "brume/LightTracer.h"

#include "brume/Random.h"
#include "brume/Sampling.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace brume
{

LightTracer::LightTracer(const Scene& scene, const RayCaster& caster, const TraceSettings& settings)
  : SceneRef(scene)
  , Caster(caster)
  , Settings(settings)
  , TotalPower(0.f)
{
  // Emitters are chosen in proportion to their power (mean over channels).
  double total = 0.0;
  Vec3 power(0.f);
  for (std::uint32_t s = 0; s < scene.Surfaces.size(); ++s)
  {
    const Surface& surface = scene.Surfaces[s];
    if (!surface.IsEmitter())
    {
      continue;
    }
    for (std::uint32_t t = 0; t < surface.Triangles.size(); ++t)
    {
      const auto& tri = surface.Triangles[t];
      const Vec3 n = Cross(surface.Vertices[tri[1]] - surface.Vertices[tri[0]],
        surface.Vertices[tri[2]] - surface.Vertices[tri[0]]);
      const double area = 0.5 * Length(n);
      if (!(area > 0.0))
      {
        continue;
      }
      this->Emitters.push_back({ s, t, Normalize(n), surface.Emission, area });
      // Phi = pi * L_e * A for a one-sided Lambertian emitter.
      power += surface.Emission * static_cast<float>(Pi * area);
      total += Pi * area * Average(surface.Emission);
      this->EmitterCdf.push_back(total);
    }
  }
  for (double& c : this->EmitterCdf)
  {
    c /= total;
  }
  this->TotalPower = power;
}

namespace
{
// Offset that moves a ray origin off a surface: relative to the magnitude of
// the coordinates, which bounds float rounding of the hit point.
float OffsetEpsilon(const Vec3& p)
{
  return 1e-4f * std::max(1.f, std::max(std::abs(p.x), std::max(std::abs(p.y), std::abs(p.z))));
}
}

void LightTracer::TraceParticle(
  std::uint64_t index, std::uint64_t count, std::vector<Hit>& hits, TraceCounters& counters) const
{
  if (this->Emitters.empty() || count == 0)
  {
    return;
  }
  Random rng(this->Settings.Seed, index);
  const Scene& scene = this->SceneRef;
  const auto numberOfSurfaces = static_cast<std::uint16_t>(scene.Surfaces.size());

  // Choose an emitter triangle in proportion to its power.
  const double u = rng.NextDouble();
  const auto it = std::upper_bound(this->EmitterCdf.begin(), this->EmitterCdf.end(), u);
  const std::size_t k =
    std::min<std::size_t>(it - this->EmitterCdf.begin(), this->Emitters.size() - 1);
  const EmitterTriangle& emitter = this->Emitters[k];
  const double pdfTriangle = this->EmitterCdf[k] - (k > 0 ? this->EmitterCdf[k - 1] : 0.0);

  // Uniform point on the triangle.
  const Surface& surface = scene.Surfaces[emitter.Surface];
  const auto& tri = surface.Triangles[emitter.Triangle];
  const float su = std::sqrt(rng.NextFloat());
  const float b1 = 1.f - su, b2 = rng.NextFloat() * su;
  Vec3 origin = surface.Vertices[tri[0]] * b1 + surface.Vertices[tri[1]] * b2 +
    surface.Vertices[tri[2]] * (1.f - b1 - b2);

  // Cosine-weighted direction: flux = pi L_e A / (N p_triangle).
  const float r1 = rng.NextFloat(), r2 = rng.NextFloat();
  Vec3 direction = Normalize(Frame(emitter.Normal).ToWorld(SampleCosineHemisphere(r1, r2)));
  Vec3 flux = emitter.Radiance *
    static_cast<float>(Pi * emitter.Area / (static_cast<double>(count) * pdfTriangle));
  const float initialFlux = MaxComponent(flux);
  origin += emitter.Normal * OffsetEpsilon(origin);
  const auto emitterId = static_cast<std::uint16_t>(emitter.Surface);

  auto store = [&](const Vec3& p, std::uint16_t object, int depth)
  {
    Hit h;
    h.Position[0] = p.x;
    h.Position[1] = p.y;
    h.Position[2] = p.z;
    h.Direction[0] = direction.x;
    h.Direction[1] = direction.y;
    h.Direction[2] = direction.z;
    h.Flux[0] = flux.x;
    h.Flux[1] = flux.y;
    h.Flux[2] = flux.z;
    h.Object = object;
    h.Emitter = emitterId;
    h.Depth = static_cast<std::uint8_t>(std::min(depth, 255));
    h.Padding[0] = h.Padding[1] = h.Padding[2] = 0;
    hits.push_back(h);
    ++counters.Hits;
  };

  for (int depth = 0; depth < this->Settings.MaxDepth; ++depth)
  {
    SurfaceHit surfaceHit;
    ++counters.Rays;
    const bool hitSurface = this->Caster.Intersect(
      origin, direction, 0.f, std::numeric_limits<float>::infinity(), surfaceHit);
    const float tSurface = hitSurface ? surfaceHit.T : std::numeric_limits<float>::infinity();

    // Free flight in each medium the segment crosses; the earliest collision
    // wins (independent exponential races are exact for overlapping media).
    float tCollision = tSurface;
    int collided = -1;
    for (std::size_t m = 0; m < scene.Media.size(); ++m)
    {
      const Medium& medium = scene.Media[m];
      const float sigmaT = medium.SigmaT().x;
      float t0 = 0.f, t1 = tSurface;
      if (!(sigmaT > 0.f) || !medium.Bounds.Intersect(origin, direction, t0, t1))
      {
        continue;
      }
      // t ~ sigma_t exp(-sigma_t t) from the entry point.
      const float t = t0 - std::log1p(-rng.NextFloat()) / sigmaT;
      if (t < t1 && t < tCollision)
      {
        tCollision = t;
        collided = static_cast<int>(m);
      }
    }

    if (collided >= 0)
    {
      const Medium& medium = scene.Media[collided];
      origin = origin + direction * tCollision;
      store(origin, static_cast<std::uint16_t>(numberOfSurfaces + collided), depth);
      // Always scatter, weighting by the albedo (less variance than absorbing).
      flux *= medium.Albedo();
      if (!(MaxComponent(flux) > 0.f))
      {
        return;
      }
      direction = HenyeyGreenstein(medium.G).Sample(direction, rng.NextFloat(), rng.NextFloat());
    }
    else if (hitSurface)
    {
      const Surface& hitObject = scene.Surfaces[surfaceHit.Surface];
      const Vec3 position = origin + direction * tSurface;
      store(position, static_cast<std::uint16_t>(surfaceHit.Surface), depth);
      flux *= hitObject.Reflectance;
      if (!(MaxComponent(flux) > 0.f))
      {
        return;
      }
      // Lambertian reflection on the side the particle came from.
      Vec3 n = Normalize(surfaceHit.Ng);
      if (Dot(n, direction) > 0.f)
      {
        n = -n;
      }
      direction =
        Normalize(Frame(n).ToWorld(SampleCosineHemisphere(rng.NextFloat(), rng.NextFloat())));
      origin = position + n * OffsetEpsilon(position);
    }
    else
    {
      return; // escaped
    }

    // Russian roulette, dividing the survivors' flux by the survival probability.
    if (depth + 1 >= this->Settings.RouletteDepth)
    {
      const float q = std::min(1.f, MaxComponent(flux) / initialFlux);
      if (q < 1.f)
      {
        if (!(rng.NextFloat() < q))
        {
          return;
        }
        flux = flux / q;
      }
    }
  }
}

} // namespace brume
