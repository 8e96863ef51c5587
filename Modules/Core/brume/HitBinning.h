// SPDX-License-Identifier: BSD-3-Clause
// The histograms of one object's hits (brume::ObjectRadiance): each hit's
// histogram cell (its (u, v) on a surface's chart, or its position in a
// medium's box) and the exact sums of its incident flux (which drives the
// regions' growth) and of its flux weighted toward the eye (the BRDF, or
// the phase function's remainder). View-independent objects, and objects
// whose view is fixed, add every hit to its cell as it comes; view-dependent
// ones keep their hits (brume::KeptHitStore) and weigh them toward each new eye.
#ifndef brume_HitBinning_h
#define brume_HitBinning_h

#include "brume/ExactHistogram.h"
#include "brume/Histogram.h"
#include "brume/HitArrays.h"
#include "brume/KeptHits.h"
#include "brume/ObjectLayout.h"
#include "brume/Parallel.h"

#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

namespace brume
{

class DirectLight;

/**
 * The half (0 or 1) a hit at `position` belongs to: a hash of its
 * coordinates' bits, which carry no information about where regions stop
 * growing. Each half's histogram grows regions for the other half's
 * estimate (ObjectRadiance), so that where a region stops does not depend
 * on the hits it averages: a region that stops where its own hits happen to
 * be dense would read them as brighter than they are, by about 1/k for k
 * hits a region (1-2 % at the default thresholds), whatever the number of
 * particles. Deterministic, independent of the order of hits and threads.
 */
inline int HitHalf(const float* position)
{
  std::uint32_t b[3];
  std::memcpy(b, position, sizeof(b));
  std::uint32_t h = b[0] * 0x9E3779B1u ^ b[1] * 0x85EBCA77u ^ b[2] * 0xC2B2AE3Du;
  h ^= h >> 15;
  h *= 0x2C1B3C6Du;
  h ^= h >> 12;
  h *= 0x297A2D39u;
  h ^= h >> 15;
  return static_cast<int>(h >> 31);
}

class HitBinning
{
public:
  explicit HitBinning(const ObjectLayout& layout);

  /**
   * One viewpoint only (ObjectRadiance::FixView()): a view-dependent object
   * then bins each hit's flux weighted toward `eye` as it comes, keeping no
   * hits. No effect on view-independent objects.
   */
  void FixView(const ObjectLayout& layout, const Vec3& eye);
  bool IsViewFixed() const { return this->ViewFixed; }
  const Vec3& GetFixedEye() const { return this->FixedEye; }
  /// Whether the object keeps its hits for later views.
  bool KeepsHits() const { return this->ViewDependent && !this->ViewFixed; }

  /// A new build: no hits kept; with `deferred`, the hits kept wait for
  /// MergePending() (batches of a run that do not estimate).
  void Clear(bool deferred);
  void SetDeferred(bool deferred) { this->Store.SetDeferred(deferred); }
  /**
   * Fresh sums whose quantum is 2^sumsExponent (ExactHistogram), where the
   * object does not keep its hits; `lobeCast`: sharp Phong lobes are left
   * out of the weighted flux (ObjectRadiance options).
   */
  void Start(const ObjectLayout& layout, int sumsExponent, bool lobeCast);
  /**
   * Bins `count` hits (indices into `hits`), after the ones binned since
   * Start(). With `direct`, the first interactions after its lights are
   * left out (computed, not estimated). `runShare`: ObjectOptions::RunShare.
   */
  void Bin(const ObjectLayout& layout, const HitArrays& hits, const std::uint32_t* index,
    std::size_t count, const DirectLight* direct, double runShare, const ParallelFor& parallelFor,
    bool everyThread = false);
  /// Multiplies what was binned by `scale` (progressive runs), the sums'
  /// quantum becoming 2^sumsExponent.
  void Scale(double scale, int sumsExponent, const ParallelFor& parallelFor);
  /// Merges the hits kept while deferred, and defers no more.
  void MergePending(const ParallelFor& parallelFor);
  /// The kept hits' flux weighted toward `eye` into the value sums, and
  /// with `weights` their incident flux into the weight sums.
  void WeighKept(
    const ObjectLayout& layout, const Vec3& eye, bool weights, const ParallelFor& parallelFor);

