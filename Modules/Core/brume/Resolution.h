// SPDX-License-Identifier: BSD-3-Clause
// How many texels an object's texture gets: from its size, its hits and
// where they concentrate (part of the reconstruction, brume/Reconstruction.h).
#ifndef brume_Resolution_h
#define brume_Resolution_h

#include "brume/HitArrays.h"
#include "brume/Parallel.h"
#include "brume/Scene.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace brume
{
/**
 * Texture resolution along each axis of an object of the given extent (zero
 * along unused axes) so that a texel holds about `hitsPerTexel` of the object's
 * `hitCount` hits, clamped to [minimum, maximum] per axis.
 */
std::array<int, 3> ChooseResolution(
  const Vec3& extent, std::size_t hitCount, double hitsPerTexel, int minimum, int maximum);

/**
 * The hits per texel to ask of ChooseResolution() for a medium's box, so that its
 * texels resolve the scale its multiply scattered light varies on where the
 * hits allow: `threshold` for a homogeneous medium; for a heterogeneous one
 * the texel edge the hits give over its box, shrunk toward its transport
 * mean free path 1 / (sigma_t (1 - albedo g)) at its mean occupied density,
 * but no smaller than the edge the hits give over the occupied part of the
 * box alone. A thin cloud keeps the box's texels; a dense medium (a mean
 * free path below a texel) gets texels counted over where it is.
 */
double MediumHitsPerTexel(const Medium& medium, std::size_t hitCount, double threshold);

/**
 * How many output texels each of a heterogeneous medium's own voxels is cut
 * into along each axis (1 or MaxVoxelRefinement), so that an output texel
 * is no larger than about the medium's mean free path 1 / sigma_t at its
 * largest density (its majorants', the largest channel's): voxels per mean
 * free path, rounded, and no finer than the particles' own texture of
 * `particleTexels` resolves (as many per voxel, rounded up: its texels
 * shrink as the particles grow, so the cut follows the budget). The light
 * of a dense medium changes within a mean free path of its skin, and the
 * direct light's shadow depths and the particles' texture, resampled at
 * texels of a whole voxel, averaged the dragon's lit skin (half a voxel)
 * with what lies a voxel deeper. 1 for a medium without a density, with a
 * mean free path over two thirds of a voxel (every thin cloud of the
 * shipped and shared scenes), or whose particles' texels are a voxel or
 * larger.
 */
int MediumVoxelRefinement(const Medium& medium, const std::array<int, 3>& particleTexels);
constexpr int MaxVoxelRefinement = 2;

/**
 * Where a medium's hits are, before its texture is sized: its hits counted
 * over a coarse pilot grid of its box (`PilotGridResolution`, near-cubic
 * cells, about 4,096 of them), added to `counts` so that processes can sum
 * their counts before `HitConcentration`.
 */
std::array<int, 3> PilotGridResolution(const Box& box);
void CountHitsOverPilotGrid(const HitArrays& hits, const std::uint32_t* index, std::size_t count,
  const Box& box, std::vector<std::int64_t>& counts, const ParallelFor& parallelFor = SerialFor());

/**
 * The same for a planar surface: its hits counted over a pilot grid of its
 * frame's parallelogram (near-square cells, about 4,096 of them), the hits
 * the direct light replaces left out (a particle's first interaction after
 * one of `deltaLights` lights whose emitter ids start at `firstDeltaEmitter`;
 * none with 0 lights or no Emitter and Depth arrays).
 */
std::array<int, 3> PilotGridResolution(const PlanarFrame& frame);
void CountHitsOverPilotGrid(const HitArrays& hits, const std::uint32_t* index, std::size_t count,
  const PlanarFrame& frame, std::size_t firstDeltaEmitter, std::size_t deltaLights,
  std::vector<std::int64_t>& counts, const ParallelFor& parallelFor = SerialFor());

/// The largest factor HitConcentration() returns.
constexpr double MaxHitConcentration = 8.0;

/**
 * A planar surface under delta lights whose direct light is computed has
 * its texel count multiplied by its hits' concentration (those the direct
 * light replaces left out) from this value on: a sunlit
 * floor or wall, where the light the haze scatters forward gathers around
 * the sun's patch (god-rays.json: 3.0), gets texels as fine as its hits
 * allow, while evenly lit walls (the default scene's: 1.02-1.11) keep
 * theirs, which a concentration below it would refine for no gain (the
 * default scene with every wall refined: the same block error, 0.01 more
 * per-pixel error).
 */
constexpr double MinSurfaceConcentration = 1.5;

/**
 * How concentrated hits are over a pilot grid of m cells: m Σ n(n − 1) / (Σ n)²,
 * the grid's volume over the volume the hits effectively occupy (the
 * participation ratio of their density; Σ n(n − 1) is the unbiased estimate
 * of Σ λ² for Poisson counts, so that evenly spread hits give 1 whatever
 * their number). 1 where the hits are spread evenly, 8 where they fill an
 * eighth of the box; clamped to [1, MaxHitConcentration]. A medium's texel
 * count is multiplied by it, so that about `threshold` hits fall in a texel
 * where the hits are rather than on average over the box: a shaft, a
 * cloud's lit side, a plume get texels as fine as their hits allow, and the
 * adaptive regions still grow where the hits are sparse.
 */
double HitConcentration(const std::vector<std::int64_t>& counts);
}

#endif
