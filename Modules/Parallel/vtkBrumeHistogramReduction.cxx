// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeHistogramReduction.h"

#include "vtkCommunicator.h"
#include "vtkMultiProcessController.h"

#include <chrono>

namespace
{
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
  // In pieces of at most 2^26 values: MPI counts are ints.
  constexpr std::size_t Piece = std::size_t(1) << 26;
  std::vector<long long> in(values.begin(), values.end()), out(values.size());
  for (std::size_t first = 0; first < values.size(); first += Piece)
  {
    const std::size_t n = std::min(Piece, values.size() - first);
    this->Controller->AllReduce(
      in.data() + first, out.data() + first, static_cast<vtkIdType>(n), vtkCommunicator::SUM_OP);
  }
  std::copy(out.begin(), out.end(), values.begin());
  // What an all-reduce moves per process, about: its values out and the totals in.
  this->Bytes += 2 * values.size() * sizeof(std::int64_t);
  this->Seconds += Since(start);
}
