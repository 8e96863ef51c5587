// SPDX-License-Identifier: BSD-3-Clause
// Deterministic single scattering in a reconstruction (brume/DirectLight.h):
// the particles' texture, which no longer holds the first interactions
// after point, spot and directional lights, resampled on a finer grid, plus
// the direct light those lights give at each of its texels.
#include "brume/DirectLight.h"
#include "brume/Material.h"
#include "brume/Reconstruction.h"
#include "brume/Sampling.h"
#include "brume/SparseTexture.h"
#include "brume/SphericalHarmonics.h"

#include <algorithm>
#include <cmath>

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
}

bool ObjectRadiance::SupportsDirect() const
{
  if (this->MediumRef)
  {
    return true;
  }
  const Surface& surface = *this->SurfaceRef;
  const auto mirror = [](const Material& m) { return m.Type == MaterialType::Mirror; };
  return this->Chart.Type == SurfaceChart::Kind::Planar && !surface.Triangles.empty() &&
    (surface.TriangleMaterials.empty()
        ? !mirror(surface.Mat)
        : std::none_of(surface.TriangleMaterials.begin(), surface.TriangleMaterials.end(), mirror));
}

void ObjectRadiance::LocateDirectTriangles()
{
  // Each output texel's centre in the plane's (s, t) coordinates, found in
  // the triangles that cover it (the first one wins, serially: the same
  // whatever the threads).
  this->DirectTriangles.clear();
  if (this->MediumRef || !this->SurfaceRef)
  {
    return;
  }
  const Surface& surface = *this->SurfaceRef;
  if (surface.TriangleMaterials.empty() && surface.VertexReflectance.empty())
  {
    return;
  }
  const std::size_t nx = this->DirectDims[0], ny = this->DirectDims[1];
  this->DirectTriangles.assign(nx * ny, -1);
  const PlanarFrame& frame = this->Chart.Frame;
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
        std::int32_t& triangle = this->DirectTriangles[j * nx + i];
        if (triangle < 0 && b1 >= tolerance && b2 >= tolerance && b1 + b2 <= 1.f - tolerance)
        {
          triangle = static_cast<std::int32_t>(k);
        }
      }
    }
  }
}

void ObjectRadiance::EnableDirect(const DirectLight* light, const std::array<int, 3>& resolution)
{
  this->Arrivals.clear();
  this->DirectRadiance.clear();
  this->DirectExtinction.clear();
  if (!light || !this->SupportsDirect() || light->NumberOfLights() == 0)
  {
    this->Direct = nullptr;
    return;
  }
  this->Direct = light;
  for (int a = 0; a < 3; ++a)
  {
    this->DirectDims[a] = std::max(1, resolution[a]);
  }
  if (!this->MediumRef)
  {
    this->DirectDims[2] = 1;
    const auto& tri = this->SurfaceRef->Triangles.front();
    const auto& v = this->SurfaceRef->Vertices;
    this->SurfaceNormal = Normalize(Cross(v[tri[1]] - v[tri[0]], v[tri[2]] - v[tri[0]]));
  }
}

Vec3 ObjectRadiance::OutputPosition(std::size_t t) const
{
  const Vec3 q = TexelCentre(t, this->DirectDims);
  if (this->MediumRef)
  {
    return this->MediumRef->Bounds.lower + q * this->MediumRef->Bounds.Extent();
  }
  const PlanarFrame& f = this->Chart.Frame;
  return f.Origin + f.U * q.x + f.V * q.y;
}

