// SPDX-License-Identifier: BSD-3-Clause
// Binning the hits of an object into its histograms (brume/Reconstruction.h):
// the cell of every hit, one pass in hit order for view-independent objects,
// the kept hits grouped by cell for view-dependent ones.
#include "brume/Reconstruction.h"

#include "brume/DirectLight.h"
#include "brume/Material.h"
#include "brume/Sampling.h"

#include <algorithm>
#include <cmath>

namespace brume
{

namespace
{
// Barycentric coordinates of p (projected) in the triangle abc.
void Barycentric(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& p, float& u, float& v)
{
  const Vec3 e0 = b - a, e1 = c - a, e2 = p - a;
  const float d00 = Dot(e0, e0), d01 = Dot(e0, e1), d11 = Dot(e1, e1);
  const float d20 = Dot(e2, e0), d21 = Dot(e2, e1);
  const float det = d00 * d11 - d01 * d01;
  u = det != 0.f ? (d11 * d20 - d01 * d21) / det : 0.f;
  v = det != 0.f ? (d00 * d21 - d01 * d20) / det : 0.f;
}

// A stable counting sort of n items into `ranges` groups: item k belongs to
// group rangeOf(k), and place(k, position) puts it at its position, items
// of a group in their order. Returns where each group starts (ranges + 1).
template <typename RangeOf, typename Place>
std::vector<std::size_t> GroupByRanges(
  std::size_t n, std::size_t ranges, RangeOf rangeOf, Place place)
{
  std::vector<std::size_t> start(ranges + 1, 0);
  for (std::size_t k = 0; k < n; ++k)
  {
    ++start[rangeOf(k) + 1];
  }
  for (std::size_t r = 0; r < ranges; ++r)
  {
    start[r + 1] += start[r];
  }
  std::vector<std::size_t> cursor(start.begin(), start.end() - 1);
  for (std::size_t k = 0; k < n; ++k)
  {
    place(k, cursor[rangeOf(k)]++);
  }
  return start;
}
}

namespace
{
// The histogram cell of a hit: its (u, v) on the surface's chart, or its
// position in the medium's box.
class CellLocator
{
public:
  CellLocator(const std::array<int, 3>& dims, const Medium* medium, const Surface* surface,
    const SurfaceChart& chart)
    : Dims(dims)
    , MediumRef(medium)
    , SurfaceRef(surface)
    , Chart(chart)
    , Planar(!medium && chart.Type == SurfaceChart::Kind::Planar)
    , Bounds(medium ? medium->Bounds : Box())
    , UU(Dot(chart.Frame.U, chart.Frame.U))
    , VV(Dot(chart.Frame.V, chart.Frame.V))
  {
  }

  std::uint32_t operator()(const HitArrays& hits, std::uint32_t i) const
  {
    const Vec3 p(hits.Position[3 * i], hits.Position[3 * i + 1], hits.Position[3 * i + 2]);
    if (this->MediumRef)
    {
      const Vec3 q = (p - this->Bounds.lower) / this->Bounds.Extent();
      return this->Index(q.x, q.y, q.z);
    }
    if (this->Planar)
    {
      const Vec3 d = p - this->Chart.Frame.Origin;
      return this->Index(
        Dot(d, this->Chart.Frame.U) / this->UU, Dot(d, this->Chart.Frame.V) / this->VV, 0.0);
    }
    const std::uint32_t t = hits.Triangle[i];
    const auto& tri = this->SurfaceRef->Triangles[t];
    float b1, b2;
    Barycentric(this->SurfaceRef->Vertices[tri[0]], this->SurfaceRef->Vertices[tri[1]],
      this->SurfaceRef->Vertices[tri[2]], p, b1, b2);
    const auto& uv = this->Chart.TriangleUV[t];
    const float b0 = 1.f - b1 - b2;
    return this->Index(
      b0 * uv[0] + b1 * uv[2] + b2 * uv[4], b0 * uv[1] + b1 * uv[3] + b2 * uv[5], 0.0);
  }

private:
  std::uint32_t Index(double s, double t, double r) const
  {
    std::array<int, 3> c{};
    const double q[3] = { s, t, r };
    for (int a = 0; a < 3; ++a)
    {
      const double x = std::floor(q[a] * this->Dims[a]);
      c[a] = x >= 0.0 ? static_cast<int>(std::min<double>(x, this->Dims[a] - 1)) : 0;
    }
    return static_cast<std::uint32_t>(
      (static_cast<std::size_t>(c[2]) * this->Dims[1] + c[1]) * this->Dims[0] + c[0]);
  }

