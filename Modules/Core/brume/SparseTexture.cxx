// SPDX-License-Identifier: BSD-3-Clause
#include "brume/SparseTexture.h"

#include "brume/BrickedGrid.h"

#include <algorithm>
#include <cmath>

namespace brume
{

std::vector<std::uint8_t> SparseTexture::CellsRead(
  const std::array<int, 3>& dims, const Box& box, const BrickedGrid& density)
{
  std::size_t cells = 1;
  for (int a = 0; a < 3; ++a)
  {
    cells *= static_cast<std::size_t>(std::max(dims[a], 0));
  }
  std::vector<std::uint8_t> near(cells, 0);
  if (cells == 0 || density.Empty())
  {
    return near;
  }
  // Texture cells whose box meets a non-zero density cell's centre give or
  // take one density cell (where trilinear interpolation reaches it) ...
  const auto& nativeDims = density.GetDims();
  const Box& nativeBox = density.GetBox();
  double lower[3], cell[3], nativeLower[3], nativeCell[3];
  for (int a = 0; a < 3; ++a)
  {
    lower[a] = box.lower[a];
    cell[a] = (static_cast<double>(box.upper[a]) - box.lower[a]) / dims[a];
    nativeLower[a] = nativeBox.lower[a];
    nativeCell[a] = (static_cast<double>(nativeBox.upper[a]) - nativeBox.lower[a]) / nativeDims[a];
  }
  auto index = [&](int i, int j, int k)
  { return (static_cast<std::size_t>(k) * dims[1] + j) * dims[0] + i; };
  density.ForEachNonZeroCell(
    [&](int i, int j, int k, float value)
    {
      if (value == 0.f)
      {
        return;
      }
      const int c[3] = { i, j, k };
      int from[3], to[3];
      for (int a = 0; a < 3; ++a)
      {
        const double centre = nativeLower[a] + (c[a] + 0.5) * nativeCell[a];
        from[a] = static_cast<int>(std::floor((centre - nativeCell[a] - lower[a]) / cell[a]));
        to[a] = static_cast<int>(std::floor((centre + nativeCell[a] - lower[a]) / cell[a]));
        from[a] = std::max(from[a], 0);
        to[a] = std::min(to[a], dims[a] - 1);
        if (from[a] > to[a])
        {
          return; // outside the texture's box
        }
      }
      for (int z = from[2]; z <= to[2]; ++z)
        for (int y = from[1]; y <= to[1]; ++y)
          for (int x = from[0]; x <= to[0]; ++x)
          {
            near[index(x, y, z)] = 1;
          }
    });
  // ... and their neighbours, whose values trilinear interpolation of the
  // texture mixes in up to one cell away.
  for (int a = 0; a < 3; ++a)
  {
    std::vector<std::uint8_t> grown(near);
    const std::size_t step =
      a == 0 ? 1 : (a == 1 ? dims[0] : static_cast<std::size_t>(dims[0]) * dims[1]);
    for (int k = 0; k < dims[2]; ++k)
      for (int j = 0; j < dims[1]; ++j)
        for (int i = 0; i < dims[0]; ++i)
        {
          const std::size_t n = index(i, j, k);
          const int at = a == 0 ? i : (a == 1 ? j : k);
          if (near[n] || (at > 0 && near[n - step]) || (at + 1 < dims[a] && near[n + step]))
          {
            grown[n] = 1;
          }
        }
    near.swap(grown);
  }
  return near;
}

SparseTexture SparseTexture::WhereDensity(
  const std::array<int, 3>& dims, const Box& box, const BrickedGrid& density)
{
  SparseTexture t;
  t.Dims = dims;
  std::size_t bricks = 1;
  for (int a = 0; a < 3; ++a)
  {
    t.BrickDims[a] = BricksAlong(dims[a]);
    bricks *= static_cast<std::size_t>(t.BrickDims[a]);
  }
  t.Slots.assign(bricks, -1);
  const std::vector<std::uint8_t> read = CellsRead(dims, box, density);
  std::size_t cell = 0;
  for (int k = 0; k < dims[2]; ++k)
    for (int j = 0; j < dims[1]; ++j)
      for (int i = 0; i < dims[0]; ++i, ++cell)
      {
        if (read[cell])
        {
          const std::size_t b = (static_cast<std::size_t>(k / BrickEdge(dims[2])) * t.BrickDims[1] +
                                  j / BrickEdge(dims[1])) *
              t.BrickDims[0] +
            i / BrickEdge(dims[0]);
          t.Slots[b] = 0;
        }
      }
  for (std::int32_t& slot : t.Slots)
  {
    if (slot == 0)
    {
      slot = static_cast<std::int32_t>(t.Stored++);
    }
  }
  return t;
}

std::ptrdiff_t SparseTexture::BrickCellOf(int i, int j, int k) const
{
  const int ex = BrickEdge(this->Dims[0]), ey = BrickEdge(this->Dims[1]),
            ez = BrickEdge(this->Dims[2]);
  const std::size_t b =
    (static_cast<std::size_t>(k / ez) * this->BrickDims[1] + j / ey) * this->BrickDims[0] + i / ex;
  if (this->Slots[b] < 0)
  {
    return -1;
  }
  return static_cast<std::ptrdiff_t>(this->Slots[b]) * ex * ey * ez +
    (static_cast<std::ptrdiff_t>(k % ez) * ey + j % ey) * ex + i % ex;
}

std::vector<float> SparseTexture::Gather(const std::vector<float>& values, int components) const
{
  std::vector<float> bricks(this->Stored * this->GetBrickCells() * components, 0.f);
  std::size_t cell = 0;
  for (int k = 0; k < this->Dims[2]; ++k)
    for (int j = 0; j < this->Dims[1]; ++j)
      for (int i = 0; i < this->Dims[0]; ++i, ++cell)
      {
        const std::ptrdiff_t at = this->BrickCellOf(i, j, k);
        if (at >= 0)
        {
          std::copy_n(values.begin() + static_cast<std::ptrdiff_t>(cell) * components, components,
            bricks.begin() + at * components);
        }
      }
  return bricks;
}

} // namespace brume
