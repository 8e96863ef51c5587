// SPDX-License-Identifier: BSD-3-Clause
// PCG32 random number generator (O'Neill 2014, pcg-random.org).
//
// Every particle owns a generator seeded from (seed, particle index): the
// index selects the PCG stream, so a particle's random numbers do not depend
// on which thread traces it or in which order.
#ifndef brume_Random_h
#define brume_Random_h

#include <cstdint>

namespace brume
{

class Random
{
public:
  Random(std::uint64_t seed, std::uint64_t stream)
  {
    this->State = 0u;
    this->Increment = (stream << 1u) | 1u;
    this->NextUInt();
    this->State += Mix(seed);
    this->NextUInt();
  }

  std::uint32_t NextUInt()
  {
    const std::uint64_t old = this->State;
    this->State = old * 6364136223846793005ULL + this->Increment;
    const auto xorshifted = static_cast<std::uint32_t>(((old >> 18u) ^ old) >> 27u);
    const auto rot = static_cast<std::uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((~rot + 1u) & 31u));
  }

  /// Uniform float in [0, 1).
  float NextFloat()
  {
    // 24 random mantissa bits: exactly representable, never 1.
    return static_cast<float>(this->NextUInt() >> 8) * 0x1p-24f;
  }

  /// Uniform double in [0, 1) with 53 random bits.
  double NextDouble()
  {
    const std::uint64_t hi = this->NextUInt() >> 5;
    const std::uint64_t lo = this->NextUInt() >> 6;
    return static_cast<double>((hi << 26) | lo) * 0x1p-53;
  }

private:
  // SplitMix64 finalizer: decorrelates nearby user seeds.
  static std::uint64_t Mix(std::uint64_t z)
  {
    z += 0x9e3779b97f4a7c15ULL;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }

  std::uint64_t State;
  std::uint64_t Increment;
};

} // namespace brume

#endif
