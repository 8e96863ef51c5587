// SPDX-License-Identifier: BSD-3-Clause
#include "brume/ExactHistogram.h"

#include <algorithm>
#include <cmath>

namespace brume
{

namespace
{
__extension__ typedef unsigned __int128 UInt128;
}

ExactHistogram::ExactHistogram(const std::array<int, 3>& dims, int channels, int exponent)
  : Dims(dims)
  , Channels(channels)
  , Exponent(exponent)
  , InverseQuantum(std::ldexp(1.0, -exponent))
  , Quantum(std::ldexp(1.0, exponent))
  , Low(static_cast<std::size_t>(dims[0]) * dims[1] * dims[2] * channels, 0)
{
}

void ExactHistogram::MoveHigh(std::size_t i, std::int64_t step)
{
  std::lock_guard<std::mutex> lock(*this->HighLock.Mutex);
  if (this->High.empty())
  {
    this->High.assign(this->Low.size(), 0);
  }
  this->High[i] += step;
}

Int128 ExactHistogram::GetSum(std::size_t i) const
{
  const UInt128 high =
    this->High.empty() ? 0 : static_cast<UInt128>(static_cast<Int128>(this->High[i]));
  return static_cast<Int128>((high << 64) + this->Low[i]);
}

std::vector<Int128> ExactHistogram::GetSums() const
{
  std::vector<Int128> sums(this->Low.size());
  for (std::size_t i = 0; i < sums.size(); ++i)
  {
    sums[i] = this->GetSum(i);
  }
  return sums;
}

void ExactHistogram::SetSum(std::size_t i, Int128 sum)
{
  const UInt128 u = static_cast<UInt128>(sum);
  this->Low[i] = static_cast<std::uint64_t>(u);
  const std::int64_t high = static_cast<std::int64_t>(sum >> 64);
  if (high != 0 && this->High.empty())
  {
    this->High.assign(this->Low.size(), 0);
  }
  if (!this->High.empty())
  {
    this->High[i] = high;
  }
}

int ExactHistogram::QuantumExponent(double particleFlux)
{
  int e = 0;
  std::frexp(particleFlux > 0.0 && std::isfinite(particleFlux) ? particleFlux : 1.0, &e);
  return e - FractionBits; // particleFlux in [2^(e-1), 2^e)
}

std::int64_t ExactHistogram::Clamp(double x)
{
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
  for (std::size_t i = 0; i < this->Low.size(); ++i)
  {
    this->SetSum(i, this->GetSum(i) + other.GetSum(i));
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
    this->Quantum = std::ldexp(1.0, this->Exponent);
    return;
  }
  for (std::size_t i = 0; i < this->Low.size(); ++i)
  {
    this->SetSum(i, static_cast<Int128>(std::round(static_cast<double>(this->GetSum(i)) * factor)));
  }
}

double ExactHistogram::ExactValue(std::size_t i) const
{
  return std::ldexp(static_cast<double>(this->GetSum(i)), this->Exponent);
}

void ExactHistogram::ToHistogram(Histogram& out) const
{
  if (out.GetDimensions() != this->Dims || out.GetNumberOfChannels() != this->Channels)
  {
    out = Histogram(this->Dims, this->Channels);
  }
  std::vector<double>& values = out.GetValues();
  for (std::size_t i = 0; i < this->Low.size(); ++i)
  {
    values[i] = this->GetValue(i);
  }
}

void ExactHistogram::ToHistogram(Histogram& out, int groups) const
{
  const int channels = this->Channels / std::max(groups, 1);
  if (out.GetDimensions() != this->Dims || out.GetNumberOfChannels() != channels)
  {
    out = Histogram(this->Dims, channels);
  }
  std::vector<double>& values = out.GetValues();
  const std::size_t cells = channels > 0 ? this->Low.size() / this->Channels : 0;
  for (std::size_t cell = 0; cell < cells; ++cell)
  {
    for (int c = 0; c < channels; ++c)
    {
      Int128 sum = 0;
      for (int g = 0; g < groups; ++g)
      {
        sum += this->GetSum(cell * this->Channels + g * channels + c);
      }
      values[cell * channels + c] = std::ldexp(static_cast<double>(sum), this->Exponent);
    }
  }
}

Int128 ExactHistogram::MaxMagnitude() const
{
  Int128 m = 0;
  for (std::size_t i = 0; i < this->Low.size(); ++i)
  {
    const Int128 s = this->GetSum(i);
    const Int128 a = s < 0 ? -s : s;
    m = a > m ? a : m;
  }
  return m;
}

bool ExactHistogram::FitsOneLimb(Int128 maxMagnitude, int processes)
{
  return maxMagnitude < (static_cast<Int128>(1) << 62) / (processes > 0 ? processes : 1);
}

void ExactHistogram::ToLimbs(
  int limbs, std::size_t first, std::size_t count, std::int64_t* out) const
{
  constexpr UInt128 Mask = (static_cast<UInt128>(1) << LimbBits) - 1;
  for (std::size_t i = first; i < first + count; ++i)
  {
    const Int128 s = this->GetSum(i);
    if (limbs == 1)
    {
      *out++ = static_cast<std::int64_t>(s);
      continue;
    }
    const UInt128 u = static_cast<UInt128>(s); // two's complement
    *out++ = static_cast<std::int64_t>(u & Mask);
    *out++ = static_cast<std::int64_t>((u >> LimbBits) & Mask);
    *out++ = static_cast<std::int64_t>(s >> (2 * LimbBits)); // signed top
  }
}

void ExactHistogram::FromLimbs(
  int limbs, const std::int64_t* in, std::size_t first, std::size_t count)
{
  for (std::size_t i = first; i < first + count; ++i)
  {
    if (limbs == 1)
    {
      this->SetSum(i, *in++);
      continue;
    }
    // Modulo 2^128 (unsigned): the total fits, the partial sums may wrap.
    const UInt128 u = static_cast<UInt128>(static_cast<Int128>(in[0])) +
      (static_cast<UInt128>(static_cast<Int128>(in[1])) << LimbBits) +
      (static_cast<UInt128>(static_cast<Int128>(in[2])) << (2 * LimbBits));
    this->SetSum(i, static_cast<Int128>(u));
    in += 3;
  }
}

} // namespace brume
