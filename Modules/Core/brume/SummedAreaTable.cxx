// SPDX-License-Identifier: BSD-3-Clause
#include "brume/SummedAreaTable.h"

namespace brume
{

SummedAreaTable::SummedAreaTable(const Histogram& histogram)
  : Dims(histogram.GetDimensions())
  , Channels(histogram.GetNumberOfChannels())
  , Table(static_cast<std::size_t>(Dims[0] + 1) * (Dims[1] + 1) * (Dims[2] + 1) * Channels, 0.0)
{
  this->Build([&](std::size_t cell, int c) { return histogram.Get(cell)[c]; });
}

SummedAreaTable::SummedAreaTable(const ExactHistogram& histogram)
  : Dims(histogram.GetDimensions())
  , Channels(histogram.GetNumberOfChannels())
  , Table(static_cast<std::size_t>(Dims[0] + 1) * (Dims[1] + 1) * (Dims[2] + 1) * Channels, 0.0)
{
  const std::size_t nc = static_cast<std::size_t>(this->Channels);
  this->Build([&](std::size_t cell, int c) { return histogram.GetValue(cell * nc + c); });
}

template <typename Value>
void SummedAreaTable::Build(const Value& value)
{
  const int nc = this->Channels;
  // Separable prefix sums: one pass per axis.
  for (int k = 0; k < this->Dims[2]; ++k)
  {
    for (int j = 0; j < this->Dims[1]; ++j)
    {
      for (int i = 0; i < this->Dims[0]; ++i)
      {
        const std::size_t cell =
          (static_cast<std::size_t>(k) * this->Dims[1] + j) * this->Dims[0] + i;
        double* dst = &this->Table[this->Index(i + 1, j + 1, k + 1)];
        const double* left = &this->Table[this->Index(i, j + 1, k + 1)];
        for (int c = 0; c < nc; ++c)
        {
          dst[c] = left[c] + value(cell, c);
        }
      }
    }
  }
  for (int k = 1; k <= this->Dims[2]; ++k)
  {
    for (int j = 1; j <= this->Dims[1]; ++j)
    {
      for (int i = 1; i <= this->Dims[0]; ++i)
      {
        double* dst = &this->Table[this->Index(i, j, k)];
        const double* below = &this->Table[this->Index(i, j - 1, k)];
        for (int c = 0; c < nc; ++c)
        {
          dst[c] += below[c];
        }
      }
    }
  }
  for (int k = 1; k <= this->Dims[2]; ++k)
  {
    for (int j = 1; j <= this->Dims[1]; ++j)
    {
      for (int i = 1; i <= this->Dims[0]; ++i)
      {
        double* dst = &this->Table[this->Index(i, j, k)];
        const double* back = &this->Table[this->Index(i, j, k - 1)];
        for (int c = 0; c < nc; ++c)
        {
          dst[c] += back[c];
        }
      }
    }
  }
}

void SummedAreaTable::RegionSum(
  const std::array<int, 3>& lo, const std::array<int, 3>& hi, double* sum) const
{
  this->RegionSum(lo, hi, sum, 0, this->Channels);
}

void SummedAreaTable::RegionSum(const std::array<int, 3>& lo, const std::array<int, 3>& hi,
  double* sum, int first, int count) const
{
  const double* a = &this->Table[this->Index(hi[0], hi[1], hi[2])];
  const double* b = &this->Table[this->Index(lo[0], hi[1], hi[2])];
  const double* c = &this->Table[this->Index(hi[0], lo[1], hi[2])];
  const double* d = &this->Table[this->Index(hi[0], hi[1], lo[2])];
  const double* e = &this->Table[this->Index(lo[0], lo[1], hi[2])];
  const double* f = &this->Table[this->Index(lo[0], hi[1], lo[2])];
  const double* g = &this->Table[this->Index(hi[0], lo[1], lo[2])];
  const double* h = &this->Table[this->Index(lo[0], lo[1], lo[2])];
  for (int k = 0; k < count; ++k)
  {
    const int ch = first + k;
    sum[k] = a[ch] - b[ch] - c[ch] - d[ch] + e[ch] + f[ch] + g[ch] - h[ch];
  }
}

} // namespace brume
