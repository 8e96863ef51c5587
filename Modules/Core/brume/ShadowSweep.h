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
// the texels' own rays). Rays from a lamp near the grid, RaysPerTexel apart
// on the farthest plane, would crowd on the nearest: the planes are swept
// in runs, each from one plane to the farthest at most RunSpread times as
// far from the lamp, whose rays start with the depths of the run before
// interpolated where they cross its last plane.
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
  /// A run of planes from a point or spot light reaches from one plane to
  /// the farthest at most RunSpread times as far from the light.
  static constexpr float RunSpread = 1.25f;

  /**
   * Plans the rays of light `k` of `light` over the grid of `dims` texels
   * whose centres are those of `dims` cells over `box`. False where a
   * sweep does not apply: a point or spot light between the grid's first
   * and last planes along every axis, a grid of fewer than two planes, or
   * a run whose rays would number more than MaxRayFactor times a plane's.
   */
  bool Plan(
    const DirectLight& light, std::size_t k, const Box& box, const std::array<int, 3>& dims);
  /// Whether Plan() succeeded.
  bool IsPlanned() const { return this->Direct != nullptr; }
  /// The planned rays (of every run), and the texels' planes they cross.
  std::size_t NumberOfRays() const
  {
    std::size_t n = 0;
    for (const Run& r : this->Runs)
    {
      n += r.Rays[0] * r.Rays[1];
    }
    return n;
  }
  /// The runs of planes whose rays are cast afresh (1 for a directional light).
  std::size_t NumberOfRuns() const { return this->Runs.size(); }
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
  // The rays of a run of planes: for a point or spot light, the planes from
  // one to the farthest at most RunSpread times as far from the light, so
  // that the rays through the farthest plane's texels, RaysPerTexel per
  // texel side, are at most RunSpread times as dense on the nearest (a lamp
  // close to the grid would otherwise need its rays spread far past it,
  // and march them all); the next run's rays
  // start with the depths of these interpolated where they cross the run's
  // last plane. A directional light's rays are parallel: one run.
  struct Run
  {
    int First = 0, Last = 0; // steps from the light (step 0: the plane it meets first)
    float Reference = 0.f;   // the plane where the rays lie Pitch apart
    float Low[2] = { 0.f, 0.f };
    float Pitch[2] = { 1.f, 1.f };
    std::size_t Rays[2] = { 0, 0 };
  };
  // The plane of step s from the light.
  int PlaneOfStep(int step) const
  {
    return this->Ascending ? step : this->Dims[this->Axis] - 1 - step;
  }
  // Lateral coordinate s's map (x to a x + b) from the plane at z to run r's
  // reference plane.
  void Map(const Run& r, int s, float z, float& a, float& b) const;
  // Run r's map of the plane of `step` (Map() along both lateral axes), made
  // once a plane rather than once a ray.
  struct PlaneMap
  {
    float Z = 0.f;
    float A[2] = { 1.f, 1.f }, B[2] = { 0.f, 0.f };
  };
  PlaneMap MapOf(const Run& r, int step) const;
  // The lateral coordinates of the point (x, y) of a plane, in run r's rays
  // (ray (i, j) at (i, j)).
  void RayCoordinates(const Run& r, const PlaneMap& m, float x, float y, float& u, float& v) const;
  // Ray (i, j) of run r where it crosses a plane.
  Vec3 RayPoint(const Run& r, const PlaneMap& m, std::size_t i, std::size_t j) const;

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
  std::vector<Run> Runs;      // from the light
};

} // namespace brume

#endif
