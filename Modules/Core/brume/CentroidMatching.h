// SPDX-License-Identifier: BSD-3-Clause
// A texture whose trilinear interpolation meets each texel's estimate where
// the estimate belongs: at its region's weighted centroid.
#ifndef brume_CentroidMatching_h
#define brume_CentroidMatching_h

#include "brume/Parallel.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace brume
{

/**
 * A medium's texel estimate is a weighted mean over the texel's adaptive
 * region (the sigma_t-weighted mean of the source radiance, ../RADIOMETRY
 * "Two resolutions in one medium"). For a quantity that varies linearly it
 * is exact at the region's weighted centroid, not at the texel's centre. The
 * two differ where a region is filled unevenly: a texel across a cloud's
 * edge, a region grown into a denser part. Interpolating the estimates as
 * though they belonged to the centres carries interior values out to the
 * edge, and a dense cloud's outer skin, which is all a viewer sees of it,
 * comes out too bright (a ball of optical radius 5.7: +9.6 % of its multiply
 * scattered light).
 *
 * Apply() finds the texture V whose interpolation at each texel's centroid
 * (trilinear between texel centres and clamped at the faces, as the
 * renderer samples it) equals the texel's estimate S. It uses simultaneous
 * iterative reconstruction: every texel's value moves by the mean of the
 * residuals of the equations it takes part in, weighted by its
 * interpolation weights. It starts from the estimates, takes Iterations
 * steps, and bounds each value to
 * the range of the estimates among the texel and its 26 neighbours,
 * widened to 0 (a source stays in [0, the largest estimate around]; a
 * signed quantity, a spherical-harmonics coefficient, may also reach 0),
 * so that noise is not amplified into new extremes.
 *
 * Only a centroid inside its texel's own cell (within half a texel on
 * every axis) sets an equation. One farther out belongs to a region that
 * grew well beyond its texel: a texel beside a thin dense structure whose
 * region reached into it, its estimate a mean over a region far wider than
 * those of the texels around its centroid, which set their own equations
 * there. Such rows pulled those texels toward the wider means; on a dense
 * dragon at threshold 32 they brightened the image by 1.6 % (block error
 * 2.98 % without them, 4.11 % with them, 2.87 % with no matching at all).
 *
 * Where every centroid is its texel's centre the texture is the estimates
 * unchanged. A linear field is reproduced wherever the bounds allow it.
 * Everything is summed in a fixed order, so the texture does not depend on
 * the thread count.
 */
class CentroidMatching
{
public:
  static constexpr int Iterations = 32;
  /// Fewer moving texels than this iterate on the calling thread.
  static constexpr std::size_t ParallelColumns = 4096;

  CentroidMatching() = default;
  /// `centroids`: 3 per texel of a `dims` grid, in texel units (texel
  /// (i, j, k)'s centre at (i, j, k)).
  CentroidMatching(
    const std::array<int, 3>& dims, const std::vector<float>& centroids, const ParallelFor& pf);

  bool Empty() const { return this->Texels == 0; }
  std::size_t NumberOfTexels() const { return this->Texels; }
  /// The texels whose values the iterations move: those that a centroid
  /// off its texel's centre interpolates. The others keep their estimates.
  std::size_t NumberOfMovingTexels() const { return this->Columns.size(); }

  /**
   * `values`: `channels` per texel, the estimates, replaced by the
   * texture. A texel whose estimate is 0 in every channel (a region
   * holding no medium) sets no equation, though its value may move to meet
   * its neighbours' equations. Returns the residual left after
   * the last step: the sum of |V(centroid) - S| over the equations, over
   * the sum of |S|.
   */
  double Apply(std::vector<float>& values, int channels, const ParallelFor& pf) const;

private:
  std::array<int, 3> Dims{ 0, 0, 0 };
  std::size_t Texels = 0;
  // The texels that move (columns), the rows they take part in (rows), and
  // per column those rows, in row order, with their weights.
  std::vector<std::uint32_t> Columns, Rows;
  std::vector<std::size_t> ColumnStart;
  std::vector<std::uint32_t> ColumnRow;
  std::vector<float> ColumnWeight;
  // Per row, the texels its centroid interpolates and their weights.
  std::vector<std::size_t> RowStart;
  std::vector<std::uint32_t> RowColumn;
  std::vector<float> RowWeight;
  // Per texel: whether its centroid lies outside its own cell (no equation).
  std::vector<char> Far;
};

} // namespace brume

#endif
