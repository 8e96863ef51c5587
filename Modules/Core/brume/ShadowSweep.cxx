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
  // The runs of planes: one for parallel rays, its rays Pitch apart on the
  // first plane the light meets; for rays from a point, each run's planes
  // from one to the farthest at most RunSpread times as far from the light, its rays
  // Pitch apart on the farthest (there they lie farthest apart).
  this->Runs.clear();
  auto at = [&](int step)
  { return this->PlaneAt[static_cast<std::size_t>(this->PlaneOfStep(step))]; };
  if (this->Directional)
  {
    Run r;
    r.First = 0;
    r.Last = n - 1;
    r.Reference = at(0);
    this->Runs.push_back(r);
  }
  else
  {
    const float source = l.Position[axis];
    for (int first = 0; first < n;)
    {
      int last = first;
      while (
        last + 1 < n && std::abs(at(last + 1) - source) <= RunSpread * std::abs(at(first) - source))
      {
        ++last;
      }
      Run r;
      r.First = first;
      r.Last = last;
      r.Reference = at(last);
      this->Runs.push_back(r);
      first = last + 1;
    }
  }
  // Each run's rays cover its planes' texels and, but for the last run,
  // where the next run's rays cross its last plane (their depths start
  // there): planned from the farthest run back.
  const double onePlane = static_cast<double>(RaysPerTexel) * RaysPerTexel *
    dims[this->Lateral[0]] * dims[this->Lateral[1]];
  for (std::size_t run = this->Runs.size(); run-- > 0;)
  {
    Run& r = this->Runs[run];
    double rays[2] = { 0.0, 0.0 };
    for (int s = 0; s < 2; ++s)
    {
      const int b = this->Lateral[s];
      float lo = 0.f, hi = 0.f;
      for (int step = r.First; step <= r.Last; ++step)
      {
        float a = 1.f, shift = 0.f;
        this->Map(r, s, at(step), a, shift);
        const float first = a * plane(b, 0) + shift, last = a * plane(b, dims[b] - 1) + shift;
        lo = step == r.First ? first : std::min(lo, first);
        hi = step == r.First ? last : std::max(hi, last);
      }
      if (run + 1 < this->Runs.size())
      {
        // The next run's outermost rays on this run's last plane, this
        // run's reference.
        const Run& next = this->Runs[run + 1];
        float a = 1.f, shift = 0.f;
        this->Map(next, s, at(r.Last), a, shift);
        const float u0 = next.Low[s];
        const float u1 = next.Low[s] + static_cast<float>(next.Rays[s] - 1) * next.Pitch[s];
        lo = std::min(lo, (u0 - shift) / a);
        hi = std::max(hi, (u1 - shift) / a);
      }
      r.Pitch[s] = pitch[b] / static_cast<float>(RaysPerTexel);
      r.Low[s] = lo;
      rays[s] = std::floor((static_cast<double>(hi) - lo) / r.Pitch[s]) + 2.0;
    }
    // Rays from a lamp just beyond a run's nearest plane would spread over
    // many times what its farthest needs: past MaxRayFactor times a
    // plane's, none.
    if (!(rays[0] * rays[1] <= MaxRayFactor * onePlane))
    {
      this->Runs.clear();
      return false;
    }
    for (int s = 0; s < 2; ++s)
    {
      r.Rays[s] = static_cast<std::size_t>(rays[s]);
    }
  }
  this->Direct = &light;
  return true;
}

void ShadowSweep::Map(const Run& r, int s, float z, float& a, float& b) const
{
  const int lateral = this->Lateral[s];
  if (this->Directional)
  {
    a = 1.f;
    b = -this->Travel[lateral] / this->Travel[this->Axis] * (z - r.Reference);
  }
  else
  {
    const float t = (z - this->Source[this->Axis]) / (r.Reference - this->Source[this->Axis]);
    a = 1.f / t;
    b = this->Source[lateral] * (1.f - a);
  }
}

ShadowSweep::PlaneMap ShadowSweep::MapOf(const Run& r, int step) const
{
  PlaneMap m;
  m.Z = this->PlaneAt[static_cast<std::size_t>(this->PlaneOfStep(step))];
  this->Map(r, 0, m.Z, m.A[0], m.B[0]);
  this->Map(r, 1, m.Z, m.A[1], m.B[1]);
  return m;
}

void ShadowSweep::RayCoordinates(
  const Run& r, const PlaneMap& m, float x, float y, float& u, float& v) const
{
  u = (m.A[0] * x + m.B[0] - r.Low[0]) / r.Pitch[0];
  v = (m.A[1] * y + m.B[1] - r.Low[1]) / r.Pitch[1];
}

