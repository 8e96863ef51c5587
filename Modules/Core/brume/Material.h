// SPDX-License-Identifier: BSD-3-Clause
// Surface reflection: Lambertian, energy-conserving normalized Phong, mirror.
//
// Directions follow the physics convention: wi and wo point away from the
// surface, n is the normal on their side.
//  - Lambertian:  f = rho_d / pi
//  - Phong:       f = rho_d / pi + rho_s (e + 2) / (2 pi) max(0, r.wo)^e,
//                 r the mirror direction of wi (Lafortune & Willems 1994; the
//                 (e + 2) / (2 pi) normalization keeps the directional albedo
//                 at most rho_d + rho_s <= 1 for every incidence).
//  - Mirror:      f = rho_s delta(wo - r) / cos(theta).
#ifndef brume_Material_h
#define brume_Material_h

#include "brume/Random.h"
#include "brume/Vec3.h"

#include <string>

namespace brume
{

enum class MaterialType
{
  Lambertian,
  Phong,
  Mirror
};

struct Material
{
  MaterialType Type = MaterialType::Lambertian;
  /// Diffuse reflectance rho_d per channel.
  Vec3 Reflectance{ 0.75f };
  /// Specular reflectance rho_s (Phong lobe or mirror) per channel.
  Vec3 Specular{ 0.f };
  /// Phong exponent e (> 0).
  float Exponent = 32.f;
  /// Emitted radiance (W m^-2 sr^-1) on the front side.
  Vec3 Emission{ 0.f };

  bool IsEmitter() const { return MaxComponent(this->Emission) > 0.f; }
  /// True when the reflected radiance depends on the outgoing direction.
  bool IsViewDependent() const
  {
    return this->Type != MaterialType::Lambertian && MaxComponent(this->Specular) > 0.f;
  }
  /// Empty when valid, otherwise what is wrong.
  std::string Validate() const;
};

/// BRDF value f_r(wi, wo) (per channel); zero for the mirror's delta lobe.
Vec3 EvaluateBrdf(const Material& m, const Vec3& n, const Vec3& wi, const Vec3& wo);

/// Its diffuse part alone, rho_d / pi (zero below the surface): what is
/// left when a lobe is rendered another way (brume::MirrorReflection).
Vec3 EvaluateDiffuseBrdf(const Material& m, const Vec3& n, const Vec3& wi, const Vec3& wo);

/// Density (solid angle) with which SampleBrdf picks wo given wi.
float BrdfPdf(const Material& m, const Vec3& n, const Vec3& wi, const Vec3& wo);

/**
 * Samples an outgoing direction for a particle arriving from wi (pointing
 * away from the surface, on the side of n). Returns false when the particle
 * is absorbed; otherwise wo and the weight f cos(theta_o) / pdf by which the
 * particle's flux is multiplied.
 */
bool SampleBrdf(
  const Material& m, const Vec3& n, const Vec3& wi, Random& rng, Vec3& wo, Vec3& weight);

/// Mirror direction of w about n.
inline Vec3 Reflect(const Vec3& w, const Vec3& n)
{
  return n * (2.f * Dot(w, n)) - w;
}

} // namespace brume

#endif
