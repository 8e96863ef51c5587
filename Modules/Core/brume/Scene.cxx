// SPDX-License-Identifier: BSD-3-Clause
#include "brume/Scene.h"

#include <cmath>
#include <sstream>

namespace brume
{

namespace
{
bool NonNegativeFinite(const Vec3& v)
{
  return IsFinite(v) && MinComponent(v) >= 0.f;
}

// A thin quad (two triangles) with corners a, b, c, d in counter-clockwise order
// seen from the side its normal points to.
Surface MakeQuad(const std::string& name, const Vec3& a, const Vec3& b, const Vec3& c,
  const Vec3& d, const Vec3& reflectance, const Vec3& emission = Vec3(0.f))
{
  Surface s;
  s.Name = name;
  s.Vertices = { a, b, c, d };
  s.Triangles = { { 0, 1, 2 }, { 0, 2, 3 } };
  s.Reflectance = reflectance;
  s.Emission = emission;
  return s;
}
}

double Surface::Area() const
{
  double area = 0.0;
  for (const auto& tri : this->Triangles)
  {
    const Vec3 e1 = this->Vertices[tri[1]] - this->Vertices[tri[0]];
    const Vec3 e2 = this->Vertices[tri[2]] - this->Vertices[tri[0]];
    area += 0.5 * Length(Cross(e1, e2));
  }
  return area;
}

bool Surface::ComputePlanarFrame(PlanarFrame& frame, float tolerance) const
{
  // Normal: area-weighted sum of triangle normals.
  Vec3 n(0.f);
  for (const auto& tri : this->Triangles)
  {
    n += Cross(this->Vertices[tri[1]] - this->Vertices[tri[0]],
      this->Vertices[tri[2]] - this->Vertices[tri[0]]);
  }
  if (this->Triangles.empty() || !(Length(n) > 0.f))
  {
    return false;
  }
  n = Normalize(n);
  const Vec3 p0 = this->Vertices[this->Triangles[0][0]];
  // In-plane axes: the first edge direction and its perpendicular.
  Vec3 u = this->Vertices[this->Triangles[0][1]] - p0;
  u = Normalize(u - n * Dot(u, n));
  const Vec3 v = Cross(n, u);
  float smin = 1e30f, smax = -1e30f, tmin = 1e30f, tmax = -1e30f, extent = 0.f;
  for (const auto& tri : this->Triangles)
  {
    for (const auto idx : tri)
    {
      const Vec3 d = this->Vertices[idx] - p0;
      const float s = Dot(d, u), t = Dot(d, v);
      smin = std::min(smin, s);
      smax = std::max(smax, s);
      tmin = std::min(tmin, t);
      tmax = std::max(tmax, t);
      extent = std::max(extent, Length(d));
      if (std::abs(Dot(d, n)) > tolerance * std::max(1.f, extent))
      {
        return false;
      }
    }
  }
  if (!(smax > smin) || !(tmax > tmin))
  {
    return false;
  }
  frame.Origin = p0 + u * smin + v * tmin;
  frame.U = u * (smax - smin);
  frame.V = v * (tmax - tmin);
  frame.Normal = n;
  return true;
}

Vec3 Medium::Albedo() const
{
  const Vec3 st = this->SigmaT();
  Vec3 a;
  for (int c = 0; c < 3; ++c)
  {
    a[c] = st[c] > 0.f ? this->SigmaS[c] / st[c] : 0.f;
  }
  return a;
}

std::string Scene::Validate() const
{
  std::ostringstream err;
  if (this->Surfaces.empty() && this->Media.empty())
  {
    return "the scene is empty: it has no surfaces and no media";
  }
  if (this->NumberOfObjects() > 65535)
  {
    return "the scene has more than 65535 objects";
  }
  bool hasEmitter = false;
  for (const auto& s : this->Surfaces)
  {
    if (s.Triangles.empty())
    {
      err << "surface '" << s.Name << "' has no triangles";
      return err.str();
    }
    for (const auto& tri : s.Triangles)
    {
      for (const auto idx : tri)
      {
        if (idx >= s.Vertices.size())
        {
          err << "surface '" << s.Name << "' has a triangle index out of range";
          return err.str();
        }
      }
    }
    for (const auto& v : s.Vertices)
    {
      if (!IsFinite(v))
      {
        err << "surface '" << s.Name << "' has a non-finite vertex";
        return err.str();
      }
    }
    if (!(s.Area() > 0.0))
    {
      err << "surface '" << s.Name << "' is degenerate (zero area)";
      return err.str();
    }
    if (!NonNegativeFinite(s.Reflectance) || MaxComponent(s.Reflectance) > 1.f)
    {
      err << "surface '" << s.Name << "' has a reflectance outside [0, 1]";
      return err.str();
    }
    if (!NonNegativeFinite(s.Emission))
    {
      err << "surface '" << s.Name << "' has a negative or non-finite emission";
      return err.str();
    }
    hasEmitter = hasEmitter || s.IsEmitter();
  }
  for (const auto& m : this->Media)
  {
    if (!NonNegativeFinite(m.SigmaA) || !NonNegativeFinite(m.SigmaS))
    {
      err << "medium '" << m.Name << "' has a negative or non-finite sigma_a or sigma_s";
      return err.str();
    }
    if (!(std::abs(m.G) < 1.f))
    {
      err << "medium '" << m.Name << "' has |g| >= 1 (g = " << m.G << ")";
      return err.str();
    }
    if (!IsFinite(m.Bounds.lower) || !IsFinite(m.Bounds.upper) ||
      !(MinComponent(m.Bounds.Extent()) > 0.f))
    {
      err << "medium '" << m.Name << "' has an empty or non-finite box";
      return err.str();
    }
    const Vec3 st = m.SigmaT();
    if (MaxComponent(st) - MinComponent(st) > 1e-6f * MaxComponent(st))
    {
      err << "medium '" << m.Name
          << "' has a colour-dependent extinction sigma_a + sigma_s, which this "
             "tracer does not support yet (the albedo may be coloured)";
      return err.str();
    }
  }
  if (!hasEmitter)
  {
    return "the scene has no light: no surface has a positive emission";
  }
  return {};
}

Scene MakeDefaultScene()
{
  Scene scene;
  const Vec3 white(0.75f), red(0.75f, 0.25f, 0.25f), green(0.25f, 0.75f, 0.25f);
  // Walls of the box [-1, 1]^3 with inward normals (counter-clockwise seen from inside).
  scene.Surfaces.push_back(
    MakeQuad("floor", { -1, -1, -1 }, { -1, -1, 1 }, { 1, -1, 1 }, { 1, -1, -1 }, white));
  scene.Surfaces.push_back(
    MakeQuad("ceiling", { -1, 1, -1 }, { 1, 1, -1 }, { 1, 1, 1 }, { -1, 1, 1 }, white));
  scene.Surfaces.push_back(
    MakeQuad("back", { -1, -1, -1 }, { 1, -1, -1 }, { 1, 1, -1 }, { -1, 1, -1 }, white));
  scene.Surfaces.push_back(
    MakeQuad("left", { -1, -1, -1 }, { -1, 1, -1 }, { -1, 1, 1 }, { -1, -1, 1 }, red));
  scene.Surfaces.push_back(
    MakeQuad("right", { 1, -1, -1 }, { 1, -1, 1 }, { 1, 1, 1 }, { 1, 1, -1 }, green));
  // One-sided square emitter facing -y, black itself.
  scene.Surfaces.push_back(MakeQuad("light", { -0.25f, 0.99f, -0.25f }, { 0.25f, 0.99f, -0.25f },
    { 0.25f, 0.99f, 0.25f }, { -0.25f, 0.99f, 0.25f }, Vec3(0.f), Vec3(15.f)));

  Medium fog;
  fog.Name = "fog";
  fog.Bounds = { { -0.5f, -0.5f, -0.5f }, { 0.5f, 0.5f, 0.5f } };
  fog.SigmaS = Vec3(1.0f);
  fog.SigmaA = Vec3(0.1f);
  fog.G = 0.7f;
  scene.Media.push_back(fog);
  return scene;
}

} // namespace brume
