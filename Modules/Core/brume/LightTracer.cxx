// SPDX-License-Identifier: BSD-3-Clause
#include "brume/LightTracer.h"

#include "brume/Random.h"
#include "brume/Sampling.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace brume
{

void TraceCounters::Add(const TraceCounters& o)
{
  this->Rays += o.Rays;
  this->Hits += o.Hits;
  for (int c = 0; c < 3; ++c)
  {
    this->Emitted[c] += o.Emitted[c];
    this->Absorbed[c] += o.Absorbed[c];
    this->Escaped[c] += o.Escaped[c];
    this->Truncated[c] += o.Truncated[c];
    this->EstimatorNet[c] += o.EstimatorNet[c];
  }
}

LightTracer::LightTracer(const Scene& scene, const RayCaster& caster, const TraceSettings& settings)
  : SceneRef(scene)
  , Caster(caster)
  , Settings(settings)
  , TotalPower(0.f)
{
  double total = 0.0;
  auto add = [&](const Emitter& e)
  {
    const double weight = Average(e.Power);
    if (!(weight > 0.0))
    {
      return;
    }
    this->Emitters.push_back(e);
    this->TotalPower += e.Power;
    total += weight;
    this->EmitterCdf.push_back(total);
  };
  for (std::uint32_t s = 0; s < scene.Surfaces.size(); ++s)
  {
    const Surface& surface = scene.Surfaces[s];
    for (std::uint32_t t = 0; t < surface.Triangles.size(); ++t)
    {
      const Material& m = surface.MaterialOf(t);
      if (!m.IsEmitter())
      {
        continue;
      }
      const auto& tri = surface.Triangles[t];
      const Vec3 n = Cross(surface.Vertices[tri[1]] - surface.Vertices[tri[0]],
        surface.Vertices[tri[2]] - surface.Vertices[tri[0]]);
      const float area = 0.5f * Length(n);
      if (!(area > 0.f))
      {
        continue;
      }
      Emitter e;
      e.Surface = s;
      e.Triangle = t;
      e.Normal = Normalize(n);
      // Phi = pi * L_e * A for a one-sided Lambertian emitter.
      e.Power = m.Emission * (Pi * area);
      e.Id = static_cast<std::uint16_t>(s);
      add(e);
    }
  }
  for (std::size_t k = 0; k < scene.Lights.size(); ++k)
  {
    Emitter e;
    e.Light = static_cast<int>(k);
    e.Power = scene.Lights[k].Power();
    e.Id = static_cast<std::uint16_t>(scene.LightEmitterId(k));
    add(e);
  }
  for (double& c : this->EmitterCdf)
  {
    c /= total;
  }
}

namespace
{
// Offset that moves a ray origin off a surface: relative to the magnitude of
// the coordinates, which bounds float rounding of the hit point.
float OffsetEpsilon(const Vec3& p)
{
  return 1e-4f * std::max(1.f, std::max(std::abs(p.x), std::max(std::abs(p.y), std::abs(p.z))));
}

void Tally(double* tally, const Vec3& flux, double sign = 1.0)
{
  for (int c = 0; c < 3; ++c)
  {
    tally[c] += sign * static_cast<double>(flux[c]);
  }
}

// Flux removed (positive) or added (negative) when `before` becomes `after`.
void TallyChange(double* tally, const Vec3& before, const Vec3& after)
{
  for (int c = 0; c < 3; ++c)
  {
    tally[c] += static_cast<double>(before[c]) - static_cast<double>(after[c]);
  }
}

constexpr int InlineTrackers = 4;
}

void LightTracer::TraceParticles(std::uint64_t first, std::uint64_t end, std::uint64_t count,
  std::vector<Hit>& hits, TraceCounters& counters, RayLog* rays, bool keepHits) const
{
  for (std::uint64_t i = first; i < end; ++i)
  {
    if (!keepHits)
    {
      hits.clear();
    }
    this->TraceParticle(i, count, hits, counters, nullptr, rays);
  }
}

const LightTracer::Emitter& LightTracer::Emit(Random& rng, std::uint64_t count, Vec3& flux,
  Vec3& origin, Vec3& direction, std::uint8_t& aim) const
{
  const Scene& scene = this->SceneRef;
  // Choose an emitter in proportion to its power.
  const double u = rng.NextDouble();
  const auto it = std::upper_bound(this->EmitterCdf.begin(), this->EmitterCdf.end(), u);
  const std::size_t k =
    std::min<std::size_t>(it - this->EmitterCdf.begin(), this->Emitters.size() - 1);
  const Emitter& emitter = this->Emitters[k];
  const double pdfEmitter = this->EmitterCdf[k] - (k > 0 ? this->EmitterCdf[k - 1] : 0.0);
  // Flux = Phi_emitter / (N p_emitter).
  flux = emitter.Power * static_cast<float>(1.0 / (static_cast<double>(count) * pdfEmitter));

  aim = 0;
  if (emitter.Light >= 0)
  {
    flux *= scene.Lights[emitter.Light].SampleEmission(rng, origin, direction, aim);
  }
  else
  {
    // Uniform point on the triangle, cosine-weighted direction on its front side.
    const Surface& surface = scene.Surfaces[emitter.Surface];
    const auto& tri = surface.Triangles[emitter.Triangle];
    const float su = std::sqrt(rng.NextFloat());
    const float b1 = 1.f - su, b2 = rng.NextFloat() * su;
    origin = surface.Vertices[tri[0]] * b1 + surface.Vertices[tri[1]] * b2 +
      surface.Vertices[tri[2]] * (1.f - b1 - b2);
    const float r1 = rng.NextFloat(), r2 = rng.NextFloat();
    direction = Normalize(Frame(emitter.Normal).ToWorld(SampleCosineHemisphere(r1, r2)));
    origin += emitter.Normal * OffsetEpsilon(origin);
  }
  return emitter;
}

void LightTracer::TraceParticle(std::uint64_t index, std::uint64_t count, std::vector<Hit>& hits,
  TraceCounters& counters, ParticleExit* exit, RayLog* rays) const
{
  if (exit)
  {
    *exit = ParticleExit();
  }
  if (this->Emitters.empty() || count == 0)
  {
    return;
  }
  Random rng(this->Settings.Seed, index);
  Walker w;
  const Emitter& emitter = this->Emit(rng, count, w.Flux, w.Origin, w.Direction, w.Aim);
  Tally(counters.Emitted, w.Flux);
  if (!(MaxComponent(w.Flux) > 0.f))
  {
    return; // an aimed light's point beyond its beam
  }
  w.InitialFlux = MaxComponent(w.Flux);
  this->Walk(index, rng, emitter, w, hits, counters, exit, rays);
}

bool LightTracer::CrossesMedium(const Vec3& o, const Vec3& d, float tEnd) const
{
  for (const Medium& m : this->SceneRef.Media)
  {
    float t0 = 0.f, t1 = tEnd; // Box::Intersect clips to [0, t1]
    if (m.Bounds.Intersect(o, d, t0, t1) && t1 > t0)
    {
      return true;
    }
  }
  return false;
}

bool LightTracer::Roulette(Walker& w, Random& rng, TraceCounters& counters) const
{
  // Russian roulette, dividing the survivors' flux by the survival probability.
  if (w.Depth + 1 >= this->Settings.RouletteDepth)
  {
    const float q = std::min(1.f, MaxComponent(w.Flux) / w.InitialFlux);
    if (q < 1.f)
    {
      const Vec3 before = w.Flux;
      if (!(rng.NextFloat() < q))
      {
        Tally(counters.EstimatorNet, w.Flux);
        return false;
      }
      w.Flux = w.Flux / q;
      TallyChange(counters.EstimatorNet, before, w.Flux);
    }
  }
  return true;
}

namespace
{
// Reflects a particle at `position` (normal `n` on its side): BRDF
// sampling, the absorbed flux tallied; false when the particle ends there.
bool Reflect(const Material& material, const Vec3& n, const Vec3& position, Random& rng, Vec3& flux,
  Vec3& origin, Vec3& direction, TraceCounters& counters)
{
  Vec3 weight;
  const Vec3 before = flux;
  if (!SampleBrdf(material, n, -direction, rng, direction, weight))
  {
    Tally(counters.Absorbed, flux);
    return false;
  }
  flux *= weight;
  TallyChange(counters.Absorbed, before, flux);
  if (!(MaxComponent(flux) > 0.f))
  {
    return false;
  }
  origin = position + n * OffsetEpsilon(position);
  return true;
}
}

// A heavy particle heading into a medium (the light the ground reflects
// into a cloud) splits into r = w1 / w2 particles of an aimed particle's
// weight: n of them, n = floor(r) or floor(r) + 1 with the probability of
// r's fraction (E[n] = r), each carrying flux / r, so that the expected
// flux is the particle's. They are aimed particles from there on (class 2:
// the reconstruction counts each as one aimed particle), on streams of
// their own, and walk this segment anew, each its own free flight and
// scattering in the medium.
void LightTracer::Split(std::uint64_t index, Random& rng, const Emitter& emitter,
  const Light& aimedLight, const Walker& w, std::vector<Hit>& hits, TraceCounters& counters,
  ParticleExit* exit, RayLog* rays) const
{
  const Vec3& flux = w.Flux;
  const double ratio = static_cast<double>(aimedLight.EmissionWeight(1)) /
    static_cast<double>(aimedLight.EmissionWeight(2));
  const double r = std::min(ratio, static_cast<double>(MaxSplit));
  const double whole = std::floor(r);
  const int n = static_cast<int>(whole) + (rng.NextDouble() < r - whole ? 1 : 0);
  Walker child = w;
  child.Flux = flux * static_cast<float>(1.0 / r);
  child.InitialFlux = static_cast<float>(w.InitialFlux / r);
  child.Aim = 2;
  TallyChange(counters.EstimatorNet, flux, child.Flux * static_cast<float>(n));
  if (exit)
  {
    exit->Children = n;
  }
  for (int k = 0; k < n; ++k)
  {
    Random childRng(this->Settings.Seed, ChildStream(index, k));
    this->Walk(index, childRng, emitter, child, hits, counters, nullptr, rays);
  }
}

void LightTracer::Walk(std::uint64_t index, Random& rng, const Emitter& emitter, Walker w,
  std::vector<Hit>& hits, TraceCounters& counters, ParticleExit* exit, RayLog* rays) const
{
  const Scene& scene = this->SceneRef;
  const auto numberOfSurfaces = static_cast<std::uint16_t>(scene.Surfaces.size());
  Vec3& flux = w.Flux;
  Vec3& origin = w.Origin;
  Vec3& direction = w.Direction;
  // Only particles emitted outside an aimed disk are heavy.
  const Light* aimedLight = emitter.Light >= 0 && w.Aim == 1 &&
      this->Settings.SplitHeavyParticles && !scene.Media.empty() &&
      scene.Lights[emitter.Light].Aims()
    ? &scene.Lights[emitter.Light]
    : nullptr;
  MediumTracker inlineTrackers[InlineTrackers];
  std::vector<MediumTracker> heapTrackers;
  MediumTracker* trackers = inlineTrackers;
  if (scene.Media.size() > static_cast<std::size_t>(InlineTrackers))
  {
    heapTrackers.resize(scene.Media.size());
    trackers = heapTrackers.data();
  }

  auto store = [&](const Vec3& p, std::uint16_t object, int depth, std::uint32_t triangle)
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
    h.Emitter = emitter.Id;
    h.Depth = static_cast<std::uint8_t>(std::min(depth, 255));
    h.Aim = w.Aim;
    h.Padding[0] = h.Padding[1] = 0;
    h.Triangle = triangle;
    hits.push_back(h);
    ++counters.Hits;
  };

  for (int& depth = w.Depth;; ++depth)
  {
    if (depth >= this->Settings.MaxDepth)
    {
      Tally(counters.Truncated, flux);
      return;
    }
    SurfaceHit surfaceHit;
    ++counters.Rays;
    if (rays)
    {
      const float r[6] = { origin.x, origin.y, origin.z, direction.x, direction.y, direction.z };
      rays->OriginsAndDirections.insert(rays->OriginsAndDirections.end(), r, r + 6);
    }
    const bool hitSurface = this->Caster.Intersect(
      origin, direction, 0.f, std::numeric_limits<float>::infinity(), surfaceHit);
    const float tSurface = hitSurface ? surfaceHit.T : std::numeric_limits<float>::infinity();

    if (aimedLight && this->CrossesMedium(origin, direction, tSurface))
    {
      this->Split(index, rng, emitter, *aimedLight, w, hits, counters, exit, rays);
      return;
    }

    // Delta tracking in every medium the segment crosses.
    float tCollision = tSurface;
    const Vec3 beforeTracking = flux;
    const Medium* collided =
      SampleCollision(scene.Media, origin, direction, tSurface, rng, flux, tCollision, trackers);
    TallyChange(counters.EstimatorNet, beforeTracking, flux);
    const std::size_t collidedIndex =
      collided ? static_cast<std::size_t>(collided - scene.Media.data()) : 0;

    if (collided)
    {
      origin = origin + direction * tCollision;
      store(origin, static_cast<std::uint16_t>(numberOfSurfaces + collidedIndex), depth, 0);
      // Always scatter, weighting by the albedo (less variance than absorbing).
      const Vec3 before = flux;
      flux *= collided->AlbedoAt(origin);
      TallyChange(counters.Absorbed, before, flux);
      if (!(MaxComponent(flux) > 0.f))
      {
        return;
      }
      direction = HenyeyGreenstein(collided->G).Sample(direction, rng.NextFloat(), rng.NextFloat());
    }
    else if (hitSurface)
    {
      const Surface& surface = scene.Surfaces[surfaceHit.Surface];
      const Vec3 position = origin + direction * tSurface;
      Material coloured; // where the surface's reflectance varies over it
      const Material& material = surface.VertexReflectance.empty()
        ? surface.MaterialOf(surfaceHit.Triangle)
        : (coloured = surface.MaterialAt(surfaceHit.Triangle, position));
      store(position, static_cast<std::uint16_t>(surfaceHit.Surface), depth, surfaceHit.Triangle);
      // Reflection on the side the particle came from.
      Vec3 n = Normalize(surfaceHit.Ng);
      if (Dot(n, direction) > 0.f)
      {
        n = -n;
      }
      if (!Reflect(material, n, position, rng, flux, origin, direction, counters))
      {
        return;
      }
    }
    else
    {
      Tally(counters.Escaped, flux);
      if (exit)
      {
        exit->Escaped = true;
        exit->Flux = flux;
        exit->Direction = direction;
        exit->Depth = depth;
      }
      return;
    }

    if (!this->Roulette(w, rng, counters))
    {
      return;
    }
  }
}