void ObjectRadiance::ComputeDirect(const ParallelFor& parallelFor)
{
  this->Arrivals.clear();
  if (!this->Direct || this->Radiance.empty())
  {
    return;
  }
  const std::size_t lights = this->Direct->NumberOfLights();
  const std::array<int, 3> dims = this->DirectDims;
  const std::size_t texels = static_cast<std::size_t>(dims[0]) * dims[1] * dims[2];
  std::vector<float> arrivals(texels * lights * ArrivalFloats, 0.f);
  const Vec3 bias = this->MediumRef ? Vec3(0.f) : this->SurfaceNormal * this->Direct->GetEpsilon();
  // Light l's arrival at x (zero when none), surfaces' weighted by the cosine
  // (they store E cos(theta), shown on their front side only).
  auto arrive = [&](std::size_t l, const Vec3& x, Vec3& irradiance)
  {
    LightArrival a;
    irradiance = Vec3(0.f);
    if (!this->MediumRef && Dot(this->Direct->DirectionAt(l, x), this->SurfaceNormal) >= 0.f)
    {
      return; // light on the back side: no shadow ray
    }
    if (!this->Direct->Arrive(l, x, bias, a))
    {
      return;
    }
    const float weight =
      this->MediumRef ? 1.f : std::max(0.f, -Dot(a.Direction, this->SurfaceNormal));
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
  const auto mine = this->Share(texels);
  const std::size_t floats = lights * ArrivalFloats;
  // A medium with a density grid of its own: only the texels a renderer
  // reads (near the density, SparseTexture::CellsRead) get their light; the
  // others stay 0, as no image shows them. Their face neighbours' rays are
  // cast too, so that the edges below are found as with every texel.
  const int used = this->MediumRef ? 3 : 2;
  std::vector<std::uint8_t> read, cast;
  if (this->MediumRef && !this->NativeDensity.Empty())
  {
    read = SparseTexture::CellsRead(dims, this->MediumRef->Bounds, this->NativeDensity);
    cast = WithFaceNeighbours(read, dims, used);
  }
  // 1. One shadow ray per texel centre.
  parallelFor(mine[0], mine[1],
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t t = begin; t < end; ++t)
      {
        if (!cast.empty() && !cast[t])
        {
          continue;
        }
        const Vec3 x = this->OutputPosition(t);
        for (std::size_t l = 0; l < lights; ++l)
        {
          Vec3 irradiance;
          arrive(l, x, irradiance);
          store(t, l, irradiance, this->Direct->DirectionAt(l, x));
        }
      }
    });
  this->GatherShares(texels, floats, arrivals);
  // 2. Texels on a shadow's or a beam's edge (lit while a face neighbour is
  // not, or the reverse) hold the mean over RefinedSamples^d stratified
  // points of the texel instead: the edge then lies where it is, not half
  // way between two texel centres, once the renderer interpolates.
  const std::vector<std::uint8_t> edge = LightEdges(arrivals, lights, read, dims, used);
  const Vec3 texel = (this->MediumRef ? this->MediumRef->Bounds.Extent() : Vec3(1.f)) /
    Vec3(static_cast<float>(dims[0]), static_cast<float>(dims[1]), static_cast<float>(dims[2]));
  const PlanarFrame& frame = this->Chart.Frame;
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
          const Vec3 centre = this->OutputPosition(t);
          Vec3 sum(0.f);
          const int n = used == 3 ? S * S * S : S * S;
          for (int k = 0; k < n; ++k)
          {
            const Vec3 f((static_cast<float>(k % S) + 0.5f) / S - 0.5f,
              (static_cast<float>((k / S) % S) + 0.5f) / S - 0.5f,
              used == 3 ? (static_cast<float>(k / (S * S)) + 0.5f) / S - 0.5f : 0.f);
            const Vec3 x = this->MediumRef
              ? centre + f * texel
              : centre + frame.U * (f.x * texel.x) + frame.V * (f.y * texel.y);
            Vec3 irradiance;
            arrive(l, x, irradiance);
            sum += irradiance;
          }
          store(t, l, sum / static_cast<float>(n), this->Direct->DirectionAt(l, centre));
        }
      }
    });
  this->GatherShares(texels, floats, arrivals);
  this->Arrivals.swap(arrivals);
  this->LocateDirectTriangles();
  if (this->MediumRef)
  {
    // sigma_t on the output grid (renderers without the native grid).
    this->DirectExtinction.resize(3 * texels);
    parallelFor(0, texels,
      [&](std::size_t begin, std::size_t end)
      {
        for (std::size_t t = begin; t < end; ++t)
        {
          const Vec3 sigma = this->MediumRef->SigmaTAt(this->OutputPosition(t));
          for (int c = 0; c < 3; ++c)
          {
            this->DirectExtinction[3 * t + c] = sigma[c];
          }
        }
      });
  }
  this->CombineDirect(parallelFor);
  if (this->DirectionalOrder >= 0)
  {
    this->BuildDirectional(this->DirectionalOrder, parallelFor);
  }
}