  const std::array<int, 3>& Dims;
  const Medium* MediumRef;
  const Surface* SurfaceRef;
  const SurfaceChart& Chart;
  bool Planar;
  Box Bounds;
  float UU, VV;
};
}

template <typename CellOf, typename Write>
void ObjectRadiance::MergeIntoRanges(
  std::size_t count, CellOf cellOf, Write write, const ParallelFor& parallelFor)
{
  // Group the new hits by ranges of cells (a coarse, stable counting sort):
  // each range is then one task, and a cell's sum follows hit order.
  const std::size_t cells = static_cast<std::size_t>(this->Dims[0]) * this->Dims[1] * this->Dims[2];
  std::vector<std::uint32_t> order(count);
  const std::vector<std::size_t> start = GroupByRanges(
    count, Ranges,
    [&](std::size_t k) { return static_cast<std::size_t>(cellOf(k)) * Ranges / cells; },
    [&](std::size_t k, std::size_t position) { order[position] = static_cast<std::uint32_t>(k); });
  // The hits in that order, after the hits already kept in each range
  // (particles added later come later in hit order): every later pass reads
  // them sequentially.
  std::vector<KeptHit> merged(this->Kept.size() + count);
  std::vector<std::size_t> mergedStart(Ranges + 1, 0);
  for (std::size_t r = 0; r < Ranges; ++r)
  {
    mergedStart[r + 1] =
      mergedStart[r] + (this->RangeStart[r + 1] - this->RangeStart[r]) + (start[r + 1] - start[r]);
  }
  parallelFor(0, Ranges,
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t r = begin; r < end; ++r)
      {
        KeptHit* out = merged.data() + mergedStart[r];
        out = std::copy(this->Kept.begin() + static_cast<std::ptrdiff_t>(this->RangeStart[r]),
          this->Kept.begin() + static_cast<std::ptrdiff_t>(this->RangeStart[r + 1]), out);
        for (std::size_t k = start[r]; k < start[r + 1]; ++k, ++out)
        {
          write(order[k], *out);
        }
      }
    });
  this->Kept.swap(merged);
  this->RangeStart.swap(mergedStart);
}

void ObjectRadiance::Bin(const HitArrays& hits, const std::uint32_t* index, std::size_t count,
  const ParallelFor& parallelFor)
{
  const CellLocator cellOfHit(this->Dims, this->MediumRef, this->SurfaceRef, this->Chart);
  std::vector<std::uint32_t> scattered;
  if (this->Direct)
  {
    // The first interactions after a delta light are computed, not estimated.
    scattered.reserve(count);
    for (std::size_t k = 0; k < count; ++k)
    {
      if (!this->Direct->IsFirstInteraction(hits.Emitter[index[k]], hits.Depth[index[k]]))
      {
        scattered.push_back(index[k]);
      }
    }
    index = scattered.data();
    count = scattered.size();
  }
  if (!this->ViewDependent)
  {
    this->BinInPlace(hits, index, count, cellOfHit);
  }
  else
  {
    this->KeepHits(hits, index, count, cellOfHit, parallelFor);
  }
}

