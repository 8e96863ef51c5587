// SPDX-License-Identifier: BSD-3-Clause
// Perfect mirrors at display time, beyond the paper (its section 6 leaves
// them out): a mirror's radiance is a delta in direction that density
// estimation cannot represent, so its texture toward an eye is made by
// casting, from every texel, the ray the eye sees reflected there through
// Embree into the other objects' reconstructed textures and media:
//
//   L_o(x, w_o) = L_tex(x) + rho_s L_i(x, r),  r = 2 (w_o . n) n - w_o
//   L_i(x, r)   = T(t_y) L(y, -r) + int_0^t_y T(t) sigma_t(x + t r) S(x + t r) dt
//
// L_tex the mirror's own texture (its emission; a mirror reflects nothing
// diffusely), y the first surface the reflected ray meets (its texture,
// bilinear as a renderer samples it; a mirror again: its own reflection,
// up to MaxDepth bounces, past which only its texture), S and sigma_t a
// medium's source radiance texture (trilinear) and extinction (its native
// density grid, or its constant sigma_t; times the factor of a forward
// peak drawn as transport), T the transmittance: the slice renderer's
// compositing along the eye's rays, done here along the reflected ones by
// a midpoint march at half the finest cell of the media the ray crosses.
//
// Sharp glossy surfaces (Phong lobes of exponent at least CastExponent)
// are cast the same way: the lobe's integral over the light arriving,
//   rho_s (e + 2) / (2 pi) int max(0, r . w)^e L_i(x, w) cos(theta) dw,
// by LobeSamples rays per texel drawn from the lobe (jittered strata,
// keyed by the texel: deterministic), each weighted by
// rho_s (e + 2) / (e + 1) cos(theta); their texture (brume::ObjectOptions::
// LobeCast) then holds the diffuse part and the delta lights' direct light
// only. Density estimation would need the few particles leaving
// each texel within a degree of the eye.
//
// Every ray reflected by a planar mirror lies on a line from the eye
// mirrored by its plane (MirroredEye()): view-dependent objects (glossy
// surfaces, anisotropic media) are then looked up in textures estimated
// toward that point (SetTexture()), which is exact within the method.
// Curved mirrors use the textures toward the eye: their reflections of
// view-dependent objects are approximate.
#ifndef brume_Reflection_h
#define brume_Reflection_h

#include "brume/Parallel.h"
#include "brume/RayCaster.h"
#include "brume/Scene.h"

#include <array>
#include <vector>

namespace brume
{

class ObjectRadiance;

/// What one object shows along a ray: RGB per texel of Dims, x fastest.
struct TextureLookup
{
  const float* Radiance = nullptr;
  std::array<int, 3> Dims{ 0, 0, 0 };
};

class MirrorReflection
{
public:
  /// Mirror bounces followed from a texel (a mirror facing a mirror).
  static constexpr int MaxDepth = 8;
  /// Phong lobes at least this sharp are cast (see above), rays per texel.
  static constexpr float CastExponent = 100.f;
  static constexpr int LobeSamples = 16;

  /**
   * `objects`: every object's reconstruction, in scene order (surfaces,
   * then media), built; none is owned. By default an object is looked up in
   * its output texture (GetOutput()); a surface that Casts(), in
   * its own texture (GetRadiance(), or with direct light the output grid's
   * before any reflection), which holds what it emits and, for a glossy
   * one, its diffuse light; SetTexture() gives a glossy one seen in a
   * mirror its lobe cast toward the mirror's mirrored eye
   * (vtkBrumeRadianceReconstruction does).
   */
  MirrorReflection(
    const Scene& scene, const RayCaster& caster, const std::vector<const ObjectRadiance*>& objects);

  /// Whether `m` reflects through cast rays: a mirror, or a Phong lobe of
  /// exponent at least CastExponent, with rho_s > 0.
  static bool Casts(const Material& m);
  /// Whether some triangle of `surface` does (see Casts()).
  static bool Casts(const Surface& surface);
  /// Whether some triangle of `surface` is a mirror (of any rho_s).
  static bool HasMirror(const Surface& surface);

  /// A planar surface's eye mirrored by its plane; false for a curved one.
  static bool MirroredEye(const Surface& surface, const Vec3& eye, Vec3& mirrored);

  /// Object `o` looked up in `texture` (which must outlive the lookups).
  void SetTexture(std::size_t o, const TextureLookup& texture);

  /**
   * The radiance arriving at `origin` from direction -d: what the ray
   * origin + t d, t > 0, meets, with `depth` mirror bounces already taken.
   */
  Vec3 Incoming(const Vec3& origin, const Vec3& d, int depth) const;

  /**
   * The texture of surface `s` (scene index; one that Casts()) toward
   * `eye`: its own texture plus what its mirrors and sharp lobes reflect,
   * RGB per texel of `dims` over its chart, x fastest. Texels that no
   * triangle of the chart covers keep its own texture's value.
   * Deterministic whatever the threads.
   */
  void Reflect(std::size_t s, const Vec3& eye, const std::array<int, 2>& dims,
    std::vector<float>& radiance, const ParallelFor& parallelFor) const;

private:
  // A glossy lobe's integral about the mirror direction r (see above).
  Vec3 Lobe(const Vec3& origin, const Vec3& n, const Vec3& r, float exponent, std::size_t s,
    std::size_t texel) const;
  Vec3 SurfaceTexture(std::size_t s, unsigned int triangle, const Vec3& p) const;
  // The media between t = 0 and `tEnd` along origin + t d: the light they
  // send toward the origin (added to L) and their transmittance (T).
  void MarchMedia(const Vec3& origin, const Vec3& d, float tEnd, Vec3& L, Vec3& T) const;
  // Object o's march step, when it is a medium (from its texture and grid).
  void UpdateStep(std::size_t o);

  const Scene& SceneRef;
  const RayCaster& Caster;
  std::vector<const ObjectRadiance*> Objects;
  std::vector<TextureLookup> Textures;
  std::vector<float> Steps; // per medium
  float Epsilon;
};

} // namespace brume

#endif
