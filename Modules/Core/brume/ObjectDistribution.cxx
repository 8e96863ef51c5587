// SPDX-License-Identifier: BSD-3-Clause
#include "brume/ObjectDistribution.h"

#include <algorithm>
#include <cstring>

namespace brume
{

bool ObjectDistribution::EstimatesHere() const
{
  return !this->Reduction || this->Owner < 0 || this->Reduction->Rank() == this->Owner;
}

bool ObjectDistribution::SharesTexture() const
{
  return this->Reduction && this->Owner >= 0 && this->Reduction->NumberOfProcesses() > 1;
}

void ObjectDistribution::Reduce(ExactHistogram& a, ExactHistogram* b) const
{
  if (!this->Reduction)
  {
    return;
  }
  // One 64-bit integer per value when every process's sums fit in it (the
  // usual case), otherwise three limbs; all processes agree.
  Int128 largest = a.MaxMagnitude();
  if (b)
  {
    const Int128 mb = b->MaxMagnitude();
    largest = mb > largest ? mb : largest;
  }
  std::int64_t bits = 0;
  while (bits < 127 && (largest >> bits) != 0)
  {
    ++bits;
  }
  bits = this->Reduction->Max(bits);
  const int limbs = bits < 62 &&
      ExactHistogram::FitsOneLimb(
        static_cast<Int128>(1) << bits, this->Reduction->NumberOfProcesses())
    ? 1
    : 3;
  // Piece by piece, in a buffer kept from one reduction to the next: a
  // reduction touches no fresh memory, whatever the histograms' size (a
  // fresh page costs a fault, and the fog's histograms of 10^7 particles
  // are 14 MB).
  std::vector<std::int64_t>& v = this->Reduction->Values;
  const bool here = this->EstimatesHere();
  for (ExactHistogram* h : { &a, b })
  {
    const std::size_t n = h ? h->GetNumberOfValues() : 0;
    for (std::size_t first = 0; first < n; first += HistogramReduction::PieceValues)
    {
      const std::size_t count = std::min(HistogramReduction::PieceValues, n - first);
      v.resize(count * static_cast<std::size_t>(limbs));
      h->ToLimbs(limbs, first, count, v.data());
      if (this->Owner < 0)
      {
        this->Reduction->Sum(v);
      }
      else
      {
        this->Reduction->SumOnto(v, this->Owner); // the totals are the owner's alone
      }
      if (here)
      {
        h->FromLimbs(limbs, v.data(), first, count);
      }
    }
  }
}

void ObjectDistribution::Broadcast(std::vector<float>& data) const
{
  if (this->SharesTexture())
  {
    this->Reduction->Broadcast(data, this->Owner);
  }
}

std::vector<int> AssignOwners(const std::vector<double>& costs, int processes)
{
  std::vector<int> owners(costs.size(), 0);
  if (processes < 2)
  {
    return owners;
  }
  // Largest first (the lowest index among equal costs), each to the least
  // loaded process so far (the lowest rank among equals).
  std::vector<std::size_t> order(costs.size());
  for (std::size_t o = 0; o < order.size(); ++o)
  {
    order[o] = o;
  }
  std::stable_sort(
    order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return costs[x] > costs[y]; });
  std::vector<double> load(static_cast<std::size_t>(processes), 0.0);
  for (const std::size_t o : order)
  {
    const auto least = std::min_element(load.begin(), load.end());
    owners[o] = static_cast<int>(least - load.begin());
    *least += costs[o];
  }
  return owners;
}

namespace
{
// Where process r of R starts its share of n items.
std::size_t ShareStart(std::size_t n, int r, int processes)
{
  return static_cast<std::size_t>(static_cast<unsigned long long>(n) * r / processes);
}
}

std::array<std::size_t, 2> ObjectDistribution::Share(std::size_t n) const
{
  const int processes = this->Reduction ? this->Reduction->NumberOfProcesses() : 1;
  const int rank = processes > 1 ? this->Reduction->Rank() : 0;
  return { ShareStart(n, rank, processes), ShareStart(n, rank + 1, processes) };
}

void ObjectDistribution::GatherShares(
  std::size_t n, std::size_t floats, std::vector<float>& data) const
{
  const int processes = this->Reduction ? this->Reduction->NumberOfProcesses() : 1;
  if (processes < 2)
  {
    return;
  }
  // Floats travel as their bits: every process ends with the same values.
  const auto mine = this->Share(n);
  std::vector<std::int32_t> sent((mine[1] - mine[0]) * floats), all;
  std::memcpy(sent.data(), data.data() + mine[0] * floats, sent.size() * sizeof(float));
  std::vector<std::size_t> counts(processes);
  for (int r = 0; r < processes; ++r)
  {
    counts[r] = (ShareStart(n, r + 1, processes) - ShareStart(n, r, processes)) * floats;
  }
  this->Reduction->Gather(sent, counts, all);
  std::memcpy(data.data(), all.data(), n * floats * sizeof(float));
}

} // namespace brume
