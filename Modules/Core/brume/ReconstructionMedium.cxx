// SPDX-License-Identifier: BSD-3-Clause
// Heterogeneous media in two resolutions (../RADIOMETRY: "Two resolutions in
// one medium"): the source radiance S = J / sigma_t is smooth where the light
// is, so the texture estimates it over adaptive regions as the
// sigma_t-weighted mean, sum(albedo p Phi) / integral of sigma_t over the
// region; sigma_t keeps the medium's own resolution for the renderer. Both
// come from one grid of the density's means, so that what the texture is
// divided by is what the renderer draws.
#include "brume/Reconstruction.h"

#include <algorithm>
#include <cmath>

namespace brume
{

namespace
{
// The mean of the density over the box [lower, lower + size], from s^3
// stratified samples at the centres of a regular subdivision; samples
// beyond the medium's bounds (the half cells of the native box outside
// them) take the density on the bounds' faces.
double MeanDensity(
  const DensityField& density, const Box& bounds, const Vec3& lower, const Vec3& size, int s)
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
        Vec3 p = lower + size * f;
        for (int a = 0; a < 3; ++a)
        {
          p[a] = std::clamp(p[a], bounds.lower[a], bounds.upper[a]);
        }
        sum += density.Evaluate(p);
      }
    }
  }
  return sum / (static_cast<double>(s) * s * s);
}

// Along one axis, n fine cells over [lo, hi] and m coarse cells over
// [coarseLo, coarseHi] (inside it or equal): for each fine cell, the coarse
// cells it overlaps and the overlap as a fraction of the fine cell (the part
// of a fine cell beyond the coarse cells overlaps none).
struct Overlap
{
  int Coarse;
  double Fraction;
};
std::vector<std::vector<Overlap>> Overlaps(
  int n, double lo, double hi, int m, double coarseLo, double coarseHi)
{
  std::vector<std::vector<Overlap>> result(static_cast<std::size_t>(n));
  const double fine = (hi - lo) / n, coarse = (coarseHi - coarseLo) / m;
  for (int i = 0; i < n; ++i)
  {
    const double a = lo + i * fine, b = lo + (i + 1) * fine;
    const int first = std::max(0, static_cast<int>(std::floor((a - coarseLo) / coarse)));
    const int last = std::min(m - 1, static_cast<int>(std::ceil((b - coarseLo) / coarse)) - 1);
    for (int c = first; c <= last; ++c)
    {
      const double overlap =
        std::min(b, coarseLo + (c + 1) * coarse) - std::max(a, coarseLo + c * coarse);
      if (overlap > 0.0)
      {
        result[i].push_back({ c, overlap / fine });
      }
    }
  }
  return result;
}
}

void ObjectRadiance::SampleNativeDensity(const ParallelFor& parallelFor)
{
  const DensityField& density = *this->MediumRef->Density;
  const std::array<int, 3> native = density.NativeResolution();
  // The smallest integer coarsening that fits the cell budget and a 3D
  // texture's usual axis limit, the same on every axis.
  int factor = 1;
  auto fits = [&](int f)
  {
    double cells = 1.0;
    for (int a = 0; a < 3; ++a)
    {
      const int n = (native[a] + f - 1) / f;
      if (n > MaxNativeAxis)
      {
        return false;
      }
      cells *= n;
    }
    return cells <= static_cast<double>(MaxNativeCells);
  };
  while (!fits(factor))
  {
    ++factor;
  }
  // Coarsened cells cover whole native cells: the box grows on the far
  // side to a multiple of the factor.
  const Box nativeBox = density.NativeBox();
  Box box = nativeBox;
  for (int a = 0; a < 3; ++a)
  {
    this->NativeDims[a] = std::max(1, (native[a] + factor - 1) / factor);
    const float nativeCell = nativeBox.Extent()[a] / static_cast<float>(native[a]);
    box.upper[a] = box.lower[a] + nativeCell * static_cast<float>(this->NativeDims[a] * factor);
  }
  this->NativeBox = box;
  const Vec3 cell = box.Extent() /
    Vec3(static_cast<float>(this->NativeDims[0]), static_cast<float>(this->NativeDims[1]),
      static_cast<float>(this->NativeDims[2]));
  // One sample at the centre of a native cell; a coarsened cell averages 2^3.
  const int samples = factor > 1 ? 2 : 1;
  const std::size_t n =
    static_cast<std::size_t>(this->NativeDims[0]) * this->NativeDims[1] * this->NativeDims[2];
  this->NativeDensity.assign(n, 0.f);
  const std::size_t nx = this->NativeDims[0], nxy = nx * this->NativeDims[1];
  parallelFor(0, n,
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t c = begin; c < end; ++c)
      {
        const Vec3 corner(static_cast<float>(c % nx), static_cast<float>((c % nxy) / nx),
          static_cast<float>(c / nxy));
        this->NativeDensity[c] = static_cast<float>(
          MeanDensity(density, this->MediumRef->Bounds, box.lower + corner * cell, cell, samples));
      }
    });
}

void ObjectRadiance::BuildDensityTable()
{
  // The density's integral over each histogram cell, summed from the native
  // cells by their exact overlaps (separable along the axes).
  // Native cells beyond the medium's bounds count for the part inside.
  const auto& nd = this->NativeDims;
  const Box box = this->MediumRef->Bounds;
  const Box& native = this->NativeBox;
  std::array<std::vector<std::vector<Overlap>>, 3> overlaps;
  for (int a = 0; a < 3; ++a)
  {
    overlaps[a] =
      Overlaps(nd[a], native.lower[a], native.upper[a], this->Dims[a], box.lower[a], box.upper[a]);
  }
  const double nativeVolume =
    static_cast<double>(native.Volume()) / (static_cast<double>(nd[0]) * nd[1] * nd[2]);
  Histogram integral(this->Dims, 1);
  std::vector<double>& values = integral.GetValues();
  double total = 0.0;
  for (int k = 0; k < nd[2]; ++k)
  {
    for (int j = 0; j < nd[1]; ++j)
    {
      for (int i = 0; i < nd[0]; ++i)
      {
        const double mass =
          this->NativeDensity[(static_cast<std::size_t>(k) * nd[1] + j) * nd[0] + i] * nativeVolume;
        if (mass == 0.0)
        {
          continue;
        }
        total += mass;
        for (const Overlap& z : overlaps[2][k])
          for (const Overlap& y : overlaps[1][j])
            for (const Overlap& x : overlaps[0][i])
            {
              values[integral.Index(x.Coarse, y.Coarse, z.Coarse)] +=
                mass * x.Fraction * y.Fraction * z.Fraction;
            }
      }
    }
  }
  this->DensityTable = SummedAreaTable(integral);
  // Regions whose integral is below this are empty: their source radiance
  // is 0, not a ratio of two rounding leftovers of the table.
  this->EmptyIntegral = 1e-9 * total;
}

} // namespace brume
