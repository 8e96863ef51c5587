// SPDX-License-Identifier: BSD-3-Clause
#include "brume/PathTracer.h"

#include "brume/Material.h"
#include "brume/Random.h"
#include "brume/Sampling.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace brume
{

namespace
{
constexpr float Infinity = std::numeric_limits<float>::infinity();

float OffsetEpsilon(const Vec3& p)
{
  return 1e-4f * std::max(1.f, std::max(std::abs(p.x), std::max(std::abs(p.y), std::abs(p.z))));
}

float PowerHeuristic(float a, float b)
{
  return a * a / (a * a + b * b);
}

// Streams of camera samples: disjoint from the light tracer's particle streams.
std::uint64_t Stream(int x, int y, int sample, int width)
{
  return (static_cast<std::uint64_t>(y) * static_cast<std::uint64_t>(width) +
           static_cast<std::uint64_t>(x)) *
    0x100000ULL +
    static_cast<std::uint64_t>(sample) + (1ULL << 62);
}
}

PathTracer::PathTracer(const Scene& scene, const RayCaster& caster, const PathSettings& settings)
  : SceneRef(scene)
  , Caster(caster)
  , Settings(settings)
{
  double total = 0.0;
  std::vector<double> weights;
  this->TriangleProbability.resize(scene.Surfaces.size());
  for (std::uint32_t s = 0; s < scene.Surfaces.size(); ++s)
  {
    const Surface& surface = scene.Surfaces[s];
    this->TriangleProbability[s].assign(surface.Triangles.size(), 0.f);
    for (std::uint32_t t = 0; t < surface.Triangles.size(); ++t)
    {
      const Material& m = surface.MaterialOf(t);
      const auto& tri = surface.Triangles[t];
      const Vec3 n = Cross(surface.Vertices[tri[1]] - surface.Vertices[tri[0]],
        surface.Vertices[tri[2]] - surface.Vertices[tri[0]]);
      const float area = 0.5f * Length(n);
      if (!m.IsEmitter() || !(area > 0.f))
      {
        continue;
      }
      Emitter e;
      e.Surface = s;
      e.Triangle = t;
      e.Normal = Normalize(n);
      e.Area = area;
      this->Emitters.push_back(e);
      weights.push_back(Pi * area * Average(m.Emission));
    }
  }
  for (std::size_t k = 0; k < scene.Lights.size(); ++k)
  {
    Emitter e;
    e.Light = static_cast<int>(k);
    this->Emitters.push_back(e);
    weights.push_back(Average(scene.Lights[k].Power()));
  }
  for (double w : weights)
  {
    total += w;
  }
  double cumulative = 0.0;
  for (std::size_t k = 0; k < this->Emitters.size(); ++k)
  {
    this->Emitters[k].Probability = weights[k] / total;
    cumulative += weights[k] / total;
    this->EmitterCdf.push_back(cumulative);
    if (this->Emitters[k].Light < 0)
    {
      this->TriangleProbability[this->Emitters[k].Surface][this->Emitters[k].Triangle] =
        static_cast<float>(weights[k] / total);
    }
  }
}

float PathTracer::LightPdf(std::uint32_t s, std::uint32_t t, float distance, float cosLight) const
{
  const float select = this->TriangleProbability[s][t];
  if (!(select > 0.f) || !(cosLight > 0.f))
  {
    return 0.f;
  }
  const Surface& surface = this->SceneRef.Surfaces[s];
  const auto& tri = surface.Triangles[t];
  const float area = 0.5f *
    Length(Cross(surface.Vertices[tri[1]] - surface.Vertices[tri[0]],
      surface.Vertices[tri[2]] - surface.Vertices[tri[0]]));
  return select * distance * distance / (area * cosLight);
}

bool PathTracer::SampleLight(const Vec3& p, Random& rng, LightSample& s) const
{
  if (this->Emitters.empty())
  {
    return false;
  }
  const double u = rng.NextDouble();
  const auto it = std::upper_bound(this->EmitterCdf.begin(), this->EmitterCdf.end(), u);
  const std::size_t k =
    std::min<std::size_t>(it - this->EmitterCdf.begin(), this->Emitters.size() - 1);
  const Emitter& e = this->Emitters[k];
  const float select = static_cast<float>(e.Probability);
  if (e.Light < 0)
  {
    const Surface& surface = this->SceneRef.Surfaces[e.Surface];
    const auto& tri = surface.Triangles[e.Triangle];
    const float su = std::sqrt(rng.NextFloat());
    const float b1 = 1.f - su, b2 = rng.NextFloat() * su;
    const Vec3 q = surface.Vertices[tri[0]] * b1 + surface.Vertices[tri[1]] * b2 +
      surface.Vertices[tri[2]] * (1.f - b1 - b2);
    const Vec3 toLight = q - p;
    const float distance = Length(toLight);
    if (!(distance > 0.f))
    {
      return false;
    }
    s.Direction = toLight / distance;
    s.Distance = distance;
    const float cosLight = -Dot(s.Direction, e.Normal); // one-sided emitter
    if (!(cosLight > 0.f))
    {
      return false;
    }
    s.Radiance = surface.MaterialOf(e.Triangle).Emission;
    s.Pdf = select * distance * distance / (e.Area * cosLight);
    s.Delta = false;
    return true;
  }
  const Light& light = this->SceneRef.Lights[e.Light];
  s.Delta = true;
  s.Pdf = select;
  switch (light.Type)
  {
    case LightType::Point:
    case LightType::Spot:
    {
      const Vec3 toLight = light.Position - p;
      const float distance = Length(toLight);
      if (!(distance > 0.f))
      {
        return false;
      }
      s.Direction = toLight / distance;
      s.Distance = distance;
      if (light.Type == LightType::Spot &&
        Dot(-s.Direction, light.Direction) < std::cos(light.ConeAngle * Pi / 180.f))
      {
        return false;
      }
      s.Radiance = light.Intensity / (distance * distance); // irradiance at normal incidence
      return true;
    }
    case LightType::Directional:
    {
      // Inside the beam's cylinder, downstream of its disk.
      const Vec3 rel = p - light.BeamCenter;
      const float along = Dot(rel, light.Direction);
      const Vec3 across = rel - light.Direction * along;
      if (!(along > 0.f) || Length(across) > light.BeamRadius)
      {
        return false;
      }
      s.Direction = -light.Direction;
      s.Distance = along;
      s.Radiance = light.Intensity;
      return true;
    }
  }
  return false;
}

Vec3 PathTracer::Radiance(Vec3 origin, Vec3 direction, Random& rng) const
{
  const Scene& scene = this->SceneRef;
  std::vector<MediumTracker> trackers(std::max<std::size_t>(1, scene.Media.size()));
  Vec3 L(0.f), beta(1.f);
  bool specular = true; // the camera ray, or a mirror bounce
  float previousPdf = 0.f;
  for (int depth = 0; depth < this->Settings.MaxDepth; ++depth)
  {
    const bool last = depth + 1 == this->Settings.MaxDepth;
    SurfaceHit hit;
    const bool hitSurface = this->Caster.Intersect(origin, direction, 0.f, Infinity, hit);
    const float tSurface = hitSurface ? hit.T : Infinity;
    float t = tSurface;
    const Medium* medium =
      SampleCollision(scene.Media, origin, direction, tSurface, rng, beta, t, trackers.data());
    if (!(MaxComponent(beta) > 0.f))
    {
      break;
    }
    if (medium)
    {
      // A real collision: scatter with the albedo's weight.
      const Vec3 p = origin + direction * t;
      beta *= medium->AlbedoAt(p);
      const HenyeyGreenstein phase(medium->G);
      LightSample ls;
      if (SampleLight(p, rng, ls))
      {
        const float f = phase.Evaluate(Dot(direction, ls.Direction));
        const Vec3 tr = Transmittance(scene.Media, p, ls.Direction, ls.Distance, rng, trackers[0]);
        SurfaceHit blocker;
        const bool visible = MaxComponent(tr) > 0.f &&
          !this->Caster.Intersect(p, ls.Direction, 0.f, ls.Distance * (1.f - 1e-4f), blocker);
        if (visible)
        {
          // At the last vertex no phase-sampled ray follows to meet the
          // light: its sample takes the whole weight.
          const float w = ls.Delta || last ? 1.f : PowerHeuristic(ls.Pdf, f);
          L += beta * ls.Radiance * tr * (f * w / ls.Pdf);
        }
      }
      const Vec3 next = phase.Sample(direction, rng.NextFloat(), rng.NextFloat());
      previousPdf = phase.Evaluate(Dot(direction, next));
      direction = next;
      origin = p;
      specular = false;
    }
    else if (hitSurface)
    {
      const Surface& surface = scene.Surfaces[hit.Surface];
      const Vec3 p = origin + direction * tSurface;
      Material coloured; // where the surface's reflectance varies over it
      const Material& m = surface.VertexReflectance.empty()
        ? surface.MaterialOf(hit.Triangle)
        : (coloured = surface.MaterialAt(hit.Triangle, p));
      const auto& tri = surface.Triangles[hit.Triangle];
      const Vec3 front = Normalize(Cross(surface.Vertices[tri[1]] - surface.Vertices[tri[0]],
        surface.Vertices[tri[2]] - surface.Vertices[tri[0]]));
      // Emission seen on the front side, weighted against light sampling.
      const float cosLight = -Dot(direction, front);
      if (m.IsEmitter() && cosLight > 0.f)
      {
        float w = 1.f;
        if (!specular)
        {
          w = PowerHeuristic(
            previousPdf, this->LightPdf(hit.Surface, hit.Triangle, tSurface, cosLight));
        }
        L += beta * m.Emission * w;
      }
      Vec3 n = front;
      if (Dot(n, direction) > 0.f)
      {
        n = -n;
      }
      const Vec3 wo = -direction;
      const Vec3 q = p + n * OffsetEpsilon(p);
      if (m.Type != MaterialType::Mirror)
      {
        LightSample ls;
        if (SampleLight(q, rng, ls) && Dot(ls.Direction, n) > 0.f)
        {
          const Vec3 f = EvaluateBrdf(m, n, ls.Direction, wo);
          const Vec3 tr =
            Transmittance(scene.Media, q, ls.Direction, ls.Distance, rng, trackers[0]);
          SurfaceHit blocker;
          if (MaxComponent(f) > 0.f && MaxComponent(tr) > 0.f &&
            !this->Caster.Intersect(q, ls.Direction, 0.f, ls.Distance * (1.f - 1e-4f), blocker))
          {
            const float w =
              ls.Delta || last ? 1.f : PowerHeuristic(ls.Pdf, BrdfPdf(m, n, wo, ls.Direction));
            L += beta * f * ls.Radiance * tr * (Dot(ls.Direction, n) * w / ls.Pdf);
          }
        }
      }
      Vec3 wi, weight;
      if (!SampleBrdf(m, n, wo, rng, wi, weight))
      {
        break;
      }
      beta *= weight;
      specular = m.Type == MaterialType::Mirror;
      previousPdf = specular ? 0.f : BrdfPdf(m, n, wo, wi);
      direction = wi;
      origin = q;
    }
    else
    {
      break; // no environment light
    }
    // Russian roulette on the throughput.
    if (depth + 1 >= this->Settings.RouletteDepth)
    {
      const float survive = std::min(1.f, MaxComponent(beta));
      if (!(rng.NextFloat() < survive))
      {
        break;
      }
      beta = beta / survive;
    }
  }
  return L;
}

Vec3 PathTracer::Sample(const PinholeCamera& camera, int x, int y, int sample) const
{
  Random rng(this->Settings.Seed, Stream(x, y, sample, camera.Width));
  Vec3 origin, direction;
  camera.Ray(static_cast<float>(x) + rng.NextFloat(), static_cast<float>(y) + rng.NextFloat(),
    origin, direction);
  return this->Radiance(origin, direction, rng);
}

void PathTracer::RenderRows(
  const PinholeCamera& camera, int y0, int y1, float* mean, float* variance) const
{
  const int spp = std::max(1, this->Settings.SamplesPerPixel);
  for (int y = y0; y < y1; ++y)
  {
    for (int x = 0; x < camera.Width; ++x)
    {
      double sum[3] = { 0, 0, 0 }, sum2[3] = { 0, 0, 0 };
      for (int s = 0; s < spp; ++s)
      {
        const Vec3 L = this->Sample(camera, x, y, s);
        for (int c = 0; c < 3; ++c)
        {
          const double v = L[c];
          sum[c] += v;
          sum2[c] += v * v;
        }
      }
      const std::size_t o = 3 * (static_cast<std::size_t>(y - y0) * camera.Width + x);
      for (int c = 0; c < 3; ++c)
      {
        const double m = sum[c] / spp;
        mean[o + c] = static_cast<float>(m);
        variance[o + c] =
          spp > 1 ? static_cast<float>(std::max(0.0, (sum2[c] / spp - m * m) / (spp - 1))) : 0.f;
      }
    }
  }
}

} // namespace brume
