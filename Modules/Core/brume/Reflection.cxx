// SPDX-License-Identifier: BSD-3-Clause
#include "brume/Reflection.h"

#include "brume/Random.h"
#include "brume/Reconstruction.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace brume
{

namespace
{
constexpr float Infinity = std::numeric_limits<float>::infinity();

// x clamped to [0, n - 1]; 0 for a NaN (an index must never come of one).
float ClampIndex(float x, int n)
{
  return x > 0.f ? std::min(x, static_cast<float>(n - 1)) : 0.f;
}

// Bilinear between texel centres, clamped at the outer ones (a renderer's
// linear filtering with clamp-to-edge), of an RGB texture over [0, 1]^2.
Vec3 Sample2D(const TextureLookup& t, float u, float v)
{
  const int nx = t.Dims[0], ny = t.Dims[1];
  const float x = ClampIndex(u * nx - 0.5f, nx);
  const float y = ClampIndex(v * ny - 0.5f, ny);
  const int i = std::min(static_cast<int>(x), nx - 1), j = std::min(static_cast<int>(y), ny - 1);
  const int i1 = std::min(i + 1, nx - 1), j1 = std::min(j + 1, ny - 1);
  const float fx = x - i, fy = y - j;
  auto at = [&](int a, int b)
  {
    const float* p = t.Radiance + 3 * (static_cast<std::size_t>(b) * nx + a);
    return Vec3(p[0], p[1], p[2]);
  };
  return (at(i, j) * (1.f - fx) + at(i1, j) * fx) * (1.f - fy) +
    (at(i, j1) * (1.f - fx) + at(i1, j1) * fx) * fy;
}

// Trilinear between voxel centres, clamped, of an RGB texture over `box`.
Vec3 Sample3D(const TextureLookup& t, const Box& box, const Vec3& p)
{
  const Vec3 q = (p - box.lower) / box.Extent();
  int i0[3], i1[3];
  float f[3];
  for (int a = 0; a < 3; ++a)
  {
    const int n = t.Dims[a];
    const float x = ClampIndex(q[a] * n - 0.5f, n);
    i0[a] = std::min(static_cast<int>(x), n - 1);
    i1[a] = std::min(i0[a] + 1, n - 1);
    f[a] = x - i0[a];
  }
  const std::size_t nx = t.Dims[0], nxy = nx * t.Dims[1];
  Vec3 sum(0.f);
  for (int c = 0; c < 8; ++c)
  {
    const int x = c & 1 ? i1[0] : i0[0], y = c & 2 ? i1[1] : i0[1], z = c & 4 ? i1[2] : i0[2];
    const float w =
      (c & 1 ? f[0] : 1.f - f[0]) * (c & 2 ? f[1] : 1.f - f[1]) * (c & 4 ? f[2] : 1.f - f[2]);
    const float* v = t.Radiance + 3 * (z * nxy + y * nx + x);
    sum += Vec3(v[0], v[1], v[2]) * w;
  }
  return sum;
}

// The ray's parameter range inside `box`; false when it misses.
bool ClipToBox(const Box& box, const Vec3& o, const Vec3& d, float& t0, float& t1)
{
  for (int a = 0; a < 3; ++a)
  {
    if (d[a] == 0.f)
    {
      if (o[a] < box.lower[a] || o[a] > box.upper[a])
      {
        return false;
      }
      continue;
    }
    float a0 = (box.lower[a] - o[a]) / d[a], a1 = (box.upper[a] - o[a]) / d[a];
    if (a0 > a1)
    {
      std::swap(a0, a1);
    }
    t0 = std::max(t0, a0);
    t1 = std::min(t1, a1);
  }
  return t1 > t0;
}

Vec3 FaceNormal(const Surface& s, std::size_t triangle)
{
  const auto& tri = s.Triangles[triangle];
  return Normalize(
    Cross(s.Vertices[tri[1]] - s.Vertices[tri[0]], s.Vertices[tri[2]] - s.Vertices[tri[0]]));
}

// Barycentric weights (of corners 1 and 2) of point (u, v) in the triangle
// of texture corners uv[0..5]; false for a degenerate triangle.
bool Barycentric(const float* uv, float u, float v, float& b1, float& b2)
{
  const float e1u = uv[2] - uv[0], e1v = uv[3] - uv[1];
  const float e2u = uv[4] - uv[0], e2v = uv[5] - uv[1];
  const float det = e1u * e2v - e2u * e1v;
  if (det == 0.f)
  {
    return false;
  }
  const float pu = u - uv[0], pv = v - uv[1];
  b1 = (pu * e2v - e2u * pv) / det;
  b2 = (e1u * pv - pu * e1v) / det;
  return true;
}

bool Inside(float b1, float b2)
{
  constexpr float tolerance = -1e-6f;
  return b1 >= tolerance && b2 >= tolerance && b1 + b2 <= 1.f - tolerance;
}

// The weights moved into the triangle, and the texture-space distance moved.
float ClampIntoTriangle(const float* uv, float& b1, float& b2)
{
  const float c1 = std::max(0.f, b1), c2 = std::max(0.f, b2);
  const float sum = c1 + c2;
  const float n1 = sum > 1.f ? c1 / sum : c1, n2 = sum > 1.f ? c2 / sum : c2;
  const float du = (n1 - b1) * (uv[2] - uv[0]) + (n2 - b2) * (uv[4] - uv[0]);
  const float dv = (n1 - b1) * (uv[3] - uv[1]) + (n2 - b2) * (uv[5] - uv[1]);
  b1 = n1;
  b2 = n2;
  return std::sqrt(du * du + dv * dv);
}
}

MirrorReflection::MirrorReflection(
  const Scene& scene, const RayCaster& caster, const std::vector<const ObjectRadiance*>& objects)
  : SceneRef(scene)
  , Caster(caster)
  , Objects(objects)
  , Textures(objects.size())
  , Steps(scene.Media.size(), 0.f)
{
  for (std::size_t o = 0; o < objects.size(); ++o)
  {
    const ObjectRadiance& r = *objects[o];
    const bool casts = !scene.IsMedium(o) && Casts(scene.Surfaces[o]);
    this->Textures[o].Radiance =
      casts ? r.GetUnreflected().Radiance.data() : r.GetOutput().Radiance.data();
    this->Textures[o].Dims = casts ? r.GetUnreflected().Dims : r.GetOutput().Dims;
    this->UpdateStep(o);
  }
  const Vec3 extent = caster.GetBounds().Extent();
  const float diagonal = Length(extent);
  this->Epsilon = 1e-4f * (std::isfinite(diagonal) && diagonal > 0.f ? diagonal : 1.f);
}

bool MirrorReflection::Casts(const Material& m)
{
  return MaxComponent(m.Specular) > 0.f &&
    (m.Type == MaterialType::Mirror ||
      (m.Type == MaterialType::Phong && m.Exponent >= CastExponent));
}

bool MirrorReflection::Casts(const Surface& surface)
{
  if (surface.TriangleMaterials.empty())
  {
    return Casts(surface.Mat);
  }
  return std::any_of(surface.TriangleMaterials.begin(), surface.TriangleMaterials.end(),
    [](const Material& m) { return Casts(m); });
}

bool MirrorReflection::HasMirror(const Surface& surface)
{
  for (std::size_t t = 0; t < surface.Triangles.size(); ++t)
  {
    if (surface.MaterialOf(t).Type == MaterialType::Mirror)
    {
      return true;
    }
  }
  return false;
}

bool MirrorReflection::MirroredEye(const Surface& surface, const Vec3& eye, Vec3& mirrored)
{
  PlanarFrame frame;
  if (!surface.ComputePlanarFrame(frame))
  {
    return false;
  }
  mirrored = eye - frame.Normal * (2.f * Dot(eye - frame.Origin, frame.Normal));
  return true;
}

void MirrorReflection::SetTexture(std::size_t o, const TextureLookup& texture)
{
  this->Textures[o] = texture;
  this->UpdateStep(o);
}

void MirrorReflection::UpdateStep(std::size_t o)
{
  // A medium is marched at half its finest cell: of its density's grid, or
  // of its texture.
  const std::size_t surfaces = this->SceneRef.Surfaces.size();
  if (o < surfaces)
  {
    return;
  }
  const Medium& medium = this->SceneRef.Media[o - surfaces];
  const ObjectRadiance& r = *this->Objects[o];
  float cell = Infinity;
  for (int a = 0; a < 3; ++a)
  {
    cell =
      std::min(cell, medium.Bounds.Extent()[a] / static_cast<float>(this->Textures[o].Dims[a]));
    if (!r.GetNative().GetDensity().Empty())
    {
      cell = std::min(cell, r.GetNative().GetBox().Extent()[a] / r.GetNative().GetResolution()[a]);
    }
  }
  this->Steps[o - surfaces] = 0.5f * cell;
}

Vec3 MirrorReflection::SurfaceTexture(std::size_t s, unsigned int triangle, const Vec3& p) const
{
  const SurfaceChart& chart = this->Objects[s]->GetLayout().Chart;
  float u = 0.f, v = 0.f;
  if (chart.Type == SurfaceChart::Kind::Planar)
  {
    const PlanarFrame& f = chart.Frame;
    u = Dot(p - f.Origin, f.U) / Dot(f.U, f.U);
    v = Dot(p - f.Origin, f.V) / Dot(f.V, f.V);
  }
  else
  {
    // The hit's barycentric weights in the world triangle, applied to its
    // texture corners.
    const Surface& surface = this->SceneRef.Surfaces[s];
    const auto& tri = surface.Triangles[triangle];
    const Vec3 a = surface.Vertices[tri[0]];
    const Vec3 e1 = surface.Vertices[tri[1]] - a, e2 = surface.Vertices[tri[2]] - a, q = p - a;
    const float d11 = Dot(e1, e1), d12 = Dot(e1, e2), d22 = Dot(e2, e2);
    const float q1 = Dot(q, e1), q2 = Dot(q, e2);
    const float det = d11 * d22 - d12 * d12;
    const float b1 = det != 0.f ? (d22 * q1 - d12 * q2) / det : 0.f;
    const float b2 = det != 0.f ? (d11 * q2 - d12 * q1) / det : 0.f;
    const float* uv = chart.TriangleUV[triangle].data();
    u = uv[0] + b1 * (uv[2] - uv[0]) + b2 * (uv[4] - uv[0]);
    v = uv[1] + b1 * (uv[3] - uv[1]) + b2 * (uv[5] - uv[1]);
  }
  return Sample2D(this->Textures[s], u, v);
}

void MirrorReflection::MarchMedia(
  const Vec3& origin, const Vec3& d, float tEnd, Vec3& L, Vec3& T) const
{
  struct Segment
  {
    float T0, T1, Step;
    std::size_t Object;
  };
  const std::size_t surfaces = this->SceneRef.Surfaces.size();
  const std::size_t media = this->SceneRef.Media.size();
  // On the stack for the usual few media, on the heap past them.
  constexpr std::size_t Few = 16;
  Segment few[Few];
  std::vector<Segment> many(media > Few ? media : 0);
  Segment* segments = media > Few ? many.data() : few;
  std::size_t count = 0;
  for (std::size_t m = 0; m < media; ++m)
  {
    float t0 = 0.f, t1 = tEnd;
    if (ClipToBox(this->SceneRef.Media[m].Bounds, origin, d, t0, t1))
    {
      segments[count++] = { t0, t1, this->Steps[m], surfaces + m };
    }
  }
  std::sort(
    segments, segments + count, [](const Segment& a, const Segment& b) { return a.T0 < b.T0; });
  // Overlapping segments are marched together, at the finest of their steps.
  for (std::size_t first = 0; first < count;)
  {
    float g0 = segments[first].T0, g1 = segments[first].T1, step = segments[first].Step;
    std::size_t last = first + 1;
    while (last < count && segments[last].T0 < g1)
    {
      g1 = std::max(g1, segments[last].T1);
      step = std::min(step, segments[last].Step);
      ++last;
    }
    constexpr float MaxSteps = 4096.f;
    const int n =
      static_cast<int>(std::clamp(std::ceil((g1 - g0) / std::max(step, 1e-30f)), 1.f, MaxSteps));
    const float dt = (g1 - g0) / n;
    for (int i = 0; i < n && MaxComponent(T) > 0.f; ++i)
    {
      const float t = g0 + (i + 0.5f) * dt;
      const Vec3 p = origin + d * t;
      Vec3 sigma(0.f), emitted(0.f);
      for (std::size_t k = first; k < last; ++k)
      {
        if (t < segments[k].T0 || t > segments[k].T1)
        {
          continue;
        }
        const std::size_t o = segments[k].Object;
        const Medium& medium = this->SceneRef.Media[o - surfaces];
        const ObjectRadiance& r = *this->Objects[o];
        const BrickedGrid& density = r.GetNative().GetDensity();
        Vec3 factor;
        const Vec3 source = r.GetLayout().Scattering.SourceAt(
          r.GetLayout().Scattering.HasVaryingAlbedo() ? medium.AlbedoAt(p) : Vec3(1.f),
          Sample3D(this->Textures[o], medium.Bounds, p), false, factor);
        const Vec3 s =
          (density.Empty() ? medium.SigmaT() : medium.SigmaT() * density.Interpolate(p)) * factor;
        sigma += s;
        emitted += s * source;
      }
      for (int c = 0; c < 3; ++c)
      {
        if (sigma[c] > 0.f)
        {
          const float tr = std::exp(-sigma[c] * dt);
          L[c] += T[c] * (1.f - tr) * emitted[c] / sigma[c];
          T[c] *= tr;
        }
      }
    }
    first = last;
  }
}

Vec3 MirrorReflection::Incoming(const Vec3& origin, const Vec3& d, int depth) const
{
  if (!IsFinite(origin) || !IsFinite(d))
  {
    return Vec3(0.f); // a degenerate reflection (the eye on the mirror itself)
  }
  SurfaceHit hit;
  const bool hitSurface = this->Caster.Intersect(origin, d, 0.f, Infinity, hit);
  const float tEnd = hitSurface ? hit.T : Infinity;
  Vec3 L(0.f), T(1.f);
  this->MarchMedia(origin, d, tEnd, L, T);
  if (!hitSurface || !(MaxComponent(T) > 0.f))
  {
    return L; // no environment light
  }
  const Vec3 y = origin + d * hit.T;
  Vec3 Ly = this->SurfaceTexture(hit.Surface, hit.Triangle, y);
  const Surface& surface = this->SceneRef.Surfaces[hit.Surface];
  const Material& m = surface.MaterialOf(hit.Triangle);
  // Mirrors seen in a mirror reflect again; glossy lobes are not followed
  // (LobeSamples rays per bounce would multiply).
  if (m.Type == MaterialType::Mirror && MaxComponent(m.Specular) > 0.f && depth < MaxDepth)
  {
    Vec3 n = FaceNormal(surface, hit.Triangle);
    if (Dot(n, d) > 0.f)
    {
      n = -n;
    }
    Ly += m.Specular * this->Incoming(y + n * this->Epsilon, brume::Reflect(-d, n), depth + 1);
  }
  return L + T * Ly;
}

Vec3 MirrorReflection::Lobe(const Vec3& origin, const Vec3& n, const Vec3& r, float exponent,
  std::size_t s, std::size_t texel) const
{
  // cos(alpha) = u^(1 / (e + 1)) has density (e + 1) / (2 pi) cos^e(alpha):
  // f cos(theta) / pdf = (e + 2) / (e + 1) cos(theta) per unit rho_s.
  constexpr int side = 4;
  static_assert(side * side == LobeSamples, "strata");
  Random rng(0x4c6f6265ull + s, texel); // "Lobe"
  const Frame frame(r);
  const float norm = (exponent + 2.f) / (exponent + 1.f);
  Vec3 sum(0.f);
  for (int k = 0; k < LobeSamples; ++k)
  {
    const float u1 = ((k % side) + rng.NextFloat()) / side;
    const float u2 = ((k / side) + rng.NextFloat()) / side;
    const float cosAlpha = std::pow(u1, 1.f / (exponent + 1.f));
    const float sinAlpha = std::sqrt(std::max(0.f, 1.f - cosAlpha * cosAlpha));
    const float phi = 2.f * Pi * u2;
    const Vec3 w =
      Normalize(frame.ToWorld({ sinAlpha * std::cos(phi), sinAlpha * std::sin(phi), cosAlpha }));
    const float cosTheta = Dot(w, n);
    if (cosTheta > 0.f)
    {
      sum += this->Incoming(origin, w, 1) * (norm * cosTheta);
    }
  }
  return sum / static_cast<float>(LobeSamples);
}

void MirrorReflection::Reflect(std::size_t s, const Vec3& eye, const std::array<int, 2>& dims,
  std::vector<float>& radiance, const ParallelFor& parallelFor) const
{
  const Surface& surface = this->SceneRef.Surfaces[s];
  const SurfaceChart& chart = this->Objects[s]->GetLayout().Chart;
  const bool planar = chart.Type == SurfaceChart::Kind::Planar;
  const std::size_t nx = dims[0], ny = dims[1], texels = nx * ny;
  // Which triangle covers each texel centre, and where (serial: the first
  // triangle wins, whatever the threads). Pass 1 covers the texels whose
  // centres lie in a triangle; pass 2 gives the texels next to an atlas
  // chart's triangles (within two texels) the nearest point of the nearest
  // one, so that a renderer's interpolation at the seams meets reflected
  // light, not the gutter's.
  // A planar chart of one material needs none of it: its frame gives every
  // texel's point.
  const bool rasterize = !planar || !surface.TriangleMaterials.empty();
  std::vector<std::int32_t> triangleOf(rasterize ? texels : 0, -1);
  std::vector<float> weights(rasterize ? 2 * texels : 0, 0.f);
  std::vector<float> distance(planar ? 0 : texels, Infinity);
  const float reach = 2.f / static_cast<float>(std::min(nx, ny));
  for (int pass = 0; pass < (!rasterize ? 0 : (planar ? 1 : 2)); ++pass)
  {
    for (std::size_t k = 0; k < surface.Triangles.size(); ++k)
    {
      float uv[6];
      for (int c = 0; c < 3; ++c)
      {
        if (planar)
        {
          const Vec3 q = surface.Vertices[surface.Triangles[k][c]] - chart.Frame.Origin;
          uv[2 * c] = Dot(q, chart.Frame.U) / Dot(chart.Frame.U, chart.Frame.U);
          uv[2 * c + 1] = Dot(q, chart.Frame.V) / Dot(chart.Frame.V, chart.Frame.V);
        }
        else
        {
          uv[2 * c] = chart.TriangleUV[k][2 * c];
          uv[2 * c + 1] = chart.TriangleUV[k][2 * c + 1];
        }
      }
      auto texelRange = [](float lo, float hi, std::size_t n)
      {
        const long first = std::max(0L, static_cast<long>(std::floor(lo * n - 0.5f)));
        const long last =
          std::min(static_cast<long>(n) - 1, static_cast<long>(std::ceil(hi * n - 0.5f)));
        return std::make_pair(first, last);
      };
      const float grow = pass == 0 ? 0.f : reach;
      const auto [i0, i1] = texelRange(
        std::min({ uv[0], uv[2], uv[4] }) - grow, std::max({ uv[0], uv[2], uv[4] }) + grow, nx);
      const auto [j0, j1] = texelRange(
        std::min({ uv[1], uv[3], uv[5] }) - grow, std::max({ uv[1], uv[3], uv[5] }) + grow, ny);
      for (long j = j0; j <= j1; ++j)
      {
        for (long i = i0; i <= i1; ++i)
        {
          const std::size_t t = j * nx + i;
          float b1, b2;
          if (!Barycentric(uv, (i + 0.5f) / nx, (j + 0.5f) / ny, b1, b2))
          {
            continue;
          }
          if (pass == 0 && triangleOf[t] < 0 && Inside(b1, b2))
          {
            triangleOf[t] = static_cast<std::int32_t>(k);
            weights[2 * t] = b1;
            weights[2 * t + 1] = b2;
            if (!planar)
            {
              distance[t] = 0.f;
            }
          }
          else if (pass == 1 && distance[t] > 0.f)
          {
            const float moved = ClampIntoTriangle(uv, b1, b2);
            if (moved <= reach && moved < distance[t])
            {
              triangleOf[t] = static_cast<std::int32_t>(k);
              weights[2 * t] = b1;
              weights[2 * t + 1] = b2;
              distance[t] = moved;
            }
          }
        }
      }
    }
  }
  radiance.assign(3 * texels, 0.f);
  parallelFor(0, ny,
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t j = begin; j < end; ++j)
      {
        for (std::size_t i = 0; i < nx; ++i)
        {
          const std::size_t t = j * nx + i;
          const float u = (i + 0.5f) / nx, v = (j + 0.5f) / ny;
          Vec3 L = Sample2D(this->Textures[s], u, v);
          const std::int32_t k = rasterize ? triangleOf[t] : -1;
          // Planar mirrors reflect over their whole chart (what a renderer
          // interpolates at their edges); others where a triangle lies.
          const Material& m = k >= 0 ? surface.MaterialOf(k) : surface.Mat;
          if ((k >= 0 || planar) && Casts(m))
          {
            Vec3 x, n;
            if (planar)
            {
              x = chart.Frame.Origin + chart.Frame.U * u + chart.Frame.V * v;
              n = chart.Frame.Normal;
            }
            else
            {
              const auto& tri = surface.Triangles[k];
              const Vec3 a = surface.Vertices[tri[0]];
              x = a + (surface.Vertices[tri[1]] - a) * weights[2 * t] +
                (surface.Vertices[tri[2]] - a) * weights[2 * t + 1];
              n = FaceNormal(surface, k);
            }
            const Vec3 wo = Normalize(eye - x);
            if (Dot(n, wo) < 0.f)
            {
              n = -n; // a mirror reflects on both sides
            }
            const Vec3 r = brume::Reflect(wo, n);
            const Vec3 origin = x + n * this->Epsilon;
            if (m.Type == MaterialType::Mirror)
            {
              L += m.Specular * this->Incoming(origin, r, 1);
            }
            else if (this->Objects[s]->Options().LobeCast)
            {
              L += m.Specular * this->Lobe(origin, n, r, m.Exponent, s, t);
            }
          }
          radiance[3 * t] = L.x;
          radiance[3 * t + 1] = L.y;
          radiance[3 * t + 2] = L.z;
        }
      }
    });
}

} // namespace brume
