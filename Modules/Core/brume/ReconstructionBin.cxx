// SPDX-License-Identifier: BSD-3-Clause
// Binning the hits of an object into its histograms (brume/Reconstruction.h):
// the cell of every hit, one pass in hit order for view-independent objects,
// the kept hits grouped by cell for view-dependent ones.
#include "brume/Reconstruction.h"
#include "brume/ReconstructionWeights.h"

#include "brume/DirectLight.h"
#include "brume/Material.h"
#include "brume/Reflection.h"
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
    for (int a = 0; a < 3; ++a)
    {
      this->Size[a] = dims[a];
      this->Top[a] = dims[a] - 1;
    }
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
  // The cell of (s, t, r) in [0, 1)^3, clamped to the grid (NaN: cell 0).
  std::uint32_t Index(double s, double t, double r) const
  {
    const std::size_t c0 = this->Cell(s, 0), c1 = this->Cell(t, 1);
    const std::size_t c2 = this->Top[2] > 0.0 ? this->Cell(r, 2) : 0;
    return static_cast<std::uint32_t>((c2 * this->Dims[1] + c1) * this->Dims[0] + c0);
  }
  // floor(q n) clamped to [0, n - 1] along axis a, without floor(): x >= 0
  // exactly when floor(x) >= 0, x >= n - 1 exactly when floor(x) >= n - 1
  // (an integer), and truncation is floor in between. A third of the
  // binning's instructions went to floor()'s expansion (SSE2 has no roundsd).
  std::size_t Cell(double q, int a) const
  {
    const double x = q * this->Size[a];
    if (!(x >= 0.0))
    {
      return 0;
    }
    return static_cast<std::size_t>(static_cast<int>(std::min(x, this->Top[a])));
  }

  const std::array<int, 3>& Dims;
  double Size[3], Top[3]; // Dims and Dims - 1
  const Medium* MediumRef;
  const Surface* SurfaceRef;
  const SurfaceChart& Chart;
  bool Planar;
  Box Bounds;
  float UU, VV;
};
}

// Here, where the binning calls it for every hit: inlined.
inline bool ObjectRadiance::FromFront(const HitArrays& hits, std::uint32_t i) const
{
  // The particle travels against the front (winding) normal of its triangle.
  const std::uint32_t t = hits.Triangle ? hits.Triangle[i] : 0;
  const Vec3& n = this->TriangleNormals[t < this->TriangleNormals.size() ? t : 0];
  const Vec3 d(hits.Direction[3 * i], hits.Direction[3 * i + 1], hits.Direction[3 * i + 2]);
  return Dot(n, d) < 0.f;
}

void ObjectRadiance::KeptHits::Resize(std::size_t n, bool triangles, bool growth)
{
  const std::size_t before = this->Hits.size();
  this->Hits.resize(n);
  if (triangles)
  {
    this->Triangle.resize(n);
  }
  if (growth || !this->Growth.empty())
  {
    const bool scaled = !this->Growth.empty();
    this->Growth.resize(n);
    if (!scaled)
    {
      std::fill(
        this->Growth.begin(), this->Growth.begin() + static_cast<std::ptrdiff_t>(before), 1.f);
    }
  }
}

void ObjectRadiance::KeptHits::Reserve(std::size_t n, bool triangles, bool growth)
{
  this->Hits.reserve(n);
  if (triangles)
  {
    this->Triangle.reserve(n);
  }
  if (growth || !this->Growth.empty())
  {
    this->Growth.reserve(n);
  }
}

