// SPDX-License-Identifier: BSD-3-Clause
// The scene as the physics core sees it: triangle surfaces with materials
// and optional emission, homogeneous or heterogeneous media, and lights.
#ifndef brume_Scene_h
#define brume_Scene_h

#include "brume/Light.h"
#include "brume/Material.h"
#include "brume/Medium.h"
#include "brume/Vec3.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace brume
{

/// A planar surface's texture placement: x = Origin + s*U + t*V, (s, t) in [0,1]^2.
struct PlanarFrame
{
  Vec3 Origin;
  Vec3 U;
  Vec3 V;
  Vec3 Normal;
  float Area() const { return Length(Cross(this->U, this->V)); }
};

struct Surface
{
  std::string Name;
  std::vector<Vec3> Vertices;
  std::vector<std::array<std::uint32_t, 3>> Triangles;
  /// The surface's material (Lambertian of reflectance 0.75 by default).
  Material Mat;
  /// Per-triangle materials; empty when every triangle uses Mat.
  std::vector<Material> TriangleMaterials;

  /// Per-vertex diffuse reflectance (a surface coloured by point scalars),
  /// interpolated linearly over each triangle in place of its material's
  /// Reflectance; empty when the materials' own apply.
  std::vector<Vec3> VertexReflectance;

  const Material& MaterialOf(std::size_t triangle) const
  {
    return this->TriangleMaterials.empty() ? this->Mat : this->TriangleMaterials[triangle];
  }
  /// The material at `position` on `triangle`: MaterialOf(triangle), its
  /// diffuse reflectance interpolated from VertexReflectance where given.
  Material MaterialAt(std::size_t triangle, const Vec3& position) const;
  bool IsEmitter() const;
  /// True when some triangle's reflected radiance depends on the view.
  bool IsViewDependent() const;
  double Area() const;
  /// Texture placement of a planar surface; false if the surface is not planar.
  bool ComputePlanarFrame(PlanarFrame& frame, float tolerance = 1e-4f) const;
};

struct Scene
{
  std::vector<Surface> Surfaces;
  std::vector<Medium> Media;
  /// Point, spot and directional lights (emissive surfaces are lights too).
  std::vector<Light> Lights;

  /// Object ids: surfaces first, then media.
  std::size_t NumberOfObjects() const { return this->Surfaces.size() + this->Media.size(); }
  /// Objects and lights together, at most: hits carry 16-bit ids.
  static constexpr std::size_t MaxObjectsAndLights = 65535;
  bool IsMedium(std::size_t objectId) const { return objectId >= this->Surfaces.size(); }

  /// Emitter id of light k in Lights (area lights use their surface's object id).
  std::size_t LightEmitterId(std::size_t k) const { return this->NumberOfObjects() + k; }

  /// Empty string when the scene can be traced, otherwise what is wrong with it.
  std::string Validate() const;
};

/// The built-in default scene (a Cornell box around a cube of forward-scattering
/// fog), exactly as specified so that its images compare with other renderers.
Scene MakeDefaultScene();

} // namespace brume

#endif
