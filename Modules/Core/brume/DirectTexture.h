// SPDX-License-Identifier: BSD-3-Clause
// Deterministic single scattering in one object's reconstruction
// (brume::ObjectRadiance, brume/DirectLight.h): the output grid of an
// object whose particles leave out their first interaction after a point,
// spot or directional light, holding per texel the particles' texture
// resampled plus the direct light of those lights, from shadow rays cast
// once per build and weighted toward each new eye.
#ifndef brume_DirectTexture_h
#define brume_DirectTexture_h

#include "brume/NativeMediumGrid.h"
#include "brume/ObjectDistribution.h"
#include "brume/ObjectLayout.h"
#include "brume/Parallel.h"
#include "brume/ShadowSweep.h"

#include <array>
#include <cstdint>
#include <vector>

namespace brume
{

class DirectLight;

class DirectTexture
{
public:
  /// Media, and planar surfaces without mirrors (per-triangle materials
  /// reflect the direct light at each output texel by the triangle there).
  static bool Supports(const ObjectLayout& layout);
  /// Direct light of `light` (not owned; null: none) on an output grid of
  /// `resolution` texels, where Supports() and the light has lights.
  void Enable(
    const ObjectLayout& layout, const DirectLight* light, const std::array<int, 3>& resolution);
  bool IsEnabled() const { return this->Light != nullptr; }
  const DirectLight* GetLight() const { return this->Light; }

  /**
   * The shadow ray of every light at every output texel (a distributed
   * run shares the texels out), given the object's estimated `texture`
   * (none: nothing is computed) and, for a medium, its native grid (only
   * the texels a renderer reads get their light). Whether it computed.
   * `kept`: the arrivals (GetArrivals()) of an earlier texture of the same
   * grid under the same lights, surfaces and media's extinction, taken
   * instead of casting the rays again (an edit of a colour).
   */
  bool Compute(const ObjectLayout& layout, const std::vector<float>& texture,
    const NativeMediumGrid& native, const ObjectDistribution& distribution,
    const ParallelFor& parallelFor, const std::vector<float>* kept = nullptr);
  bool HasArrivals() const { return !this->Arrivals.empty(); }
  /// Each output texel's light per light: irradiance RGB and direction.
  const std::vector<float>& GetArrivals() const { return this->Arrivals; }
  /// The output toward `eye`: `texture` resampled plus the direct light.
  void Combine(const ObjectLayout& layout, const std::vector<float>& texture, const Vec3& eye,
    const ParallelFor& parallelFor);
  /// Adds the direct light to a directional projection of `order`
  /// (ObjectRadiance::BuildDirectional()), per voxel of the texture.
  void AddToDirectional(
    const ObjectLayout& layout, int order, std::vector<float>& directional) const;

  /// The output grid: RGB per texel, x fastest; media: sigma_t too.
  const std::array<int, 3>& GetDims() const { return this->Dims; }
  const std::vector<float>& GetRadiance() const { return this->Radiance; }
  const std::vector<float>& GetExtinction() const { return this->Extinction; }
  /**
   * A medium with a native grid: per output texel (x fastest), 1 where a
   * renderer reads it (SparseTexture::CellsRead() of the medium's bounds
   * and native density), as the last Compute() found it to cast only
   * those texels' rays. Empty when it took kept arrivals instead, or found
   * none.
   */
  const std::vector<std::uint8_t>& GetCellsRead() const { return this->Read; }

private:
  // Per light, the sweep of its shadow rays over the texels `cast` (every
  // texel where empty) where the medium's own grid makes it cheaper than
  // one march per texel (ShadowSweep); an unplanned one for the lights cast
  // texel by texel.
  std::vector<ShadowSweep> PlanSweeps(const ObjectLayout& layout, const NativeMediumGrid& native,
    const std::vector<std::uint8_t>& cast) const;
  // The output texel's world position.
  Vec3 OutputPosition(const ObjectLayout& layout, std::size_t texel) const;
  // Surfaces of per-triangle materials or per-vertex reflectance: the
  // triangle at each output texel's centre.
  void LocateTriangles(const ObjectLayout& layout);

  const DirectLight* Light = nullptr;
  std::array<int, 3> Dims{ 0, 0, 0 };
  std::vector<float> Arrivals;    // per output texel and light: irradiance RGB, direction
  std::vector<std::uint8_t> Read; // GetCellsRead()
  // The triangle at each output texel's centre (-1 where none), whose
  // material (there) reflects its direct light; empty for one material.
  std::vector<std::int32_t> Triangles;
  std::vector<float> Radiance;
  std::vector<float> Extinction;
  Vec3 SurfaceNormal; // planar surfaces: the front side
};

} // namespace brume

#endif
