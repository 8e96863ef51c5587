// SPDX-License-Identifier: BSD-3-Clause
// Heterogeneous media in two resolutions (../RADIOMETRY: "Two resolutions in
// one medium"): the source radiance S = J / sigma_t is smooth where the light
// is, so the texture estimates it over adaptive regions as the
// sigma_t-weighted mean, sum(albedo p Phi) / integral of sigma_t over the
// region; sigma_t keeps the medium's own resolution for the renderer. Both
// come from one grid of the density's means, so that what the texture is
// divided by is what the renderer draws.
#include "brume/NativeMediumGrid.h"

#include "brume/Density.h"
#include "brume/Histogram.h"
#include "brume/TransferFunction.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

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
  double Centre; // of the overlap, in coarse cells from coarseLo
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
        const double from = std::max(a, coarseLo + c * coarse);
        result[i].push_back({ c, overlap / fine, (from + 0.5 * overlap - coarseLo) / coarse });
      }
    }
  }
  return result;
}

// Overlaps() of fine cells whose values are points at their centres,
// interpolated linearly between them (a trilinear field is their tensor
// product): each point's share of the field is its hat function, 1 at its
// centre and 0 at its neighbours', so its mass (its value times a fine
// cell) falls into the coarse cells that hat overlaps, a fraction its
// integral there over the fine cell, centred at the hat's own centroid
// over the overlap. The hats of a row add up to 1 between its first and
// last points; beyond them (half a fine cell at either end) the field is
// not the medium's, whose bounds stop at those points.
std::vector<std::vector<Overlap>> HatOverlaps(
  int n, double lo, double hi, int m, double coarseLo, double coarseHi)
{
  if (n < 2)
  {
    return Overlaps(n, lo, hi, m, coarseLo, coarseHi); // constant along the axis
  }
  std::vector<std::vector<Overlap>> result(static_cast<std::size_t>(n));
  const double fine = (hi - lo) / n, coarse = (coarseHi - coarseLo) / m;
  // The integrals of the hat and of t times it over [u, v] inside one of
  // its sides (t from the point's centre; rising: sign -1, falling: +1).
  auto side = [&](double u, double v, double sign, double& mass, double& moment)
  {
    mass += (v - u) - sign * (v * v - u * u) / (2.0 * fine);
    moment += (v * v - u * u) / 2.0 - sign * (v * v * v - u * u * u) / (3.0 * fine);
  };
  for (int i = 0; i < n; ++i)
  {
    const double centre = lo + (i + 0.5) * fine;
    const double a = centre - fine, b = centre + fine;
    const int first = std::max(0, static_cast<int>(std::floor((a - coarseLo) / coarse)));
    const int last = std::min(m - 1, static_cast<int>(std::ceil((b - coarseLo) / coarse)) - 1);
    for (int c = first; c <= last; ++c)
    {
      // In t = x - centre.
      const double from = std::max(a, coarseLo + c * coarse) - centre;
      const double to = std::min(b, coarseLo + (c + 1) * coarse) - centre;
      if (!(to > from))
      {
        continue;
      }
      double mass = 0.0, moment = 0.0;
      if (from < 0.0)
      {
        side(from, std::min(to, 0.0), -1.0, mass, moment);
      }
      if (to > 0.0)
      {
        side(std::max(from, 0.0), to, 1.0, mass, moment);
      }
      if (mass > 0.0)
      {
        result[i].push_back({ c, mass / fine, (centre + moment / mass - coarseLo) / coarse });
      }
    }
  }
  return result;
}

// Whether the density's majorants are 0 over the world box [lower, upper]
// (clamped to the medium's bounds, as the samples are): then the density is
// 0 there, since it is never negative.
bool ZeroOver(const DensityField& density, const Box& bounds, Vec3 lower, Vec3 upper)
{
  const MajorantGrid& mg = density.GetMajorants();
  const Vec3 block = mg.Bounds.Extent() /
    Vec3(static_cast<float>(mg.Dims[0]), static_cast<float>(mg.Dims[1]),
      static_cast<float>(mg.Dims[2]));
  int b0[3], b1[3];
  for (int a = 0; a < 3; ++a)
  {
    lower[a] = std::clamp(lower[a], bounds.lower[a], bounds.upper[a]);
    upper[a] = std::clamp(upper[a], bounds.lower[a], bounds.upper[a]);
    auto index = [&](float x)
    {
      const float f = std::floor((x - mg.Bounds.lower[a]) / block[a]);
      return f < 0.f ? 0
                     : (f >= static_cast<float>(mg.Dims[a]) ? mg.Dims[a] - 1 : static_cast<int>(f));
    };
    // Points on a block's face belong to both blocks.
    b0[a] = index(lower[a] - 1e-4f * block[a]);
    b1[a] = index(upper[a] + 1e-4f * block[a]);
  }
  // Blocks in regions found empty are 0: the regions first, a few
  // kilobytes for a sparse grid's 10^7 blocks.
  if (!mg.EmptyRegions.empty())
  {
    constexpr int R = MajorantGrid::RegionBlocks;
    bool empty = true;
    for (int k = b0[2] / R; empty && k <= b1[2] / R; ++k)
      for (int j = b0[1] / R; empty && j <= b1[1] / R; ++j)
        for (int i = b0[0] / R; empty && i <= b1[0] / R; ++i)
        {
          const int region[3] = { i * R, j * R, k * R };
          empty = mg.InEmptyRegion(region);
        }
    if (empty)
    {
      return true;
    }
  }
  for (int k = b0[2]; k <= b1[2]; ++k)
    for (int j = b0[1]; j <= b1[1]; ++j)
      for (int i = b0[0]; i <= b1[0]; ++i)
      {
        if (mg.At(i, j, k) != 0.f)
        {
          return false;
        }
      }
  return true;
}
}

