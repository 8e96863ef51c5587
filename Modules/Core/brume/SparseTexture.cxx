// SPDX-License-Identifier: BSD-3-Clause
#include "brume/SparseTexture.h"

#include "brume/BrickedGrid.h"

#include <algorithm>
#include <cmath>

namespace brume
{

std::vector<std::uint8_t> SparseTexture::CellsRead(const std::array<int, 3>& dims, const Box& box,
  const BrickedGrid& density, const ParallelFor& parallelFor)
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
  // take one density cell (where trilinear interpolation reaches it): per
  // axis, the texture cells each density cell reaches ...
  const auto& nativeDims = density.GetDims();
  const Box& nativeBox = density.GetBox();
  std::array<std::vector<int>, 3> from, to;
  for (int a = 0; a < 3; ++a)
  {
    const double lower = box.lower[a];
    const double cell = (static_cast<double>(box.upper[a]) - box.lower[a]) / dims[a];
    const double nativeCell =
      (static_cast<double>(nativeBox.upper[a]) - nativeBox.lower[a]) / nativeDims[a];
    for (int i = 0; i < nativeDims[a]; ++i)
    {
      const double centre = nativeBox.lower[a] + (i + 0.5) * nativeCell;
      from[a].push_back(
        std::max(static_cast<int>(std::floor((centre - nativeCell - lower) / cell)), 0));
      to[a].push_back(
        std::min(static_cast<int>(std::floor((centre + nativeCell - lower) / cell)), dims[a] - 1));
    }
  }
  const std::size_t plane = static_cast<std::size_t>(dims[0]) * dims[1];
  // ... marked for the cells lower..upper (inclusive) of the density, each
  // layer of bricks along z into a slab of its own (the texture's z cells
  // it reaches), on every thread; the slabs are then merged. Marks are only
  // ever set, so the result does not depend on the threads.
  constexpr int Stride = BrickedGrid::Stride, Size = BrickedGrid::Size;
  const auto& bricks = density.GetBrickDims();
  struct Slab
  {
    int First = 0; // the texture's z cell of its first plane
    std::vector<std::uint8_t> Marks;
  };
  std::vector<Slab> slabs(static_cast<std::size_t>(bricks[2]));
  parallelFor(0, slabs.size(),
    [&](std::size_t firstLayer, std::size_t endLayer)
    {
      for (std::size_t layer = firstLayer; layer < endLayer; ++layer)
      {
        const int bk = static_cast<int>(layer);
        const int k0 = Stride * bk;
        const int k1 = (bk == bricks[2] - 1 ? nativeDims[2] : k0 + Stride) - 1;
        Slab& slab = slabs[layer];
        slab.First = from[2][k0];
        const int planes = to[2][k1] - slab.First + 1;
        if (planes <= 0)
        {
          continue;
        }
        std::vector<std::uint8_t>& marks = slab.Marks;
        auto mark = [&](const int lower[3], const int upper[3])
        {
          const int x0 = from[0][lower[0]], x1 = to[0][upper[0]], y0 = from[1][lower[1]],
                    y1 = to[1][upper[1]], z0 = from[2][lower[2]], z1 = to[2][upper[2]];
          if (marks.empty())
          {
            marks.assign(plane * static_cast<std::size_t>(planes), 0);
          }
          for (int z = z0; z <= z1; ++z)
            for (int y = y0; y <= y1; ++y)
            {
              std::uint8_t* row =
                &marks[(static_cast<std::size_t>(z - slab.First) * dims[1] + y) * dims[0]];
              std::fill(row + x0, row + x1 + 1, std::uint8_t(1));
            }
        };
        const FloatBuffer& samples = density.GetSamples();
        for (int bj = 0; bj < bricks[1]; ++bj)
          for (int bi = 0; bi < bricks[0]; ++bi)
          {
            const std::size_t brick =
              (static_cast<std::size_t>(bk) * bricks[1] + bj) * bricks[0] + bi;
            const int slot = density.GetSlots()[brick];
            if (slot < 0 && density.GetConstants()[brick] == 0.f)
            {
              continue;
            }
            // The brick's own cells (Stride per axis, the last brick the rest).
            const int b[3] = { bi, bj, bk };
            int lower[3], upper[3];
            for (int a = 0; a < 3; ++a)
            {
              lower[a] = Stride * b[a];
              upper[a] = (b[a] == bricks[a] - 1 ? nativeDims[a] : lower[a] + Stride) - 1;
            }
            if (slot < 0)
            {
              mark(lower, upper); // one value, not 0, everywhere
              continue;
            }
            const float* values =
              samples.Data() + static_cast<std::size_t>(slot) * BrickedGrid::BrickSamples;
            for (int k = lower[2]; k <= upper[2]; ++k)
              for (int j = lower[1]; j <= upper[1]; ++j)
              {
                // Each run of non-zero cells along the row at once: the
                // texture cells its cells reach are those from its first's
                // to its last's.
                const float* row = values + ((k - lower[2]) * Size + (j - lower[1])) * Size;
                for (int i = lower[0]; i <= upper[0]; ++i)
                {
                  if (row[i - lower[0]] == 0.f)
                  {
                    continue;
                  }
                  int last = i;
                  while (last < upper[0] && row[last + 1 - lower[0]] != 0.f)
                  {
                    ++last;
                  }
                  const int first[3] = { i, j, k }, end[3] = { last, j, k };
                  mark(first, end);
                  i = last;
                }
              }
          }
      }
    });
  for (const Slab& slab : slabs)
  {
    std::uint8_t* out = near.data() + plane * static_cast<std::size_t>(slab.First);
    for (std::size_t c = 0; c < slab.Marks.size(); ++c)
    {
      out[c] |= slab.Marks[c];
    }
  }
  // ... and their neighbours, whose values trilinear interpolation of the
  // texture mixes in up to one cell away.
  auto index = [&](int i, int j, int k)
  { return (static_cast<std::size_t>(k) * dims[1] + j) * dims[0] + i; };
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

SparseTexture SparseTexture::WhereDensity(const std::array<int, 3>& dims, const Box& box,
  const BrickedGrid& density, const ParallelFor& parallelFor)
{
  return FromCellsRead(dims, CellsRead(dims, box, density, parallelFor));
}

SparseTexture SparseTexture::FromCellsRead(
  const std::array<int, 3>& dims, const std::vector<std::uint8_t>& read)
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
  if (read.size() !=
    static_cast<std::size_t>(std::max(dims[0], 0)) * std::max(dims[1], 0) * std::max(dims[2], 0))
  {
    return t; // not a mask of these cells: nothing read
  }
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
