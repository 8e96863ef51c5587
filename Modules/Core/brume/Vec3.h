// SPDX-License-Identifier: BSD-3-Clause
// Small fixed-size vector used by the physics core.
#ifndef brume_Vec3_h
#define brume_Vec3_h

#include <algorithm>
#include <cmath>

namespace brume
{

struct Vec3
{
  float x = 0.f, y = 0.f, z = 0.f;

  constexpr Vec3() = default;
  constexpr Vec3(float a, float b, float c)
    : x(a)
    , y(b)
    , z(c)
  {
  }
  constexpr explicit Vec3(float a)
    : x(a)
    , y(a)
    , z(a)
  {
  }

  float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  float& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }

  Vec3 operator+(const Vec3& o) const { return { x + o.x, y + o.y, z + o.z }; }
  Vec3 operator-(const Vec3& o) const { return { x - o.x, y - o.y, z - o.z }; }
  Vec3 operator*(const Vec3& o) const { return { x * o.x, y * o.y, z * o.z }; }
  Vec3 operator/(const Vec3& o) const { return { x / o.x, y / o.y, z / o.z }; }
  Vec3 operator*(float s) const { return { x * s, y * s, z * s }; }
  Vec3 operator/(float s) const { return { x / s, y / s, z / s }; }
  Vec3 operator-() const { return { -x, -y, -z }; }
  Vec3& operator+=(const Vec3& o)
  {
    x += o.x;
    y += o.y;
    z += o.z;
    return *this;
  }
  Vec3& operator*=(const Vec3& o)
  {
    x *= o.x;
    y *= o.y;
    z *= o.z;
    return *this;
  }
  Vec3& operator*=(float s)
  {
    x *= s;
    y *= s;
    z *= s;
    return *this;
  }
};

inline Vec3 operator*(float s, const Vec3& v)
{
  return v * s;
}
inline float Dot(const Vec3& a, const Vec3& b)
{
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline Vec3 Cross(const Vec3& a, const Vec3& b)
{
  return { a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x };
}
inline float Length(const Vec3& v)
{
  return std::sqrt(Dot(v, v));
}
inline Vec3 Normalize(const Vec3& v)
{
  return v / Length(v);
}
inline float MaxComponent(const Vec3& v)
{
  return std::max(v.x, std::max(v.y, v.z));
}
inline float MinComponent(const Vec3& v)
{
  return std::min(v.x, std::min(v.y, v.z));
}
inline float Average(const Vec3& v)
{
  return (v.x + v.y + v.z) / 3.f;
}
inline bool IsFinite(const Vec3& v)
{
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

/// Orthonormal basis around a unit vector n (Duff et al., JCGT 2017).
struct Frame
{
  Vec3 s, t, n;
  explicit Frame(const Vec3& normal)
    : n(normal)
  {
    const float sign = std::copysign(1.f, n.z);
    const float a = -1.f / (sign + n.z);
    const float b = n.x * n.y * a;
    s = { 1.f + sign * n.x * n.x * a, sign * b, -sign * n.x };
    t = { b, sign + n.y * n.y * a, -n.y };
  }
  Vec3 ToWorld(const Vec3& v) const { return s * v.x + t * v.y + n * v.z; }
  Vec3 ToLocal(const Vec3& v) const { return { Dot(v, s), Dot(v, t), Dot(v, n) }; }
};

/// Axis-aligned box.
struct Box
{
  Vec3 lower, upper;

  Vec3 Extent() const { return upper - lower; }
  float Volume() const
  {
    const Vec3 e = Extent();
    return e.x * e.y * e.z;
  }
  bool Contains(const Vec3& p) const
  {
    return p.x >= lower.x && p.x <= upper.x && p.y >= lower.y && p.y <= upper.y && p.z >= lower.z &&
      p.z <= upper.z;
  }
  /// Parametric interval [t0, t1] of the ray o + t d inside the box; false if none.
  bool Intersect(const Vec3& o, const Vec3& d, float& t0, float& t1) const
  {
    float lo = 0.f, hi = t1;
    for (int a = 0; a < 3; ++a)
    {
      const float inv = 1.f / d[a];
      float tn = (lower[a] - o[a]) * inv;
      float tf = (upper[a] - o[a]) * inv;
      if (tn > tf)
      {
        std::swap(tn, tf);
      }
      // NaN-safe (d[a] == 0 with o on a slab plane): keep the current interval.
      lo = tn > lo ? tn : lo;
      hi = tf < hi ? tf : hi;
      if (lo > hi)
      {
        return false;
      }
    }
    t0 = lo;
    t1 = hi;
    return true;
  }
};

/// Linear interpolation between the centres of n cells over [0, 1], clamped
/// at the outer centres (as a texture's linear filtering with clamping): the
/// two cells and the weight of the second for the coordinate q.
struct CellCentreWeights
{
  int I0, I1;
  float W;
  CellCentreWeights(float q, int n)
  {
    const float x = q * static_cast<float>(n) - 0.5f;
    const float c = x < 0.f ? 0.f : (x > static_cast<float>(n - 1) ? static_cast<float>(n - 1) : x);
    this->I0 = static_cast<int>(c) < n - 1 ? static_cast<int>(c) : n - 1;
    this->I1 = this->I0 + 1 < n - 1 ? this->I0 + 1 : n - 1;
    this->W = c - static_cast<float>(this->I0);
  }
};

} // namespace brume

#endif
