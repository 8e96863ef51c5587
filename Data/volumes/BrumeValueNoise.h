// SPDX-License-Identifier: BSD-3-Clause
// Value noise for the volumes the project makes itself (MakeCumulus,
// MakeShells): a hash of the lattice point, smoothstep interpolated, so
// that a volume is the same file on every machine.
#ifndef BrumeValueNoise_h
#define BrumeValueNoise_h

#include <cmath>
#include <cstdint>

namespace BrumeValueNoise
{
// A lattice value in [0, 1) from the integer point (i, j, k).
inline double Lattice(int i, int j, int k)
{
  std::uint64_t h =
    static_cast<std::uint64_t>(static_cast<std::uint32_t>(i)) * 0x9E3779B97F4A7C15ULL;
  h ^= static_cast<std::uint64_t>(static_cast<std::uint32_t>(j)) * 0xC2B2AE3D27D4EB4FULL;
  h ^= static_cast<std::uint64_t>(static_cast<std::uint32_t>(k)) * 0x165667B19E3779F9ULL;
  h ^= h >> 31;
  h *= 0xBF58476D1CE4E5B9ULL;
  h ^= h >> 29;
  return static_cast<double>(h >> 11) * 0x1p-53;
}

inline double Smooth(double t)
{
  return t * t * (3.0 - 2.0 * t);
}

// Value noise in [0, 1).
inline double Noise(double x, double y, double z)
{
  const int i = static_cast<int>(std::floor(x)), j = static_cast<int>(std::floor(y)),
            k = static_cast<int>(std::floor(z));
  const double u = Smooth(x - i), v = Smooth(y - j), w = Smooth(z - k);
  double result = 0.0;
  for (int c = 0; c < 8; ++c)
  {
    const int a = c & 1, b = (c >> 1) & 1, d = c >> 2;
    result +=
      (a ? u : 1.0 - u) * (b ? v : 1.0 - v) * (d ? w : 1.0 - w) * Lattice(i + a, j + b, k + d);
  }
  return result;
}
}

#endif
