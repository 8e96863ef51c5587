// SPDX-License-Identifier: BSD-3-Clause
// Point, spot and directional lights (area lights are emissive surfaces).
#ifndef brume_Light_h
#define brume_Light_h

#include "brume/Random.h"
#include "brume/Vec3.h"

#include <cstdint>
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
  /**
   * Directional beam aimed at a smaller disk of its emitting plane (AimAtMedia):
   * a fraction AimFraction of the particles leave the disk of radius
   * AimRadius about AimCenter, the others the whole beam, and every particle's
   * flux is weighted by the beam's uniform density over the mixture's
   * (EmissionWeight), so that the light's expected flux everywhere is
   * unchanged. 0: the whole beam, uniformly.
   */
  Vec3 AimCenter{ 0.f };
  float AimRadius = 0.f;
  float AimFraction = 0.f;

  /// Emitted power per channel (W).
  Vec3 Power() const;
  /// Empty when valid, otherwise what is wrong.
  std::string Validate() const;
  /// Samples an emission ray; its flux is Power() divided by the caller.
  void SampleEmission(Random& rng, Vec3& origin, Vec3& direction) const;

  /// Whether the beam is aimed (AimFraction in (0, 1) and a positive AimRadius).
  bool Aims() const;
  /**
   * Samples an emission ray of an aimed or unaimed light and returns the
   * weight its flux takes (1 for an unaimed light; 0 for a point of the
   * aimed disk outside the beam, which carries nothing), with `aim` the
   * class the weight follows from: 0 unaimed, 1 outside the aimed disk,
   * 2 inside it. Unaimed, the same draws as SampleEmission().
   */
  float SampleEmission(Random& rng, Vec3& origin, Vec3& direction, std::uint8_t& aim) const;
  /// The weight of an emission ray of class `aim` (see above).
  float EmissionWeight(std::uint8_t aim) const;
};

} // namespace brume

#endif