  /// The exact sums, each hit in its half's (HitHalf()): incident flux (1
  /// channel a half: 2), weighted flux (RGB a half: 6, half 0's first).
  ExactHistogram& WeightSums() { return this->Weights; }
  ExactHistogram& ValueSums() { return this->Values; }
  /// Both sums emptied (a process whose sums were reduced onto another).
  void ClearSums();
  /// The sums of both halves: incident flux (1 channel), weighted flux (RGB).
  Histogram GetWeightHistogram() const;
  Histogram GetValueHistogram() const;
  /// A new exact histogram of this build's quantum.
  ExactHistogram NewSums(const std::array<int, 3>& dims, int channels) const;
  int GetSumsExponent() const { return this->SumsExponent; }
  /// Records that a term was clamped in sums of this build.
  void NoteSaturation(bool saturated) { this->Clamped = this->Clamped || saturated; }
  /// Empty unless a term was clamped in the exact sums: why.
  std::string Saturation() const;

  const KeptHitStore& GetStore() const { return this->Store; }
  KeptHitStore& GetStore() { return this->Store; }

private:
  bool FromFront(const ObjectLayout& layout, const HitArrays& hits, std::uint32_t i) const;
  // Bin()'s two ways: view-independent objects add every hit to its cell;
  // view-dependent ones keep their hits by cell.
  template <typename Locator>
  void BinInPlace(const ObjectLayout& layout, const HitArrays& hits, const std::uint32_t* index,
    std::size_t count, const Locator& cellOfHit, const ParallelFor& parallelFor, bool everyThread);
  // BinInPlace() of `count` hits, from one thread (Shared: from one of
  // several at once, adding atomically).
  template <bool Shared, typename Locator>
  void BinInto(const ObjectLayout& layout, const HitArrays& hits, const std::uint32_t* index,
    std::size_t count, const Locator& cellOfHit);
  template <typename Locator>
  void KeepHits(const ObjectLayout& layout, const HitArrays& hits, const std::uint32_t* index,
    std::size_t count, const Locator& cellOfHit, double runShare, const ParallelFor& parallelFor);
  // What a view-independent bin or a fixed view's adds for hit i at its
  // cell, into `weights` and `values`.
  template <bool Shared>
  void AddTerms(
    const ObjectLayout& layout, const HitArrays& hits, std::uint32_t i, std::uint32_t cell);
  // The flux of a hit arriving at `position` along `direction` weighted
  // toward `eye`: the phase function's remainder (media), or the BRDF of
  // its triangle (surfaces, with `normals` the triangles' unit normals);
  // WeighKept() and a fixed view's binning share it, term for term.
  void WeighHit(const ObjectLayout& layout, const Vec3& eye, const float* position,
    const float* direction, const float* flux, std::uint32_t triangle,
    const std::vector<Vec3>& normals, double* value) const;

  bool ViewDependent;
  bool ViewFixed = false; // FixView(): binned toward FixedEye, no hits kept
  Vec3 FixedEye;
  std::vector<Vec3> FixedNormals; // surfaces with a fixed view: unit normals
  bool LobeCast = false;
  KeptHitStore Store;
  // View-independent objects: kept for later Add()s; view-dependent ones:
  // made from the kept hits.
  ExactHistogram Weights;
  ExactHistogram Values;
  int SumsExponent = 0; // the exact sums' quantum, 2^SumsExponent
  bool Clamped = false; // a term beyond the exact sums' bound since Start()
  // Bin()'s medium's albedo per cell, where it varies (ToRadiance()).
  std::optional<CellAlbedo> Albedo;
};

} // namespace brume

#endif
