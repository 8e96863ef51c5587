// SPDX-License-Identifier: BSD-3-Clause
#include "brume/Density.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>
#include <type_traits>

namespace brume
{

float MajorantGrid::GlobalMax() const
{
  return this->Max.empty() ? 0.f : *std::max_element(this->Max.begin(), this->Max.end());
}

void MajorantGrid::MarkEmptyRegions()
{
  this->EmptyRegions.clear();
  this->RegionDims = { 0, 0, 0 };
  const std::size_t blocks =
    static_cast<std::size_t>(this->Dims[0]) * this->Dims[1] * this->Dims[2];
  if (this->Max.size() != blocks ||
    std::max({ this->Dims[0], this->Dims[1], this->Dims[2] }) <= RegionBlocks)
  {
    return;
  }
  for (int a = 0; a < 3; ++a)
  {
    this->RegionDims[a] = (this->Dims[a] + RegionBlocks - 1) / RegionBlocks;
  }
  this->EmptyRegions.assign(
    static_cast<std::size_t>(this->RegionDims[0]) * this->RegionDims[1] * this->RegionDims[2], 1);
  for (int k = 0; k < this->Dims[2]; ++k)
    for (int j = 0; j < this->Dims[1]; ++j)
    {
      const float* row =
        &this->Max[(static_cast<std::size_t>(k) * this->Dims[1] + j) * this->Dims[0]];
      unsigned char* regions =
        &this->EmptyRegions[(static_cast<std::size_t>(k / RegionBlocks) * this->RegionDims[1] +
                              j / RegionBlocks) *
          this->RegionDims[0]];
      for (int i = 0; i < this->Dims[0]; ++i)
      {
        if (!(row[i] == 0.f))
        {
          regions[i / RegionBlocks] = 0;
        }
      }
    }
}

std::size_t DensityField::NumberOfOccupiedBlocks() const
{
  return static_cast<std::size_t>(std::count_if(
    this->Majorants.Max.begin(), this->Majorants.Max.end(), [](float m) { return m > 0.f; }));
}

double DensityField::OccupiedFraction() const
{
  if (this->GridValues > 0.0)
  {
    return std::clamp(this->OccupiedValues / this->GridValues, 1.0 / this->GridValues, 1.0);
  }
  const std::size_t blocks = this->Majorants.Max.size();
  return blocks == 0 ? 1.0
                     : std::max(static_cast<double>(this->NumberOfOccupiedBlocks()), 1.0) /
      static_cast<double>(blocks);
}

double DensityField::MeanOccupiedDensity() const
{
  return this->OccupiedValues > 0.0 ? this->OccupiedSum / this->OccupiedValues
                                    : this->Majorants.GlobalMax();
}

void DensityField::SetOccupied(
  double values, const std::vector<double>& occupied, const std::vector<double>& sums)
{
  this->GridValues = values;
  this->OccupiedValues = 0.0;
  this->OccupiedSum = 0.0;
  for (std::size_t c = 0; c < occupied.size(); ++c)
  {
    this->OccupiedValues += occupied[c];
    this->OccupiedSum += sums[c];
  }
}

double DensityField::NativeMean(
  int i, int j, int k, const Box& cell, const Box& bounds, int s) const
{
  (void)i;
  (void)j;
  (void)k;
  double sum = 0.0;
  const Vec3 size = cell.Extent();
  for (int z = 0; z < s; ++z)
    for (int y = 0; y < s; ++y)
      for (int x = 0; x < s; ++x)
      {
        const Vec3 f((static_cast<float>(x) + 0.5f) / static_cast<float>(s),
          (static_cast<float>(y) + 0.5f) / static_cast<float>(s),
          (static_cast<float>(z) + 0.5f) / static_cast<float>(s));
        Vec3 p = cell.lower + size * f;
        for (int a = 0; a < 3; ++a)
        {
          p[a] = std::clamp(p[a], bounds.lower[a], bounds.upper[a]);
        }
        sum += this->Evaluate(p);
      }
  return sum / (static_cast<double>(s) * s * s);
}

bool GridDensity::NativeSamples(int i, int j, int k, int s, float* out) const
{
  if (this->CellValues || this->Interpolated != Interpolation::Linear || s < 1 ||
    s > MaxNativeSamples)
  {
    return false;
  }
  // The samples lie within half a spacing of point (i, j, k): the points
  // they read are at most the 3^3 around it, read once.
  const int index[3] = { i, j, k };
  int lo[3], count[3];
  for (int a = 0; a < 3; ++a)
  {
    lo[a] = std::max(0, index[a] - 1);
    count[a] = std::min(this->Dims[a] - 1, index[a] + 1) - lo[a] + 1;
  }
  float near[27];
  this->Values.Visit(
    [&](const auto* values)
    {
      float* to = near;
      for (int z = 0; z < count[2]; ++z)
        for (int y = 0; y < count[1]; ++y)
        {
          const auto* row = values +
            (static_cast<std::size_t>(lo[2] + z) * this->Dims[1] + lo[1] + y) * this->Dims[0];
          for (int x = 0; x < count[0]; ++x)
          {
            *to++ = static_cast<float>(row[lo[0] + x]);
          }
        }
    });
  InterpolateNativeSamples(
    index, this->Dims, s,
    [&](int x, int y, int z)
    { return near[((z - lo[2]) * count[1] + (y - lo[1])) * count[0] + (x - lo[0])]; },
    out);
  return true;
}

double GridDensity::NativeMean(int i, int j, int k, const Box& cell, const Box& bounds, int s) const
{
  float samples[MaxNativeSamples * MaxNativeSamples * MaxNativeSamples];
  if (!this->NativeSamples(i, j, k, s, samples))
  {
    return DensityField::NativeMean(i, j, k, cell, bounds, s);
  }
  return NativeSampleMean(samples, s * s * s);
}

std::array<int, 3> DensityField::NativeResolution() const
{
  constexpr int Cells = 8; // cells per majorant block
  return { this->Majorants.Dims[0] * Cells, this->Majorants.Dims[1] * Cells,
    this->Majorants.Dims[2] * Cells };
}

bool GridDensity::NativePoints(
  const std::array<int, 3>& lower, const std::array<int, 3>& count, float* out) const
{
  if (this->CellValues || this->Interpolated != Interpolation::Linear)
  {
    return false;
  }
  const std::array<int, 3>& dims = this->Dims;
  this->Values.Visit(
    [&](const auto* values)
    {
      for (int z = 0; z < count[2]; ++z)
        for (int y = 0; y < count[1]; ++y)
        {
          const auto* row =
            values + (static_cast<std::size_t>(lower[2] + z) * dims[1] + lower[1] + y) * dims[0];
          for (int x = 0; x < count[0]; ++x)
          {
            *out++ = static_cast<float>(row[lower[0] + x]);
          }
        }
    });
  return true;
}

std::array<int, 3> GridDensity::NativeResolution() const
{
  // One cell per value: cell values are the cells, point values the
  // centres of cells around the points.
  return this->Dims;
}

Box GridDensity::NativeBox() const
{
  if (this->CellValues)
  {
    return this->Bounds;
  }
  // Half a point spacing beyond the bounds on every side (an axis of one
  // point: the bounds' extent).
  Box box = this->Bounds;
  for (int a = 0; a < 3; ++a)
  {
    const float half = this->Dims[a] > 1
      ? 0.5f * this->Bounds.Extent()[a] / static_cast<float>(this->Dims[a] - 1)
      : 0.f;
    box.lower[a] -= half;
    box.upper[a] += half;
  }
  return box;
}

namespace
{
TypedValues Buffer(const std::vector<float>& values)
{
  FloatBuffer buffer = FloatBuffer::Allocate(values.size());
  std::copy(values.begin(), values.end(), buffer.Data());
  return TypedValues(std::move(buffer));
}
}

const GridDensity::ValueCounts& GridDensity::GetValueCounts(const ParallelFor& parallelFor) const
{
  FoundOnce& found = *this->Found;
  std::call_once(found.CountsOnce, [&]() { found.Counts = this->CountValues(parallelFor); });
  return found.Counts;
}

const std::vector<float>& GridDensity::GetChunkRanges(const ParallelFor& parallelFor) const
{
  FoundOnce& found = *this->Found;
  std::call_once(found.RangesOnce,
    [&]()
    {
      const std::size_t count = this->Values.Size();
      const std::size_t chunks = (count + OccupiedChunk - 1) / OccupiedChunk;
      std::vector<float>& ranges = found.ChunkRanges;
      ranges.assign(2 * chunks, 0.f);
      this->Values.Visit(
        [&](const auto* stored)
        {
          parallelFor(0, chunks,
            [&](std::size_t begin, std::size_t end)
            {
              for (std::size_t c = begin; c < end; ++c)
              {
                float lo = static_cast<float>(stored[c * OccupiedChunk]), hi = lo;
                bool finite = true;
                for (std::size_t i = c * OccupiedChunk;
                     i < std::min(count, (c + 1) * OccupiedChunk); ++i)
                {
                  const float v = static_cast<float>(stored[i]);
                  finite = finite && std::isfinite(v);
                  lo = std::min(lo, v);
                  hi = std::max(hi, v);
                }
                ranges[2 * c] = finite ? lo : std::numeric_limits<float>::quiet_NaN();
                ranges[2 * c + 1] = finite ? hi : std::numeric_limits<float>::quiet_NaN();
              }
            });
        });
    });
  return found.ChunkRanges;
}

GridDensity::ValueCounts GridDensity::CountValues(const ParallelFor& parallelFor) const
{
  constexpr std::size_t Chunk = std::size_t(1) << 22;
  const std::size_t count = this->Values.Size();
  const std::size_t chunks = (count + Chunk - 1) / Chunk;
  // The integers the values take: a type's whole range, or the range of
  // floats that are all whole numbers within 16 bits' (a scan saved as
  // floats); none for other floats, found at their first fraction.
  int lowest = 0, highest = -1;
  this->Values.Visit(
    [&](const auto* stored)
    {
      using Stored = std::remove_cv_t<std::remove_pointer_t<decltype(stored)>>;
      if constexpr (std::is_integral_v<Stored>)
      {
        lowest = static_cast<int>(std::numeric_limits<Stored>::lowest());
        highest = static_cast<int>(std::numeric_limits<Stored>::max());
      }
      else
      {
        constexpr float Low = -32768.f, High = 65535.f;
        std::atomic<bool> whole{ count > 0 };
        std::vector<float> lows(chunks, High), highs(chunks, Low);
        parallelFor(0, chunks,
          [&](std::size_t begin, std::size_t end)
          {
            for (std::size_t c = begin; c < end && whole.load(std::memory_order_relaxed); ++c)
            {
              float lo = High, hi = Low;
              for (std::size_t i = c * Chunk; i < std::min(count, (c + 1) * Chunk); ++i)
              {
                const float v = stored[i];
                // NaN fails every comparison: not whole.
                if (!(v >= Low && v <= High && v == std::floor(v)))
                {
                  whole.store(false, std::memory_order_relaxed);
                  return;
                }
                lo = std::min(lo, v);
                hi = std::max(hi, v);
              }
              lows[c] = lo;
              highs[c] = hi;
            }
          });
        if (whole.load())
        {
          lowest = static_cast<int>(*std::min_element(lows.begin(), lows.end()));
          highest = static_cast<int>(*std::max_element(highs.begin(), highs.end()));
        }
      }
    });
  if (highest < lowest)
  {
    return {};
  }
  // Counts per chunk of values, added together: integers, so the same
  // whatever the threads.
  const std::size_t bins = static_cast<std::size_t>(highest - lowest) + 1;
  std::vector<std::uint64_t> counts(bins, 0);
  std::mutex adding;
  this->Values.Visit(
    [&](const auto* stored)
    {
      parallelFor(0, chunks,
        [&](std::size_t begin, std::size_t end)
        {
          std::vector<std::uint64_t> mine(bins, 0);
          for (std::size_t i = begin * Chunk; i < std::min(count, end * Chunk); ++i)
          {
            ++mine[static_cast<std::size_t>(static_cast<int>(stored[i]) - lowest)];
          }
          const std::lock_guard<std::mutex> lock(adding);
          for (std::size_t b = 0; b < bins; ++b)
          {
            counts[b] += mine[b];
          }
        });
    });
  return { lowest, std::move(counts) };
}

GridDensity::GridDensity(const Box& bounds, std::array<int, 3> dims, std::vector<float> values,
  bool cellValues, Interpolation interpolation, const ParallelFor& parallelFor)
  : GridDensity(bounds, dims, Buffer(values), cellValues, interpolation, parallelFor)
{
}

GridDensity::GridDensity(const Box& bounds, std::array<int, 3> dims, TypedValues values,
  bool cellValues, Interpolation interpolation, const ParallelFor& parallelFor)
  : Dims(dims)
  , Values(std::move(values))
  , CellValues(cellValues)
  , Interpolated(interpolation)
{
  this->Bounds = bounds;
  this->Values.Visit(
    [&](const auto* stored)
    {
      this->CountOccupied(
        this->Values.Size(), [stored](std::size_t i) { return static_cast<float>(stored[i]); },
        parallelFor);
    });
  // Cells of the grid (point data: one fewer than the points).
  std::array<int, 3> cells{};
  for (int a = 0; a < 3; ++a)
  {
    cells[a] = cellValues ? dims[a] : std::max(1, dims[a] - 1);
  }
  MajorantGrid& mg = this->Majorants;
  mg.Bounds = bounds;
  for (int a = 0; a < 3; ++a)
  {
    mg.Dims[a] = (cells[a] + BlockSize - 1) / BlockSize;
  }
  // Blocks are BlockSize cells wide: the majorant grid's box is a whole number of blocks.
  for (int a = 0; a < 3; ++a)
  {
    const double cell = static_cast<double>(bounds.Extent()[a]) / cells[a];
    mg.Bounds.upper[a] = static_cast<float>(bounds.lower[a] + cell * BlockSize * mg.Dims[a]);
  }
  // A density's majorant is its largest value in the block (0 where none is positive).
  this->FindBlockRanges(parallelFor);
  const std::vector<float>& hi = this->BlockHigh;
  mg.Max.resize(hi.size());
  std::transform(hi.begin(), hi.end(), mg.Max.begin(), [](float v) { return v > 0.f ? v : 0.f; });
  mg.MarkEmptyRegions();
}

void GridDensity::FindBlockRanges(const ParallelFor& parallelFor)
{
  const MajorantGrid& mg = this->Majorants;
  const std::size_t blocks = static_cast<std::size_t>(mg.Dims[0]) * mg.Dims[1] * mg.Dims[2];
  std::vector<float>& lo = this->BlockLow;
  std::vector<float>& hi = this->BlockHigh;
  lo.assign(blocks, std::numeric_limits<float>::infinity());
  hi.assign(blocks, -std::numeric_limits<float>::infinity());
  // A block's cells read the values of indices [first, last] along each
  // axis: its own cells, and for point values the points one beyond.
  const int reach = this->CellValues ? 0 : 1;
  parallelFor(0, static_cast<std::size_t>(mg.Dims[2]),
    [&](std::size_t kBegin, std::size_t kEnd)
    {
      for (int bk = static_cast<int>(kBegin); bk < static_cast<int>(kEnd); ++bk)
      {
        std::size_t b = static_cast<std::size_t>(bk) * mg.Dims[1] * mg.Dims[0];
        for (int bj = 0; bj < mg.Dims[1]; ++bj)
          for (int bi = 0; bi < mg.Dims[0]; ++bi, ++b)
          {
            const int block[3] = { bi, bj, bk };
            int first[3], last[3];
            for (int a = 0; a < 3; ++a)
            {
              first[a] = block[a] * BlockSize;
              last[a] = std::min(this->Dims[a] - 1, first[a] + BlockSize - 1 + reach);
            }
            float l = lo[b], h = hi[b];
            for (int k = first[2]; k <= last[2]; ++k)
              for (int j = first[1]; j <= last[1]; ++j)
                for (int i = first[0]; i <= last[0]; ++i)
                {
                  const float v = this->Value(i, j, k);
                  l = std::min(l, v);
                  h = std::max(h, v);
                }
            lo[b] = l;
            hi[b] = h;
          }
      }
    });
}

float GridDensity::Evaluate(const Vec3& p) const
{
  const Vec3 q = (p - this->Bounds.lower) / this->Bounds.Extent();
  if (this->CellValues || this->Interpolated == Interpolation::Nearest)
  {
    // The cell's value, or the nearest point's.
    int idx[3];
    for (int a = 0; a < 3; ++a)
    {
      const float x = this->CellValues ? q[a] * static_cast<float>(this->Dims[a])
                                       : q[a] * static_cast<float>(this->Dims[a] - 1) + 0.5f;
      idx[a] = std::min(this->Dims[a] - 1, std::max(0, static_cast<int>(x)));
    }
    return this->Value(idx[0], idx[1], idx[2]);
  }
  // Trilinear interpolation between point values.
  int i0[3];
  float f[3];
  for (int a = 0; a < 3; ++a)
  {
    const int n = this->Dims[a];
    if (n == 1)
    {
      i0[a] = 0;
      f[a] = 0.f;
      continue;
    }
    const float x = std::min(std::max(q[a], 0.f), 1.f) * static_cast<float>(n - 1);
    i0[a] = std::min(n - 2, static_cast<int>(x));
    f[a] = x - static_cast<float>(i0[a]);
  }
  const int i1[3] = { std::min(i0[0] + 1, this->Dims[0] - 1),
    std::min(i0[1] + 1, this->Dims[1] - 1), std::min(i0[2] + 1, this->Dims[2] - 1) };
  auto lerp = [](float a, float b, float t) { return a + (b - a) * t; };
  const float c00 = lerp(this->Value(i0[0], i0[1], i0[2]), this->Value(i1[0], i0[1], i0[2]), f[0]);
  const float c10 = lerp(this->Value(i0[0], i1[1], i0[2]), this->Value(i1[0], i1[1], i0[2]), f[0]);
  const float c01 = lerp(this->Value(i0[0], i0[1], i1[2]), this->Value(i1[0], i0[1], i1[2]), f[0]);
  const float c11 = lerp(this->Value(i0[0], i1[1], i1[2]), this->Value(i1[0], i1[1], i1[2]), f[0]);
  return lerp(lerp(c00, c10, f[1]), lerp(c01, c11, f[1]), f[2]);
}

} // namespace brume
