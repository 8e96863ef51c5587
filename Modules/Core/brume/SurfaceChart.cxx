// SPDX-License-Identifier: BSD-3-Clause
#include "brume/SurfaceChart.h"

#include "brume/Histogram.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace brume
{

namespace
{
float UVArea(const std::array<float, 6>& uv)
{
  return 0.5f * std::abs((uv[2] - uv[0]) * (uv[5] - uv[1]) - (uv[4] - uv[0]) * (uv[3] - uv[1]));
}

// Area of the triangle `uv` inside the rectangle [u0, u1] x [v0, v1]
// (Sutherland-Hodgman clipping, then the shoelace formula).
double ClippedArea(const std::array<float, 6>& uv, double u0, double u1, double v0, double v1)
{
  struct P
  {
    double u, v;
  };
  // A triangle clipped by four half-planes keeps at most 7 vertices: fixed
  // arrays (a surface's every cell is clipped against every triangle over it).
  P a[8] = { { uv[0], uv[1] }, { uv[2], uv[3] }, { uv[4], uv[5] } }, b[8];
  P* poly = a;
  P* next = b;
  std::size_t size = 3;
  // Keep the side where f(p) >= 0 for each of the four edges.
  auto clip = [&](auto f)
  {
    std::size_t kept = 0;
    for (std::size_t k = 0; k < size; ++k)
    {
      const P& p = poly[k];
      const P& q = poly[(k + 1) % size];
      const double fp = f(p), fq = f(q);
      if (fp >= 0.0)
      {
        next[kept++] = p;
      }
      if ((fp >= 0.0) != (fq >= 0.0))
      {
        const double t = fp / (fp - fq);
        next[kept++] = { p.u + t * (q.u - p.u), p.v + t * (q.v - p.v) };
      }
    }
    std::swap(poly, next);
    size = kept;
  };
  clip([&](const P& p) { return p.u - u0; });
  clip([&](const P& p) { return u1 - p.u; });
  clip([&](const P& p) { return p.v - v0; });
  clip([&](const P& p) { return v1 - p.v; });
  double area = 0.0;
  for (std::size_t k = 0; k < size; ++k)
  {
    const P& p = poly[k];
    const P& q = poly[(k + 1) % size];
    area += p.u * q.v - q.u * p.v;
  }
  return 0.5 * std::abs(area);
}
}

SurfaceChart MakeChart(
  const Surface& surface, const std::vector<std::array<float, 2>>* vertexTextureCoordinates)
{
  SurfaceChart chart;
  const std::size_t triangles = surface.Triangles.size();
  chart.TriangleUV.resize(triangles);
  if (surface.ComputePlanarFrame(chart.Frame))
  {
    chart.Type = SurfaceChart::Kind::Planar;
    const float uu = Dot(chart.Frame.U, chart.Frame.U), vv = Dot(chart.Frame.V, chart.Frame.V);
    for (std::size_t t = 0; t < triangles; ++t)
    {
      for (int k = 0; k < 3; ++k)
      {
        const Vec3 d = surface.Vertices[surface.Triangles[t][k]] - chart.Frame.Origin;
        chart.TriangleUV[t][2 * k] = Dot(d, chart.Frame.U) / uu;
        chart.TriangleUV[t][2 * k + 1] = Dot(d, chart.Frame.V) / vv;
      }
    }
    chart.Width = Length(chart.Frame.U);
    chart.Height = Length(chart.Frame.V);
    return chart;
  }
  const float side = std::sqrt(static_cast<float>(surface.Area()));
  chart.Width = chart.Height = side;
  if (vertexTextureCoordinates && vertexTextureCoordinates->size() == surface.Vertices.size())
  {
    bool valid = true;
    for (std::size_t t = 0; t < triangles && valid; ++t)
    {
      for (int k = 0; k < 3; ++k)
      {
        const auto& tc = (*vertexTextureCoordinates)[surface.Triangles[t][k]];
        chart.TriangleUV[t][2 * k] = tc[0];
        chart.TriangleUV[t][2 * k + 1] = tc[1];
        valid = valid && std::isfinite(tc[0]) && std::isfinite(tc[1]) && tc[0] >= 0.f &&
          tc[0] <= 1.f && tc[1] >= 0.f && tc[1] <= 1.f;
      }
      valid = valid && UVArea(chart.TriangleUV[t]) > 0.f;
    }
    if (valid)
    {
      chart.Type = SurfaceChart::Kind::TextureCoordinates;
      return chart;
    }
  }
  // One square chart per triangle on a G x G grid; the triangle fills the
  // lower-left half, inside a margin (an affine map: constant area scale).
  chart.Type = SurfaceChart::Kind::Atlas;
  const int g = std::max(1, static_cast<int>(std::ceil(std::sqrt(static_cast<double>(triangles)))));
  const float cell = 1.f / static_cast<float>(g), margin = 0.1f * cell;
  for (std::size_t t = 0; t < triangles; ++t)
  {
    const float x0 = static_cast<float>(t % g) * cell, y0 = static_cast<float>(t / g) * cell;
    chart.TriangleUV[t] = { x0 + margin, y0 + margin, x0 + cell - margin, y0 + margin, x0 + margin,
      y0 + cell - margin };
  }
  chart.Width = chart.Height = side * std::sqrt(2.f) / (1.f - 2.f * 0.1f);
  return chart;
}

void AddChartAreas(const Surface& surface, const SurfaceChart& chart, Histogram& area)
{
  // World area of the surface inside each histogram cell: every triangle's
  // exact (u, v) overlap with the cell times its world/texture area ratio.
  const int nx = area.GetDimensions()[0], ny = area.GetDimensions()[1];
  for (std::size_t t = 0; t < surface.Triangles.size(); ++t)
  {
    const auto& uv = chart.TriangleUV[t];
    const auto& tri = surface.Triangles[t];
    const double world = 0.5 *
      Length(Cross(surface.Vertices[tri[1]] - surface.Vertices[tri[0]],
        surface.Vertices[tri[2]] - surface.Vertices[tri[0]]));
    const double texture = UVArea(uv);
    if (!(texture > 0.0))
    {
      continue;
    }
    const double scale = world / texture;
    const float umin = std::min({ uv[0], uv[2], uv[4] }), umax = std::max({ uv[0], uv[2], uv[4] });
    const float vmin = std::min({ uv[1], uv[3], uv[5] }), vmax = std::max({ uv[1], uv[3], uv[5] });
    const int i0 = std::max(0, static_cast<int>(std::floor(umin * nx)));
    const int i1 = std::min(nx - 1, static_cast<int>(std::floor(umax * nx)));
    const int j0 = std::max(0, static_cast<int>(std::floor(vmin * ny)));
    const int j1 = std::min(ny - 1, static_cast<int>(std::floor(vmax * ny)));
    for (int j = j0; j <= j1; ++j)
    {
      for (int i = i0; i <= i1; ++i)
      {
        const double a = scale *
          ClippedArea(uv, static_cast<double>(i) / nx, static_cast<double>(i + 1) / nx,
            static_cast<double>(j) / ny, static_cast<double>(j + 1) / ny);
        if (a > 0.0)
        {
          area.Add(area.Index(i, j, 0), &a);
        }
      }
    }
  }
}

} // namespace brume