void ObjectRadiance::CombineDirect(const ParallelFor& parallelFor)
{
  // Once per view for view-dependent objects: per output texel, the
  // texture resampled (its interpolation weights and the texel's position
  // are separable, tabulated per axis) plus each light's direct term toward
  // the eye.
  const std::size_t lights = this->Direct->NumberOfLights();
  const std::array<int, 3>& dims = this->DirectDims;
  const std::size_t texels = static_cast<std::size_t>(dims[0]) * dims[1] * dims[2];
  this->DirectRadiance.resize(3 * texels);
  struct Axis
  {
    std::vector<int> I0, I1;
    std::vector<float> W;
    std::vector<Vec3> Offset; // the position's part along this axis
  };
  Axis axes[3];
  const PlanarFrame& frame = this->Chart.Frame;
  for (int a = 0; a < 3; ++a)
  {
    const int n = this->Resolution[a];
    Axis& axis = axes[a];
    for (int i = 0; i < dims[a]; ++i)
    {
      const float q = (static_cast<float>(i) + 0.5f) / static_cast<float>(dims[a]);
      const CellCentreWeights weights(q, n);
      axis.I0.push_back(weights.I0);
      axis.I1.push_back(weights.I1);
      axis.W.push_back(weights.W);
      Vec3 offset(0.f);
      if (this->MediumRef)
      {
        offset[a] = this->MediumRef->Bounds.lower[a] + q * this->MediumRef->Bounds.Extent()[a];
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
  // As the particles' light: the phase function's remainder, per unit of
  // the reduced extinction.
  const HenyeyGreenstein phase(this->MediumRef ? this->Peaks[0].G : 0.f);
  const Vec3 scale =
    this->MediumAlbedo * (1.f - this->Peaks[0].Forward) / this->ExtinctionFactors[0];
  const std::size_t nx = this->Resolution[0], nxy = nx * this->Resolution[1];
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
      std::vector<float> phaseOf(this->MediumRef ? dims[0] : 0);
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
          float* out = &this->DirectRadiance[3 * t];
          const std::size_t x0 = axes[0].I0[x], x1 = axes[0].I1[x];
          const float wx = axes[0].W[x];
          for (int c = 0; c < 3; ++c)
          {
            float value = 0.f;
            for (int k = 0; k < 4; ++k)
            {
              value += wyz[k] *
                ((1.f - wx) * this->Radiance[3 * (base[k] + x0) + c] +
                  wx * this->Radiance[3 * (base[k] + x1) + c]);
            }
            out[c] = value;
          }
        }
        if (this->MediumRef)
        {
          // S_1 = albedo p E T (the source radiance J_1 / sigma_t), light by
          // light along the row: the phase function first, in a loop the
          // compiler vectorizes (ReconstructionDirect.cxx is built without
          // errno from square roots), then the sums.
          const Vec3 eye = this->Eye - rowOffset;
          const std::size_t first = row * dims[0];
          float* out = &this->DirectRadiance[3 * first];
          for (std::size_t l = 0; l < lights; ++l)
          {
            const float* a = &this->Arrivals[(first * lights + l) * ArrivalFloats];
            const std::size_t stride = lights * ArrivalFloats;
            for (int x = 0; x < dims[0]; ++x)
            {
              const float* ax = a + x * stride;
              const float ex = eye.x - offsetX[0][x], ey = eye.y - offsetX[1][x],
                          ez = eye.z - offsetX[2][x];
              const float dot = ax[3] * ex + ax[4] * ey + ax[5] * ez;
              phaseOf[x] = phase.Evaluate(dot / std::sqrt(ex * ex + ey * ey + ez * ez));
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
          float* out = &this->DirectRadiance[3 * t];
          const Vec3 toEye = Normalize(this->Eye - (axes[0].Offset[x] + rowOffset));
          for (std::size_t l = 0; l < lights; ++l)
          {
            const float* a = &this->Arrivals[(t * lights + l) * ArrivalFloats];
            if (a[0] == 0.f && a[1] == 0.f && a[2] == 0.f)
            {
              continue;
            }
            const Vec3 direction(a[3], a[4], a[5]);
            const std::int32_t triangle =
              this->DirectTriangles.empty() ? -1 : this->DirectTriangles[t];
            Material coloured; // where the surface's reflectance varies over it
            const Material& m = triangle < 0 ? this->SurfaceRef->Mat
              : this->SurfaceRef->VertexReflectance.empty()
              ? this->SurfaceRef->MaterialOf(triangle)
              : (coloured = this->SurfaceRef->MaterialAt(triangle, axes[0].Offset[x] + rowOffset));
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

void ObjectRadiance::AddDirectToDirectional(int order)
{
  // Each output texel's S_1 lobe, albedo E T p(w_l, .), projected as the
  // particles' light is (coefficient Y_k(w_l) per unit of S) and averaged
  // over the output texels whose centres fall in each voxel.
  const std::size_t lights = this->Direct->NumberOfLights();
  const std::size_t texels = this->Arrivals.size() / (lights * ArrivalFloats);
  const int nk = ShCoefficients(order);
  const std::size_t voxels = this->Texels();
  std::vector<double> sums(voxels * nk * 3, 0.0);
  std::vector<std::size_t> members(voxels, 0);
  auto voxelOf = [&](std::size_t t)
  {
    const Vec3 q = TexelCentre(t, this->DirectDims);
    std::size_t v = 0;
    for (int a = 2; a >= 0; --a)
    {
      const int i = std::clamp(static_cast<int>(q[a] * static_cast<float>(this->Resolution[a])), 0,
        this->Resolution[a] - 1);
      v = v * this->Resolution[a] + i;
    }
    return v;
  };
  // The remainder of the phase function, per unit of the reduced extinction.
  const Vec3 scale =
    this->MediumAlbedo * (1.f - this->Peaks[1].Forward) / this->ExtinctionFactors[1];
  float y[ShCoefficients(MaxShOrder)];
  for (std::size_t t = 0; t < texels; ++t)
  {
    const std::size_t v = voxelOf(t);
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
  }
  for (std::size_t v = 0; v < voxels; ++v)
  {
    if (members[v] == 0)
    {
      continue;
    }
    for (std::size_t j = 0; j < static_cast<std::size_t>(nk) * 3; ++j)
    {
      this->Directional[v * nk * 3 + j] +=
        static_cast<float>(sums[v * nk * 3 + j] / static_cast<double>(members[v]));
    }
  }
}

} // namespace brume