namespace
{
// Overlaps() of a grid's cells with `dims` cells over `box`, axis by axis;
// HatOverlaps() where the grid's values are points of a trilinear field.
using GridOverlaps = std::array<std::vector<std::vector<Overlap>>, 3>;
GridOverlaps CellOverlaps(
  const BrickedGrid& grid, const Box& box, const std::array<int, 3>& dims, bool trilinear)
{
  const auto& nd = grid.GetDims();
  const Box& native = grid.GetBox();
  GridOverlaps overlaps;
  for (int a = 0; a < 3; ++a)
  {
    overlaps[a] = (trilinear ? HatOverlaps : Overlaps)(
      nd[a], native.lower[a], native.upper[a], dims[a], box.lower[a], box.upper[a]);
  }
  return overlaps;
}

// The cells k0 <= k < k1 of layer l of the grid's bricks along z, and the
// range [first, last] of the coarse z cells they overlap (last < first: none).
struct BrickLayer
{
  int K0, K1, First, Last;
};
BrickLayer LayerOverlap(
  const BrickedGrid& grid, const GridOverlaps& overlaps, std::size_t l, int coarseCells)
{
  const int layers = grid.GetBrickDims()[2];
  BrickLayer layer;
  layer.K0 = BrickedGrid::Stride * static_cast<int>(l);
  layer.K1 = static_cast<int>(l) + 1 == layers ? grid.GetDims()[2] : layer.K0 + BrickedGrid::Stride;
  layer.First = coarseCells;
  layer.Last = -1;
  for (int k = layer.K0; k < layer.K1; ++k)
  {
    for (const Overlap& z : overlaps[2][static_cast<std::size_t>(k)])
    {
      layer.First = std::min(layer.First, z.Coarse);
      layer.Last = std::max(layer.Last, z.Coarse);
    }
  }
  return layer;
}

bool SameBox(const Box& a, const Box& b)
{
  for (int i = 0; i < 3; ++i)
  {
    if (a.lower[i] != b.lower[i] || a.upper[i] != b.upper[i])
    {
      return false;
    }
  }
  return true;
}
}

bool NativeMediumGrid::HasTables(const Box& box, const std::array<int, 3>& dims) const
{
  return this->HasTables() && this->TableDims == dims && SameBox(this->TableBox, box);
}

bool NativeMediumGrid::SameField(const Medium& medium) const
{
  const auto* mine = dynamic_cast<const ClassifiedDensity*>(this->Source.get());
  const auto* theirs = dynamic_cast<const ClassifiedDensity*>(medium.Density.get());
  return mine && theirs && this->Classification && this->Coarsening == 1 &&
    !this->Scalars.Empty() && &mine->GetScalars() == &theirs->GetScalars();
}

void NativeMediumGrid::Sample(
  const Medium& medium, std::size_t memory, const ParallelFor& parallelFor)
{
  this->Sample(medium, memory, parallelFor, nullptr);
}

void NativeMediumGrid::Sample(const Medium& medium, std::size_t memory,
  const ParallelFor& parallelFor, const NativeMediumGrid* previous)
{
  this->SampleFrom(medium, memory, parallelFor, previous, nullptr);
}

void NativeMediumGrid::Sample(const Medium& medium, std::size_t memory,
  const ParallelFor& parallelFor, NativeMediumGrid&& previous)
{
  this->SampleFrom(medium, memory, parallelFor, &previous, &previous);
  previous = NativeMediumGrid();
}

