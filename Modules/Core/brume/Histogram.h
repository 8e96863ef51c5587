// SPDX-License-Identifier: BSD-3-Clause
// Regular histogram over a 2D rectangle or a 3D box (paper, section 3).
//
// A 2D histogram is a 3D one with one cell along z. Each cell accumulates
// `Channels` values in double precision.
#ifndef brume_Histogram_h
#define brume_Histogram_h

#include <array>
#include <cstddef>
#include <vector>

namespace brume
{

class Histogram
{
public:
  Histogram() = default;
  Histogram(std::array<int, 3> dims, int channels);

  const std::array<int, 3>& GetDimensions() const { return this->Dims; }
  int GetNumberOfChannels() const { return this->Channels; }
  std::size_t GetNumberOfCells() const
  {
    return static_cast<std::size_t>(this->Dims[0]) * this->Dims[1] * this->Dims[2];
  }

  /// Cell of a point given in normalized coordinates (each in [0, 1]);
  /// coordinates outside are clamped to the border cells.
  std::array<int, 3> CellOf(double s, double t, double r) const;
  std::size_t Index(int i, int j, int k) const
  {
    return (static_cast<std::size_t>(k) * this->Dims[1] + j) * this->Dims[0] + i;
  }

  void Add(std::size_t cell, const double* values)
  {
    double* dst = &this->Values[cell * this->Channels];
    for (int c = 0; c < this->Channels; ++c)
    {
      dst[c] += values[c];
    }
  }
  /// Multiplies every value by `factor`.
  void Scale(double factor)
  {
    for (double& v : this->Values)
    {
      v *= factor;
    }
  }
  const double* Get(std::size_t cell) const { return &this->Values[cell * this->Channels]; }
  const std::vector<double>& GetValues() const { return this->Values; }
  std::vector<double>& GetValues() { return this->Values; }

private:
  std::array<int, 3> Dims{ 0, 0, 0 };
  int Channels = 0;
  std::vector<double> Values;
};

} // namespace brume

#endif
