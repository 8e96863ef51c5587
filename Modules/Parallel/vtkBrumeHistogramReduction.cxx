// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeHistogramReduction.h"

#include "vtkCommunicator.h"
#include "vtkMultiProcessController.h"

#include <algorithm>
#include <chrono>
#include <type_traits>

namespace
{
// Values per message at most: MPI counts are ints.
constexpr std::size_t Piece = std::size_t(1) << 26;

double Since(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
}

vtkBrumeHistogramReduction::vtkBrumeHistogramReduction(vtkMultiProcessController* controller)
  : Controller(controller)
{
}

int vtkBrumeHistogramReduction::NumberOfProcesses() const
{
  return this->Controller->GetNumberOfProcesses();
}

int vtkBrumeHistogramReduction::Rank() const
{
  return this->Controller->GetLocalProcessId();
}

void vtkBrumeHistogramReduction::Gather(const std::vector<std::int32_t>& mine,
  const std::vector<std::size_t>& counts, std::vector<std::int32_t>& all)
{
  const auto start = std::chrono::steady_clock::now();
  std::vector<vtkIdType> lengths(counts.begin(), counts.end()), offsets(counts.size(), 0);
  std::size_t total = 0;
  for (std::size_t r = 0; r < counts.size(); ++r)
  {
    offsets[r] = static_cast<vtkIdType>(total);
    total += counts[r];
  }
  all.resize(total);
  static_assert(std::is_same<std::int32_t, int>::value, "MPI's int is the gathered type");
  this->Controller->AllGatherV(
    mine.data(), all.data(), static_cast<vtkIdType>(mine.size()), lengths.data(), offsets.data());
  // What an all-gather moves per process, about: its values out and all of them in.
  this->Bytes += (mine.size() + total) * sizeof(std::int32_t);
  this->Seconds += Since(start);
}

std::int64_t vtkBrumeHistogramReduction::Max(std::int64_t value)
{
  const auto start = std::chrono::steady_clock::now();
  long long in = value, out = 0;
  this->Controller->AllReduce(&in, &out, 1, vtkCommunicator::MAX_OP);
  this->Seconds += Since(start);
  return static_cast<std::int64_t>(out);
}

void vtkBrumeHistogramReduction::Sum(std::vector<std::int64_t>& values)
{
  const auto start = std::chrono::steady_clock::now();
  // Into a buffer kept from one reduction to the next (its pages are
  // touched once), in pieces of at most 2^26 values: MPI counts are ints.
  this->Totals.resize(std::max(this->Totals.size(), values.size()));
  for (std::size_t first = 0; first < values.size(); first += Piece)
  {
    const std::size_t n = std::min(Piece, values.size() - first);
    this->Controller->AllReduce(values.data() + first, this->Totals.data() + first,
      static_cast<vtkIdType>(n), vtkCommunicator::SUM_OP);
  }
  std::copy(this->Totals.begin(), this->Totals.begin() + static_cast<std::ptrdiff_t>(values.size()),
    values.begin());
  // What an all-reduce moves per process, about: its values out and the totals in.
  this->Bytes += 2 * values.size() * sizeof(std::int64_t);
  this->Seconds += Since(start);
}

void vtkBrumeHistogramReduction::SumOnto(std::vector<std::int64_t>& values, int root)
{
  const auto start = std::chrono::steady_clock::now();
  const bool here = this->Rank() == root;
  if (here)
  {
    this->Totals.resize(std::max(this->Totals.size(), values.size()));
  }
  for (std::size_t first = 0; first < values.size(); first += Piece)
  {
    const std::size_t n = std::min(Piece, values.size() - first);
    this->Controller->Reduce(values.data() + first, here ? this->Totals.data() + first : nullptr,
      static_cast<vtkIdType>(n), vtkCommunicator::SUM_OP, root);
  }
  if (here)
  {
    std::copy(this->Totals.begin(),
      this->Totals.begin() + static_cast<std::ptrdiff_t>(values.size()), values.begin());
  }
  // Every process sends its values once; the root receives as many.
  this->Bytes += values.size() * sizeof(std::int64_t);
  this->Seconds += Since(start);
}

void vtkBrumeHistogramReduction::Broadcast(std::vector<float>& data, int root)
{
  const auto start = std::chrono::steady_clock::now();
  for (std::size_t first = 0; first < data.size(); first += Piece)
  {
    const std::size_t n = std::min(Piece, data.size() - first);
    this->Controller->Broadcast(data.data() + first, static_cast<vtkIdType>(n), root);
  }
  this->Bytes += data.size() * sizeof(float);
  this->Seconds += Since(start);
}
