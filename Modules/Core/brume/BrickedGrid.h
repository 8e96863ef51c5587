// SPDX-License-Identifier: BSD-3-Clause
// A scalar grid stored sparsely in bricks: memory follows the bricks where
// the values vary, not the grid's box.
#ifndef brume_BrickedGrid_h
#define brume_BrickedGrid_h

#include "brume/FloatBuffer.h"
#include "brume/Parallel.h"
#include "brume/Vec3.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

namespace brume
{

/**
 * Samples at the centres of Dims cells over a box, interpolated trilinearly
 * between the centres and clamped at the outer ones (a cell-data 3D texture
 * with linear filtering and clamp-to-edge), stored in bricks of Size^3
 * samples. Brick b along an axis holds samples Stride*b ... Stride*b + Size - 1
 * (neighbours share one layer), so that the eight samples any point
 * interpolates lie in one brick: the trilinear lookup is one brick-table
 * read and a fetch inside one brick, on the CPU and in a GPU atlas alike.
 * Samples past the last one repeat it.
 *
 * A brick whose samples are all equal keeps only that value: memory is
 * Size^3 floats per brick where the values vary, plus 8 bytes per brick of
 * the box. The layout is the one vtkBrumeSliceVolumeMapper draws (see its
 * ExtinctionData).
 */
class BrickedGrid
{
public:
  static constexpr int Size = 8;
  static constexpr int Stride = Size - 1;
  static constexpr int BrickSamples = Size * Size * Size;

  /// The number of bricks along an axis of n samples.
  static int BricksAlong(int n) { return n > 1 ? (n - 2) / Stride + 1 : 1; }

  /**
   * Samples a grid of `dims` cells over `box`: `value(i, j, k)` gives the
   * sample of cell (i, j, k) (thread safe); `zeroOver(lower, upper)` may say
   * that every sample of cells lower..upper (inclusive) is 0 without
   * evaluating them (a majorant of 0), so that empty space costs no
   * evaluation; those bricks hold `skipped` (a grid of scalars that a
   * transfer function classifies gives one the function takes to 0).
   * Deterministic whatever the threads.
   */
  static BrickedGrid Sample(const std::array<int, 3>& dims, const Box& box,
    const std::function<float(int, int, int)>& value,
    const std::function<bool(const std::array<int, 3>&, const std::array<int, 3>&)>& zeroOver,
    const ParallelFor& parallelFor, float skipped = 0.f);

  /**
   * Sample() a brick at a time: `brick(lower, out)` writes the BrickSamples
   * samples of the cells lower .. lower + Size - 1 (x fastest; cells past
   * the grid's last take the last's sample), for values that are cheaper
   * found together (thread safe).
   */
  static BrickedGrid SampleBricks(const std::array<int, 3>& dims, const Box& box,
    const std::function<void(const std::array<int, 3>&, float*)>& brick,
    const std::function<bool(const std::array<int, 3>&, const std::array<int, 3>&)>& zeroOver,
    const ParallelFor& parallelFor, float skipped = 0.f);
  /// The same with the bricks to evaluate given (Candidates()).
  static BrickedGrid SampleBricks(const std::array<int, 3>& dims, const Box& box,
    const std::function<void(const std::array<int, 3>&, float*)>& brick,
    const std::vector<char>& candidate, const ParallelFor& parallelFor, float skipped = 0.f);

  /**
   * The slots and constants SampleBricks() gives, without its samples: an
   * outline of a grid whose samples are kept elsewhere (a classified
   * density's scalars, which its own array holds: brume::NativeMediumGrid).
   * Each candidate brick is evaluated into a buffer of one brick and told
   * constant or stored; the stored ones take slots in brick order, as
   * SampleBricks() gives them. The outline answers NumberOfStoredBricks(),
   * GetSlots() and GetConstants(); it holds no samples (HasSamples() is
   * false where a brick is stored), so At(), CopyBrick(), Interpolate()
   * and the marches are not for it.
   */
  static BrickedGrid Outline(const std::array<int, 3>& dims, const Box& box,
    const std::function<void(const std::array<int, 3>&, float*)>& brick,
    const std::vector<char>& candidate, const ParallelFor& parallelFor, float skipped = 0.f);

