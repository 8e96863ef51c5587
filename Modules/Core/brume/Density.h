// SPDX-License-Identifier: BSD-3-Clause
// Heterogeneous media: density fields and the majorants that make delta
// tracking cheap where the medium is sparse.
#ifndef brume_Density_h
#define brume_Density_h

#include "brume/FloatBuffer.h"
#include "brume/Parallel.h"
#include "brume/Vec3.h"

#include <algorithm>
#include <array>
#include <functional>
#include <memory>
#include <mutex>
#include <vector>

namespace brume
{

/// Upper bounds of a density over a coarse grid of blocks covering a box.
struct MajorantGrid
{
  Box Bounds;
  std::array<int, 3> Dims{ 1, 1, 1 };
  std::vector<float> Max{ 0.f };

  float At(int i, int j, int k) const
  {
    return this->Max[(static_cast<std::size_t>(k) * this->Dims[1] + j) * this->Dims[0] + i];
  }
  /// Maximum over all blocks.
  float GlobalMax() const;

  /**
   * Regions of RegionBlocks^3 blocks whose every majorant is 0, marked by
   * MarkEmptyRegions() once Max is final: a tracker steps through them
   * without reading their blocks (a sparse cloud's empty air, 10^7
   * blocks of a 2048^3 OpenVDB grid). None are marked in grids under a
   * region along every axis.
   */
  static constexpr int RegionBlocks = 8;
  std::array<int, 3> RegionDims{ 0, 0, 0 };
  std::vector<unsigned char> EmptyRegions;
  void MarkEmptyRegions();
  /// Whether block `cell` lies in a region MarkEmptyRegions() found empty.
  bool InEmptyRegion(const int cell[3]) const
  {
    return !this->EmptyRegions.empty() &&
      this->EmptyRegions[(static_cast<std::size_t>(cell[2] / RegionBlocks) * this->RegionDims[1] +
                           cell[1] / RegionBlocks) *
          this->RegionDims[0] +
        cell[0] / RegionBlocks] != 0;
  }
};

/// The mean of a native cell's `n` samples (NativeMean()), summed in
/// double in order: every caller gives the same double.
inline double NativeSampleMean(const float* samples, int n)
{
  double sum = 0.0;
  for (int m = 0; m < n; ++m)
  {
    sum += samples[m];
  }
  return sum / static_cast<double>(n);
}

/// A scalar density over a box; sigma(x) = density(x) * sigma (per channel).
class DensityField
{
public:
  virtual ~DensityField() = default;
  /// Density at a world point inside GetBounds(); must be thread safe.
  virtual float Evaluate(const Vec3& p) const = 0;
  const Box& GetBounds() const { return this->Bounds; }
  /**
   * The field's own grid: NativeResolution() cells over NativeBox(), the
   * resolution at which its structure is resolved, placed so that each
   * cell's centre is one of the field's own samples (a cell value, a point
   * value, an OpenVDB voxel). Sampling the field at those centres and
   * interpolating them trilinearly reproduces a trilinear field exactly.
   * The box holds GetBounds(), and may reach half a cell beyond it (point
   * values and voxels sit on or beyond the bounds' faces). The default is
   * the majorant blocks' cells over the bounds.
   */
  virtual std::array<int, 3> NativeResolution() const;
  virtual Box NativeBox() const { return this->Bounds; }
  /**
   * The field at the centre of its native cell (i, j, k), which lies at
   * world point `centre` (clamped to the bounds): Evaluate(centre), or the
   * sample itself where the field holds it (a grid's value).
   */
  virtual float NativeValue(int i, int j, int k, const Vec3& centre) const
  {
    (void)i;
    (void)j;
    (void)k;
    return this->Evaluate(centre);
  }
  /**
   * The mean of the field over its native cell (i, j, k), whose box is
   * `cell`, from s^3 samples at the centres of a regular subdivision
   * (clamped to `bounds`, the medium's). Grids of point values, interpolated
   * linearly, give it from the 27 values around the cell's point, not by
   * 64 evaluations (ClassifiedDensity classifies those).
   */
  virtual double NativeMean(int i, int j, int k, const Box& cell, const Box& bounds, int s) const;
  /**
   * The values at the centres of the native cells from `lower`, `count`
   * along each axis (x fastest, inside NativeResolution()), for a field
   * that is exactly their trilinear interpolation, clamped at the grid's
   * ends (a grid of point values interpolated linearly, an OpenVDB grid):
   * for a caller that interpolates them itself. False, with nothing
   * written, for other fields.
   */
  virtual bool NativePoints(
    const std::array<int, 3>& lower, const std::array<int, 3>& count, float* out) const
  {
    (void)lower;
    (void)count;
    (void)out;
    return false;
  }
  const MajorantGrid& GetMajorants() const { return this->Majorants; }
  /// Number of non-empty majorant blocks (for reporting sparsity).
  std::size_t NumberOfOccupiedBlocks() const;
  /**
   * The fraction of the native cells where the density is not 0, in
   * (0, 1]: where particles can interact (a cloud filling a third of its
   * box). Grids count their values; without them, the non-empty majorant
   * blocks.
   */
  double OccupiedFraction() const;
  /// The mean density over those cells (without the values: the largest).
  double MeanOccupiedDensity() const;
  /**
   * Per majorant block (in GetMajorants()'s order), the smallest and
   * largest value anywhere in the block (what a transfer function
   * classifying the field must bound there); false when the field cannot say.
   */
  virtual bool ValueRanges(std::vector<float>& lo, std::vector<float>& hi) const
  {
    (void)lo;
    (void)hi;
    return false;
  }

protected:
  /**
   * Counts into GridValues, OccupiedValues and OccupiedSum the `count`
   * values value(i) that are above 0, on `parallelFor`: in fixed chunks
   * summed in order, so the sums are the same whatever the threads (and
   * those of a plain loop up to one chunk). `value` is inlined: over a
   * 512^3 grid a call per value through std::function took half a second
   * of each edit of a transfer function.
   */
  template <typename Value>
  void CountOccupied(std::size_t count, const Value& value, const ParallelFor& parallelFor)
  {
    std::vector<double> occupied, sums;
    this->CountOccupiedChunks(count, value, parallelFor, {}, occupied, sums);
    this->SetOccupied(static_cast<double>(count), occupied, sums);
  }
  /// The values CountOccupied() counts in one chunk.
  static constexpr std::size_t OccupiedChunk = std::size_t(1) << 16;
  /**
   * CountOccupied()'s counts and sums per chunk of OccupiedChunk values,
   * into `occupied` and `sums` (resized to the chunks), without setting
   * the totals; chunks marked in `known` (empty: none) keep what the two
   * vectors hold for them.
   */
  template <typename Value>
  static void CountOccupiedChunks(std::size_t count, const Value& value,
    const ParallelFor& parallelFor, const std::vector<char>& known, std::vector<double>& occupied,
    std::vector<double>& sums)
  {
    CountOccupiedChunkRuns(
      count,
      [&](std::size_t first, std::size_t n, float* out)
      {
        for (std::size_t i = 0; i < n; ++i)
        {
          out[i] = value(first + i);
        }
      },
      parallelFor, known, occupied, sums);
  }
  /// The values CountOccupiedChunkRuns() asks for at once.
  static constexpr std::size_t OccupiedRun = 1024;
  /**
   * CountOccupiedChunks() with the values found a run at a time:
   * `run(first, n, out)` writes values first ... first + n - 1 (n at most
   * OccupiedRun, within one chunk) to `out`, for values cheaper found
   * together (a transfer function's, OpacityTransferFunction::Extinctions());
   * the same counts and sums, added in the same order.
   */
  template <typename Run>
  static void CountOccupiedChunkRuns(std::size_t count, const Run& run,
    const ParallelFor& parallelFor, const std::vector<char>& known, std::vector<double>& occupied,
    std::vector<double>& sums)
  {
    constexpr std::size_t Chunk = OccupiedChunk;
    const std::size_t chunks = (count + Chunk - 1) / Chunk;
    occupied.resize(chunks, 0.0);
    sums.resize(chunks, 0.0);
    parallelFor(0, chunks,
      [&](std::size_t begin, std::size_t end)
      {
        float values[OccupiedRun];
        for (std::size_t c = begin; c < end; ++c)
        {
          if (!known.empty() && known[c])
          {
            continue;
          }
          double n = 0.0, sum = 0.0;
          const std::size_t last = std::min(count, (c + 1) * Chunk);
          for (std::size_t first = c * Chunk; first < last; first += OccupiedRun)
          {
            const std::size_t length = std::min(OccupiedRun, last - first);
            run(first, length, values);
            for (std::size_t i = 0; i < length; ++i)
            {
              if (values[i] > 0.f)
              {
                n += 1.0;
                sum += values[i];
              }
            }
          }
          occupied[c] = n;
          sums[c] = sum;
        }
      });
  }
  /// CountOccupied()'s totals, from its chunks' counts and sums, in order.
  void SetOccupied(
    double values, const std::vector<double>& occupied, const std::vector<double>& sums);

