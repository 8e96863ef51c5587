// SPDX-License-Identifier: BSD-3-Clause
#include "brume/ExactHistogram.h"

#include <cmath>

namespace brume
{

namespace
{
__extension__ typedef unsigned __int128 UInt128;
constexpr double TermBound = 4611686018427387904.0; // 2^62
}

ExactHistogram::ExactHistogram(const std::array<int, 3>& dims, int channels, int exponent)
  : Dims(dims)
  , Channels(channels)
  , Exponent(exponent)
  , InverseQuantum(std::ldexp(1.0, -exponent))
  , Sums(static_cast<std::size_t>(dims[0]) * dims[1] * dims[2] * channels, 0)
{
}

int ExactHistogram::QuantumExponent(double particleFlux)
{
  int e = 0;
  std::frexp(particleFlux > 0.0 && std::isfinite(particleFlux) ? particleFlux : 1.0, &e);
  return e - FractionBits; // particleFlux in [2^(e-1), 2^e)
}

std::int64_t ExactHistogram::Quantize(double v)
{
  const double x = v * this->InverseQuantum; // exact: a power of two
  if (std::abs(x) < TermBound)
  {
    return std::llround(x);
  }
  this->Clamped.Value.store(true, std::memory_order_relaxed);
  if (std::isnan(x))
  {
    return 0;
  }
  return x > 0.0 ? static_cast<std::int64_t>(TermBound) - 1
                 : 1 - static_cast<std::int64_t>(TermBound);
}

void ExactHistogram::Merge(const ExactHistogram& other)
{
  for (std::size_t i = 0; i < this->Sums.size(); ++i)
  {
    this->Sums[i] += other.Sums[i];
  }
  if (other.Saturated())
  {
    this->Clamped.Value.store(true);
  }
}

void ExactHistogram::Scale(double factor)
{
  int e = 0;
  const double mantissa = std::frexp(factor, &e);
  if (mantissa == 0.5)
  {
    // factor = 2^(e - 1): the same integers of a quantum 2^(e - 1) times larger.
    this->Exponent += e - 1;
    this->InverseQuantum = std::ldexp(1.0, -this->Exponent);
    return;
  }
  for (Int128& s : this->Sums)
  {
    s = static_cast<Int128>(std::round(static_cast<double>(s) * factor));
  }
}

double ExactHistogram::GetValue(std::size_t i) const
{
  return std::ldexp(static_cast<double>(this->Sums[i]), this->Exponent);
}

void ExactHistogram::ToHistogram(Histogram& out) const
{
  if (out.GetDimensions() != this->Dims || out.GetNumberOfChannels() != this->Channels)
  {
    out = Histogram(this->Dims, this->Channels);
  }
  std::vector<double>& values = out.GetValues();
  for (std::size_t i = 0; i < this->Sums.size(); ++i)
  {
    values[i] = this->GetValue(i);
  }
}

Int128 ExactHistogram::MaxMagnitude() const
{
  Int128 m = 0;
  for (const Int128& s : this->Sums)
  {
    const Int128 a = s < 0 ? -s : s;
    m = a > m ? a : m;
  }
  return m;
}

bool ExactHistogram::FitsOneLimb(Int128 maxMagnitude, int processes)
{
  return maxMagnitude < (static_cast<Int128>(1) << 62) / (processes > 0 ? processes : 1);
}

void ExactHistogram::ToLimbs(int limbs, std::vector<std::int64_t>& out) const
{
  constexpr UInt128 Mask = (static_cast<UInt128>(1) << LimbBits) - 1;
  for (const Int128& s : this->Sums)
  {
    if (limbs == 1)
    {
      out.push_back(static_cast<std::int64_t>(s));
      continue;
    }
    const UInt128 u = static_cast<UInt128>(s); // two's complement
    out.push_back(static_cast<std::int64_t>(u & Mask));
    out.push_back(static_cast<std::int64_t>((u >> LimbBits) & Mask));
    out.push_back(static_cast<std::int64_t>(s >> (2 * LimbBits))); // signed top
  }
}

std::size_t ExactHistogram::FromLimbs(
  int limbs, const std::vector<std::int64_t>& in, std::size_t offset)
{
  for (Int128& s : this->Sums)
  {
    if (limbs == 1)
    {
      s = in[offset++];
      continue;
    }
    // Modulo 2^128 (unsigned): the total fits, the partial sums may wrap.
    const UInt128 u = static_cast<UInt128>(static_cast<Int128>(in[offset])) +
      (static_cast<UInt128>(static_cast<Int128>(in[offset + 1])) << LimbBits) +
      (static_cast<UInt128>(static_cast<Int128>(in[offset + 2])) << (2 * LimbBits));
    s = static_cast<Int128>(u);
    offset += 3;
  }
  return offset;
}

} // namespace brume