  /**
   * SampleBricks() of `previous`'s cells again, written into `previous`'s
   * own memory where it alone holds its samples (SoleOwner(); otherwise
   * into new memory, as SampleBricks() does): an edit of a function of the
   * grid's values, so that a large grid and its successor are never held
   * at once. A candidate brick b is `previous`'s where `keep[b]` (its
   * samples, or its constant, are what `brick` would write: nothing is
   * written), otherwise `brick(lower, out)` writes it. A brick stored
   * before and written again takes its own slot; one that becomes constant
   * frees it; one constant before that now varies takes a freed slot, else
   * one past the last (the memory then grows, by a copy); slots left free
   * are filled from the last ones. At() and every sample are bitwise those
   * of SampleBricks() with the same `brick`; the slots may differ.
   * `previous` is left empty; the grid has a new GetIdentity().
   */
  static BrickedGrid ResampleInPlace(BrickedGrid&& previous, const std::vector<char>& keep,
    const std::function<void(const std::array<int, 3>&, float*)>& brick,
    const std::vector<char>& candidate, const ParallelFor& parallelFor, float skipped = 0.f);

  /**
   * Per brick of a grid of `dims` cells (in brick order): whether Sample()
   * evaluates it, i.e. `zeroOver` does not leave it out.
   */
  static std::vector<char> Candidates(const std::array<int, 3>& dims,
    const std::function<bool(const std::array<int, 3>&, const std::array<int, 3>&)>& zeroOver,
    const ParallelFor& parallelFor);

  bool Empty() const { return this->Slots.empty(); }
  const std::array<int, 3>& GetDims() const { return this->Dims; }
  const Box& GetBox() const { return this->Bounds; }
  const std::array<int, 3>& GetBrickDims() const { return this->BrickDims; }
  std::size_t NumberOfBricks() const { return this->Slots.size(); }
  /// Bricks that store their samples.
  std::size_t NumberOfStoredBricks() const { return this->Stored; }
  /// Whether the stored bricks' samples are here (not an Outline()).
  bool HasSamples() const { return this->Samples.Size() == this->Stored * BrickSamples; }

  /// Per brick (x fastest): its slot in GetSamples(), or -1 when constant.
  const std::vector<std::int32_t>& GetSlots() const { return this->Slots; }
  /// Per brick: the value of a constant brick (0 for a stored one).
  const std::vector<float>& GetConstants() const { return this->Constants; }
  /// Size^3 samples per stored brick, x fastest within a brick (a buffer
  /// that a VTK array may share: vtkBrumeRadianceConversion::NativeExtinction).
  const FloatBuffer& GetSamples() const { return this->Samples; }
  /// The same cells, slots and constants, and its samples the same memory
  /// (a copy of the grid, sharing them).
  bool SameAs(const BrickedGrid& other) const;
  /**
   * The same for a grid and its copies (which share its samples), another
   * for every grid sampled, and for a grid sampled again in its own memory
   * (ResampleInPlace()): what tells that a grid is the one something was
   * computed from, where its memory may be reused.
   */
  std::uint64_t GetIdentity() const { return this->Identity; }
  /// Whether no copy of this grid, and no array, shares its samples.
  bool SoleOwner() const { return this->Samples.Share().use_count() == 1; }
  /// The bytes of the three arrays above.
  std::size_t GetMemorySize() const;

  /// The brick whose first cell is `lower` (multiples of Stride), in brick order.
  std::size_t BrickAt(const std::array<int, 3>& lower) const
  {
    return this->BrickIndex(lower[0] / Stride, lower[1] / Stride, lower[2] / Stride);
  }
  /// The BrickSamples samples of `brick` (x fastest), a constant one's repeated.
  void CopyBrick(std::size_t brick, float* out) const;

  /// The brick whose own cells hold cell (i, j, k), in brick order.
  std::size_t BrickOf(int i, int j, int k) const
  {
    return this->BrickIndex(std::min(i / Stride, this->BrickDims[0] - 1),
      std::min(j / Stride, this->BrickDims[1] - 1), std::min(k / Stride, this->BrickDims[2] - 1));
  }
  /// The sample of cell (i, j, k), 0 <= i < Dims[0] ...
  float At(int i, int j, int k) const;
  /// Trilinear between the cells' centres at world point `p`, clamped at the faces.
  float Interpolate(const Vec3& p) const;
  /**
   * How many of the points p, p + step, p + 2 step, ... (at most `most`)
   * lie in p's brick when that brick holds one value (written to `value`):
   * Interpolate() gives `value` at each of them, so a ray marching the grid
   * adds it without looking it up. Points within 10^-3 cell of the brick's
   * faces end the run (their brick is left to Interpolate()); 0 where p's
   * brick stores its samples, or p lies that close to a face.
   */
  int ConstantSamples(const Vec3& p, const Vec3& step, int most, float& value) const;
  /**
   * The midpoint march of a shadow ray: the sum, in double and in order, of
   * Interpolate() at the `n` points x + d (t0 + (i + 1/2) h), i = 0 ... n - 1,
   * ended at the first point where it passes `stop` when `stop` > 0. The
   * same sum as Interpolate() called at each point, with each point's brick
   * found once, a constant brick's run (ConstantSamples()) added without a
   * lookup per point, and the samples of the point a few steps ahead asked
   * of memory while the current one is interpolated.
   */
  double SumAlong(const Vec3& x, const Vec3& d, float t0, float h, int n, double stop) const;