void NativeMediumGrid::SampleFrom(const Medium& medium, std::size_t memory,
  const ParallelFor& parallelFor, const NativeMediumGrid* previous, NativeMediumGrid* owned)
{
  this->ReusedBricks = 0;
  this->SampledBricks = 0;
  this->Source = medium.Density;
  this->BrickRanges.clear();
  this->Candidates.clear();
  // The previous grid of the same density (an edit of the medium's albedo),
  // or of the same scalars classified by another function.
  const bool sameDensity = previous && previous->Source == medium.Density;
  if (previous && !sameDensity && !previous->SameField(medium))
  {
    previous = nullptr;
  }
  const DensityField& density = *medium.Density;
  const Box& bounds = medium.Bounds;
  const std::array<int, 3> native = density.NativeResolution();
  const Box nativeBox = density.NativeBox();
  const auto* classified = dynamic_cast<const ClassifiedDensity*>(&density);
  // At coarsening `factor`: the cells, their box (coarsened cells cover
  // whole native cells: the box grows on the far side to a multiple of the
  // factor) and which cells' samples are 0 by the majorants.
  std::array<int, 3> dims{};
  Box box;
  Vec3 cell;
  auto layout = [&](int factor)
  {
    box = nativeBox;
    for (int a = 0; a < 3; ++a)
    {
      dims[a] = std::max(1, (native[a] + factor - 1) / factor);
      const float nativeCell = nativeBox.Extent()[a] / static_cast<float>(native[a]);
      box.upper[a] = box.lower[a] + nativeCell * static_cast<float>(dims[a] * factor);
    }
    cell = box.Extent() /
      Vec3(static_cast<float>(dims[0]), static_cast<float>(dims[1]), static_cast<float>(dims[2]));
  };
  auto zeroOver = [&](const std::array<int, 3>& lower, const std::array<int, 3>& upper)
  {
    const Vec3 lo(
      static_cast<float>(lower[0]), static_cast<float>(lower[1]), static_cast<float>(lower[2]));
    const Vec3 hi(static_cast<float>(upper[0] + 1), static_cast<float>(upper[1] + 1),
      static_cast<float>(upper[2] + 1));
    return ZeroOver(density, bounds, box.lower + lo * cell, box.lower + hi * cell);
  };
  // A classified grid's own values, read in place (a GridDensity of the
  // native cells): at the field's resolution its scalars are not copied.
  const auto* scalarGrid =
    classified ? dynamic_cast<const GridDensity*>(&classified->GetScalars()) : nullptr;
  if (scalarGrid && (scalarGrid->GetDimensions() != native || scalarGrid->GetValues().Empty()))
  {
    scalarGrid = nullptr;
  }
  // The smallest integer coarsening, the same on every axis, whose grids
  // fit the memory: the occupied bricks' samples and every brick's table
  // entry, twice for a classified density kept with its scalars (their
  // samples once where they are the field's own; bricks of one value other
  // than 0 count as stored here: only sampling tells them apart).
  auto fits = [&](int factor)
  {
    layout(factor);
    double bricks = 1.0;
    for (int a = 0; a < 3; ++a)
    {
      if (dims[a] > MaxAxis)
      {
        return false;
      }
      bricks *= BrickedGrid::BricksAlong(dims[a]);
    }
    const double grids = classified && factor == 1 ? 2.0 : 1.0;
    constexpr double tableBytes = sizeof(std::int32_t) + sizeof(float);
    constexpr double brickBytes = BrickedGrid::BrickSamples * sizeof(float);
    if (grids * bricks * tableBytes > static_cast<double>(memory))
    {
      return false;
    }
    const int bx = BrickedGrid::BricksAlong(dims[0]), by = BrickedGrid::BricksAlong(dims[1]),
              bz = BrickedGrid::BricksAlong(dims[2]);
    std::vector<std::size_t> occupied(static_cast<std::size_t>(bz), 0);
    parallelFor(0, static_cast<std::size_t>(bz),
      [&](std::size_t begin, std::size_t end)
      {
        for (std::size_t k = begin; k < end; ++k)
          for (int j = 0; j < by; ++j)
            for (int i = 0; i < bx; ++i)
            {
              const std::array<int, 3> lower{ i * BrickedGrid::Stride, j * BrickedGrid::Stride,
                static_cast<int>(k) * BrickedGrid::Stride };
              const std::array<int, 3> upper{ std::min(lower[0] + BrickedGrid::Size, dims[0]) - 1,
                std::min(lower[1] + BrickedGrid::Size, dims[1]) - 1,
                std::min(lower[2] + BrickedGrid::Size, dims[2]) - 1 };
              occupied[k] += zeroOver(lower, upper) ? 0 : 1;
            }
      });
    double stored = 0.0;
    for (const std::size_t n : occupied)
    {
      stored += static_cast<double>(n);
    }
    const double copies = factor == 1 && scalarGrid ? 1.0 : grids;
    return copies * stored * brickBytes + grids * bricks * tableBytes <=
      static_cast<double>(memory);
  };
  int factor = 1;
  while (!fits(factor))
  {
    if (dims[0] == 1 && dims[1] == 1 && dims[2] == 1)
    {
      break; // one cell: the coarsest grid there is, whatever the memory
    }
    ++factor;
  }
  layout(factor);
  this->Coarsening = factor;
  // The field the tracer samples, where the grid holds its points.
  float probe = 0.f;
  this->Trilinear = factor == 1 && !classified &&
    density.NativePoints(std::array<int, 3>{ 0, 0, 0 }, std::array<int, 3>{ 1, 1, 1 }, &probe);
  this->FieldResolution = native;
  // A classified density's scalars at the cells' centres (not coarsened;
  // the field's own values):
  // bricks the majorants leave out hold a scalar the function takes to 0
  // (a node of opacity 0; with none, no brick is left out).
  this->Scalars = BrickedGrid();
  this->ScalarField = nullptr;
  this->Classification = nullptr;
  auto centre = [&](int i, int j, int k)
  {
    // The centre of cell (i, j, k), on the bounds' faces beyond them.
    const Vec3 corner(static_cast<float>(i), static_cast<float>(j), static_cast<float>(k));
    Vec3 p = box.lower + corner * cell + cell * 0.5f;
    for (int a = 0; a < 3; ++a)
    {
      p[a] = std::clamp(p[a], bounds.lower[a], bounds.upper[a]);
    }
    return p;
  };
  // The previous grid, where its cells are these: the same layout.
  if (previous &&
    ((factor != 1 && !sameDensity) || previous->Coarsening != factor ||
      previous->Density.GetDims() != dims || !SameBox(previous->Density.GetBox(), box)))
  {
    previous = nullptr;
  }
  if (previous && (sameDensity || previous->Classification->SameAs(classified->GetOpacity())))
  {
    // The same density, or the same function of the same scalars: the
    // same grids and tables.
    this->Density = previous->Density;
    this->Scalars = previous->Scalars;
    this->ScalarField = previous->ScalarField;
    this->Classification = classified && factor == 1 ? &classified->GetOpacity() : nullptr;
    this->BrickRanges = previous->BrickRanges;
    this->Candidates = previous->Candidates;
    this->ScalarSkipped = previous->ScalarSkipped;
    this->DensityTable = previous->DensityTable;
    this->DensityMoments = previous->DensityMoments;
    this->EmptyIntegral = previous->EmptyIntegral;
    this->TableDims = previous->TableDims;
    this->TableBox = previous->TableBox;
    this->AlbedoTable = previous->AlbedoTable;
    this->TableAlbedo = previous->TableAlbedo;
    this->AlbedoDims = previous->AlbedoDims;
    this->AlbedoBox = previous->AlbedoBox;
    this->ReusedBricks = previous->ReusedBricks + previous->SampledBricks;
    return;
  }
  this->DensityTable = SummedAreaTable();
  this->DensityMoments = SummedAreaTable();
  this->AlbedoTable = SummedAreaTable();
  this->TableAlbedo = nullptr;
  if (classified && factor == 1)
  {
    const OpacityTransferFunction& function = classified->GetOpacity();
    float nothing = function.GetNodes().front().Scalar;
    for (const auto& node : function.GetNodes())
    {
      if (node.Opacity == 0.f)
      {
        nothing = node.Scalar;
        break;
      }
    }
    // A brick's scalars read together where the field gives its points
    // (DensityField::NativePoints: a grid's values, an OpenVDB grid's
    // voxels), else one by one.
    const DensityField& scalars = classified->GetScalars();
    // Which bricks the function leaves out (the scalars' and the
    // extinction's alike). The scalars do not depend on the function, only
    // on those (holding `nothing`): where they are the previous grid's, so
    // are the scalars' bricks, shared (and a renderer that holds them need
    // not send them again).
    std::vector<char> candidates = BrickedGrid::Candidates(dims, zeroOver, parallelFor);
    const bool sameScalars =
      previous && previous->Candidates == candidates && previous->ScalarSkipped == nothing;
    this->Candidates = std::move(candidates);
    this->ScalarSkipped = nothing;
    auto scalarBrick = [&](const std::array<int, 3>& lower, float* out)
    {
      constexpr int S = BrickedGrid::Size;
      std::array<int, 3> count{};
      for (int a = 0; a < 3; ++a)
      {
        count[a] = std::min(lower[a] + S, dims[a]) - lower[a];
      }
      if (previous && previous->Scalars.HasSamples())
      {
        // The field's own values, whichever function: a brick stored
        // before holds them (one left out held a value of the function's).
        const std::size_t b = previous->Scalars.BrickAt(lower);
        if (previous->Scalars.GetSlots()[b] >= 0)
        {
          previous->Scalars.CopyBrick(b, out);
          return;
        }
      }
      // A brick inside the grid: its points are its samples, in order.
      if (count[0] == S && count[1] == S && count[2] == S &&
        scalars.NativePoints(lower, count, out))
      {
        return;
      }
      float points[S * S * S];
      const bool read = scalars.NativePoints(lower, count, points);
      for (int k = 0; k < S; ++k)
        for (int j = 0; j < S; ++j)
          for (int i = 0; i < S; ++i)
          {
            // Cells past the grid's last take the last's.
            const int x = std::min(i, count[0] - 1), y = std::min(j, count[1] - 1),
                      z = std::min(k, count[2] - 1);
            *out++ = read ? points[(z * count[1] + y) * count[0] + x]
                          : scalars.NativeValue(lower[0] + x, lower[1] + y, lower[2] + z,
                              centre(lower[0] + x, lower[1] + y, lower[2] + z));
          }
    };
    // The field's own values are not copied: an outline of the same slots.
    this->Scalars = sameScalars ? previous->Scalars
      : scalarGrid
      ? BrickedGrid::Outline(dims, box, scalarBrick, this->Candidates, parallelFor, nothing)
      : BrickedGrid::SampleBricks(dims, box, scalarBrick, this->Candidates, parallelFor, nothing);
    this->ScalarField = this->Scalars.HasSamples() ? nullptr : scalarGrid;
    this->Classification = &function;
  }
  // One sample at the centre of a native cell (the field's own value
  // there: DensityField::NativeValue); a coarsened cell averages 2^3.
  // A classified density is classified after interpolation, so its
  // function may step or bend anywhere in a cell: cells whose scalars span
  // one of its points average BendSamples^3 samples. Elsewhere a
  // classified cell is the function at its scalar.
  const int samples = factor > 1 ? 2 : 1;
  const OpacityTransferFunction* function = this->Classification;
  auto value = [&](int i, int j, int k)
  {
    if (function)
    {
      const Vec3 corner(static_cast<float>(i), static_cast<float>(j), static_cast<float>(k));
      const Vec3 lower = box.lower + corner * cell;
      if (classified->BendsWithinNativeCell(i, j, k, Box{ lower, lower + cell }))
      {
        return static_cast<float>(
          density.NativeMean(i, j, k, Box{ lower, lower + cell }, bounds, BendSamples));
      }
      return function->Extinction(this->ScalarAt(i, j, k));
    }
    if (samples == 1)
    {
      return density.NativeValue(i, j, k, centre(i, j, k));
    }
    const Vec3 corner(static_cast<float>(i), static_cast<float>(j), static_cast<float>(k));
    const Vec3 lower = box.lower + corner * cell;
    return static_cast<float>(MeanDensity(density, bounds, lower, cell, samples));
  };
  if (!function)
  {
    this->Density = BrickedGrid::Sample(dims, box, value, zeroOver, parallelFor);
    return;
  }
  // A classified grid of point values: a brick's cells together, from its
  // points read once (ClassifiedDensity::NativeBrick), the same values.
  // Each brick's range of scalars is kept for the next edit of the
  // function: a brick whose range the edit left as it was is taken from
  // the previous grid.
  std::array<int, 3> brickDims{};
  for (int a = 0; a < 3; ++a)
  {
    brickDims[a] = BrickedGrid::BricksAlong(dims[a]);
  }
  const std::size_t bricks = static_cast<std::size_t>(brickDims[0]) * brickDims[1] * brickDims[2];
  if (previous && previous->BrickRanges.size() == 2 * bricks)
  {
    this->BrickRanges = previous->BrickRanges;
  }
  else
  {
    this->BrickRanges.assign(2 * bricks, std::numeric_limits<float>::quiet_NaN());
  }
  std::atomic<std::size_t> reused{ 0 }, sampled{ 0 };
  std::unique_ptr<OpacityFunctionEdit> edit;
  if (previous)
  {
    edit.reset(new OpacityFunctionEdit(*previous->Classification, *function));
  }
  auto brickIndex = [&](const std::array<int, 3>& lower)
  {
    return (static_cast<std::size_t>(lower[2] / BrickedGrid::Stride) * brickDims[1] +
             lower[1] / BrickedGrid::Stride) *
      brickDims[0] +
      lower[0] / BrickedGrid::Stride;
  };
  // Whether brick b, whose first cell is `lower`, is the previous grid's:
  // its scalars lie where the two functions give the same floats.
  auto kept = [&](const std::array<int, 3>& lower, std::size_t b)
  {
    float* range = &this->BrickRanges[2 * b];
    if (!(range[0] <= range[1]))
    {
      classified->NativeBrickRange(lower, BrickedGrid::Size, range);
    }
    const bool same = range[0] <= range[1] && edit->SameOver(range[0], range[1]);
    if (same)
    {
      reused.fetch_add(1, std::memory_order_relaxed);
    }
    return same;
  };
  // A brick whose cells the function classifies as its own values.
  auto sampleBrick = [&](const std::array<int, 3>& lower, float* out)
  {
    sampled.fetch_add(1, std::memory_order_relaxed);
    if (classified->NativeBrick(
          lower, BrickedGrid::Size, BendSamples, out, &this->BrickRanges[2 * brickIndex(lower)]))
    {
      return;
    }
    for (int k = 0; k < BrickedGrid::Size; ++k)
      for (int j = 0; j < BrickedGrid::Size; ++j)
        for (int i = 0; i < BrickedGrid::Size; ++i)
        {
          *out++ = value(std::min(lower[0] + i, dims[0] - 1), std::min(lower[1] + j, dims[1] - 1),
            std::min(lower[2] + k, dims[2] - 1));
        }
  };
  if (owned == previous && previous && previous->Density.SoleOwner())
  {
    // An edit of the function, this grid alone holding the last one's
    // samples: sampled again in their memory, the bricks over whose
    // scalars the two functions agree left where they are.
    std::vector<char> keep(bricks, 0);
    parallelFor(0, bricks,
      [&](std::size_t begin, std::size_t end)
      {
        for (std::size_t b = begin; b < end; ++b)
        {
          const std::array<int, 3> lower{ static_cast<int>(b % brickDims[0]) * BrickedGrid::Stride,
            static_cast<int>((b / brickDims[0]) % brickDims[1]) * BrickedGrid::Stride,
            static_cast<int>(b / (static_cast<std::size_t>(brickDims[0]) * brickDims[1])) *
              BrickedGrid::Stride };
          keep[b] = this->Candidates[b] && kept(lower, b) ? 1 : 0;
        }
      });
    this->Density = BrickedGrid::ResampleInPlace(
      std::move(owned->Density), keep, sampleBrick, this->Candidates, parallelFor);
  }
  else
  {
    this->Density = BrickedGrid::SampleBricks(
      dims, box,
      [&](const std::array<int, 3>& lower, float* out)
      {
        const std::size_t b = brickIndex(lower);
        if (previous && kept(lower, b))
        {
          previous->Density.CopyBrick(b, out);
          return;
        }
        sampleBrick(lower, out);
      },
      this->Candidates, parallelFor);
  }
  this->ReusedBricks = reused.load();
  this->SampledBricks = sampled.load();
}

