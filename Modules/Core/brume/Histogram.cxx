// SPDX-License-Identifier: BSD-3-Clause
#include "brume/Histogram.h"

#include <algorithm>
#include <cmath>

namespace brume
{

Histogram::Histogram(std::array<int, 3> dims, int channels)
  : Dims(dims)
  , Channels(channels)
  , Values(static_cast<std::size_t>(dims[0]) * dims[1] * dims[2] * channels, 0.0)
{
}

std::array<int, 3> Histogram::CellOf(double s, double t, double r) const
{
  const double coords[3] = { s, t, r };
  std::array<int, 3> cell{};
  for (int a = 0; a < 3; ++a)
  {
    // NaN maps to cell 0 through the clamp below (comparison fails).
    const double x = std::floor(coords[a] * this->Dims[a]);
    cell[a] = x >= 0.0 ? static_cast<int>(std::min<double>(x, this->Dims[a] - 1)) : 0;
  }
  return cell;
}

} // namespace brume