template <typename Locator>
void ObjectRadiance::BinInPlace(
  const HitArrays& hits, const std::uint32_t* index, std::size_t count, const Locator& cellOfHit)
{
  // View-independent objects: every hit is added to its cell (exact sums:
  // any order gives the same bits); nothing is kept.
  auto add = [this](std::uint32_t cell, const float* f, std::uint32_t triangle)
  {
    const double w[1] = { (static_cast<double>(f[0]) + f[1] + f[2]) / 3.0 };
    this->WeightSums.AddNonNegative(cell, w);
    double v[3];
    if (this->MediumRef)
    {
      for (int c = 0; c < 3; ++c)
      {
        v[c] = Inv4Pi * static_cast<double>(f[c]);
      }
    }
    else
    {
      const Material& m = this->SurfaceRef->MaterialOf(triangle);
      for (int c = 0; c < 3; ++c)
      {
        v[c] = m.Reflectance[c] * InvPi * static_cast<double>(f[c]);
      }
    }
    this->ValueSums.AddNonNegative(cell, v);
  };
  const std::size_t cells = static_cast<std::size_t>(this->Dims[0]) * this->Dims[1] * this->Dims[2];
  // The sums take 32 bytes a cell (a weight and three values). Histograms
  // that fit the caches take the hits in hit order, in one pass.
  constexpr std::size_t CacheBytes = std::size_t(2) << 20;
  const std::size_t bytes = 32 * cells;
  if (bytes <= CacheBytes)
  {
    for (std::size_t k = 0; k < count; ++k)
    {
      const std::uint32_t i = index[k];
      if (!this->MediumRef && !this->FromFront(hits, i))
      {
        continue; // light on the back side: reflected, not shown
      }
      add(cellOfHit(hits, i), hits.Flux + 3 * i, hits.Triangle ? hits.Triangle[i] : 0);
    }
  }
  else
  {
    // Larger ones (many particles: fine textures) would miss the caches at
    // nearly every hit. The hits' terms are grouped by ranges of cells that
    // fit the caches (a counting sort), then added range by range: the same
    // sums, at a fraction of the time for 10^7 hits and more.
    struct Term
    {
      std::uint32_t Cell;
      float Flux[3];
      std::uint32_t Triangle;
    };
    const std::size_t ranges = std::min<std::size_t>(4096, bytes / (CacheBytes / 4) + 1);
    std::vector<std::uint32_t> front, cellOf; // the hits binned, and their cells
    front.reserve(count);
    cellOf.reserve(count);
    for (std::size_t k = 0; k < count; ++k)
    {
      const std::uint32_t i = index[k];
      if (this->MediumRef || this->FromFront(hits, i))
      {
        front.push_back(i);
        cellOf.push_back(cellOfHit(hits, i));
      }
    }
    std::vector<Term> grouped(front.size());
    GroupByRanges(
      front.size(), ranges,
      [&](std::size_t k) { return static_cast<std::size_t>(cellOf[k]) * ranges / cells; },
      [&](std::size_t k, std::size_t position)
      {
        const std::uint32_t i = front[k];
        Term& t = grouped[position];
        t.Cell = cellOf[k];
        for (int c = 0; c < 3; ++c)
        {
          t.Flux[c] = hits.Flux[3 * i + c];
        }
        t.Triangle = hits.Triangle ? hits.Triangle[i] : 0;
      });
    for (const Term& t : grouped)
    {
      add(t.Cell, t.Flux, t.Triangle);
    }
  }
  this->Reduce(this->WeightSums, &this->ValueSums);
}

template <typename Locator>
void ObjectRadiance::KeepHits(const HitArrays& hits, const std::uint32_t* index, std::size_t count,
  const Locator& cellOfHit, const ParallelFor& parallelFor)
{
  // View-dependent objects keep their hits with their histogram cells,
  // grouped by ranges of cells: a new eye re-weights them (WeighCells).
  // Surfaces keep the hits arriving on their front side only.
  std::vector<std::uint32_t> front;
  if (!this->MediumRef)
  {
    for (std::size_t k = 0; k < count; ++k)
    {
      if (this->FromFront(hits, index[k]))
      {
        front.push_back(index[k]);
      }
    }
    index = front.data();
    count = front.size();
  }
  std::vector<std::uint32_t> cellOf(count);
  parallelFor(0, count,
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t k = begin; k < end; ++k)
      {
        cellOf[k] = cellOfHit(hits, index[k]);
      }
    });
  auto keep = [&](std::size_t k, KeptHit& out)
  {
    const std::size_t i = index[k];
    // Element by element: std::copy of three floats is a memmove call.
    for (int a = 0; a < 3; ++a)
    {
      out.Position[a] = hits.Position[3 * i + a];
      out.Direction[a] = hits.Direction[3 * i + a];
      out.Flux[a] = hits.Flux[3 * i + a];
    }
    out.Cell = cellOf[k];
    out.Triangle = hits.Triangle ? hits.Triangle[i] : 0;
  };
  if (!this->DeferMerge && this->Pending.empty())
  {
    this->MergeIntoRanges(
      count, [&](std::size_t k) { return cellOf[k]; }, keep, parallelFor);
    return;
  }
  // A batch of a run: its hits wait, in hit order, for the batch that
  // estimates, which merges them all at once.
  const std::size_t before = this->Pending.size();
  if (this->Pending.capacity() < before + count)
  {
    // Room for the run's hits at once, 5 % to spare, where its share is known.
    const double share = this->RunShare > 0.0 && this->RunShare < 1.0 ? this->RunShare : 1.0;
    const double expected = 1.05 * static_cast<double>(before + count) / share;
    this->Pending.reserve(std::max(before + count, static_cast<std::size_t>(expected)));
  }
  this->Pending.resize(before + count);
  parallelFor(0, count,
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t k = begin; k < end; ++k)
      {
        keep(k, this->Pending[before + k]);
      }
    });
  if (!this->DeferMerge)
  {
    this->MergePending(parallelFor);
  }
}

void ObjectRadiance::MergePending(const ParallelFor& parallelFor)
{
  // Kept ends as if each batch had been merged in turn.
  this->MergeIntoRanges(
    this->Pending.size(), [&](std::size_t k) { return this->Pending[k].Cell; },
    [&](std::size_t k, KeptHit& out) { out = this->Pending[k]; }, parallelFor);
  std::vector<KeptHit>().swap(this->Pending);
}

} // namespace brume
