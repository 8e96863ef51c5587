// SPDX-License-Identifier: BSD-3-Clause
#include "brume/CentroidMatching.h"

#include "brume/Vec3.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace brume
{

CentroidMatching::CentroidMatching(
  const std::array<int, 3>& dims, const std::vector<float>& centroids, const ParallelFor& pf)
  : Dims(dims)
{
  const std::size_t nx = dims[0], nxy = nx * dims[1];
  const std::size_t texels = nxy * dims[2];
  if (centroids.size() != 3 * texels)
  {
    throw std::invalid_argument("CentroidMatching: 3 centroid coordinates per texel");
  }
  if (texels > 0xffffffffu)
  {
    throw std::invalid_argument("CentroidMatching: more texels than 32-bit indices hold");
  }
  this->Texels = texels;
  std::vector<std::uint32_t> index(8 * texels);
  std::vector<float> weight(8 * texels);
  pf(0, texels,
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t t = begin; t < end; ++t)
      {
        int i0[3], i1[3];
        float w[3];
        for (int a = 0; a < 3; ++a)
        {
          // CellCentreWeights takes the position as a fraction of the axis.
          const float c = centroids[3 * t + a];
          const CellCentreWeights cw(
            std::isfinite(c) ? (c + 0.5f) / static_cast<float>(dims[a]) : 0.f, dims[a]);
          i0[a] = cw.I0;
          i1[a] = cw.I1;
          w[a] = cw.W;
        }
        for (int k = 0; k < 8; ++k)
        {
          const std::size_t x = (k & 1) ? i1[0] : i0[0], y = (k & 2) ? i1[1] : i0[1],
                            z = (k & 4) ? i1[2] : i0[2];
          index[8 * t + k] = static_cast<std::uint32_t>(z * nxy + y * nx + x);
          weight[8 * t + k] = ((k & 1) ? w[0] : 1.f - w[0]) * ((k & 2) ? w[1] : 1.f - w[1]) *
            ((k & 4) ? w[2] : 1.f - w[2]);
        }
      }
    });
  // Rows whose centroid is their texel's centre (to 10^-4 of its weight)
  // hold V_t = S_t, and so do the texels that no other row interpolates:
  // the iterations need only the texels that off-centre rows interpolate
  // (the columns) and the rows those take part in. A row whose centroid
  // lies outside its texel's own cell sets no equation (far).
  std::vector<char> column(texels, 0), row(texels, 0);
  this->Far.assign(texels, 0);
  for (std::size_t t = 0; t < texels; ++t)
  {
    const std::size_t ijk[3] = { t % nx, (t / nx) % dims[1], t / nxy };
    for (int a = 0; a < 3; ++a)
    {
      const float offset = centroids[3 * t + a] - static_cast<float>(ijk[a]);
      this->Far[t] = this->Far[t] || !(std::abs(offset) <= 0.5f);
    }
    float own = 0.f;
    for (int k = 0; k < 8; ++k)
    {
      own += index[8 * t + k] == t ? weight[8 * t + k] : 0.f;
    }
    if (this->Far[t] || own >= 1.f - 1e-4f)
    {
      for (int k = 0; k < 8; ++k)
      {
        index[8 * t + k] = static_cast<std::uint32_t>(t);
        weight[8 * t + k] = k == 0 ? 1.f : 0.f;
      }
      continue;
    }
    row[t] = 1;
    for (int k = 0; k < 8; ++k)
    {
      column[index[8 * t + k]] = 1;
    }
  }
  for (std::size_t t = 0; t < texels; ++t)
  {
    if (column[t])
    {
      this->Columns.push_back(static_cast<std::uint32_t>(t));
      row[t] = 1;
    }
  }
  for (std::size_t t = 0; t < texels; ++t)
  {
    if (row[t])
    {
      this->Rows.push_back(static_cast<std::uint32_t>(t));
    }
  }
  // The columns' rows in row order, with their weights (a transpose by
  // counting; an identity row counts once, with weight 1).
  std::vector<std::uint32_t> slotOf(texels, 0);
  for (std::size_t c = 0; c < this->Columns.size(); ++c)
  {
    slotOf[this->Columns[c]] = static_cast<std::uint32_t>(c);
  }
  this->ColumnStart.assign(this->Columns.size() + 1, 0);
  auto entries = [&](std::uint32_t t, auto&& f)
  {
    for (int k = 0; k < 8; ++k)
    {
      if (weight[8 * t + k] > 0.f)
      {
        f(index[8 * t + k], weight[8 * t + k]);
      }
    }
  };
  // The rows' entries whose weights are not 0 (a centroid off-centre along
  // one axis interpolates 2 texels, not 8).
  this->RowStart.assign(1, 0);
  for (const std::uint32_t t : this->Rows)
  {
    entries(t,
      [&](std::uint32_t c, float w)
      {
        this->RowColumn.push_back(c);
        this->RowWeight.push_back(w);
        ++this->ColumnStart[slotOf[c] + 1];
      });
    this->RowStart.push_back(this->RowColumn.size());
  }
  for (std::size_t c = 0; c < this->Columns.size(); ++c)
  {
    this->ColumnStart[c + 1] += this->ColumnStart[c];
  }
  std::vector<std::size_t> fill(this->ColumnStart.begin(), this->ColumnStart.end() - 1);
  this->ColumnRow.resize(this->ColumnStart.back());
  this->ColumnWeight.resize(this->ColumnStart.back());
  for (std::size_t r = 0; r < this->Rows.size(); ++r)
  {
    for (std::size_t e = this->RowStart[r]; e < this->RowStart[r + 1]; ++e)
    {
      const std::size_t slot = fill[slotOf[this->RowColumn[e]]]++;
      this->ColumnRow[slot] = static_cast<std::uint32_t>(r);
      this->ColumnWeight[slot] = this->RowWeight[e];
    }
  }
}