float NativeMediumGrid::ScalarAt(int i, int j, int k) const
{
  if (!this->ScalarField)
  {
    return this->Scalars.At(i, j, k);
  }
  const std::size_t brick = this->Scalars.BrickOf(i, j, k);
  return this->Scalars.GetSlots()[brick] < 0 ? this->Scalars.GetConstants()[brick]
                                             : this->ScalarField->NativeValue(i, j, k, Vec3(0.f));
}

void NativeMediumGrid::BuildTables(
  const Box& box, const std::array<int, 3>& dims, const ParallelFor& parallelFor)
{
  // The density's integral over each histogram cell, summed from the native
  // cells by their exact overlaps (separable along the axes): of each
  // cell's constant density, or, where the field is the trilinear
  // interpolation of the cells' values (Trilinear), of each value's hat
  // (HatOverlaps()), so that a histogram cell finer than a voxel holds the
  // mass the tracer's collisions sample there. Native cells beyond the
  // medium's bounds count for the part inside.
  const BrickedGrid& grid = this->Density;
  const auto& nd = grid.GetDims();
  const Box& native = grid.GetBox();
  const GridOverlaps overlaps = CellOverlaps(grid, box, dims, this->Trilinear);
  const double nativeVolume =
    static_cast<double>(native.Volume()) / (static_cast<double>(nd[0]) * nd[1] * nd[2]);
  // Each layer of bricks along z sums into the histogram cells its cells
  // overlap (a few along z), on every thread; the layers are then added in
  // order, so that the sums do not depend on the threads.
  struct Layer
  {
    int First = 0, Last = -1; // the histogram's z cells it overlaps
    std::vector<double> Values, Firsts;
    double Total = 0.0;
  };
  const int layers = grid.GetBrickDims()[2];
  const std::size_t plane = static_cast<std::size_t>(dims[0]) * dims[1];
  std::vector<Layer> parts(static_cast<std::size_t>(layers));
  parallelFor(0, parts.size(),
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t l = begin; l < end; ++l)
      {
        Layer& part = parts[l];
        const BrickLayer layer = LayerOverlap(grid, overlaps, l, dims[2]);
        const int k0 = layer.K0, k1 = layer.K1;
        part.First = layer.First;
        part.Last = layer.Last;
        if (part.Last < part.First)
        {
          continue;
        }
        const std::size_t cells = plane * static_cast<std::size_t>(part.Last - part.First + 1);
        part.Values.assign(cells, 0.0);
        part.Firsts.assign(3 * cells, 0.0);
        // Separably: each row's mass into the histogram's x cells (mass and
        // x moment), those rows into its y cells (and the y moment), then
        // into its z cells: the same sums as each cell's share of each
        // overlapped histogram cell, in fewer products.
        const std::size_t nx = static_cast<std::size_t>(dims[0]);
        const std::size_t rows = static_cast<std::size_t>(k1 - k0) * nd[1];
        std::vector<double> byX(2 * rows * nx, 0.0);
        // The histogram x cell the last cells added into is summed in
        // registers until another is: the same additions in the same order
        // as into memory, without waiting on a store per cell.
        double* at = nullptr;
        double mass0 = 0.0, moment0 = 0.0, total = 0.0;
        grid.ForEachNonZeroCellOfLayers(static_cast<int>(l), static_cast<int>(l) + 1,
          [&](int i, int j, int k, float density)
          {
            const double mass = density * nativeVolume;
            if (mass == 0.0)
            {
              return;
            }
            total += mass;
            double* row = &byX[2 * ((static_cast<std::size_t>(k - k0) * nd[1] + j) * nx)];
            for (const Overlap& x : overlaps[0][static_cast<std::size_t>(i)])
            {
              double* cell = row + 2 * x.Coarse;
              if (cell != at)
              {
                if (at)
                {
                  at[0] = mass0;
                  at[1] = moment0;
                }
                at = cell;
                mass0 = cell[0];
                moment0 = cell[1];
              }
              const double share = mass * x.Fraction;
              mass0 += share;
              moment0 += share * x.Centre;
            }
          });
        if (at)
        {
          at[0] = mass0;
          at[1] = moment0;
        }
        part.Total = total;
        const std::size_t ny = static_cast<std::size_t>(dims[1]);
        std::vector<double> byY(3 * nx * ny);
        for (int k = k0; k < k1; ++k)
        {
          std::fill(byY.begin(), byY.end(), 0.0);
          for (int j = 0; j < nd[1]; ++j)
          {
            const double* row = &byX[2 * ((static_cast<std::size_t>(k - k0) * nd[1] + j) * nx)];
            for (const Overlap& y : overlaps[1][static_cast<std::size_t>(j)])
            {
              double* to = &byY[3 * (static_cast<std::size_t>(y.Coarse) * nx)];
              for (std::size_t x = 0; x < nx; ++x)
              {
                const double share = row[2 * x] * y.Fraction;
                to[3 * x] += share;
                to[3 * x + 1] += row[2 * x + 1] * y.Fraction;
                to[3 * x + 2] += share * y.Centre;
              }
            }
          }
          for (const Overlap& z : overlaps[2][static_cast<std::size_t>(k)])
          {
            const std::size_t offset = plane * static_cast<std::size_t>(z.Coarse - part.First);
            for (std::size_t c = 0; c < plane; ++c)
            {
              const double share = byY[3 * c] * z.Fraction;
              part.Values[offset + c] += share;
              part.Firsts[3 * (offset + c)] += byY[3 * c + 1] * z.Fraction;
              part.Firsts[3 * (offset + c) + 1] += byY[3 * c + 2] * z.Fraction;
              part.Firsts[3 * (offset + c) + 2] += share * z.Centre;
            }
          }
        }
      }
    });
  Histogram integral(dims, 1), moments(dims, 3);
  std::vector<double>& values = integral.GetValues();
  std::vector<double>& firsts = moments.GetValues();
  double total = 0.0;
  for (const Layer& part : parts)
  {
    total += part.Total;
    const std::size_t offset = plane * static_cast<std::size_t>(std::max(part.First, 0));
    for (std::size_t c = 0; c < part.Values.size(); ++c)
    {
      values[offset + c] += part.Values[c];
      for (int m = 0; m < 3; ++m)
      {
        firsts[3 * (offset + c) + m] += part.Firsts[3 * c + m];
      }
    }
  }
  this->DensityTable = SummedAreaTable(integral);
  this->DensityMoments = SummedAreaTable(moments);
  this->TableDims = dims;
  this->TableBox = box;
  // Regions whose integral is below this are empty: their source radiance
  // is 0, not a ratio of two rounding leftovers of the table.
  this->EmptyIntegral = 1e-9 * total;
}