  Box Bounds;
  MajorantGrid Majorants;
  // Set by grids: their values (or voxels) in all, those above 0, and the
  // sum of those.
  double GridValues = 0.0;
  double OccupiedValues = 0.0;
  double OccupiedSum = 0.0;
};

/**
 * Dense density on a regular grid (a vtkImageData's array): point values are
 * interpolated trilinearly (or the nearest point's value is taken), cell
 * values are constant per cell. Majorants are kept per block of
 * BlockSize^3 cells.
 */
class GridDensity : public DensityField
{
public:
  static constexpr int BlockSize = 8;
  enum class Interpolation
  {
    Linear,
    Nearest
  };

  /**
   * `dims` counts the values along each axis: points (>= 2 each) or cells
   * (>= 1 each). Interpolation applies to point values; cell values are
   * constant per cell either way.
   */
  GridDensity(const Box& bounds, std::array<int, 3> dims, std::vector<float> values,
    bool cellValues, Interpolation interpolation = Interpolation::Linear,
    const ParallelFor& parallelFor = SerialFor());
  /// The values in their own type, in memory that may be someone else's (a
  /// VTK array's: vtkBrumeSceneConversion reads float, 8- and 16-bit arrays
  /// in place).
  GridDensity(const Box& bounds, std::array<int, 3> dims, TypedValues values, bool cellValues,
    Interpolation interpolation = Interpolation::Linear,
    const ParallelFor& parallelFor = SerialFor());
  float Evaluate(const Vec3& p) const override;
  std::array<int, 3> NativeResolution() const override;
  Box NativeBox() const override;
  /// The most samples per axis NativeSamples() takes.
  static constexpr int MaxNativeSamples = 8;
  /**
   * Point values, interpolated linearly: the s^3 samples (s at most
   * MaxNativeSamples) of native cell (i, j, k) around point (i, j, k),
   * each interpolated from its corner points, written to `out` (x
   * fastest), where NativeMean() puts them; false for other grids.
   */
  bool NativeSamples(int i, int j, int k, int s, float* out) const;
  /**
   * The arithmetic of NativeSamples() for point `index` of a grid of
   * `dims` points whose values `at(x, y, z)` gives (it is asked for points
   * within one of `index` only): for a caller that holds the points already.
   */
  template <typename At>
  static void InterpolateNativeSamples(
    const int index[3], const std::array<int, 3>& dims, int s, const At& at, float* out)
  {
    // Along each axis, sample m sits (m + 1/2) / s - 1/2 point spacings from
    // its point: between two points (clamped at the grid's ends, where the
    // bounds clamp it), with its weight on the second.
    int first[3][MaxNativeSamples], second[3][MaxNativeSamples];
    float weight[3][MaxNativeSamples];
    for (int a = 0; a < 3; ++a)
    {
      const int n = dims[a];
      for (int m = 0; m < s; ++m)
      {
        const float u = (static_cast<float>(m) + 0.5f) / static_cast<float>(s) - 0.5f;
        const float x =
          std::clamp(static_cast<float>(index[a]) + u, 0.f, static_cast<float>(n - 1));
        const int i0 = n == 1 ? 0 : std::min(n - 2, static_cast<int>(x));
        first[a][m] = i0;
        second[a][m] = std::min(i0 + 1, n - 1);
        weight[a][m] = n == 1 ? 0.f : x - static_cast<float>(i0);
      }
    }
    // Separably, the same operations as one trilinear interpolation per
    // sample (the same floats): along x for each row of points the samples
    // read (at most 3 x 3), then along y, then along z.
    auto lerp = [](float a, float b, float t) { return a + (b - a) * t; };
    int low[3], high[3];
    for (int a = 0; a < 3; ++a)
    {
      low[a] = first[a][0];
      high[a] = second[a][s - 1];
    }
    constexpr int M = MaxNativeSamples;
    float alongX[3][3][M], alongY[3][M][M];
    for (int z = low[2]; z <= high[2]; ++z)
      for (int y = low[1]; y <= high[1]; ++y)
        for (int x = 0; x < s; ++x)
        {
          alongX[z - low[2]][y - low[1]][x] =
            lerp(at(first[0][x], y, z), at(second[0][x], y, z), weight[0][x]);
        }
    for (int z = low[2]; z <= high[2]; ++z)
      for (int y = 0; y < s; ++y)
        for (int x = 0; x < s; ++x)
        {
          alongY[z - low[2]][y][x] = lerp(alongX[z - low[2]][first[1][y] - low[1]][x],
            alongX[z - low[2]][second[1][y] - low[1]][x], weight[1][y]);
        }
    for (int z = 0; z < s; ++z)
      for (int y = 0; y < s; ++y)
        for (int x = 0; x < s; ++x)
        {
          *out++ = lerp(
            alongY[first[2][z] - low[2]][y][x], alongY[second[2][z] - low[2]][y][x], weight[2][z]);
        }
  }
  double NativeMean(int i, int j, int k, const Box& cell, const Box& bounds, int s) const override;
  /// Point values interpolated linearly: the values themselves.
  bool NativePoints(
    const std::array<int, 3>& lower, const std::array<int, 3>& count, float* out) const override;
  /// The value itself: point values are the native cells' centres, cell
  /// values the cells.
  float NativeValue(int i, int j, int k, const Vec3& centre) const override
  {
    (void)centre;
    return this->Value(i, j, k);
  }

