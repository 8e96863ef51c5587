// SPDX-License-Identifier: BSD-3-Clause
// Deterministic single scattering (../RADIOMETRY: "Two resolutions in one
// medium"): the light of point, spot and directional lights arriving at a
// point without having interacted with anything, computed with a shadow ray
// instead of being estimated from particles.
//
// A delta light's direct light has sharp edges (a shaft through a window, a
// cloud's self-shadow, a shadow on the ground) that density estimation over
// a texel or an adaptive region blurs. So a reconstruction that uses this
// class leaves out each particle's first interaction after leaving such a
// light (IsFirstInteraction) and adds, per texel of a finer grid, what the
// shadow ray gives:
//   media:    S_1(x, w_o) = albedo * sum_l p(w_l, w_o) E_l(x) T_l(x)
//   surfaces: L_1(x, w_o) = sum_l f_r(-w_l, w_o) E_l(x) T_l(x) cos(theta_l)
// with E_l the light's irradiance on a plane normal to its direction of
// travel w_l (I / r^2 for point and spot lights, the beam's irradiance for
// a directional light, inside the cone or the beam) and T_l the shadow
// ray's transmittance: zero past a surface, exp(-optical depth) through the
// media (exact for homogeneous media, a midpoint march for heterogeneous
// ones, at steps of half a cell of the density's grid).
//
// Area lights (emissive surfaces) are left to the particles.
#ifndef brume_DirectLight_h
#define brume_DirectLight_h

#include "brume/BrickedGrid.h"
#include "brume/Parallel.h"
#include "brume/RayCaster.h"
#include "brume/Scene.h"

#include <array>
#include <cstdint>
#include <vector>

namespace brume
{

/// One light's direct arrival at a point.
struct LightArrival
{
  /// Irradiance on a plane normal to Direction, after the shadow ray (W m^-2).
  Vec3 Irradiance;
  /// Unit direction of travel of the light.
  Vec3 Direction;
};

class DirectLight
{
public:
  /// The scene (valid) and a caster over its surfaces; both must outlive this.
  DirectLight(const Scene& scene, const RayCaster& caster);

  /// Point, spot and directional lights of the scene (may be zero).
  std::size_t NumberOfLights() const { return this->SceneRef.Lights.size(); }

  /// Whether the hit of a particle from `emitter` after `depth` earlier
  /// interactions is one this class computes (depth 0 from a delta light).
  bool IsFirstInteraction(std::uint16_t emitter, std::uint8_t depth) const
  {
    return IsFirstInteraction(emitter, depth, this->FirstLightId, this->NumberOfLights());
  }
  /// The same for `lights` delta lights whose emitter ids start at
  /// `firstLightId` (Scene::LightEmitterId(0)), before there is a DirectLight.
  static bool IsFirstInteraction(
    std::uint16_t emitter, std::uint8_t depth, std::size_t firstLightId, std::size_t lights)
  {
    return depth == 0 && emitter >= firstLightId && emitter < firstLightId + lights;
  }

  /**
   * Heterogeneous medium `m` (index in Scene::Media): its density per cell
   * of a grid (ObjectRadiance's native grid), interpolated between cell
   * centres, which the shadow rays march instead of evaluating the density
   * field. Optional; the grid must outlive this object.
   *
   * The march's midpoint rule takes steps of one cell, but of at most
   * MaxStepDepth optical depths at the grid's largest extinction and never
   * less than half a cell (a field without a grid: half a cell of its
   * native resolution). The grid's largest value is found on
   * `parallelFor`'s threads (the same whatever they are).
   */
  void SetMediumGrid(
    std::size_t m, const BrickedGrid* density, const ParallelFor& parallelFor = SerialFor());

  /**
   * Light `k`'s direct arrival at `x`; false when none arrives (outside the
   * cone or the beam, or behind a surface). `bias` lifts the shadow ray's
   * start (a surface point: its normal times a small distance).
   */
  bool Arrive(std::size_t k, const Vec3& x, const Vec3& bias, LightArrival& arrival) const;

  /**
   * Arrive() but for the media: the irradiance before the shadow ray's
   * transmittance, and the distance to the light the media attenuate over
   * (the transmittance toward the light, -Direction). False when no light
   * arrives (outside the cone or the beam, or behind a surface).
   */
  bool ArriveUnattenuated(
    std::size_t k, const Vec3& x, const Vec3& bias, LightArrival& arrival, float& distance) const;

  /// Light `k`'s direction of travel at `x` (whether or not it arrives).
  Vec3 DirectionAt(std::size_t k, const Vec3& x) const;

  /// Transmittance per channel along the segment x + t d, t in [0, length].
  Vec3 Transmittance(const Vec3& x, const Vec3& d, float length) const;
  /**
   * Adds the optical depth per channel along the same segment to `depth`
   * (Transmittance() is its exponential): the media's midpoint march,
   * which stops a medium's part once every channel is past an optical
   * depth of 30.
   */
  void AddOpticalDepth(const Vec3& x, const Vec3& d, float length, double depth[3]) const;

  /// A distance small against the scene (shadow-ray offsets).
  float GetEpsilon() const { return this->Epsilon; }
  const Scene& GetScene() const { return this->SceneRef; }

private:
  const Scene& SceneRef;
  const RayCaster& Caster;
  std::size_t FirstLightId;
  std::vector<const BrickedGrid*> Grids; // per medium: its grid, or null: the field
  std::vector<float> Steps;              // per medium with a grid: the march's step
  float Epsilon;
};

} // namespace brume

#endif
