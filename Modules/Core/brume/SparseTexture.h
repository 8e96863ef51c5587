// SPDX-License-Identifier: BSD-3-Clause
// A medium's texture kept only where a renderer reads it: the bricks of
// cells near the medium's density, not its whole box.
#ifndef brume_SparseTexture_h
#define brume_SparseTexture_h

#include "brume/Parallel.h"
#include "brume/Vec3.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace brume
{

class BrickedGrid;

/**
 * The layout of a cell texture (`dims` cells over a box) in bricks that do
 * not overlap, x fastest, BrickEdge(n) cells along an axis of n cells
 * (BrickSize, or n when fewer), brick b along an axis holding cells
 * BrickEdge(n) b ... BrickEdge(n) (b + 1) - 1 (the last brick's cells past
 * the texture's end are padding). A brick is stored (has a slot)
 * when a renderer may read one of its cells; the others are dropped and read
 * as 0.
 *
 * For a medium's source radiance S, drawn as S sigma_t with sigma_t from the
 * density at its own resolution (RADIOMETRY.md, "Two resolutions in one
 * medium"), a cell is read where sigma_t is not 0 within the reach of
 * trilinear interpolation (one texture cell and one density cell from a
 * cell's centre): a cell is kept when a density cell that is not 0 lies
 * within one density cell and one and a half texture cells of its centre,
 * along every axis. Elsewhere S sigma_t is 0 whatever S, so dropping those
 * bricks changes no image.
 */
class SparseTexture
{
public:
  static constexpr int BrickSize = 8;

  /// A brick's cells along an axis of n cells.
  static int BrickEdge(int n) { return n < BrickSize ? n : BrickSize; }
  /// The number of bricks along an axis of n cells.
  static int BricksAlong(int n) { return n > 0 ? (n + BrickSize - 1) / BrickSize : 0; }

  /**
   * The bricks of a texture of `dims` cells over `box` that a renderer reads
   * where `density` (over its own box, sampled at its cells' centres) is
   * not 0. Deterministic; does not depend on the density's values, only on
   * where they are not 0, nor on `parallelFor`'s threads.
   */
  static SparseTexture WhereDensity(const std::array<int, 3>& dims, const Box& box,
    const BrickedGrid& density, const ParallelFor& parallelFor = SerialFor());
  /**
   * The same, from CellsRead() of the same texture and density, found
   * before (brume::DirectTexture keeps it for its medium). A `read` that is
   * not one value per cell of `dims` reads nothing: no brick is stored.
   */
  static SparseTexture FromCellsRead(
    const std::array<int, 3>& dims, const std::vector<std::uint8_t>& read);

  /**
   * Per cell of that texture (x fastest), 1 where a renderer may read it:
   * the cells WhereDensity's bricks are kept for. All 0 for an empty
   * density. The density's layers of bricks are read on `parallelFor`'s
   * threads; the result does not depend on them.
   */
  static std::vector<std::uint8_t> CellsRead(const std::array<int, 3>& dims, const Box& box,
    const BrickedGrid& density, const ParallelFor& parallelFor = SerialFor());

  const std::array<int, 3>& GetDims() const { return this->Dims; }
  const std::array<int, 3>& GetBrickDims() const { return this->BrickDims; }
  /// Cells per brick.
  std::size_t GetBrickCells() const
  {
    return static_cast<std::size_t>(BrickEdge(this->Dims[0])) * BrickEdge(this->Dims[1]) *
      BrickEdge(this->Dims[2]);
  }
  /// Per brick (x fastest): its slot, or -1 when dropped.
  const std::vector<std::int32_t>& GetSlots() const { return this->Slots; }
  std::size_t NumberOfStoredBricks() const { return this->Stored; }

  /**
   * `values` (`components` floats per cell, cells x fastest) gathered brick
   * by brick: GetBrickCells() cells of `components` floats per stored
   * brick, in slot order, x fastest within a brick, padding 0.
   */
  std::vector<float> Gather(const std::vector<float>& values, int components) const;

private:
  /// Where cell (i, j, k) lies among the stored bricks' cells, or -1.
  std::ptrdiff_t BrickCellOf(int i, int j, int k) const;

  std::array<int, 3> Dims{ 0, 0, 0 };
  std::array<int, 3> BrickDims{ 0, 0, 0 };
  std::vector<std::int32_t> Slots;
  std::size_t Stored = 0;
};

} // namespace brume

#endif