template <typename CellOf, typename Write>
void ObjectRadiance::MergeIntoRanges(
  std::size_t count, CellOf cellOf, Write write, bool growth, const ParallelFor& parallelFor)
{
  // The new hits grouped by ranges of cells (a stable counting sort): each
  // range is then one task, and a cell's sum follows hit order. A range
  // holds the hits already kept in it, then its new ones (particles added
  // later come later in hit order): every later pass reads them in order.
  const std::size_t cells = static_cast<std::size_t>(this->Dims[0]) * this->Dims[1] * this->Dims[2];
  auto rangeOf = [&](std::size_t k)
  { return static_cast<std::size_t>(cellOf(k)) * Ranges / cells; };
  StableGrouping grouping(count, Ranges);
  const std::vector<std::size_t>& added = grouping.Count(rangeOf, parallelFor);
  // With nothing kept yet (a build), the hits are written into the kept
  // hits' own buffers (ReuseKeptMemory: pages a last build already mapped);
  // a merge reads the kept hits while it writes, into buffers of its own.
  const bool hadKept = !this->Kept.Empty();
  KeptHits separate;
  KeptHits& merged = hadKept ? separate : this->Kept; // every element written below
  const std::size_t total = this->Kept.Size() + count;
  const bool triangles = this->SurfaceRef != nullptr;
  const bool scales = growth || !this->Kept.Growth.empty();
  if (!hadKept && this->Kept.Hits.capacity() < total)
  {
    // 5 % to spare (pages are mapped only when written), so that the next
    // build's hits, as many give or take the noise, fit where these were.
    this->Kept.Reserve(total + total / 20, triangles, scales);
  }
  merged.Resize(total, triangles, scales);
  std::vector<std::size_t> mergedStart(Ranges + 1, 0);
  std::vector<std::size_t> firstAdded(Ranges);
  for (std::size_t r = 0; r < Ranges; ++r)
  {
    firstAdded[r] = mergedStart[r] + (this->RangeStart[r + 1] - this->RangeStart[r]);
    mergedStart[r + 1] = firstAdded[r] + added[r];
  }
  if (hadKept)
  {
    parallelFor(0, Ranges,
      [&](std::size_t begin, std::size_t end)
      {
        for (std::size_t r = begin; r < end; ++r)
        {
          const std::size_t first = this->RangeStart[r], n = this->RangeStart[r + 1] - first;
          std::copy_n(this->Kept.Hits.begin() + static_cast<std::ptrdiff_t>(first), n,
            merged.Hits.begin() + static_cast<std::ptrdiff_t>(mergedStart[r]));
          for (std::size_t k = 0; k < n; ++k)
          {
            if (!merged.Triangle.empty())
            {
              merged.Triangle[mergedStart[r] + k] = this->Kept.TriangleOf(first + k);
            }
            if (!merged.Growth.empty())
            {
              merged.Growth[mergedStart[r] + k] = this->Kept.GrowthOf(first + k);
            }
          }
        }
      });
  }
  grouping.Place(
    firstAdded, rangeOf, [&](std::size_t k, std::size_t position) { write(k, merged, position); },
    parallelFor);
  if (hadKept)
  {
    this->Kept = std::move(separate);
  }
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
  if (!this->KeepsHits())
  {
    this->BinInPlace(hits, index, count, cellOfHit);
  }
  else
  {
    this->KeepHits(hits, index, count, cellOfHit, parallelFor);
  }
}

std::vector<Vec3> ObjectRadiance::UnitNormals() const
{
  std::vector<Vec3> normals(this->TriangleNormals.size());
  for (std::size_t t = 0; t < normals.size(); ++t)
  {
    normals[t] = Normalize(this->TriangleNormals[t]);
  }
  return normals;
}

inline void ObjectRadiance::AddTerms(const HitArrays& hits, std::uint32_t i, std::uint32_t cell)
{
  const float* f = hits.Flux + 3 * i;
  const std::uint32_t triangle = hits.Triangle ? hits.Triangle[i] : 0;
  double v[3];
  if (this->ViewFixed)
  {
    // The terms the kept hits would give toward the fixed eye
    // (SumHistograms(), WeighCells()), their growth scale in float as kept.
    const double w[1] = { (static_cast<double>(f[0]) + f[1] + f[2]) / 3.0 *
      static_cast<float>(hits.GrowthScale(i)) };
    this->WeightSums.AddNonNegative(cell, w);
    this->WeighHit(this->FixedEye, hits.Position + 3 * i, hits.Direction + 3 * i, f, triangle,
      this->FixedNormals, v);
    this->ValueSums.AddNonNegative(cell, v);
    return;
  }
  const double w[1] = { (static_cast<double>(f[0]) + f[1] + f[2]) / 3.0 * hits.GrowthScale(i) };
  this->WeightSums.AddNonNegative(cell, w);
  if (this->MediumRef)
  {
    for (int c = 0; c < 3; ++c)
    {
      v[c] = Inv4Pi * static_cast<double>(f[c]);
    }
  }
  else
  {
    const Surface& surface = *this->SurfaceRef;
    Material coloured; // where the surface's reflectance varies over it
    const Material& m = surface.VertexReflectance.empty()
      ? surface.MaterialOf(triangle)
      : (coloured = surface.MaterialAt(triangle,
           Vec3(hits.Position[3 * i], hits.Position[3 * i + 1], hits.Position[3 * i + 2])));
    for (int c = 0; c < 3; ++c)
    {
      v[c] = m.Reflectance[c] * InvPi * static_cast<double>(f[c]);
    }
  }
  this->ValueSums.AddNonNegative(cell, v);
}

