// SPDX-License-Identifier: BSD-3-Clause
// Random numbers for Monte Carlo transport: Random123's Philox4x32-10
// (Salmon et al., "Parallel random numbers: as easy as 1, 2, 3", SC 2011).
//
// Philox is counter-based: the n-th block of four 32-bit numbers of a
// generator is Philox(key, counter = (n, stream)), a keyed bijection that
// passes TestU01's BigCrush for every key and every counter sequence. The
// key is the seed, the stream is (for the light tracer) the particle index,
// so a particle's numbers depend on (seed, index) only — not on the thread
// that traces it, the order of particles or the number of processes — and
// distinct particles' numbers are independent. (The PCG32 streams this
// replaces shared one state and differed only in their increment; such
// streams are correlated, and long random walks showed it: see the seed
// spread test, TestSeedSpread.)
#ifndef brume_Random_h
#define brume_Random_h

#include <Random123/philox.h>

#include <cstdint>

namespace brume
{

class Random
{
public:
  /// The generator of `stream` (for example a particle index) under `seed`.
  Random(std::uint64_t seed, std::uint64_t stream)
  {
    this->Key[0] = Low(seed);
    this->Key[1] = High(seed);
    this->Counter[0] = 0u;
    this->Counter[1] = 0u;
    this->Counter[2] = Low(stream);
    this->Counter[3] = High(stream);
  }

  std::uint32_t NextUInt()
  {
    if (this->Used == 4)
    {
      this->Block = Engine()(this->Counter, this->Key);
      // 2^64 blocks per stream: the high word carries.
      if (++this->Counter[0] == 0u)
      {
        ++this->Counter[1];
      }
      this->Used = 0;
    }
    return this->Block[this->Used++];
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
  using Engine = r123::Philox4x32;
  static std::uint32_t Low(std::uint64_t v) { return static_cast<std::uint32_t>(v); }
  static std::uint32_t High(std::uint64_t v) { return static_cast<std::uint32_t>(v >> 32u); }

  Engine::key_type Key;
  Engine::ctr_type Counter;
  Engine::ctr_type Block;
  unsigned Used = 4;
};

} // namespace brume

#endif