Vec3 ShadowSweep::RayPoint(const Run& r, const PlaneMap& m, std::size_t i, std::size_t j) const
{
  Vec3 point;
  point[this->Axis] = m.Z;
  const float u = r.Low[0] + static_cast<float>(i) * r.Pitch[0];
  const float v = r.Low[1] + static_cast<float>(j) * r.Pitch[1];
  point[this->Lateral[0]] = (u - m.B[0]) / m.A[0];
  point[this->Lateral[1]] = (v - m.B[1]) / m.A[1];
  return point;
}

double ShadowSweep::MarchLength() const
{
  double length = 0.0;
  for (std::size_t k = 0; k < this->Runs.size(); ++k)
  {
    const Run& r = this->Runs[k];
    // From the plane before the run's first (its rays start there), or the first.
    const PlaneMap first = this->MapOf(r, k == 0 ? r.First : r.First - 1);
    const PlaneMap last = this->MapOf(r, r.Last);
    for (std::size_t j = 0; j < r.Rays[1]; ++j)
      for (std::size_t i = 0; i < r.Rays[0]; ++i)
      {
        const Vec3 a = this->RayPoint(r, first, i, j), b = this->RayPoint(r, last, i, j);
        const float span = Length(b - a);
        float t0 = 0.f, t1 = span;
        if (span > 0.f && this->GridBox.Intersect(a, (b - a) / span, t0, t1))
        {
          length += t1 - t0;
        }
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
  const Vec3 extent = this->GridBox.Extent();
  const float pitch[2] = { extent[this->Lateral[0]] / static_cast<float>(dims[this->Lateral[0]]),
    extent[this->Lateral[1]] / static_cast<float>(dims[this->Lateral[1]]) };
  const std::size_t strides[3] = { 1, static_cast<std::size_t>(dims[0]),
    static_cast<std::size_t>(dims[0]) * dims[1] };
  // The depths a run's rays carry, interpolated bilinearly at (u, v) of its rays.
  auto interpolate =
    [](const std::vector<double>& carried, const Run& r, float u, float v, double* out)
  {
    const std::size_t nu = r.Rays[0], nv = r.Rays[1];
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
      out[c] =
        (1.0 - wv) * ((1.0 - wu) * d00[c] + wu * d10[c]) + wv * ((1.0 - wu) * d01[c] + wu * d11[c]);
    }
  };
  std::vector<double> carried, before;
  for (std::size_t k = 0; k < this->Runs.size(); ++k)
  {
    const Run& r = this->Runs[k];
    const std::size_t nu = r.Rays[0], nv = r.Rays[1];
    before.swap(carried);
    carried.assign(3 * nu * nv, 0.0);
    for (int s = r.First; s <= r.Last; ++s)
    {
      const int plane = this->PlaneOfStep(s);
      const PlaneMap here = this->MapOf(r, s);
      const PlaneMap back = s > 0 ? this->MapOf(r, s - 1) : here;
      const PlaneMap backBefore =
        s == r.First && k > 0 ? this->MapOf(this->Runs[k - 1], s - 1) : here;
      // Every ray on to this plane: from the light to the first, then from
      // the plane before (a run after the first starts with the depths of
      // the run before where its rays cross that plane).
      parallelFor(0, nv,
        [&](std::size_t begin, std::size_t end)
        {
          for (std::size_t j = begin; j < end; ++j)
            for (std::size_t i = 0; i < nu; ++i)
            {
              double* depth = &carried[3 * (j * nu + i)];
              if (s == r.First && k > 0)
              {
                const Vec3 q = this->RayPoint(r, back, i, j);
                float u, v;
                this->RayCoordinates(
                  this->Runs[k - 1], backBefore, q[this->Lateral[0]], q[this->Lateral[1]], u, v);
                interpolate(before, this->Runs[k - 1], u, v, depth);
              }
              if (std::min({ depth[0], depth[1], depth[2] }) > OpaqueDepth)
              {
                continue;
              }
              const Vec3 p = this->RayPoint(r, here, i, j);
              Vec3 from;
              if (s > 0)
              {
                from = this->RayPoint(r, back, i, j);
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
              this->RayCoordinates(r, here, cx, cy, u, v);
              double depth[3];
              interpolate(carried, r, u, v, depth);
              for (int c = 0; c < 3; ++c)
              {
                depths[3 * t + static_cast<std::size_t>(c)] = static_cast<float>(depth[c]);
              }
            }
        });
    }
  }
  return depths;
}

} // namespace brume
