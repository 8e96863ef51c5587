// SPDX-License-Identifier: BSD-3-Clause
// Point, spot and directional lights (area lights are emissive surfaces).
#ifndef brume_Light_h
#define brume_Light_h

#include "brume/Random.h"
#include "brume/Vec3.h"

#include <string>

namespace brume
{

enum class LightType
{
  /// Isotropic point: Intensity is the radiant intensity I (W/sr); Phi = 4 pi I.
  Point,
  /// Point emitting uniformly inside a cone of half-angle ConeAngle about
  /// Direction: Intensity is I (W/sr); Phi = 2 pi (1 - cos(ConeAngle)) I.
  Spot,
  /// Parallel light along Direction: Intensity is the irradiance E (W/m^2)
  /// on a plane perpendicular to it, over a disk of radius BeamRadius centred
  /// on BeamCenter (a collimated beam); Phi = pi r^2 E.
  Directional
};

struct Light
{
  std::string Name;
  LightType Type = LightType::Point;
  Vec3 Position{ 0.f };
  /// Unit direction the light travels (spot axis, directional beam).
  Vec3 Direction{ 0.f, -1.f, 0.f };
  Vec3 Intensity{ 1.f };
  /// Spot half-angle in degrees, in (0, 180].
  float ConeAngle = 30.f;
  /// Directional beam: centre and radius of the emitting disk.
  Vec3 BeamCenter{ 0.f };
  float BeamRadius = 1.f;

  /// Emitted power per channel (W).
  Vec3 Power() const;
  /// Empty when valid, otherwise what is wrong.
  std::string Validate() const;
  /// Samples an emission ray; its flux is Power() divided by the caller.
  void SampleEmission(Random& rng, Vec3& origin, Vec3& direction) const;
};

} // namespace brume

#endif