void AimAtMedia(Scene& scene, const RayCaster& caster, float fraction)
{
  for (Light& light : scene.Lights)
  {
    light.AimFraction = 0.f;
    light.AimRadius = 0.f;
    if (light.Type != LightType::Directional || scene.Media.empty() || !(fraction > 0.f) ||
      !(fraction < 1.f))
    {
      continue;
    }
    // Pilot rays from the centres of a grid of cells across the beam.
    const Frame frame(light.Direction);
    const int n = AimPilotRays;
    const float cell = 2.f * light.BeamRadius / static_cast<float>(n);
    float lo[2] = { std::numeric_limits<float>::max(), std::numeric_limits<float>::max() };
    float hi[2] = { std::numeric_limits<float>::lowest(), std::numeric_limits<float>::lowest() };
    std::vector<std::array<float, 2>> reaching;
    for (int j = 0; j < n; ++j)
    {
      for (int i = 0; i < n; ++i)
      {
        const float x = -light.BeamRadius + (static_cast<float>(i) + 0.5f) * cell;
        const float y = -light.BeamRadius + (static_cast<float>(j) + 0.5f) * cell;
        if (x * x + y * y > light.BeamRadius * light.BeamRadius)
        {
          continue;
        }
        const Vec3 origin = light.BeamCenter + frame.s * x + frame.t * y;
        SurfaceHit hit;
        const float stop = caster.Intersect(origin, light.Direction, 0.f,
                             std::numeric_limits<float>::infinity(), hit)
          ? hit.T
          : std::numeric_limits<float>::infinity();
        bool reaches = false;
        for (const Medium& m : scene.Media)
        {
          float t0 = 0.f, t1 = stop; // Box::Intersect clips to [0, t1]
          if (!m.Bounds.Intersect(origin, light.Direction, t0, t1))
          {
            continue;
          }
          reaches = reaches || t1 - t0 > 1e-3f * Length(m.Bounds.Extent());
        }
        if (reaches)
        {
          reaching.push_back({ x, y });
          lo[0] = std::min(lo[0], x);
          lo[1] = std::min(lo[1], y);
          hi[0] = std::max(hi[0], x);
          hi[1] = std::max(hi[1], y);
        }
      }
    }
    if (reaching.empty())
    {
      continue;
    }
    // The disk about the centre of their extent that holds their cells.
    const float cx = 0.5f * (lo[0] + hi[0]), cy = 0.5f * (lo[1] + hi[1]);
    float radius = 0.f;
    for (const auto& q : reaching)
    {
      radius = std::max(radius, std::hypot(q[0] - cx, q[1] - cy));
    }
    radius += cell * 1.4143f; // a cell beyond: the edge of what reaches may lie in it
    if (radius * radius > MaxAimedBeamShare * light.BeamRadius * light.BeamRadius)
    {
      continue;
    }
    light.AimCenter = light.BeamCenter + frame.s * cx + frame.t * cy;
    light.AimRadius = radius;
    light.AimFraction = fraction;
  }
}

} // namespace brume
