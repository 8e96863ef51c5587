// SPDX-License-Identifier: BSD-3-Clause
#include "brume/Density.h"

#include <algorithm>
#include <cmath>

namespace brume
{

float MajorantGrid::GlobalMax() const
{
  return this->Max.empty() ? 0.f : *std::max_element(this->Max.begin(), this->Max.end());
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

std::array<int, 3> DensityField::NativeResolution() const
{
  constexpr int Cells = 8; // cells per majorant block
  return { this->Majorants.Dims[0] * Cells, this->Majorants.Dims[1] * Cells,
    this->Majorants.Dims[2] * Cells };
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

GridDensity::GridDensity(
  const Box& bounds, std::array<int, 3> dims, std::vector<float> values, bool cellValues)
  : Dims(dims)
  , Values(std::move(values))
  , CellValues(cellValues)
{
  this->Bounds = bounds;
  this->GridValues = static_cast<double>(this->Values.size());
  for (const float v : this->Values)
  {
    if (v > 0.f)
    {
      this->OccupiedValues += 1.0;
      this->OccupiedSum += v;
    }
  }
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
  mg.Max.assign(static_cast<std::size_t>(mg.Dims[0]) * mg.Dims[1] * mg.Dims[2], 0.f);
  // Blocks are BlockSize cells wide: the majorant grid's box is a whole number of blocks.
  for (int a = 0; a < 3; ++a)
  {
    const double cell = static_cast<double>(bounds.Extent()[a]) / cells[a];
    mg.Bounds.upper[a] = static_cast<float>(bounds.lower[a] + cell * BlockSize * mg.Dims[a]);
  }
  // A value influences the blocks of the cells it touches: its own cell, or,
  // for point values, the up to eight cells sharing the point.
  const int reach = cellValues ? 0 : 1;
  for (int k = 0; k < dims[2]; ++k)
  {
    for (int j = 0; j < dims[1]; ++j)
    {
      for (int i = 0; i < dims[0]; ++i)
      {
        const float v = this->Value(i, j, k);
        if (!(v > 0.f))
        {
          continue;
        }
        const int ijk[3] = { i, j, k };
        int lo[3], hi[3];
        for (int a = 0; a < 3; ++a)
        {
          lo[a] = std::max(0, ijk[a] - reach) / BlockSize;
          hi[a] = std::min(cells[a] - 1, ijk[a]) / BlockSize;
        }
        for (int bk = lo[2]; bk <= hi[2]; ++bk)
          for (int bj = lo[1]; bj <= hi[1]; ++bj)
            for (int bi = lo[0]; bi <= hi[0]; ++bi)
            {
              float& m = mg.Max[(static_cast<std::size_t>(bk) * mg.Dims[1] + bj) * mg.Dims[0] + bi];
              m = std::max(m, v);
            }
      }
    }
  }
}

float GridDensity::Evaluate(const Vec3& p) const
{
  const Vec3 q = (p - this->Bounds.lower) / this->Bounds.Extent();
  if (this->CellValues)
  {
    int idx[3];
    for (int a = 0; a < 3; ++a)
    {
      idx[a] = std::min(this->Dims[a] - 1, std::max(0, static_cast<int>(q[a] * this->Dims[a])));
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