  /**
   * Calls `f(i, j, k, value)` once for every cell whose brick is not a
   * constant 0, brick by brick (each brick's own cells: Stride per axis,
   * the last brick the rest), in brick order.
   */
  void ForEachNonZeroCell(const std::function<void(int, int, int, float)>& f) const;
  /// The same for the bricks of layers [first, last) along z (their cells
  /// k from Stride first), with `f` called inline; `brick(lower, count)`
  /// first for each brick visited, with its first cell and its cells along
  /// each axis (for a caller that reads something per brick).
  template <class F>
  void ForEachNonZeroCellOfLayers(int first, int last, F&& f) const
  {
    this->ForEachNonZeroCellOfLayers(
      first, last, std::forward<F>(f), [](const std::array<int, 3>&, const std::array<int, 3>&) {});
  }
  template <class F, class B>
  void ForEachNonZeroCellOfLayers(int first, int last, F&& f, B&& brick) const;

private:
  // A grid of `dims` cells over `box` whose bricks all hold `skipped`.
  static BrickedGrid Layout(const std::array<int, 3>& dims, const Box& box, float skipped);
  std::size_t BrickIndex(int bi, int bj, int bk) const
  {
    return (static_cast<std::size_t>(bk) * this->BrickDims[1] + bj) * this->BrickDims[0] + bi;
  }
  // The brick of the point at `q` (in cells from the box's lower corner),
  // and the first of the eight samples (i0, in the brick) and the weights
  // that interpolate it.
  std::size_t Locate(const Vec3& q, int i0[3], float w[3]) const;
  // Trilinear between the eight samples of stored brick `slot` from i0.
  float Trilinear(std::int32_t slot, const int i0[3], const float w[3]) const;
  // ConstantSamples()'s run from `q` by steps `dq` (both in cells) in
  // constant brick `brick`.
  int ConstantRun(const Vec3& q, const Vec3& dq, std::size_t brick, int most) const;

  std::array<int, 3> Dims{ 0, 0, 0 };
  std::array<int, 3> BrickDims{ 0, 0, 0 };
  // Dims - 1 and BrickDims - 1 as floats, four for Locate()'s lanes.
  alignas(16) std::array<float, 4> LastSample{ 0.f, 0.f, 0.f, 0.f };
  alignas(16) std::array<float, 4> LastBrick{ 0.f, 0.f, 0.f, 0.f };
  Box Bounds;
  Vec3 CellsPerLength{ 0.f }; // Dims / Bounds.Extent()
  std::vector<std::int32_t> Slots;
  std::vector<float> Constants;
  FloatBuffer Samples;
  std::size_t Stored = 0; // bricks with a slot
  std::uint64_t Identity = 0;
};

template <class F, class B>
void BrickedGrid::ForEachNonZeroCellOfLayers(int first, int last, F&& f, B&& brick) const
{
  for (int bk = first; bk < last; ++bk)
  {
    for (int bj = 0; bj < this->BrickDims[1]; ++bj)
    {
      for (int bi = 0; bi < this->BrickDims[0]; ++bi)
      {
        const std::size_t index = this->BrickIndex(bi, bj, bk);
        if (this->Slots[index] < 0 && this->Constants[index] == 0.f)
        {
          continue;
        }
        const int b[3] = { bi, bj, bk };
        int lower[3], upper[3];
        for (int a = 0; a < 3; ++a)
        {
          lower[a] = Stride * b[a];
          upper[a] = b[a] == this->BrickDims[a] - 1 ? this->Dims[a] : lower[a] + Stride;
        }
        brick(std::array<int, 3>{ lower[0], lower[1], lower[2] },
          std::array<int, 3>{ upper[0] - lower[0], upper[1] - lower[1], upper[2] - lower[2] });
        // The brick's own samples (At()'s values, read in place).
        const std::int32_t slot = this->Slots[index];
        const float* samples =
          slot < 0 ? nullptr : this->Samples.Data() + static_cast<std::size_t>(slot) * BrickSamples;
        for (int k = lower[2]; k < upper[2]; ++k)
          for (int j = lower[1]; j < upper[1]; ++j)
            for (int i = lower[0]; i < upper[0]; ++i)
            {
              f(i, j, k,
                samples ? samples[((k - lower[2]) * Size + (j - lower[1])) * Size + (i - lower[0])]
                        : this->Constants[index]);
            }
      }
    }
  }
}

} // namespace brume

#endif