CentroidMatching NativeMediumGrid::Centroids(const std::vector<std::array<Region, 2>>& regions,
  const std::array<int, 3>& resolution, int refinement, const ParallelFor& parallelFor) const
{
  // A region's estimate is the sigma_t-weighted mean of the source
  // radiance over it: for a source that varies linearly, exactly its value
  // at the region's sigma_t-weighted centroid, which lies off the texel's
  // centre where the density fills the region unevenly (a texel across a
  // cloud's edge, a region grown into a denser part). Homogeneous media
  // keep their estimates: their centroids are their texels' centres but
  // where a region meets the box's faces, whose light none of the measured
  // scenes showed off.
  const std::size_t texels = regions.size();
  std::vector<float> centroids(3 * texels);
  for (std::size_t t = 0; t < texels; ++t)
  {
    // The estimate is the mean of the two halves' regions' (Estimate()):
    // its centroid, the mean of theirs.
    double mean[3] = { 0.0, 0.0, 0.0 };
    for (const Region& r : regions[t])
    {
      double centre[3];
      for (int a = 0; a < 3; ++a)
      {
        centre[a] = 0.5 * (r.Lo[a] + r.Hi[a]);
      }
      double integral = 0.0, first[3];
      this->DensityTable.RegionSum(r.Lo, r.Hi, &integral);
      this->DensityMoments.RegionSum(r.Lo, r.Hi, first);
      if (integral > this->EmptyIntegral)
      {
        for (int a = 0; a < 3; ++a)
        {
          centre[a] = first[a] / integral;
        }
      }
      for (int a = 0; a < 3; ++a)
      {
        mean[a] += 0.5 * centre[a];
      }
    }
    // From histogram cells to the texels' centres' coordinates (texel i's
    // centre at i).
    for (int a = 0; a < 3; ++a)
    {
      centroids[3 * t + a] = static_cast<float>(mean[a] / refinement - 0.5);
    }
  }
  return CentroidMatching(resolution, centroids, parallelFor);
}

} // namespace brume

