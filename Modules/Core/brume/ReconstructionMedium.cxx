// SPDX-License-Identifier: BSD-3-Clause
// Heterogeneous media in two resolutions (../RADIOMETRY: "Two resolutions in
// one medium"): the source radiance S = J / sigma_t is smooth where the light
// is, so the texture estimates it over adaptive regions as the
// sigma_t-weighted mean, sum(albedo p Phi) / integral of sigma_t over the
// region; sigma_t keeps the medium's own resolution for the renderer.
#include "brume/Reconstruction.h"

#include <algorithm>
#include <cmath>

namespace brume
{

namespace
{
// The mean of the density over the box [lower, lower + size], from s^3
// stratified samples at the centres of a regular subdivision.
double MeanDensity(const DensityField& density, const Vec3& lower, const Vec3& size, int s)
{
  double sum = 0.0;
  for (int k = 0; k < s; ++k)
  {
    for (int j = 0; j < s; ++j)
    {
      for (int i = 0; i < s; ++i)
      {
        const Vec3 f((static_cast<float>(i) + 0.5f) / static_cast<float>(s),
          (static_cast<float>(j) + 0.5f) / static_cast<float>(s),
          (static_cast<float>(k) + 0.5f) / static_cast<float>(s));
        sum += density.Evaluate(lower + size * f);
      }
    }
  }
  return sum / (static_cast<double>(s) * s * s);
}
}

void ObjectRadiance::BuildDensityTable(const ParallelFor& parallelFor)
{
  // Enough samples per histogram cell to see the density's own cells in
  // it (at least 2 per axis, at most 8).
  const DensityField& density = *this->MediumRef->Density;
  const std::array<int, 3> native = density.NativeResolution();
  int samples = 2;
  for (int a = 0; a < 3; ++a)
  {
    samples = std::max(samples, (native[a] + this->Dims[a] - 1) / this->Dims[a]);
  }
  samples = std::min(samples, 8);
  const Box box = this->MediumRef->Bounds;
  const Vec3 cell = box.Extent() /
    Vec3(static_cast<float>(this->Dims[0]), static_cast<float>(this->Dims[1]),
      static_cast<float>(this->Dims[2]));
  Histogram integral(this->Dims, 1);
  const std::size_t nx = this->Dims[0], nxy = nx * this->Dims[1];
  parallelFor(0, integral.GetNumberOfCells(),
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t c = begin; c < end; ++c)
      {
        const Vec3 corner(static_cast<float>(c % nx), static_cast<float>((c % nxy) / nx),
          static_cast<float>(c / nxy));
        const double value =
          MeanDensity(density, box.lower + corner * cell, cell, samples) * this->CellVolume;
        integral.GetValues()[c] = value; // one writer per cell
      }
    });
  this->DensityTable = SummedAreaTable(integral);
}

void ObjectRadiance::SampleNativeExtinction(const ParallelFor& parallelFor)
{
  const DensityField& density = *this->MediumRef->Density;
  const std::array<int, 3> native = density.NativeResolution();
  const double cells = static_cast<double>(native[0]) * native[1] * native[2];
  // The smallest integer coarsening that fits, the same on every axis.
  int factor = 1;
  while (cells / (static_cast<double>(factor) * factor * factor) >
    static_cast<double>(MaxNativeCells))
  {
    ++factor;
  }
  for (int a = 0; a < 3; ++a)
  {
    this->NativeDims[a] = std::max(1, (native[a] + factor - 1) / factor);
  }
  const Box box = this->MediumRef->Bounds;
  const Vec3 cell = box.Extent() /
    Vec3(static_cast<float>(this->NativeDims[0]), static_cast<float>(this->NativeDims[1]),
      static_cast<float>(this->NativeDims[2]));
  // One sample at the centre of a native cell; a coarsened cell averages 2^3.
  const int samples = factor > 1 ? 2 : 1;
  const Vec3 sigmaT = this->MediumRef->SigmaT();
  const std::size_t n =
    static_cast<std::size_t>(this->NativeDims[0]) * this->NativeDims[1] * this->NativeDims[2];
  this->NativeExtinction.assign(3 * n, 0.f);
  const std::size_t nx = this->NativeDims[0], nxy = nx * this->NativeDims[1];
  parallelFor(0, n,
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t c = begin; c < end; ++c)
      {
        const Vec3 corner(static_cast<float>(c % nx), static_cast<float>((c % nxy) / nx),
          static_cast<float>(c / nxy));
        const auto mean =
          static_cast<float>(MeanDensity(density, box.lower + corner * cell, cell, samples));
        for (int k = 0; k < 3; ++k)
        {
          this->NativeExtinction[3 * c + k] = sigmaT[k] * mean;
        }
      }
    });
}

} // namespace brume