template <typename Locator>
void ObjectRadiance::BinInPlace(
  const HitArrays& hits, const std::uint32_t* index, std::size_t count, const Locator& cellOfHit)
{
  // View-independent objects: every hit is added to its cell (exact sums:
  // any order of the terms gives the same bits); nothing is kept. The loop
  // is bound by memory latency, not arithmetic: an object's hits are spread
  // over the whole run's arrays, and a fine histogram (32 bytes a cell: a
  // weight and three values; megabytes at 10^7 particles) misses the
  // caches at nearly every hit. So a hit Ahead of the one whose cell is
  // found is asked for, and its cell's sums are asked for Lag hits before
  // they are added to (a software pipeline): 10^7 particles of the default
  // scene bin in 0.07-0.09 s a wall instead of 0.17 s with the hits grouped by
  // ranges of cells first, and nothing is allocated.
  // A surface shows light arriving on its front side only (the back side's
  // is reflected, not shown): other hits have no cell.
  constexpr std::uint32_t NoCell = ~std::uint32_t(0);
  constexpr std::size_t Ahead = 32, Lag = 16;
  std::uint32_t waitingHit[Lag], waitingCell[Lag];
  for (std::size_t k = 0; k < count + Lag; ++k)
  {
    // Hit k - Lag's terms added, then its slot taken by hit k.
    const std::size_t slot = k % Lag;
    if (k >= Lag && waitingCell[slot] != NoCell)
    {
      this->AddTerms(hits, waitingHit[slot], waitingCell[slot]);
    }
    if (k < count)
    {
      if (k + Ahead < count)
      {
        const std::uint32_t j = index[k + Ahead];
        __builtin_prefetch(hits.Position + 3 * j);
        __builtin_prefetch(hits.Direction + 3 * j);
        __builtin_prefetch(hits.Flux + 3 * j);
      }
      const std::uint32_t i = index[k];
      const std::uint32_t cell =
        this->MediumRef || this->FromFront(hits, i) ? cellOfHit(hits, i) : NoCell;
      if (cell != NoCell)
      {
        this->WeightSums.Prefetch(cell);
        this->ValueSums.Prefetch(cell);
      }
      waitingHit[slot] = i;
      waitingCell[slot] = cell;
    }
  }
  this->SumsClamped =
    this->SumsClamped || this->WeightSums.Saturated() || this->ValueSums.Saturated();
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
  // Every element written below, in parallel: not zeroed first.
  std::vector<std::uint32_t, UninitializedAllocator<std::uint32_t>> cellOf(count);
  parallelFor(0, count,
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t k = begin; k < end; ++k)
      {
        cellOf[k] = cellOfHit(hits, index[k]);
      }
    });
  // Growth scales are kept once a light was aimed (all 1 otherwise).
  const bool growth = hits.Aim != nullptr;
  auto keep = [&](std::size_t k, KeptHits& out, std::size_t p)
  {
    const std::size_t i = index[k];
    KeptHit& h = out.Hits[p];
    // Element by element: std::copy of three floats is a memmove call.
    for (int a = 0; a < 3; ++a)
    {
      h.Position[a] = hits.Position[3 * i + a];
      h.Direction[a] = hits.Direction[3 * i + a];
      h.Flux[a] = hits.Flux[3 * i + a];
    }
    h.Cell = cellOf[k];
    if (!out.Triangle.empty())
    {
      out.Triangle[p] = hits.Triangle ? hits.Triangle[i] : 0;
    }
    if (!out.Growth.empty())
    {
      out.Growth[p] = static_cast<float>(hits.GrowthScale(i));
    }
  };
  if (!this->DeferMerge && this->Pending.Empty())
  {
    this->MergeIntoRanges(
      count, [&](std::size_t k) { return cellOf[k]; }, keep, growth, parallelFor);
    return;
  }
  // A batch of a run: its hits wait, in hit order, for the batch that
  // estimates, which merges them all at once.
  const std::size_t before = this->Pending.Size();
  const bool triangles = this->SurfaceRef != nullptr;
  if (this->Pending.Hits.capacity() < before + count)
  {
    // Room for the run's hits at once, 5 % to spare, where its share is known.
    const double share = this->RunShare > 0.0 && this->RunShare < 1.0 ? this->RunShare : 1.0;
    const double expected = 1.05 * static_cast<double>(before + count) / share;
    this->Pending.Reserve(
      std::max(before + count, static_cast<std::size_t>(expected)), triangles, growth);
  }
  this->Pending.Resize(before + count, triangles, growth);
  parallelFor(0, count,
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t k = begin; k < end; ++k)
      {
        keep(k, this->Pending, before + k);
      }
    });
  if (!this->DeferMerge)
  {
    this->MergePending(parallelFor);
  }
}

ObjectRadiance::KeptHits ObjectRadiance::ReleaseKeptMemory()
{
  KeptHits memory = std::move(this->Kept);
  this->Kept = KeptHits();
  memory.Clear();
  this->RangeStart.assign(Ranges + 1, 0);
  return memory;
}

void ObjectRadiance::ReuseKeptMemory(KeptHits&& memory, std::size_t hits)
{
  KeptHits given = std::move(memory);
  if (this->KeepsHits() && this->Kept.Empty() &&
    given.Hits.capacity() <= std::max<std::size_t>(2 * hits, 4096))
  {
    given.Clear();
    this->Kept = std::move(given);
  }
}

void ObjectRadiance::MergePending(const ParallelFor& parallelFor)
{
  // Kept ends as if each batch had been merged in turn.
  this->MergeIntoRanges(
    this->Pending.Size(), [&](std::size_t k) { return this->Pending.Hits[k].Cell; },
    [&](std::size_t k, KeptHits& out, std::size_t p) { out.Set(p, this->Pending, k); },
    !this->Pending.Growth.empty(), parallelFor);
  this->Pending = KeptHits(); // its memory freed
}

} // namespace brume
