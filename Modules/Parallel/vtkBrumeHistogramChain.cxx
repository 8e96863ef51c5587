// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeHistogramChain.h"

#include "vtkBrumeProcesses.h"
#include "vtkMultiProcessController.h"

#include <chrono>

namespace
{
double Since(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
}

vtkBrumeHistogramChain::vtkBrumeHistogramChain(vtkMultiProcessController* controller)
  : Controller(controller)
{
}

void vtkBrumeHistogramChain::Receive(std::vector<double>& values)
{
  const auto start = std::chrono::steady_clock::now();
  const int rank = this->Controller->GetLocalProcessId();
  if (rank > 0)
  {
    this->Controller->Receive(values.data(), static_cast<vtkIdType>(values.size()), rank - 1,
      vtkBrumeProcesses::HistogramChainTag);
    this->Bytes += values.size() * sizeof(double);
  }
  this->Seconds += Since(start);
}

void vtkBrumeHistogramChain::Forward(std::vector<double>& values)
{
  const auto start = std::chrono::steady_clock::now();
  const int rank = this->Controller->GetLocalProcessId();
  const int last = this->Controller->GetNumberOfProcesses() - 1;
  if (rank < last)
  {
    this->Controller->Send(values.data(), static_cast<vtkIdType>(values.size()), rank + 1,
      vtkBrumeProcesses::HistogramChainTag);
    this->Bytes += values.size() * sizeof(double);
  }
  this->Controller->Broadcast(values.data(), static_cast<vtkIdType>(values.size()), last);
  this->Bytes += values.size() * sizeof(double);
  this->Seconds += Since(start);
}