namespace brume
{

double NativeMediumGrid::RegionIntegral(const Region& region) const
{
  double integral = 0.0;
  this->DensityTable.RegionSum(region.Lo, region.Hi, &integral);
  return integral;
}

bool NativeMediumGrid::HasAlbedoTable(
  const Box& box, const std::array<int, 3>& dims, const AlbedoField* albedo) const
{
  return albedo && this->TableAlbedo.get() == albedo && this->AlbedoDims == dims &&
    SameBox(this->AlbedoBox, box);
}

void NativeMediumGrid::RegionAlbedoIntegral(const Region& region, double integral[3]) const
{
  this->AlbedoTable.RegionSum(region.Lo, region.Hi, integral);
}

void NativeMediumGrid::BuildAlbedoTable(const Box& box, const std::array<int, 3>& dims,
  const Medium& medium, const ParallelFor& parallelFor)
{
  // As BuildTables(): each native cell's mass, times the albedo's factor at
  // its centre (CellAlbedo's, which the hits of the cell carry), into the
  // histogram cells it overlaps; each layer of bricks on its own, the
  // layers added in order (the same sums whatever the threads). A
  // coarsened cell takes its field cells' factors weighted by the density
  // at their centres: its hits carry their own field cell's.
  const BrickedGrid& grid = this->Density;
  const auto& nd = grid.GetDims();
  const Box& native = grid.GetBox();
  const GridOverlaps overlaps = CellOverlaps(grid, box, dims, this->Trilinear);
  const double nativeVolume =
    static_cast<double>(native.Volume()) / (static_cast<double>(nd[0]) * nd[1] * nd[2]);
  struct Layer
  {
    int First = 0, Last = -1; // the histogram's z cells it overlaps
    std::vector<double> Values;
  };
  const int layers = grid.GetBrickDims()[2];
  const std::size_t plane = static_cast<std::size_t>(dims[0]) * dims[1];
  std::vector<Layer> parts(static_cast<std::size_t>(layers));
  const CellAlbedo cells(medium);
  const int coarsening = this->Coarsening;
  const std::array<int, 3>& fine = this->FieldResolution;
  const DensityField& field = *medium.Density;
  auto factorOf = [&](int i, int j, int k)
  {
    double sum[3] = { 0.0, 0.0, 0.0 }, weight = 0.0;
    for (int kk = k * coarsening; kk < std::min((k + 1) * coarsening, fine[2]); ++kk)
      for (int jj = j * coarsening; jj < std::min((j + 1) * coarsening, fine[1]); ++jj)
        for (int ii = i * coarsening; ii < std::min((i + 1) * coarsening, fine[0]); ++ii)
        {
          const double w = field.NativeValue(ii, jj, kk, cells.Centre(ii, jj, kk));
          const Vec3 f = cells.AtCell(ii, jj, kk);
          for (int c = 0; c < 3; ++c)
          {
            sum[c] += w * f[c];
          }
          weight += w;
        }
    return weight > 0.0
      ? Vec3(static_cast<float>(sum[0] / weight), static_cast<float>(sum[1] / weight),
          static_cast<float>(sum[2] / weight))
      : cells.AtCell(std::min(i * coarsening, fine[0] - 1), std::min(j * coarsening, fine[1] - 1),
          std::min(k * coarsening, fine[2] - 1));
  };
  parallelFor(0, parts.size(),
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t l = begin; l < end; ++l)
      {
        Layer& part = parts[l];
        const BrickLayer layer = LayerOverlap(grid, overlaps, l, dims[2]);
        const int k0 = layer.K0, k1 = layer.K1;
        part.First = layer.First;
        part.Last = layer.Last;
        if (part.Last < part.First)
        {
          continue;
        }
        part.Values.assign(3 * plane * static_cast<std::size_t>(part.Last - part.First + 1), 0.0);
        // Separably, as BuildTables(): each row's weighted mass into the
        // histogram's x cells (summed in registers while the cells add into
        // one), those rows into its y cells, then into its z cells.
        const std::size_t nx = static_cast<std::size_t>(dims[0]);
        const std::size_t rows = static_cast<std::size_t>(k1 - k0) * nd[1];
        std::vector<double> byX(3 * rows * nx, 0.0);
        double* at = nullptr;
        double sum[3] = { 0.0, 0.0, 0.0 };
        // The cells come brick by brick: at the field's resolution their
        // factors are read a brick at a time (CellAlbedo::AtCells()).
        std::array<int, 3> brickLower{ 0, 0, 0 }, brickCount{ 0, 0, 0 };
        std::vector<Vec3> brickFactors;
        std::vector<float> scratch;
        auto readBrick = [&](const std::array<int, 3>& lower, const std::array<int, 3>& count)
        {
          if (coarsening != 1)
          {
            return;
          }
          brickLower = lower;
          brickCount = count;
          brickFactors.resize(static_cast<std::size_t>(count[0]) * count[1] * count[2]);
          cells.AtCells(lower, count, scratch, brickFactors.data());
        };
        grid.ForEachNonZeroCellOfLayers(
          static_cast<int>(l), static_cast<int>(l) + 1,
          [&](int i, int j, int k, float density)
          {
            const double mass = density * nativeVolume;
            if (mass == 0.0)
            {
              return;
            }
            const Vec3 f = coarsening == 1
              ? brickFactors[(static_cast<std::size_t>(k - brickLower[2]) * brickCount[1] +
                               (j - brickLower[1])) *
                    brickCount[0] +
                  (i - brickLower[0])]
              : factorOf(i, j, k);
            double* row = &byX[3 * ((static_cast<std::size_t>(k - k0) * nd[1] + j) * nx)];
            for (const Overlap& x : overlaps[0][static_cast<std::size_t>(i)])
            {
              double* cell = row + 3 * x.Coarse;
              if (cell != at)
              {
                if (at)
                {
                  std::copy(sum, sum + 3, at);
                }
                at = cell;
                std::copy(cell, cell + 3, sum);
              }
              const double share = mass * x.Fraction;
              for (int c = 0; c < 3; ++c)
              {
                sum[c] += share * f[c];
              }
            }
          },
          readBrick);
        if (at)
        {
          std::copy(sum, sum + 3, at);
        }
        const std::size_t ny = static_cast<std::size_t>(dims[1]);
        std::vector<double> byY(3 * nx * ny);
        for (int k = k0; k < k1; ++k)
        {
          std::fill(byY.begin(), byY.end(), 0.0);
          for (int j = 0; j < nd[1]; ++j)
          {
            const double* row = &byX[3 * ((static_cast<std::size_t>(k - k0) * nd[1] + j) * nx)];
            for (const Overlap& y : overlaps[1][static_cast<std::size_t>(j)])
            {
              double* to = &byY[3 * (static_cast<std::size_t>(y.Coarse) * nx)];
              for (std::size_t x = 0; x < 3 * nx; ++x)
              {
                to[x] += row[x] * y.Fraction;
              }
            }
          }
          for (const Overlap& z : overlaps[2][static_cast<std::size_t>(k)])
          {
            double* to = &part.Values[3 * plane * static_cast<std::size_t>(z.Coarse - part.First)];
            for (std::size_t c = 0; c < 3 * plane; ++c)
            {
              to[c] += byY[c] * z.Fraction;
            }
          }
        }
      }
    });
  Histogram integral(dims, 3);
  std::vector<double>& values = integral.GetValues();
  for (const Layer& part : parts)
  {
    const std::size_t offset = 3 * plane * static_cast<std::size_t>(std::max(part.First, 0));
    for (std::size_t c = 0; c < part.Values.size(); ++c)
    {
      values[offset + c] += part.Values[c];
    }
  }
  this->AlbedoTable = SummedAreaTable(integral);
  this->TableAlbedo = medium.AlbedoFactor;
  this->AlbedoDims = dims;
  this->AlbedoBox = box;
}

} // namespace brume
