// SPDX-License-Identifier: BSD-3-Clause
// Histograms whose sums do not depend on the order of their terms: every
// term is rounded once to a whole number of a quantum and added as an
// integer, so that threads and processes may add their terms in any order
// and any grouping and give the same bits.
#ifndef brume_ExactHistogram_h
#define brume_ExactHistogram_h

#include "brume/Histogram.h"

#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

namespace brume
{

__extension__ typedef __int128 Int128; // GCC and Clang

/**
 * A histogram of fixed-point sums: a term v becomes the integer
 * round(v / q) for the quantum q = 2^Exponent and is added to its cell's
 * 128-bit sum; GetValue() is the sum times q. A sum is kept as its low 64
 * bits, which every term touches (as many bytes as a double: binning is
 * bound by cache misses), and its high 64 bits, touched only when the low
 * word carries or borrows (about once per 2^24 particle fluxes of a cell,
 * or when a signed sum crosses zero).
 *
 * Bounds. A term must satisfy |v| < 2^MaxTermBits q (AddTerm() reports a
 * larger one; it is clamped). With QuantumExponent(particleFlux), q lies
 * in (2^-FractionBits, 2^(1-FractionBits)] times a particle's flux, so that
 * a term holds FractionBits bits below a particle's flux (its rounding is
 * under 2^-40 of a particle's flux) and may reach 2^(MaxTermBits -
 * FractionBits) = 2^22 particle fluxes, which no hit's weighted flux
 * reaches (a Henyey-Greenstein remainder of g <= 0.7 weighs at most 1.5,
 * a Phong lobe of exponent 1000 about 160). A cell's sum stays below
 * 2^127 q for fewer than 2^(127 - MaxTermBits) = 2^65 terms: 10^10
 * particles of 10^3 hits each are 2^43 terms. Sums across R processes go
 * through three 43-bit limbs per value (ToLimbs), each a 64-bit integer
 * whose sum cannot overflow for R < 2^20; when every |sum| times R stays
 * below 2^62 one 64-bit integer per value suffices (FitsOneLimb).
 */
class ExactHistogram
{
public:
  static constexpr int FractionBits = 40;
  static constexpr int MaxTermBits = 62;
  static constexpr int LimbBits = 43;

  ExactHistogram() = default;
  ExactHistogram(const std::array<int, 3>& dims, int channels, int exponent);

  /// The exponent of the quantum for terms around `particleFlux` (> 0).
  static int QuantumExponent(double particleFlux);

  const std::array<int, 3>& GetDimensions() const { return this->Dims; }
  int GetNumberOfChannels() const { return this->Channels; }
  int GetExponent() const { return this->Exponent; }
  std::size_t GetNumberOfValues() const { return this->Low.size(); }

  /// Adds one term per channel to `cell` (not thread safe for one cell).
  void Add(std::size_t cell, const double* values) { this->Add(cell, 0, values, this->Channels); }
  /// Adds `count` terms to channels [first, first + count) of `cell`.
  void Add(std::size_t cell, int first, const double* values, int count)
  {
    const std::size_t at = cell * static_cast<std::size_t>(this->Channels) + first;
    for (int c = 0; c < count; ++c)
    {
      this->AddOne(at + c, values[c]);
    }
  }
  /**
   * Add() for terms known to be non-negative (fluxes and their weights) in
   * a histogram of N channels: the same sums, fewer steps (no borrow). A
   * negative, huge or NaN term takes Add()'s way.
   */
  template <int N>
  void AddNonNegative(std::size_t cell, const double (&values)[N])
  {
    this->AddNonNegativeAt(cell * N, values);
  }
  /**
   * AddNonNegative() into N of the channels, from channel `first` on (a
   * half's channels of HitBinning's sums; the others unchanged). With
   * `Shared`, threads may add to the same cell at once: each word is added
   * atomically (the sums are exact, so the order of the terms does not
   * change a bit); the histogram is not read meanwhile.
   */
  template <bool Shared = false, int N>
  void AddNonNegative(std::size_t cell, int first, const double (&values)[N])
  {
    this->AddNonNegativeAt<Shared>(cell * static_cast<std::size_t>(this->Channels) + first, values);
  }

  /// Asks for the cache line of `cell`'s sums ahead of adding to them.
  void Prefetch(std::size_t cell) const
  {
    __builtin_prefetch(this->Low.data() + cell * static_cast<std::size_t>(this->Channels), 1);
  }

  /// Adds `other`'s sums (same dimensions, channels and exponent).
  void Merge(const ExactHistogram& other);

  /**
   * Multiplies every sum by `factor` (> 0): exactly, as a change of the
   * quantum, when it is a power of two (the exponent moves); otherwise
   * each sum is rounded again to the quantum.
   */
  void Scale(double factor);