  /**
   * Per majorant block (in GetMajorants()'s order), the smallest and largest
   * of the values its cells interpolate: its cells' own values, or the
   * points on its cells' corners. The value anywhere in a block lies in
   * that range. Found once, by the constructor.
   */
  void BlockRanges(std::vector<float>& lo, std::vector<float>& hi) const
  {
    lo = this->BlockLow;
    hi = this->BlockHigh;
  }
  bool ValueRanges(std::vector<float>& lo, std::vector<float>& hi) const override
  {
    this->BlockRanges(lo, hi);
    return true;
  }
  const std::array<int, 3>& GetDimensions() const { return this->Dims; }
  const TypedValues& GetValues() const { return this->Values; }
  bool HasCellValues() const { return this->CellValues; }
  Interpolation GetInterpolation() const { return this->Interpolated; }
  /// How many values a grid of integers holds of each (GetValueCounts()).
  struct ValueCounts
  {
    int Lowest = 0;                    // the integer Counts[0] counts
    std::vector<std::uint64_t> Counts; // empty: the values are not integers
  };
  /**
   * Values that are integers (8- or 16-bit ones, or floats that are all
   * whole numbers from -32768 to 65535, as a scan saved as floats): how
   * many values the grid holds of each integer, so that a transfer
   * function's occupancy (ClassifiedDensity) costs a lookup per integer,
   * not per value. Counted at the first call, on `parallelFor`, and kept
   * (thread safe): a grid no function classifies never counts. Empty for
   * other floats (found at their first fraction or non-finite value).
   */
  const ValueCounts& GetValueCounts(const ParallelFor& parallelFor) const;
  /**
   * Per chunk of OccupiedChunk values (in the order of the values), the
   * smallest and largest value, two floats each (NaN where one is not
   * finite): what a transfer function's occupancy of the chunk depends on
   * (ClassifiedDensity keeps a chunk's across an edit that leaves the
   * function as it was over that range). Found at the first call, on
   * `parallelFor`, and kept (thread safe).
   */
  const std::vector<float>& GetChunkRanges(const ParallelFor& parallelFor) const;

private:
  float Value(int i, int j, int k) const
  {
    return this->Values[(static_cast<std::size_t>(k) * this->Dims[1] + j) * this->Dims[0] + i];
  }
  void FindBlockRanges(const ParallelFor& parallelFor);
  ValueCounts CountValues(const ParallelFor& parallelFor) const;

  std::array<int, 3> Dims;
  TypedValues Values;
  bool CellValues;
  Interpolation Interpolated;
  std::vector<float> BlockLow, BlockHigh;
  // What is found of the values at the first call that needs it.
  struct FoundOnce
  {
    std::once_flag CountsOnce, RangesOnce;
    ValueCounts Counts;
    std::vector<float> ChunkRanges;
  };
  std::shared_ptr<FoundOnce> Found = std::make_shared<FoundOnce>();
};

} // namespace brume

#endif
