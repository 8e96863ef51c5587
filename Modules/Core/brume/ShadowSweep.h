// SPDX-License-Identifier: BSD-3-Clause
// Shadow rays shared between the texels of a medium's direct-light grid
// (brume::DirectTexture): the optical depth from one light to every texel
// centre, from rays that cross the grid's planes one after another instead
// of one march per texel.
//
// A texel's own shadow ray marches the whole way to the light through the
// medium's own-resolution grid, so a 64^3 grid of a 512^3 medium takes
// about 250 lookups per texel and light (the Wavelet's: 8.7 and 10.7 units
// through the box at steps of 0.039), nearly all of them along paths its
// neighbours' rays run beside. Here a bundle of rays, parallel for a
// directional light and from the light for a point or spot light, crosses
// the grid's planes of texel centres along the axis the light travels most
// along; each ray carries its optical depth from one plane to the next (the
// same midpoint march, DirectLight::AddOpticalDepth), and a texel takes the
// depth of the four rays around it in its plane, interpolated bilinearly.
// The rays lie RaysPerTexel apart per texel side, so the march costs the
// rays' length once per ray, not once per texel: the 512^3 Wavelet's 64^3
// grid cast 261,312 texels' rays per light, its sweeps 34,953 rays for the
// sun and 146,800 for the lamp, and its direct light took 2.6 s instead of
// 7.0 (Documentation/evaluation.md gives the figures, and the error against
// the texels' own rays).
#ifndef brume_ShadowSweep_h
#define brume_ShadowSweep_h

#include "brume/Parallel.h"
#include "brume/Vec3.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace brume
{

class DirectLight;

class ShadowSweep
{
public:
  /// Rays per texel side in the texels' planes.
  static constexpr int RaysPerTexel = 2;
  /// The most rays a sweep casts, in rays of one plane of texels.
  static constexpr double MaxRayFactor = 16.0;

  /**
   * Plans the rays of light `k` of `light` over the grid of `dims` texels
   * whose centres are those of `dims` cells over `box`. False where a
   * sweep does not apply: a point or spot light between the grid's first
   * and last planes along every axis, a grid of fewer than two planes, or
   * rays that would number more than MaxRayFactor times a plane's (a lamp
   * so close to the grid that its rays spread far past it).
   */
  bool Plan(
    const DirectLight& light, std::size_t k, const Box& box, const std::array<int, 3>& dims);
  /// Whether Plan() succeeded.
  bool IsPlanned() const { return this->Direct != nullptr; }
  /// The planned rays, and the texels' planes they cross.
  std::size_t NumberOfRays() const { return this->Rays[0] * this->Rays[1]; }
  int NumberOfPlanes() const { return this->Dims[this->Axis]; }
  /// The rays' length inside the grid's box, together: what their march
  /// costs, to weigh against the texels' own rays'.
  double MarchLength() const;

  /**
   * The optical depth per channel from the light to every texel centre
   * (RGB per texel, x fastest), for the planned light; texels where
   * `wanted` (one flag per texel, or empty for all) is 0 are left 0.
   */
  std::vector<float> Depths(
    const std::vector<std::uint8_t>& wanted, const ParallelFor& parallelFor = SerialFor()) const;

private:
  // The lateral coordinates of the texel centre at (x, y) of plane p, in
  // the rays' grid (ray (i, j) at (i, j)).
  void RayCoordinates(int plane, float x, float y, float& u, float& v) const;
  // Ray (i, j)'s point on plane p.
  Vec3 RayPoint(int plane, std::size_t i, std::size_t j) const;

  const DirectLight* Direct = nullptr;
  std::size_t LightIndex = 0;
  bool Directional = false;
  Vec3 Source{ 0.f }; // a point or spot light's position
  Vec3 Travel{ 0.f }; // a directional light's direction of travel
  Box GridBox;        // the texels' box
  std::array<int, 3> Dims{ 0, 0, 0 };
  int Axis = 0; // the axis the planes are normal to
  int Lateral[2] = { 1, 2 };
  bool Ascending = true;      // whether the light meets plane 0 first
  std::vector<float> PlaneAt; // each plane's coordinate along Axis
  // Lateral position of plane p's texel x: A[p] x + B[p] in the rays'
  // reference coordinates (the first plane's for a directional light, the
  // last's for a point light); rays every Pitch from Low.
  std::vector<float> A[2], B[2];
  float Low[2] = { 0.f, 0.f };
  float Pitch[2] = { 1.f, 1.f };
  std::size_t Rays[2] = { 0, 0 };
};

} // namespace brume

#endif
