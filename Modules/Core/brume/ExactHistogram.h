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
#include <vector>

namespace brume
{

__extension__ typedef __int128 Int128; // GCC and Clang

/**
 * A histogram of fixed-point sums: a term v becomes the integer
 * round(v / q) for the quantum q = 2^Exponent and is added to its cell's
 * 128-bit sum; GetValue() is the sum times q.
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
  std::size_t GetNumberOfValues() const { return this->Sums.size(); }

  /// Adds one term per channel to `cell` (not thread safe for one cell).
  void Add(std::size_t cell, const double* values)
  {
    Int128* dst = &this->Sums[cell * static_cast<std::size_t>(this->Channels)];
    for (int c = 0; c < this->Channels; ++c)
    {
      dst[c] += this->Quantize(values[c]);
    }
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
  double GetValue(std::size_t i) const;

  /// Whether a term was clamped to the bound since construction.
  bool Saturated() const { return this->Clamped.Value.load(std::memory_order_relaxed); }

  /// The largest |sum|, for choosing the limbs of a reduction.
  Int128 MaxMagnitude() const;
  /// Whether R processes' sums of at most `maxMagnitude` fit one int64 each.
  static bool FitsOneLimb(Int128 maxMagnitude, int processes);

  /**
   * The sums as `limbs` 64-bit integers each (1, or 3 of LimbBits bits,
   * the top one signed), appended to `out`; FromLimbs() reads the summed
   * limbs back from `in` at `offset` and returns the offset after them.
   */
  void ToLimbs(int limbs, std::vector<std::int64_t>& out) const;
  std::size_t FromLimbs(int limbs, const std::vector<std::int64_t>& in, std::size_t offset);

  /// The raw sums (for tests).
  const std::vector<Int128>& GetSums() const { return this->Sums; }

private:
  std::int64_t Quantize(double v);

  std::array<int, 3> Dims{ 0, 0, 0 };
  int Channels = 0;
  int Exponent = 0;
  double InverseQuantum = 1.0;
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
  std::vector<Int128> Sums;
};

} // namespace brume

#endif