  /// The sums as doubles (each sum rounded once), into `out` (resized).
  void ToHistogram(Histogram& out) const;
  /**
   * The sums of `groups` equal groups of channels (channel c of the result:
   * the exact sum of channels c, c + C / groups, ...; each rounded once), as
   * doubles into `out` (resized): the two halves' sums of HitBinning as one.
   */
  void ToHistogram(Histogram& out, int groups) const;
  /// Value i (cell * channels + channel): its sum times the quantum.
  double GetValue(std::size_t i) const
  {
    // Without high words no sum ever carried or borrowed: it is its low word.
    return this->High.empty() ? static_cast<double>(this->Low[i]) * this->Quantum
                              : this->ExactValue(i);
  }

  /// Whether a term was clamped to the bound since construction.
  bool Saturated() const { return this->Clamped.Value.load(std::memory_order_relaxed); }

  /// The largest |sum|, for choosing the limbs of a reduction.
  Int128 MaxMagnitude() const;
  /// Whether R processes' sums of at most `maxMagnitude` fit one int64 each.
  static bool FitsOneLimb(Int128 maxMagnitude, int processes);

  /**
   * The sums of values [first, first + count) as `limbs` 64-bit integers
   * each (1, or 3 of LimbBits bits, the top one signed), written to `out`
   * (count * limbs of them); FromLimbs() sets those values from the
   * summed limbs in `in`. A reduction goes piece by piece through them.
   */
  void ToLimbs(int limbs, std::size_t first, std::size_t count, std::int64_t* out) const;
  void FromLimbs(int limbs, const std::int64_t* in, std::size_t first, std::size_t count);

  /// The sum of value `i` in quanta, and all of them (for tests).
  Int128 GetSum(std::size_t i) const;
  std::vector<Int128> GetSums() const;

private:
  static constexpr double TermBound = 4611686018427387904.0; // 2^MaxTermBits
  // round(v / q), half away from zero, inline: one multiplication by a
  // power of two (exact) and a conversion per term.
  std::int64_t Quantize(double v)
  {
    const double x = v * this->InverseQuantum;
    if (x < TermBound && x > -TermBound)
    {
      return static_cast<std::int64_t>(x + (x < 0.0 ? -0.5 : 0.5));
    }
    return this->Clamp(x); // beyond the bound, or NaN
  }
  std::int64_t Clamp(double x);
  // Adds k to the low word `low` and returns its value before (atomically
  // where Shared).
  template <bool Shared>
  static std::uint64_t AddLow(std::uint64_t& low, std::uint64_t k)
  {
    if (Shared)
    {
      return __atomic_fetch_add(&low, k, __ATOMIC_RELAXED);
    }
    const std::uint64_t before = low;
    low = before + k;
    return before;
  }
  // Adds values[c] to sum `at + c`.
  template <bool Shared = false, int N>
  void AddNonNegativeAt(std::size_t at, const double (&values)[N])
  {
    std::uint64_t* low = this->Low.data() + at;
    const double inverse = this->InverseQuantum;
    for (int c = 0; c < N; ++c)
    {
      const double x = values[c] * inverse;
      if (!(x >= 0.0 && x < TermBound))
      {
        this->AddOne<Shared>(at + c, values[c]);
        continue;
      }
      // Below 2^62: the signed conversion (one instruction) gives the same k.
      const auto k = static_cast<std::uint64_t>(static_cast<std::int64_t>(x + 0.5));
      if (AddLow<Shared>(low[c], k) + k < k) // carried
      {
        this->MoveHigh(at + c, 1);
        low = this->Low.data() + at;
      }
    }
  }
  // One term into value i, of any sign.
  template <bool Shared = false>
  void AddOne(std::size_t i, double v)
  {
    const std::int64_t k = this->Quantize(v);
    const std::uint64_t before = AddLow<Shared>(this->Low[i], static_cast<std::uint64_t>(k));
    const bool carry = before + static_cast<std::uint64_t>(k) < before;
    if (carry != (k < 0)) // the high word moves: +1 on a carry, -1 on a borrow
    {
      this->MoveHigh(i, carry ? 1 : -1);
    }
  }
  double ExactValue(std::size_t i) const;
  void MoveHigh(std::size_t i, std::int64_t step);
  void SetSum(std::size_t i, Int128 sum);

  std::array<int, 3> Dims{ 0, 0, 0 };
  int Channels = 0;
  int Exponent = 0;
  double InverseQuantum = 1.0;
  double Quantum = 1.0;
  // Set by any thread that clamps a term; copied with the histogram.
  struct Flag
  {
    std::atomic<bool> Value{ false };
    Flag() = default;
    Flag(const Flag& other)
      : Value(other.Value.load())
    {
    }
    Flag& operator=(const Flag& other)
    {
      this->Value.store(other.Value.load());
      return *this;
    }
  };
  Flag Clamped;
  std::vector<std::uint64_t> Low;
  // The high words, made at the first carry (threads binning disjoint
  // cells may carry at once: they take the lock).
  std::vector<std::int64_t> High;
  struct Lock
  {
    std::unique_ptr<std::mutex> Mutex{ new std::mutex };
    Lock() = default;
    Lock(const Lock&)
      : Lock()
    {
    }
    Lock& operator=(const Lock&) { return *this; }
  };
  Lock HighLock;
};

} // namespace brume

#endif
