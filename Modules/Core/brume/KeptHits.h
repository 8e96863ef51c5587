// SPDX-License-Identifier: BSD-3-Clause
// The hits a view-dependent object keeps (brume::ObjectRadiance), so that a
// new eye re-weights them: grouped by ranges of histogram cells, each range
// one task of a pass over them, and in hit order within a range, so that a
// cell's sum follows hit order whatever the threads.
#ifndef brume_KeptHits_h
#define brume_KeptHits_h

#include "brume/Grouping.h"
#include "brume/HitArrays.h"
#include "brume/Medium.h"
#include "brume/Parallel.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace brume
{

/**
 * A kept hit: 40 bytes, 4 more for a surface's triangle (its BRDF toward the
 * eye) and 4 more for the growth scale (HitArrays::GrowthScale) once a light
 * was aimed or where a medium's albedo varies, kept beside them in the same
 * order, so that a fog under an unaimed light keeps 40. A medium whose
 * albedo varies keeps each hit's flux times its cell's albedo factor (the
 * light it scattered, which every view weighs), its growth scale times the
 * ratio that restores the incident flux's mean (what regions grow by).
 */
struct KeptHit
{
  float Position[3], Direction[3], Flux[3];
  std::uint32_t Cell;
};
static_assert(sizeof(KeptHit) == 40, "KeptHit layout changed: update the documentation");

/// Kept hits, with their triangles and growth scales where there are any.
struct KeptHits
{
  template <typename T>
  using Uninitialized = std::vector<T, UninitializedAllocator<T>>;
  Uninitialized<KeptHit> Hits;
  Uninitialized<std::uint32_t> Triangle; // empty, or one per hit
  Uninitialized<float> Growth;           // empty (every scale 1), or one per hit

  std::size_t Size() const { return this->Hits.size(); }
  void Clear()
  {
    this->Hits.clear();
    this->Triangle.clear();
    this->Growth.clear();
  }
  bool Empty() const { return this->Hits.empty(); }
  std::uint32_t TriangleOf(std::size_t k) const
  {
    return this->Triangle.empty() ? 0 : this->Triangle[k];
  }
  float GrowthOf(std::size_t k) const { return this->Growth.empty() ? 1.f : this->Growth[k]; }
  // n hits, the new ones left for the caller to write: with triangles when
  // asked, with growth scales when asked or already kept (the hits kept so
  // far scale 1 when the first aimed ones come).
  void Resize(std::size_t n, bool triangles, bool growth);
  void Reserve(std::size_t n, bool triangles, bool growth);
  // Hit k of `from` into place `to` (its arrays, where this one has them).
  void Set(std::size_t to, const KeptHits& from, std::size_t k)
  {
    this->Hits[to] = from.Hits[k];
    if (!this->Triangle.empty())
    {
      this->Triangle[to] = from.TriangleOf(k);
    }
    if (!this->Growth.empty())
    {
      this->Growth[to] = from.GrowthOf(k);
    }
  }
};

/**
 * An object's kept hits, grouped by Ranges ranges of its `cells` histogram
 * cells. The hits of the batches of a run that do not estimate wait in hit
 * order (pending) and are merged into the ranges once, by the batch that
 * estimates: merging at every batch would copy every hit kept so far each
 * time. Kept ends as if each batch had been merged in turn.
 */
class KeptHitStore
{
public:
  /// Ranges of histogram cells, each one task of a pass over the kept hits.
  static constexpr std::size_t Ranges = 64;

  /// `triangles`: a surface's hits, which keep their triangles.
  KeptHitStore(std::size_t cells, bool triangles);

  /// Empties the store for a new build, its buffers' capacity kept.
  void Clear();
  /// Whether hits kept from now on wait (Keep()) until MergePending().
  void SetDeferred(bool deferred) { this->Deferred = deferred; }
  bool IsDeferred() const { return this->Deferred; }

  /**
   * Keeps hits[index[k]] in cell cellOf[k], k < count: merged into the
   * ranges after the hits kept there, or pending while deferred or while
   * hits already wait. `runShare` (the share of the run's particles binned
   * once these are) sizes the pending buffer for the whole run at once.
   * With `albedo`, each hit's flux is multiplied by the albedo's factor of
   * its cell and its growth scale divided by what that did to the flux's
   * mean (KeptHit).
   */
  void Keep(const HitArrays& hits, const std::uint32_t* index, const std::uint32_t* cellOf,
    std::size_t count, double runShare, const ParallelFor& parallelFor,
    const CellAlbedo* albedo = nullptr);
  bool HasPending() const { return !this->Pending.Empty(); }
  void MergePending(const ParallelFor& parallelFor);
  /// Multiplies the flux of every hit, kept or pending, by `scale`.
  void ScaleFlux(float scale, const ParallelFor& parallelFor);

  /// The merged hits; range r holds [RangeStart(r), RangeStart(r + 1)).
  const KeptHits& GetHits() const { return this->Kept; }
  std::size_t RangeStart(std::size_t r) const { return this->Starts[r]; }

  /// The kept hits' buffers, emptied, their capacity kept; the store is
  /// empty afterwards.
  KeptHits ReleaseMemory();
  /// Takes buffers ReleaseMemory() gave while the store is empty and they
  /// hold room for no more than twice `hits`, four thousand at least;
  /// otherwise they are freed.
  void ReuseMemory(KeptHits&& memory, std::size_t hits);

private:
  // Merges `count` new hits (cellOf(k), write(k, merged, position)) after
  // Kept's hits of each range of cells, stably; with growth scales where
  // `growth` (the new hits have them) or Kept has them.
  template <typename CellOf, typename Write>
  void MergeIntoRanges(
    std::size_t count, CellOf cellOf, Write write, bool growth, const ParallelFor& parallelFor);

  std::size_t Cells;
  bool Triangles;
  KeptHits Kept;
  std::vector<std::size_t> Starts;
  KeptHits Pending;
  bool Deferred = false;
};

} // namespace brume

#endif
