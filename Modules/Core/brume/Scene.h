// SPDX-License-Identifier: BSD-3-Clause
// The scene as the physics core sees it: triangle surfaces with Lambertian
// materials and optional emission, and homogeneous media in boxes.
#ifndef brume_Scene_h
#define brume_Scene_h

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
  /// Lambertian reflectance rho per channel, in [0, 1].
  Vec3 Reflectance{ 0.75f };
  /// Emitted radiance L_e (W m^-2 sr^-1) on the front side (the side the
  /// triangle winding's normal points to). Zero for non-emitters.
  Vec3 Emission{ 0.f };

  bool IsEmitter() const { return MaxComponent(this->Emission) > 0.f; }
  double Area() const;
  /// Texture placement of a planar surface; false if the surface is not planar.
  bool ComputePlanarFrame(PlanarFrame& frame, float tolerance = 1e-4f) const;
};

struct Medium
{
  std::string Name;
  /// Axis-aligned extent of the homogeneous medium (index-matched boundary).
  Box Bounds;
  Vec3 SigmaA{ 0.1f };
  Vec3 SigmaS{ 1.f };
  /// Henyey-Greenstein asymmetry, -1 < g < 1.
  float G = 0.f;

  Vec3 SigmaT() const { return this->SigmaA + this->SigmaS; }
  /// Single-scattering albedo sigma_s / sigma_t per channel (0 where sigma_t is 0).
  Vec3 Albedo() const;
};

struct Scene
{
  std::vector<Surface> Surfaces;
  std::vector<Medium> Media;

  /// Object ids: surfaces first, then media.
  std::size_t NumberOfObjects() const { return this->Surfaces.size() + this->Media.size(); }
  bool IsMedium(std::size_t objectId) const { return objectId >= this->Surfaces.size(); }

  /// Empty string when the scene can be traced, otherwise what is wrong with it.
  std::string Validate() const;
};

/// The built-in default scene (a Cornell box around a cube of forward-scattering
/// fog), exactly as specified so that its images compare with other renderers.
Scene MakeDefaultScene();

} // namespace brume

#endif
