// SPDX-License-Identifier: BSD-3-Clause
// Distributed runs: the sums of the histograms across processes and which
// process estimates each object (part of the reconstruction,
// brume/Reconstruction.h, through brume/ObjectDistribution.h).
#ifndef brume_HistogramReduction_h
#define brume_HistogramReduction_h

#include <cstddef>
#include <cstdint>
#include <vector>

namespace brume
{
/**
 * Sums histograms across the processes of one run. Every process bins its
 * own hits into exact histograms (brume::ExactHistogram: fixed-point sums,
 * which do not depend on the order of their terms), then one reduction
 * gives the totals, bitwise those of one process holding every hit,
 * whatever the number of processes and threads: to every process (Sum), or
 * to the one process that estimates the object's texture (SumOnto), which
 * then gives the texture to the others (Broadcast). Every process must
 * make the same calls in the same order.
 */
class HistogramReduction
{
public:
  virtual ~HistogramReduction() = default;
  virtual int NumberOfProcesses() const = 0;
  /// This process's place, 0 .. NumberOfProcesses() - 1.
  virtual int Rank() const = 0;
  /// The largest of `value` over the processes, on every process.
  virtual std::int64_t Max(std::int64_t value) = 0;
  /// Sums `values` elementwise over the processes, in place, on every process.
  virtual void Sum(std::vector<std::int64_t>& values) = 0;
  /**
   * Sums `values` elementwise over the processes onto process `root` (a
   * tree: each process sends its values once, only `root` receives the
   * totals); the other processes' `values` are left as they were.
   */
  virtual void SumOnto(std::vector<std::int64_t>& values, int root) = 0;
  /// Process `root`'s `data` on every process, bit for bit; every process
  /// passes `data` at the same size.
  virtual void Broadcast(std::vector<float>& data, int root) = 0;
  /**
   * Every process's `mine` (process r brings counts[r] values; every
   * process passes the same counts), concatenated in rank order into `all`
   * on every process.
   */
  virtual void Gather(const std::vector<std::int32_t>& mine, const std::vector<std::size_t>& counts,
    std::vector<std::int32_t>& all) = 0;
  /// Bytes this process has sent and received so far.
  std::size_t Bytes = 0;
  /**
   * What ObjectRadiance lays its sums out in, PieceValues values (of one
   * or three limbs) at a time, kept from one reduction to the next: a
   * fresh buffer as large as a histogram would cost a page fault per page
   * at every reduction.
   */
  std::vector<std::int64_t> Values;
  static constexpr std::size_t PieceValues = std::size_t(1) << 16;
};

/**
 * Which process estimates each object in a distributed run: the objects
 * by `costs` (ObjectLayout::EstimateCost()), largest first, each to the
 * process with the least cost so far (the lowest rank among equals), so
 * that the processes' shares of the per-texel work are about equal. The
 * same costs give the same owners on every process.
 */
std::vector<int> AssignOwners(const std::vector<double>& costs, int processes);

}

#endif
