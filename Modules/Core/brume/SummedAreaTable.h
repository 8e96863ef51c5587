// SPDX-License-Identifier: BSD-3-Clause
// Summed-area table of a histogram (Crow 1984; Glassner, "Multidimensional sum
// tables"), paper eq. (2): Sat(x,y,z) = sum over i<=x, j<=y, k<=z.
//
// The table is stored with a leading zero plane on each axis so that a box sum
// needs no branches: 3 additions and 4 subtractions in 3D (1 and 2 in 2D).
// Sums are kept in double precision; see the tests for the exactness bound.
#ifndef brume_SummedAreaTable_h
#define brume_SummedAreaTable_h

#include "brume/ExactHistogram.h"
#include "brume/Histogram.h"

#include <array>
#include <vector>

namespace brume
{

class SummedAreaTable
{
public:
  SummedAreaTable() = default;
  explicit SummedAreaTable(const Histogram& histogram);
  /// From exact sums, each converted to a double once.
  explicit SummedAreaTable(const ExactHistogram& histogram);

  int GetNumberOfChannels() const { return this->Channels; }

  /// Sum over the cells [lo, hi) (half-open on every axis) of every channel.
  void RegionSum(const std::array<int, 3>& lo, const std::array<int, 3>& hi, double* sum) const;
  /// The same for `count` channels from channel `first` on, into sum[0, count).
  void RegionSum(const std::array<int, 3>& lo, const std::array<int, 3>& hi, double* sum,
    int first, int count) const;

private:
  // The prefix sums of the cells' values, value(cell, channel).
  template <typename Value>
  void Build(const Value& value);
  std::size_t Index(int i, int j, int k) const
  {
    return ((static_cast<std::size_t>(k) * (this->Dims[1] + 1) + j) * (this->Dims[0] + 1) + i) *
      this->Channels;
  }

  std::array<int, 3> Dims{ 0, 0, 0 };
  int Channels = 0;
  std::vector<double> Table;
};

} // namespace brume

#endif