double CentroidMatching::Apply(
  std::vector<float>& values, int channels, const ParallelFor& pf) const
{
  const std::size_t texels = this->NumberOfTexels();
  if (channels < 1 || values.size() != texels * static_cast<std::size_t>(channels))
  {
    throw std::invalid_argument("CentroidMatching: values do not match the texels");
  }
  const std::size_t nc = channels;
  const std::size_t rows = this->Rows.size(), columns = this->Columns.size();
  if (columns == 0)
  {
    return 0.0; // every centroid at its texel's centre: V = S
  }
  // Small systems (a homogeneous medium's faces) are solved on this thread:
  // there a parallel loop's start would cost more than its work.
  const ParallelFor serial = SerialFor();
  const ParallelFor& loop = columns >= ParallelColumns ? pf : serial;
  // The rows' estimates (the values before any moves; a texel that no
  // column is keeps its own), and which rows set an equation (a value not
  // 0 in some channel).
  std::vector<float> estimate(rows * nc);
  std::vector<char> equation(rows);
  for (std::size_t r = 0; r < rows; ++r)
  {
    bool any = false;
    for (std::size_t c = 0; c < nc; ++c)
    {
      estimate[nc * r + c] = values[nc * this->Rows[r] + c];
      any = any || estimate[nc * r + c] != 0.f;
    }
    equation[r] = any && !this->Far[this->Rows[r]] ? 1 : 0;
  }
  // Per column: the bounds, and the weight of the equations it takes part in.
  std::vector<float> lower(columns * nc), upper(columns * nc);
  std::vector<double> total(columns);
  const int nx = this->Dims[0], ny = this->Dims[1], nz = this->Dims[2];
  loop(0, columns,
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t col = begin; col < end; ++col)
      {
        const std::size_t t = this->Columns[col];
        const int x = static_cast<int>(t % nx), y = static_cast<int>((t / nx) % ny),
                  z = static_cast<int>(t / (static_cast<std::size_t>(nx) * ny));
        for (std::size_t c = 0; c < nc; ++c)
        {
          lower[nc * col + c] = std::min(0.f, values[nc * t + c]);
          upper[nc * col + c] = std::max(0.f, values[nc * t + c]);
        }
        for (int k = std::max(z - 1, 0); k <= std::min(z + 1, nz - 1); ++k)
          for (int j = std::max(y - 1, 0); j <= std::min(y + 1, ny - 1); ++j)
            for (int i = std::max(x - 1, 0); i <= std::min(x + 1, nx - 1); ++i)
            {
              const std::size_t u = (static_cast<std::size_t>(k) * ny + j) * nx + i;
              for (std::size_t c = 0; c < nc; ++c)
              {
                lower[nc * col + c] = std::min(lower[nc * col + c], values[nc * u + c]);
                upper[nc * col + c] = std::max(upper[nc * col + c], values[nc * u + c]);
              }
            }
        double sum = 0.0;
        for (std::size_t e = this->ColumnStart[col]; e < this->ColumnStart[col + 1]; ++e)
        {
          sum += equation[this->ColumnRow[e]] ? this->ColumnWeight[e] : 0.f;
        }
        total[col] = sum;
      }
    });
  std::vector<float> residual(rows * nc, 0.f);
  auto residuals = [&](std::size_t begin, std::size_t end)
  {
    for (std::size_t r = begin; r < end; ++r)
    {
      if (!equation[r])
      {
        continue;
      }
      for (std::size_t c = 0; c < nc; ++c)
      {
        float at = 0.f;
        for (std::size_t e = this->RowStart[r]; e < this->RowStart[r + 1]; ++e)
        {
          at += this->RowWeight[e] * values[nc * this->RowColumn[e] + c];
        }
        residual[nc * r + c] = estimate[nc * r + c] - at;
      }
    }
  };
  for (int it = 0; it < Iterations; ++it)
  {
    loop(0, rows, residuals);
    loop(0, columns,
      [&](std::size_t begin, std::size_t end)
      {
        for (std::size_t col = begin; col < end; ++col)
        {
          if (total[col] <= 0.0)
          {
            continue;
          }
          const std::size_t t = this->Columns[col];
          for (std::size_t c = 0; c < nc; ++c)
          {
            double move = 0.0;
            for (std::size_t e = this->ColumnStart[col]; e < this->ColumnStart[col + 1]; ++e)
            {
              move +=
                static_cast<double>(this->ColumnWeight[e]) * residual[nc * this->ColumnRow[e] + c];
            }
            values[nc * t + c] =
              std::clamp(static_cast<float>(values[nc * t + c] + move / total[col]),
                lower[nc * col + c], upper[nc * col + c]);
          }
        }
      });
  }
  loop(0, rows, residuals);
  double left = 0.0, estimates = 0.0;
  for (std::size_t r = 0; r < rows; ++r)
  {
    for (std::size_t c = 0; equation[r] && c < nc; ++c)
    {
      left += std::abs(residual[nc * r + c]);
      estimates += std::abs(estimate[nc * r + c]);
    }
  }
  return estimates > 0.0 ? left / estimates : 0.0;
}

} // namespace brume
