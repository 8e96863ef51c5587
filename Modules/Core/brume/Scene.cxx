// SPDX-License-Identifier: BSD-3-Clause
#include "brume/Scene.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace brume
{

namespace
{
// A thin quad (two triangles) with corners a, b, c, d in counter-clockwise order
// seen from the side its normal points to.
Surface MakeQuad(const std::string& name, const Vec3& a, const Vec3& b, const Vec3& c,
  const Vec3& d, const Vec3& reflectance, const Vec3& emission = Vec3(0.f))
{
  Surface s;
  s.Name = name;
  s.Vertices = { a, b, c, d };
  s.Triangles = { { 0, 1, 2 }, { 0, 2, 3 } };
  s.Mat.Reflectance = reflectance;
  s.Mat.Emission = emission;
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

Material Surface::MaterialAt(std::size_t triangle, const Vec3& position) const
{
  Material m = this->MaterialOf(triangle);
  if (this->VertexReflectance.empty())
  {
    return m;
  }
  // Barycentric weights of the position's projection on the triangle,
  // clamped into it.
  const auto& tri = this->Triangles[triangle];
  const Vec3 a = this->Vertices[tri[0]];
  const Vec3 e1 = this->Vertices[tri[1]] - a, e2 = this->Vertices[tri[2]] - a, p = position - a;
  const float d00 = Dot(e1, e1), d01 = Dot(e1, e2), d11 = Dot(e2, e2);
  const float d20 = Dot(p, e1), d21 = Dot(p, e2);
  const float det = d00 * d11 - d01 * d01;
  float v = det > 0.f ? (d11 * d20 - d01 * d21) / det : 0.f;
  float w = det > 0.f ? (d00 * d21 - d01 * d20) / det : 0.f;
  v = std::clamp(v, 0.f, 1.f);
  w = std::clamp(w, 0.f, 1.f);
  if (v + w > 1.f)
  {
    const float sum = v + w;
    v /= sum;
    w /= sum;
  }
  m.Reflectance = this->VertexReflectance[tri[0]] * (1.f - v - w) +
    this->VertexReflectance[tri[1]] * v + this->VertexReflectance[tri[2]] * w;
  return m;
}

bool Surface::IsEmitter() const
{
  if (this->TriangleMaterials.empty())
  {
    return this->Mat.IsEmitter();
  }
  return std::any_of(this->TriangleMaterials.begin(), this->TriangleMaterials.end(),
    [](const Material& m) { return m.IsEmitter(); });
}

bool Surface::IsViewDependent() const
{
  if (this->TriangleMaterials.empty())
  {
    return this->Mat.IsViewDependent();
  }
  return std::any_of(this->TriangleMaterials.begin(), this->TriangleMaterials.end(),
    [](const Material& m) { return m.IsViewDependent(); });
}

std::string Scene::Validate() const
{
  std::ostringstream err;
  if (this->Surfaces.empty() && this->Media.empty())
  {
    return "the scene is empty: it has no surfaces and no media";
  }
  if (this->NumberOfObjects() + this->Lights.size() > MaxObjectsAndLights)
  {
    return "the scene has more than " + std::to_string(MaxObjectsAndLights) +
      " objects and lights";
  }
  bool hasEmitter = false;
  for (const auto& s : this->Surfaces)
  {
    if (s.Triangles.empty())
    {
      err << "surface '" << s.Name << "' has no triangles";
      return err.str();
    }
    if (!s.TriangleMaterials.empty() && s.TriangleMaterials.size() != s.Triangles.size())
    {
      err << "surface '" << s.Name << "' has " << s.TriangleMaterials.size()
          << " per-triangle materials for " << s.Triangles.size() << " triangles";
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
    if (!s.VertexReflectance.empty() && s.VertexReflectance.size() != s.Vertices.size())
    {
      err << "surface '" << s.Name << "' has " << s.VertexReflectance.size()
          << " vertex reflectances for " << s.Vertices.size() << " vertices";
      return err.str();
    }
    for (const Vec3& rho : s.VertexReflectance)
    {
      // The same bound as a material's, with the surface's own specular.
      Material m = s.Mat;
      m.Reflectance = rho;
      const std::string problem = m.Validate();
      if (!problem.empty())
      {
        err << "surface '" << s.Name << "' vertex reflectance " << problem;
        return err.str();
      }
    }
    for (std::size_t t = 0; t < (s.TriangleMaterials.empty() ? 1 : s.TriangleMaterials.size()); ++t)
    {
      const std::string problem = s.MaterialOf(t).Validate();
      if (!problem.empty())
      {
        err << "surface '" << s.Name << "' " << problem;
        return err.str();
      }
    }
    hasEmitter = hasEmitter || s.IsEmitter();
  }
  for (const auto& m : this->Media)
  {
    const std::string problem = m.Validate();
    if (!problem.empty())
    {
      err << "medium '" << m.Name << "' " << problem;
      return err.str();
    }
  }
  for (std::size_t k = 0; k < this->Lights.size(); ++k)
  {
    const std::string problem = this->Lights[k].Validate();
    if (!problem.empty())
    {
      err << "light '" << (this->Lights[k].Name.empty() ? std::to_string(k) : this->Lights[k].Name)
          << "' " << problem;
      return err.str();
    }
    hasEmitter = true;
  }
  if (!hasEmitter)
  {
    return "the scene has no light: no light source and no surface with a positive emission";
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
