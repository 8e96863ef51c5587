// SPDX-License-Identifier: BSD-3-Clause
#include "brume/KeptHits.h"

#include <algorithm>

namespace brume
{

void KeptHits::Resize(std::size_t n, bool triangles, bool growth)
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

void KeptHits::Reserve(std::size_t n, bool triangles, bool growth)
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

KeptHitStore::KeptHitStore(std::size_t cells, bool triangles)
  : Cells(cells)
  , Triangles(triangles)
  , Starts(Ranges + 1, 0)
{
}

void KeptHitStore::Clear()
{
  this->Pending.Clear();
  this->Kept.Clear();
  this->Starts.assign(Ranges + 1, 0);
}

template <typename CellOf, typename Write>
void KeptHitStore::MergeIntoRanges(
  std::size_t count, CellOf cellOf, Write write, bool growth, const ParallelFor& parallelFor)
{
  // The new hits grouped by ranges of cells (a stable counting sort): each
  // range is then one task, and a cell's sum follows hit order. A range
  // holds the hits already kept in it, then its new ones (particles added
  // later come later in hit order): every later pass reads them in order.
  const std::size_t cells = this->Cells;
  auto rangeOf = [&](std::size_t k)
  { return static_cast<std::size_t>(cellOf(k)) * Ranges / cells; };
  StableGrouping grouping(count, Ranges);
  const std::vector<std::size_t>& added = grouping.Count(rangeOf, parallelFor);
  // With nothing kept yet (a build), the hits are written into the kept
  // hits' own buffers (ReuseMemory: pages a last build already mapped); a
  // merge reads the kept hits while it writes, into buffers of its own.
  const bool hadKept = !this->Kept.Empty();
  KeptHits separate;
  KeptHits& merged = hadKept ? separate : this->Kept; // every element written below
  const std::size_t total = this->Kept.Size() + count;
  const bool triangles = this->Triangles;
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
    firstAdded[r] = mergedStart[r] + (this->Starts[r + 1] - this->Starts[r]);
    mergedStart[r + 1] = firstAdded[r] + added[r];
  }
  if (hadKept)
  {
    parallelFor(0, Ranges,
      [&](std::size_t begin, std::size_t end)
      {
        for (std::size_t r = begin; r < end; ++r)
        {
          const std::size_t first = this->Starts[r], n = this->Starts[r + 1] - first;
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
  this->Starts.swap(mergedStart);
}

void KeptHitStore::Keep(const HitArrays& hits, const std::uint32_t* index,
  const std::uint32_t* cellOf, std::size_t count, double runShare, const ParallelFor& parallelFor,
  const CellAlbedo* albedo)
{
  // Growth scales are kept once a light was aimed (all 1 otherwise), or
  // where they restore the weight of a flux an albedo scaled.
  const bool growth = hits.Aim != nullptr || albedo;
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
    double restore = 1.0; // the incident flux's mean over the scaled flux's
    if (albedo)
    {
      const Vec3 a = albedo->At(Vec3(h.Position[0], h.Position[1], h.Position[2]));
      const double incident = static_cast<double>(h.Flux[0]) + h.Flux[1] + h.Flux[2];
      for (int c = 0; c < 3; ++c)
      {
        h.Flux[c] *= a[c];
      }
      const double scattered = static_cast<double>(h.Flux[0]) + h.Flux[1] + h.Flux[2];
      restore = scattered > 0.0 ? incident / scattered : 1.0;
    }
    if (!out.Growth.empty())
    {
      out.Growth[p] = static_cast<float>(hits.GrowthScale(i) * restore);
    }
  };
  if (!this->Deferred && this->Pending.Empty())
  {
    this->MergeIntoRanges(
      count, [&](std::size_t k) { return cellOf[k]; }, keep, growth, parallelFor);
    return;
  }
  // A batch of a run: its hits wait, in hit order, for the batch that
  // estimates, which merges them all at once.
  const std::size_t before = this->Pending.Size();
  if (this->Pending.Hits.capacity() < before + count)
  {
    // Room for the run's hits at once, 5 % to spare, where its share is known.
    const double share = runShare > 0.0 && runShare < 1.0 ? runShare : 1.0;
    const double expected = 1.05 * static_cast<double>(before + count) / share;
    this->Pending.Reserve(
      std::max(before + count, static_cast<std::size_t>(expected)), this->Triangles, growth);
  }
  this->Pending.Resize(before + count, this->Triangles, growth);
  parallelFor(0, count,
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t k = begin; k < end; ++k)
      {
        keep(k, this->Pending, before + k);
      }
    });
  if (!this->Deferred)
  {
    this->MergePending(parallelFor);
  }
}

void KeptHitStore::MergePending(const ParallelFor& parallelFor)
{
  this->MergeIntoRanges(
    this->Pending.Size(), [&](std::size_t k) { return this->Pending.Hits[k].Cell; },
    [&](std::size_t k, KeptHits& out, std::size_t p) { out.Set(p, this->Pending, k); },
    !this->Pending.Growth.empty(), parallelFor);
  this->Pending = KeptHits(); // its memory freed
}

void KeptHitStore::ScaleFlux(float scale, const ParallelFor& parallelFor)
{
  parallelFor(0, this->Kept.Size(),
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t k = begin; k < end; ++k)
      {
        for (float& f : this->Kept.Hits[k].Flux)
        {
          f *= scale;
        }
      }
    });
  for (KeptHit& h : this->Pending.Hits) // batches not yet merged (scale 1 in practice)
  {
    for (float& f : h.Flux)
    {
      f *= scale;
    }
  }
}

KeptHits KeptHitStore::ReleaseMemory()
{
  KeptHits memory = std::move(this->Kept);
  this->Kept = KeptHits();
  memory.Clear();
  this->Starts.assign(Ranges + 1, 0);
  return memory;
}

void KeptHitStore::ReuseMemory(KeptHits&& memory, std::size_t hits)
{
  KeptHits given = std::move(memory);
  if (this->Kept.Empty() && given.Hits.capacity() <= std::max<std::size_t>(2 * hits, 4096))
  {
    given.Clear();
    this->Kept = std::move(given);
  }
}

} // namespace brume
