// SPDX-License-Identifier: BSD-3-Clause
// One object's reconstruction across the processes of a distributed run
// (brume::ObjectRadiance): its histograms summed exactly through a
// brume::HistogramReduction, onto every process or onto the object's owner,
// which estimates its texture and gives it to the others; and the shares of
// per-texel work (the direct light's shadow rays) gathered back.
#ifndef brume_ObjectDistribution_h
#define brume_ObjectDistribution_h

#include "brume/ExactHistogram.h"
#include "brume/HistogramReduction.h"

#include <array>
#include <cstddef>
#include <vector>

namespace brume
{

class ObjectDistribution
{
public:
  /**
   * Every histogram the object builds from now on is summed across
   * processes through `reduction` (not owned; null, the default: this
   * process holds every hit). Progressive additions are not supported
   * with one.
   */
  void SetReduction(HistogramReduction* reduction) { this->Reduction = reduction; }
  HistogramReduction* GetReduction() const { return this->Reduction; }

  /**
   * The process that estimates this object's texture (SetOwner(r)), or
   * every process (-1, the default). With an owner the histograms are
   * summed onto it alone; it alone builds the summed-area tables, grows
   * the regions and estimates, then gives the texture (and a directional
   * projection) to every process, bit for bit: every process ends with the
   * texture one process holding every hit would make, while the per-texel
   * work and the reduction's traffic are shared out. The histograms and
   * regions are then held by the owner only.
   */
  void SetOwner(int rank) { this->Owner = rank; }
  int GetOwner() const { return this->Owner; }
  /// Whether this process estimates the texture: always without a
  /// reduction or an owner.
  bool EstimatesHere() const;
  /// Whether the owner gives its texture to other processes (an owner, and
  /// more than one process).
  bool SharesTexture() const;

  /// Sums one histogram, or two as one message, across the processes
  /// (nothing without a reduction).
  void Reduce(ExactHistogram& a, ExactHistogram* b = nullptr) const;
  /// The owner's `data` on every process, where SharesTexture().
  void Broadcast(std::vector<float>& data) const;
  /// This process's share [first, last) of n items (all of them without a
  /// reduction).
  std::array<std::size_t, 2> Share(std::size_t n) const;
  /// Every process's share of `data` (`floats` per item) gathered on every
  /// process, bit for bit.
  void GatherShares(std::size_t n, std::size_t floats, std::vector<float>& data) const;

private:
  HistogramReduction* Reduction = nullptr;
  int Owner = -1; // -1: every process estimates
};

} // namespace brume

#endif
