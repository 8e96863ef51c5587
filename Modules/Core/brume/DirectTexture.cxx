// SPDX-License-Identifier: BSD-3-Clause
// Deterministic single scattering in a reconstruction (brume/DirectTexture.h):
// the particles' texture, which no longer holds the first interactions
// after point, spot and directional lights, resampled on a finer grid, plus
// the direct light those lights give at each of its texels.
#include "brume/DirectTexture.h"

#include "brume/DirectLight.h"
#include "brume/Material.h"
#include "brume/Medium.h"
#include "brume/Sampling.h"
#include "brume/SparseTexture.h"
#include "brume/SphericalHarmonics.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace brume
{

namespace
{
// Normalized [0, 1]^3 coordinates of the centre of texel t of a grid.
Vec3 TexelCentre(std::size_t t, const std::array<int, 3>& dims)
{
  const std::size_t nx = dims[0], nxy = nx * dims[1];
  return Vec3((static_cast<float>(t % nx) + 0.5f) / static_cast<float>(dims[0]),
    (static_cast<float>((t % nxy) / nx) + 0.5f) / static_cast<float>(dims[1]),
    (static_cast<float>(t / nxy) + 0.5f) / static_cast<float>(dims[2]));
}

// Floats per light per output texel: irradiance RGB, direction of travel.
constexpr std::size_t ArrivalFloats = 6;
// Points per axis of a texel on a shadow's edge.
constexpr int RefinedSamples = 4;

// The texels of `read` and their face neighbours along the first `used`
// axes (a medium's texels near its density, whose shadow rays are cast).
std::vector<std::uint8_t> WithFaceNeighbours(
  const std::vector<std::uint8_t>& read, const std::array<int, 3>& dims, int used)
{
  const std::size_t nx = dims[0], nxy = nx * dims[1];
  const std::size_t texels = nxy * dims[2];
  std::vector<std::uint8_t> cast = read;
  for (std::size_t t = 0; t < texels; ++t)
  {
    const int c[3] = { static_cast<int>(t % nx), static_cast<int>((t % nxy) / nx),
      static_cast<int>(t / nxy) };
    for (int a = 0; a < used && !read[t]; ++a)
    {
      const std::size_t stride = a == 0 ? 1 : (a == 1 ? nx : nxy);
      if ((c[a] > 0 && read[t - stride]) || (c[a] + 1 < dims[a] && read[t + stride]))
      {
        cast[t] = 1;
      }
    }
  }
  return cast;
}

// Per texel and light, whether the texel lies on a shadow's or a beam's
// edge: lit while a face neighbour is not, or the reverse (texels outside
// `read`, when given, are left out).
std::vector<std::uint8_t> LightEdges(const std::vector<float>& arrivals, std::size_t lights,
  const std::vector<std::uint8_t>& read, const std::array<int, 3>& dims, int used)
{
  const std::size_t nx = dims[0], nxy = nx * dims[1];
  const std::size_t texels = nxy * dims[2];
  auto lit = [&](std::size_t t, std::size_t l)
  {
    const float* a = &arrivals[(t * lights + l) * ArrivalFloats];
    return a[0] > 0.f || a[1] > 0.f || a[2] > 0.f;
  };
  std::vector<std::uint8_t> edge(texels * lights, 0);
  for (std::size_t t = 0; t < texels; ++t)
  {
    if (!read.empty() && !read[t])
    {
      continue;
    }
    const int c[3] = { static_cast<int>(t % nx), static_cast<int>((t % nxy) / nx),
      static_cast<int>(t / nxy) };
    for (std::size_t l = 0; l < lights; ++l)
    {
      const bool here = lit(t, l);
      for (int a = 0; a < used && !edge[t * lights + l]; ++a)
      {
        const std::size_t stride = a == 0 ? 1 : (a == 1 ? nx : nxy);
        if ((c[a] > 0 && lit(t - stride, l) != here) ||
          (c[a] + 1 < dims[a] && lit(t + stride, l) != here))
        {
          edge[t * lights + l] = 1;
        }
      }
    }
  }
  return edge;
}

// Along one axis of an output grid: each output texel's two texture
// texels and the weight of the second (trilinear interpolation between
// texel centres), and the part of its position along this axis.
struct ResampledAxis
{
  std::vector<int> I0, I1;
  std::vector<float> W;
  std::vector<Vec3> Offset;
};

std::array<ResampledAxis, 3> ResampledAxes(
  const ObjectLayout& layout, const std::array<int, 3>& dims)
{
  std::array<ResampledAxis, 3> axes;
  const PlanarFrame& frame = layout.Chart.Frame;
  for (int a = 0; a < 3; ++a)
  {
    const int n = layout.Resolution[a];
    ResampledAxis& axis = axes[a];
    for (int i = 0; i < dims[a]; ++i)
    {
      const float q = (static_cast<float>(i) + 0.5f) / static_cast<float>(dims[a]);
      const CellCentreWeights weights(q, n);
      axis.I0.push_back(weights.I0);
      axis.I1.push_back(weights.I1);
      axis.W.push_back(weights.W);
      Vec3 offset(0.f);
      if (layout.MediumRef)
      {
        offset[a] = layout.MediumRef->Bounds.lower[a] + q * layout.MediumRef->Bounds.Extent()[a];
      }
      else if (a == 0)
      {
        offset = frame.Origin + frame.U * q;
      }
      else if (a == 1)
      {
        offset = frame.V * q;
      }
      axis.Offset.push_back(offset);
    }
  }
  return axes;
}
}

bool DirectTexture::Supports(const ObjectLayout& layout)
{
  if (layout.MediumRef)
  {
    return true;
  }
  const Surface& surface = *layout.SurfaceRef;
  const auto mirror = [](const Material& m) { return m.Type == MaterialType::Mirror; };
  return layout.Chart.Type == SurfaceChart::Kind::Planar && !surface.Triangles.empty() &&
    (surface.TriangleMaterials.empty()
        ? !mirror(surface.Mat)
        : std::none_of(surface.TriangleMaterials.begin(), surface.TriangleMaterials.end(), mirror));
}

void DirectTexture::LocateTriangles(const ObjectLayout& layout)
{
  // Each output texel's centre in the plane's (s, t) coordinates, found in
  // the triangles that cover it (the first one wins, serially: the same
  // whatever the threads).
  this->Triangles.clear();
  if (layout.MediumRef || !layout.SurfaceRef)
  {
    return;
  }
  const Surface& surface = *layout.SurfaceRef;
  if (surface.TriangleMaterials.empty() && surface.VertexReflectance.empty())
  {
    return;
  }
  const std::size_t nx = this->Dims[0], ny = this->Dims[1];
  this->Triangles.assign(nx * ny, -1);
  const PlanarFrame& frame = layout.Chart.Frame;
  const float uu = Dot(frame.U, frame.U), vv = Dot(frame.V, frame.V);
  for (std::size_t k = 0; k < surface.Triangles.size(); ++k)
  {
    float s[3], t[3];
    for (int c = 0; c < 3; ++c)
    {
      const Vec3 q = surface.Vertices[surface.Triangles[k][c]] - frame.Origin;
      s[c] = Dot(q, frame.U) / uu;
      t[c] = Dot(q, frame.V) / vv;
    }
    const float det = (s[1] - s[0]) * (t[2] - t[0]) - (s[2] - s[0]) * (t[1] - t[0]);
    if (det == 0.f)
    {
      continue;
    }
    // Texel centres (i + 1/2) / n within the triangle's bounds.
    auto range = [](float lo, float hi, std::size_t n)
    {
      const long first = std::max(0L, static_cast<long>(std::ceil(lo * n - 0.5f)));
      const long last =
        std::min(static_cast<long>(n) - 1, static_cast<long>(std::floor(hi * n - 0.5f)));
      return std::make_pair(first, last);
    };
    const auto [i0, i1] = range(std::min({ s[0], s[1], s[2] }), std::max({ s[0], s[1], s[2] }), nx);
    const auto [j0, j1] = range(std::min({ t[0], t[1], t[2] }), std::max({ t[0], t[1], t[2] }), ny);
    for (long j = j0; j <= j1; ++j)
    {
      for (long i = i0; i <= i1; ++i)
      {
        const float ps = (i + 0.5f) / nx - s[0], pt = (j + 0.5f) / ny - t[0];
        const float b1 = (ps * (t[2] - t[0]) - (s[2] - s[0]) * pt) / det;
        const float b2 = ((s[1] - s[0]) * pt - ps * (t[1] - t[0])) / det;
        constexpr float tolerance = -1e-6f;
        std::int32_t& triangle = this->Triangles[j * nx + i];
        if (triangle < 0 && b1 >= tolerance && b2 >= tolerance && b1 + b2 <= 1.f - tolerance)
        {
          triangle = static_cast<std::int32_t>(k);
        }
      }
    }
  }
}

void DirectTexture::Enable(
  const ObjectLayout& layout, const DirectLight* light, const std::array<int, 3>& resolution)
{
  this->Arrivals.clear();
  this->Radiance.clear();
  this->Extinction.clear();
  if (!light || !Supports(layout) || light->NumberOfLights() == 0)
  {
    this->Light = nullptr;
    return;
  }
  this->Light = light;
  for (int a = 0; a < 3; ++a)
  {
    this->Dims[a] = std::max(1, resolution[a]);
  }
  if (!layout.MediumRef)
  {
    this->Dims[2] = 1;
    const auto& tri = layout.SurfaceRef->Triangles.front();
    const auto& v = layout.SurfaceRef->Vertices;
    this->SurfaceNormal = Normalize(Cross(v[tri[1]] - v[tri[0]], v[tri[2]] - v[tri[0]]));
  }
}

Vec3 DirectTexture::OutputPosition(const ObjectLayout& layout, std::size_t t) const
{
  const Vec3 q = TexelCentre(t, this->Dims);
  if (layout.MediumRef)
  {
    return layout.MediumRef->Bounds.lower + q * layout.MediumRef->Bounds.Extent();
  }
  const PlanarFrame& f = layout.Chart.Frame;
  return f.Origin + f.U * q.x + f.V * q.y;
}

std::vector<ShadowSweep> DirectTexture::PlanSweeps(const ObjectLayout& layout,
  const NativeMediumGrid& native, const std::vector<std::uint8_t>& cast) const
{
  const std::size_t lights = this->Light->NumberOfLights();
  std::vector<ShadowSweep> sweeps(lights);
  if (!layout.MediumRef || native.Empty())
  {
    return sweeps; // nothing a march through a grid would repeat
  }
  const std::size_t texels =
    static_cast<std::size_t>(this->Dims[0]) * this->Dims[1] * this->Dims[2];
  const Box& box = layout.MediumRef->Bounds;
  for (std::size_t l = 0; l < lights; ++l)
  {
    ShadowSweep& sweep = sweeps[l];
    if (!sweep.Plan(*this->Light, l, box, this->Dims))
    {
      continue; // left unplanned
    }
    // The sweep where its rays march through the box at most half as far
    // as the texels' own would: each from its texel to where it leaves.
    // Over every texel cast, whichever process casts it, so that every
    // process decides alike and the texels do not depend on how many.
    double perTexel = 0.0;
    for (std::size_t t = 0; t < texels; ++t)
    {
      if (cast.empty() || cast[t])
      {
        const Vec3 x = this->OutputPosition(layout, t);
        float t0 = 0.f, t1 = std::numeric_limits<float>::max();
        if (box.Intersect(x, -this->Light->DirectionAt(l, x), t0, t1))
        {
          perTexel += t1 - t0;
        }
      }
    }
    if (!(sweep.MarchLength() < 0.5 * perTexel))
    {
      sweep = ShadowSweep();
    }
  }
  return sweeps;
}

bool DirectTexture::Compute(const ObjectLayout& layout, const std::vector<float>& texture,
  const NativeMediumGrid& native, const ObjectDistribution& distribution,
  const ParallelFor& parallelFor, const std::vector<float>* kept)
{
  this->Arrivals.clear();
  this->Read.clear();
  if (!this->Light || texture.empty())
  {
    return false;
  }
  const std::size_t lights = this->Light->NumberOfLights();
  const std::array<int, 3> dims = this->Dims;
  const std::size_t texels = static_cast<std::size_t>(dims[0]) * dims[1] * dims[2];
  std::vector<float> arrivals;
  if (kept && kept->size() == texels * lights * ArrivalFloats)
  {
    arrivals = *kept; // the same rays, cast before
  }
  else
  {
    arrivals.assign(texels * lights * ArrivalFloats, 0.f);
    const Vec3 bias =
      layout.MediumRef ? Vec3(0.f) : this->SurfaceNormal * this->Light->GetEpsilon();
    // Light l's arrival at x (zero when none), surfaces' weighted by the cosine
    // (they store E cos(theta), shown on their front side only).
    auto arrive = [&](std::size_t l, const Vec3& x, Vec3& irradiance)
    {
      LightArrival a;
      irradiance = Vec3(0.f);
      if (!layout.MediumRef && Dot(this->Light->DirectionAt(l, x), this->SurfaceNormal) >= 0.f)
      {
        return; // light on the back side: no shadow ray
      }
      if (!this->Light->Arrive(l, x, bias, a))
      {
        return;
      }
      const float weight =
        layout.MediumRef ? 1.f : std::max(0.f, -Dot(a.Direction, this->SurfaceNormal));
      irradiance = a.Irradiance * weight;
    };
    auto store = [&](std::size_t t, std::size_t l, const Vec3& irradiance, const Vec3& direction)
    {
      float* out = &arrivals[(t * lights + l) * ArrivalFloats];
      for (int c = 0; c < 3; ++c)
      {
        out[c] = irradiance[c];
        out[3 + c] = direction[c];
      }
    };
    // Distributed runs: each process casts the shadow rays of its share of
    // the texels, and every process gathers all of them (a texel's rays
    // depend on the texel only).
    const auto mine = distribution.Share(texels);
    const std::size_t floats = lights * ArrivalFloats;
    // A medium with a density grid of its own: only the texels a renderer
    // reads (near the density, SparseTexture::CellsRead) get their light; the
    // others stay 0, as no image shows them. Their face neighbours' rays are
    // cast too, so that the edges below are found as with every texel.
    const int used = layout.MediumRef ? 3 : 2;
    std::vector<std::uint8_t>& read = this->Read;
    std::vector<std::uint8_t> cast;
    if (layout.MediumRef && !native.Empty())
    {
      read =
        SparseTexture::CellsRead(dims, layout.MediumRef->Bounds, native.GetDensity(), parallelFor);
      cast = WithFaceNeighbours(read, dims, used);
    }
    // 1. One shadow ray per texel centre, or, through a medium's own grid,
    // the rays of a sweep where they march less (ShadowSweep): the texels
    // then hold the light before the media, which the sweep attenuates.
    std::vector<std::uint8_t> wanted(texels, 0);
    for (std::size_t t = mine[0]; t < mine[1]; ++t)
    {
      wanted[t] = cast.empty() || cast[t];
    }
    const std::vector<ShadowSweep> sweeps = this->PlanSweeps(layout, native, cast);
    parallelFor(mine[0], mine[1],
      [&](std::size_t begin, std::size_t end)
      {
        for (std::size_t t = begin; t < end; ++t)
        {
          if (!cast.empty() && !cast[t])
          {
            continue;
          }
          const Vec3 x = this->OutputPosition(layout, t);
          for (std::size_t l = 0; l < lights; ++l)
          {
            Vec3 irradiance;
            if (!sweeps[l].IsPlanned())
            {
              arrive(l, x, irradiance);
            }
            else
            {
              LightArrival a;
              float distance = 0.f;
              irradiance =
                this->Light->ArriveUnattenuated(l, x, bias, a, distance) ? a.Irradiance : Vec3(0.f);
            }
            store(t, l, irradiance, this->Light->DirectionAt(l, x));
          }
        }
      });
    for (std::size_t l = 0; l < lights; ++l)
    {
      if (sweeps[l].IsPlanned())
      {
        const std::vector<float> depths = sweeps[l].Depths(wanted, parallelFor);
        parallelFor(mine[0], mine[1],
          [&](std::size_t begin, std::size_t end)
          {
            for (std::size_t t = begin; t < end; ++t)
            {
              float* out = &arrivals[(t * lights + l) * ArrivalFloats];
              const float* depth = &depths[3 * t];
              const Vec3 irradiance = Vec3(out[0], out[1], out[2]) *
                Vec3(std::exp(-depth[0]), std::exp(-depth[1]), std::exp(-depth[2]));
              // As arrive() finds it: none where nothing is left.
              const bool lit = MaxComponent(irradiance) > 0.f;
              for (int c = 0; c < 3; ++c)
              {
                out[c] = lit ? irradiance[c] : 0.f;
              }
            }
          });
      }
    }
    distribution.GatherShares(texels, floats, arrivals);
    // 2. Texels on a shadow's or a beam's edge (lit while a face neighbour is
    // not, or the reverse) hold the mean over RefinedSamples^d stratified
    // points of the texel instead: the edge then lies where it is, not half
    // way between two texel centres, once the renderer interpolates.
    const std::vector<std::uint8_t> edge = LightEdges(arrivals, lights, read, dims, used);
    const Vec3 texel = (layout.MediumRef ? layout.MediumRef->Bounds.Extent() : Vec3(1.f)) /
      Vec3(static_cast<float>(dims[0]), static_cast<float>(dims[1]), static_cast<float>(dims[2]));
    const PlanarFrame& frame = layout.Chart.Frame;
    parallelFor(mine[0], mine[1],
      [&](std::size_t begin, std::size_t end)
      {
        constexpr int S = RefinedSamples;
        for (std::size_t t = begin; t < end; ++t)
        {
          for (std::size_t l = 0; l < lights; ++l)
          {
            if (!edge[t * lights + l])
            {
              continue;
            }
            const Vec3 centre = this->OutputPosition(layout, t);
            Vec3 sum(0.f);
            const int n = used == 3 ? S * S * S : S * S;
            for (int k = 0; k < n; ++k)
            {
              const Vec3 f((static_cast<float>(k % S) + 0.5f) / S - 0.5f,
                (static_cast<float>((k / S) % S) + 0.5f) / S - 0.5f,
                used == 3 ? (static_cast<float>(k / (S * S)) + 0.5f) / S - 0.5f : 0.f);
              const Vec3 x = layout.MediumRef
                ? centre + f * texel
                : centre + frame.U * (f.x * texel.x) + frame.V * (f.y * texel.y);
              Vec3 irradiance;
              arrive(l, x, irradiance);
              sum += irradiance;
            }
            store(t, l, sum / static_cast<float>(n), this->Light->DirectionAt(l, centre));
          }
        }
      });
    distribution.GatherShares(texels, floats, arrivals);
  }
  this->Arrivals.swap(arrivals);
  this->LocateTriangles(layout);
  if (layout.MediumRef)
  {
    // sigma_t on the output grid (renderers without the native grid).
    this->Extinction.resize(3 * texels);
    parallelFor(0, texels,
      [&](std::size_t begin, std::size_t end)
      {
        for (std::size_t t = begin; t < end; ++t)
        {
          const Vec3 sigma = layout.MediumRef->SigmaTAt(this->OutputPosition(layout, t));
          for (int c = 0; c < 3; ++c)
          {
            this->Extinction[3 * t + c] = sigma[c];
          }
        }
      });
  }
  return true;
}

void DirectTexture::Combine(const ObjectLayout& layout, const std::vector<float>& texture,
  const Vec3& eye, const ParallelFor& parallelFor)
{
  // Once per view for view-dependent objects: per output texel, the
  // texture resampled (its interpolation weights and the texel's position
  // are separable, tabulated per axis) plus each light's direct term toward
  // the eye.
  const std::size_t lights = this->Light->NumberOfLights();
  const std::array<int, 3>& dims = this->Dims;
  const std::size_t texels = static_cast<std::size_t>(dims[0]) * dims[1] * dims[2];
  this->Radiance.resize(3 * texels);
  const std::array<ResampledAxis, 3> axes = ResampledAxes(layout, dims);
  // As the particles' light: the phase function's remainder, per unit of
  // the reduced extinction.
  const MediumScattering& scattering = layout.Scattering;
  const ForwardPeak& peak = scattering.GetPeak(false);
  const Vec3 scale = scattering.GetAlbedo() / scattering.GetExtinctionFactor(false);
  const std::size_t nx = layout.Resolution[0], nxy = nx * layout.Resolution[1];
  const std::size_t rows = static_cast<std::size_t>(dims[1]) * dims[2];
  // The output texels' x positions apart, for the media's row loops.
  std::vector<float> offsetX[3];
  for (const Vec3& offset : axes[0].Offset)
  {
    for (int a = 0; a < 3; ++a)
    {
      offsetX[a].push_back(offset[a]);
    }
  }
  parallelFor(0, rows,
    [&](std::size_t begin, std::size_t end)
    {
      std::vector<float> phaseOf(layout.MediumRef ? dims[0] : 0);
      for (std::size_t row = begin; row < end; ++row)
      {
        const std::size_t y = row % dims[1], z = row / dims[1];
        const float wy = axes[1].W[y], wz = axes[2].W[z];
        const std::size_t base[4] = { axes[2].I0[z] * nxy + axes[1].I0[y] * nx,
          axes[2].I0[z] * nxy + axes[1].I1[y] * nx, axes[2].I1[z] * nxy + axes[1].I0[y] * nx,
          axes[2].I1[z] * nxy + axes[1].I1[y] * nx };
        const float wyz[4] = { (1.f - wy) * (1.f - wz), wy * (1.f - wz), (1.f - wy) * wz, wy * wz };
        const Vec3 rowOffset = axes[1].Offset[y] + axes[2].Offset[z];
        for (int x = 0; x < dims[0]; ++x)
        {
          const std::size_t t = row * dims[0] + x;
          float* out = &this->Radiance[3 * t];
          const std::size_t x0 = axes[0].I0[x], x1 = axes[0].I1[x];
          const float wx = axes[0].W[x];
          for (int c = 0; c < 3; ++c)
          {
            float value = 0.f;
            for (int k = 0; k < 4; ++k)
            {
              value += wyz[k] *
                ((1.f - wx) * texture[3 * (base[k] + x0) + c] +
                  wx * texture[3 * (base[k] + x1) + c]);
            }
            out[c] = value;
          }
        }
        if (layout.MediumRef)
        {
          // S_1 = albedo p E T (the source radiance J_1 / sigma_t), light by
          // light along the row: the phase function first, in a loop the
          // compiler vectorizes (DirectTexture.cxx is built without
          // errno from square roots), then the sums.
          const Vec3 toward = eye - rowOffset;
          const std::size_t first = row * dims[0];
          float* out = &this->Radiance[3 * first];
          for (std::size_t l = 0; l < lights; ++l)
          {
            const float* a = &this->Arrivals[(first * lights + l) * ArrivalFloats];
            const std::size_t stride = lights * ArrivalFloats;
            for (int x = 0; x < dims[0]; ++x)
            {
              const float* ax = a + x * stride;
              const float ex = toward.x - offsetX[0][x], ey = toward.y - offsetX[1][x],
                          ez = toward.z - offsetX[2][x];
              const float dot = ax[3] * ex + ax[4] * ey + ax[5] * ez;
              phaseOf[x] = peak.Remainder(dot / std::sqrt(ex * ex + ey * ey + ez * ez));
            }
            for (int x = 0; x < dims[0]; ++x)
            {
              const float* ax = a + x * stride;
              for (int c = 0; c < 3; ++c)
              {
                out[3 * x + c] += scale[c] * phaseOf[x] * ax[c];
              }
            }
          }
          continue;
        }
        for (int x = 0; x < dims[0]; ++x)
        {
          const std::size_t t = row * dims[0] + x;
          float* out = &this->Radiance[3 * t];
          const Vec3 toEye = Normalize(eye - (axes[0].Offset[x] + rowOffset));
          for (std::size_t l = 0; l < lights; ++l)
          {
            const float* a = &this->Arrivals[(t * lights + l) * ArrivalFloats];
            if (a[0] == 0.f && a[1] == 0.f && a[2] == 0.f)
            {
              continue;
            }
            const Vec3 direction(a[3], a[4], a[5]);
            const std::int32_t triangle = this->Triangles.empty() ? -1 : this->Triangles[t];
            Material coloured; // where the surface's reflectance varies over it
            const Material& m = triangle < 0 ? layout.SurfaceRef->Mat
              : layout.SurfaceRef->VertexReflectance.empty()
              ? layout.SurfaceRef->MaterialOf(triangle)
              : (coloured = layout.SurfaceRef->MaterialAt(triangle, axes[0].Offset[x] + rowOffset));
            const Vec3 f = EvaluateBrdf(m, this->SurfaceNormal, -direction, toEye);
            for (int c = 0; c < 3; ++c)
            {
              out[c] += f[c] * a[c];
            }
          }
        }
      }
    });
}

void DirectTexture::AddToDirectional(
  const ObjectLayout& layout, int order, std::vector<float>& directional) const
{
  // Each output texel's S_1 lobe, albedo E T p(w_l, .), projected as the
  // particles' light is (coefficient Y_k(w_l) per unit of S) and averaged
  // over the output texels whose centres fall in each voxel.
  const std::size_t lights = this->Light->NumberOfLights();
  const std::size_t texels = this->Arrivals.size() / (lights * ArrivalFloats);
  const int nk = ShCoefficients(order);
  const std::size_t voxels = layout.Texels();
  std::vector<double> sums(voxels * nk * 3, 0.0);
  std::vector<std::size_t> members(voxels, 0);
  auto voxelOf = [&](std::size_t t)
  {
    const Vec3 q = TexelCentre(t, this->Dims);
    std::size_t v = 0;
    for (int a = 2; a >= 0; --a)
    {
      const int i = std::clamp(static_cast<int>(q[a] * static_cast<float>(layout.Resolution[a])), 0,
        layout.Resolution[a] - 1);
      v = v * layout.Resolution[a] + i;
    }
    return v;
  };
  // The remainder of the phase function, per unit of the reduced extinction.
  const MediumScattering& scattering = layout.Scattering;
  const Vec3 scale = scattering.GetAlbedo() * (1.f - scattering.GetPeak(true).Forward) /
    scattering.GetExtinctionFactor(true);
  float y[ShCoefficients(MaxShOrder)];
  auto addLobes = [&](std::size_t t, std::size_t v)
  {
    ++members[v];
    for (std::size_t l = 0; l < lights; ++l)
    {
      const float* a = &this->Arrivals[(t * lights + l) * ArrivalFloats];
      if (a[0] == 0.f && a[1] == 0.f && a[2] == 0.f)
      {
        continue;
      }
      EvaluateSh(order, Vec3(a[3], a[4], a[5]), y);
      for (int k = 0; k < nk; ++k)
      {
        for (int c = 0; c < 3; ++c)
        {
          sums[(v * nk + k) * 3 + c] += static_cast<double>(scale[c]) * a[c] * y[k];
        }
      }
    }
  };
  for (std::size_t t = 0; t < texels; ++t)
  {
    addLobes(t, voxelOf(t));
  }
  // Where the output grid is coarser than the texture along an axis (it is
  // at most the field's own resolution; the texture's follows the
  // particles), a voxel may hold no output texel's centre: it takes the
  // lobes of the output texel holding its own centre, as a renderer
  // sampling the output grid there would.
  const std::array<int, 3>& res = layout.Resolution;
  for (std::size_t v = 0; v < voxels; ++v)
  {
    if (members[v] != 0)
    {
      continue;
    }
    const Vec3 q = TexelCentre(v, res);
    std::size_t t = 0;
    for (int a = 2; a >= 0; --a)
    {
      const int i = std::clamp(
        static_cast<int>(q[a] * static_cast<float>(this->Dims[a])), 0, this->Dims[a] - 1);
      t = t * static_cast<std::size_t>(this->Dims[a]) + static_cast<std::size_t>(i);
    }
    addLobes(t, v);
  }
  for (std::size_t v = 0; v < voxels; ++v)
  {
    if (members[v] == 0)
    {
      continue;
    }
    for (std::size_t j = 0; j < static_cast<std::size_t>(nk) * 3; ++j)
    {
      directional[v * nk * 3 + j] +=
        static_cast<float>(sums[v * nk * 3 + j] / static_cast<double>(members[v]));
    }
  }
}

} // namespace brume
