// SPDX-License-Identifier: BSD-3-Clause
#include "brume/ShadowSweep.h"

#include "brume/DirectLight.h"

#include <algorithm>
#include <cmath>

namespace brume
{

namespace
{
// Past this optical depth in every channel a ray carries no light on (as
// DirectLight's own march).
constexpr double OpaqueDepth = 30.0;
}

bool ShadowSweep::Plan(
  const DirectLight& light, std::size_t k, const Box& box, const std::array<int, 3>& dims)
{
  const brume::Light& l = light.GetScene().Lights[k];
  this->Direct = nullptr;
  this->LightIndex = k;
  this->GridBox = box;
  this->Dims = dims;
  this->Directional = l.Type == LightType::Directional;
  const Vec3 extent = box.Extent();
  Vec3 pitch;
  for (int a = 0; a < 3; ++a)
  {
    pitch[a] = extent[a] / static_cast<float>(std::max(dims[a], 1));
  }
  auto plane = [&](int a, int i)
  { return box.lower[a] + (static_cast<float>(i) + 0.5f) * pitch[a]; };
  // The planes are normal to the axis the light travels most along: for a
  // point or spot light, one whose planes all lie on one side of it.
  int axis = -1;
  if (this->Directional)
  {
    this->Travel = l.Direction;
    axis = 0;
    for (int a = 1; a < 3; ++a)
    {
      axis = std::abs(l.Direction[a]) > std::abs(l.Direction[axis]) ? a : axis;
    }
    if (!(std::abs(l.Direction[axis]) > 0.f))
    {
      return false;
    }
    this->Ascending = l.Direction[axis] > 0.f;
  }
  else
  {
    this->Source = l.Position;
    const Vec3 centre = (box.lower + box.upper) * 0.5f;
    float best = 0.f;
    for (int a = 0; a < 3; ++a)
    {
      // Half a texel beyond the outermost planes, so that no plane passes
      // through the light.
      const float first = plane(a, 0) - 0.5f * pitch[a];
      const float last = plane(a, dims[a] - 1) + 0.5f * pitch[a];
      const float along = std::abs(centre[a] - l.Position[a]);
      if ((l.Position[a] < first || l.Position[a] > last) && along > best)
      {
        best = along;
        axis = a;
      }
    }
    if (axis < 0)
    {
      return false;
    }
    this->Ascending = l.Position[axis] < box.lower[axis];
  }
  if (dims[axis] < 2)
  {
    return false;
  }
  this->Axis = axis;
  this->Lateral[0] = (axis + 1) % 3;
  this->Lateral[1] = (axis + 2) % 3;
  const int n = dims[axis];
  this->PlaneAt.resize(static_cast<std::size_t>(n));
  for (int p = 0; p < n; ++p)
  {
    this->PlaneAt[static_cast<std::size_t>(p)] = plane(axis, p);
  }
  // Each plane's map from a texel's lateral coordinate to the ray's in the
  // reference plane: the first plane the light meets for parallel rays, the
  // last for rays from a point (there they lie farthest apart, at Pitch).
  const float reference = this->PlaneAt[this->Ascending ? 0 : static_cast<std::size_t>(n - 1)];
  const float farthest = this->PlaneAt[this->Ascending ? static_cast<std::size_t>(n - 1) : 0];
  double rays[2] = { 0.0, 0.0 };
  for (int s = 0; s < 2; ++s)
  {
    const int b = this->Lateral[s];
    this->A[s].resize(static_cast<std::size_t>(n));
    this->B[s].resize(static_cast<std::size_t>(n));
    float lo = 0.f, hi = 0.f;
    for (int p = 0; p < n; ++p)
    {
      const float z = this->PlaneAt[static_cast<std::size_t>(p)];
      float a = 1.f, shift = 0.f;
      if (this->Directional)
      {
        shift = -l.Direction[b] / l.Direction[axis] * (z - reference);
      }
      else
      {
        const float t = (z - l.Position[axis]) / (farthest - l.Position[axis]);
        a = 1.f / t;
        shift = l.Position[b] * (1.f - a);
      }
      this->A[s][static_cast<std::size_t>(p)] = a;
      this->B[s][static_cast<std::size_t>(p)] = shift;
      const float first = a * plane(b, 0) + shift, last = a * plane(b, dims[b] - 1) + shift;
      lo = p == 0 ? first : std::min(lo, first);
      hi = p == 0 ? last : std::max(hi, last);
    }
    this->Pitch[s] = pitch[b] / static_cast<float>(RaysPerTexel);
    this->Low[s] = lo;
    rays[s] = std::floor((static_cast<double>(hi) - lo) / this->Pitch[s]) + 2.0;
  }
  // Rays from a lamp just beyond the first plane spread over many times
  // what the far plane needs: past MaxRayFactor times a plane's, none.
  const double onePlane = static_cast<double>(RaysPerTexel) * RaysPerTexel *
    dims[this->Lateral[0]] * dims[this->Lateral[1]];
  if (!(rays[0] * rays[1] <= MaxRayFactor * onePlane))
  {
    return false;
  }
  for (int s = 0; s < 2; ++s)
  {
    this->Rays[s] = static_cast<std::size_t>(rays[s]);
  }
  this->Direct = &light;
  return true;
}

void ShadowSweep::RayCoordinates(int plane, float x, float y, float& u, float& v) const
{
  const std::size_t p = static_cast<std::size_t>(plane);
  u = (this->A[0][p] * x + this->B[0][p] - this->Low[0]) / this->Pitch[0];
  v = (this->A[1][p] * y + this->B[1][p] - this->Low[1]) / this->Pitch[1];
}

Vec3 ShadowSweep::RayPoint(int plane, std::size_t i, std::size_t j) const
{
  const std::size_t p = static_cast<std::size_t>(plane);
  Vec3 point;
  point[this->Axis] = this->PlaneAt[p];
  const float u = this->Low[0] + static_cast<float>(i) * this->Pitch[0];
  const float v = this->Low[1] + static_cast<float>(j) * this->Pitch[1];
  point[this->Lateral[0]] = (u - this->B[0][p]) / this->A[0][p];
  point[this->Lateral[1]] = (v - this->B[1][p]) / this->A[1][p];
  return point;
}

double ShadowSweep::MarchLength() const
{
  const int n = this->Dims[this->Axis];
  const int first = this->Ascending ? 0 : n - 1, last = this->Ascending ? n - 1 : 0;
  double length = 0.0;
  for (std::size_t j = 0; j < this->Rays[1]; ++j)
    for (std::size_t i = 0; i < this->Rays[0]; ++i)
    {
      const Vec3 a = this->RayPoint(first, i, j), b = this->RayPoint(last, i, j);
      const float span = Length(b - a);
      float t0 = 0.f, t1 = span;
      if (span > 0.f && this->GridBox.Intersect(a, (b - a) / span, t0, t1))
      {
        length += t1 - t0;
      }
    }
  return length;
}

std::vector<float> ShadowSweep::Depths(
  const std::vector<std::uint8_t>& wanted, const ParallelFor& parallelFor) const
{
  const std::array<int, 3>& dims = this->Dims;
  const std::size_t texels = static_cast<std::size_t>(dims[0]) * dims[1] * dims[2];
  std::vector<float> depths(3 * texels, 0.f);
  if (!this->Direct)
  {
    return depths;
  }
  const brume::Light& light = this->Direct->GetScene().Lights[this->LightIndex];
  const std::size_t nu = this->Rays[0], nv = this->Rays[1];
  std::vector<double> carried(3 * nu * nv, 0.0);
  const int n = dims[this->Axis];
  const Vec3 extent = this->GridBox.Extent();
  const float pitch[2] = { extent[this->Lateral[0]] / static_cast<float>(dims[this->Lateral[0]]),
    extent[this->Lateral[1]] / static_cast<float>(dims[this->Lateral[1]]) };
  const std::size_t strides[3] = { 1, static_cast<std::size_t>(dims[0]),
    static_cast<std::size_t>(dims[0]) * dims[1] };
  for (int s = 0; s < n; ++s)
  {
    const int plane = this->Ascending ? s : n - 1 - s;
    const int previous = this->Ascending ? s - 1 : n - s;
    // Every ray on to this plane: from the light to the first, then from
    // the plane before.
    parallelFor(0, nv,
      [&](std::size_t begin, std::size_t end)
      {
        for (std::size_t j = begin; j < end; ++j)
          for (std::size_t i = 0; i < nu; ++i)
          {
            double* depth = &carried[3 * (j * nu + i)];
            if (std::min({ depth[0], depth[1], depth[2] }) > OpaqueDepth)
            {
              continue;
            }
            const Vec3 p = this->RayPoint(plane, i, j);
            Vec3 from;
            if (s > 0)
            {
              from = this->RayPoint(previous, i, j);
            }
            else if (this->Directional)
            {
              const float distance = Dot(p - light.BeamCenter, this->Travel);
              if (!(distance > 0.f))
              {
                continue;
              }
              from = p - this->Travel * distance;
            }
            else
            {
              from = this->Source;
            }
            const Vec3 d = from - p;
            const float length = Length(d);
            if (length > 0.f)
            {
              this->Direct->AddOpticalDepth(p, d / length, length, depth);
            }
          }
      });
    // The plane's texels from the four rays around each.
    const int ny = dims[this->Lateral[1]], nx = dims[this->Lateral[0]];
    parallelFor(0, static_cast<std::size_t>(ny),
      [&](std::size_t begin, std::size_t end)
      {
        for (std::size_t y = begin; y < end; ++y)
          for (int x = 0; x < nx; ++x)
          {
            const std::size_t t = static_cast<std::size_t>(plane) * strides[this->Axis] +
              static_cast<std::size_t>(x) * strides[this->Lateral[0]] +
              y * strides[this->Lateral[1]];
            if (!wanted.empty() && !wanted[t])
            {
              continue;
            }
            const float cx =
              this->GridBox.lower[this->Lateral[0]] + (static_cast<float>(x) + 0.5f) * pitch[0];
            const float cy =
              this->GridBox.lower[this->Lateral[1]] + (static_cast<float>(y) + 0.5f) * pitch[1];
            float u, v;
            this->RayCoordinates(plane, cx, cy, u, v);
            const float fu = std::clamp(u, 0.f, static_cast<float>(nu - 1));
            const float fv = std::clamp(v, 0.f, static_cast<float>(nv - 1));
            const std::size_t i0 = std::min(static_cast<std::size_t>(fu), nu - 2);
            const std::size_t j0 = std::min(static_cast<std::size_t>(fv), nv - 2);
            const double wu = fu - static_cast<float>(i0), wv = fv - static_cast<float>(j0);
            const double* d00 = &carried[3 * (j0 * nu + i0)];
            const double* d10 = d00 + 3;
            const double* d01 = d00 + 3 * nu;
            const double* d11 = d01 + 3;
            for (int c = 0; c < 3; ++c)
            {
              depths[3 * t + static_cast<std::size_t>(c)] =
                static_cast<float>((1.0 - wv) * ((1.0 - wu) * d00[c] + wu * d10[c]) +
                  wv * ((1.0 - wu) * d01[c] + wu * d11[c]));
            }
          }
      });
  }
  return depths;
}

} // namespace brume
