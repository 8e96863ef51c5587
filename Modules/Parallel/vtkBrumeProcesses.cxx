// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeProcesses.h"

#include "vtkCommunicator.h"
#include "vtkMultiProcessController.h"
#if VTK_MODULE_ENABLE_VTK_ParallelMPI
#include "vtkMPIController.h"
#endif

#include <cstdio>
#include <cstdlib>
#include <string>

vtkBrumeProcesses::Session::Session(int* argc, char*** argv)
{
#if VTK_MODULE_ENABLE_VTK_ParallelMPI
  // Open MPI, MPICH and PMIx launchers set one of these.
  for (const char* name : { "OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK" })
  {
    if (std::getenv(name))
    {
      // Every process of Open MPI's run on this machine: its messages go
      // through shared memory (the ob1 layer) unless the user chose another
      // layer. Open MPI's default selection probes the fabrics first (UCX,
      // PSM, OFI), which took 0.25 s of each process's start.
      const char* size = std::getenv("OMPI_COMM_WORLD_SIZE");
      const char* local = std::getenv("OMPI_COMM_WORLD_LOCAL_SIZE");
      if (size && local && std::string(size) == local)
      {
        setenv("OMPI_MCA_pml", "ob1", 0);
      }
      this->Controller = vtkMPIController::New();
      this->Controller->Initialize(argc, argv, 0);
      vtkMultiProcessController::SetGlobalController(this->Controller);
      break;
    }
  }
#else
  (void)argc;
  (void)argv;
#endif
}

vtkBrumeProcesses::Session::~Session()
{
  if (this->Controller)
  {
    this->Controller->Finalize();
    vtkMultiProcessController::SetGlobalController(nullptr);
    this->Controller->Delete();
  }
}

vtkMultiProcessController* vtkBrumeProcesses::GetGlobalController()
{
  return vtkMultiProcessController::GetGlobalController();
}

int vtkBrumeProcesses::GetRank(vtkMultiProcessController* controller)
{
  return controller ? controller->GetLocalProcessId() : 0;
}

int vtkBrumeProcesses::GetSize(vtkMultiProcessController* controller)
{
  return controller ? controller->GetNumberOfProcesses() : 1;
}

bool vtkBrumeProcesses::IsDistributed(vtkMultiProcessController* controller)
{
  return GetSize(controller) > 1;
}

bool vtkBrumeProcesses::Agree(vtkMultiProcessController* controller, bool ok)
{
  if (!IsDistributed(controller))
  {
    return ok;
  }
  const int local = ok ? 1 : 0;
  int all = 0;
  controller->AllReduce(&local, &all, 1, vtkCommunicator::MIN_OP);
  return all != 0;
}

bool vtkBrumeProcesses::AllSucceeded(bool ok, const char* step)
{
  return AllSucceeded(GetGlobalController(), ok, step);
}

bool vtkBrumeProcesses::AllSucceeded(
  vtkMultiProcessController* controller, bool ok, const char* step)
{
  const bool all = Agree(controller, ok);
  if (!all && IsDistributed(controller))
  {
    // One write per message (the launcher merges the processes' streams),
    // and every process says it before any exits: the launcher stops the
    // others as soon as one exits with an error.
    const std::string message = "brume: process " + std::to_string(GetRank(controller)) +
      (ok ? " stops: another process failed at " : " failed at ") + step + ".\n";
    std::fputs(message.c_str(), stderr);
    std::fflush(stderr);
    controller->Barrier();
  }
  return all;
}

void vtkBrumeProcesses::Sum(
  vtkMultiProcessController* controller, std::vector<vtkTypeInt64>& values)
{
  if (!IsDistributed(controller) || values.empty())
  {
    return;
  }
  const std::vector<vtkTypeInt64> local = values;
  controller->AllReduce(
    local.data(), values.data(), static_cast<vtkIdType>(values.size()), vtkCommunicator::SUM_OP);
}

vtkTypeInt64 vtkBrumeProcesses::Sum(vtkMultiProcessController* controller, vtkTypeInt64 value)
{
  vtkTypeInt64 total = value;
  if (IsDistributed(controller))
  {
    controller->AllReduce(&value, &total, 1, vtkCommunicator::SUM_OP);
  }
  return total;
}

double vtkBrumeProcesses::Max(vtkMultiProcessController* controller, double value)
{
  double largest = value;
  if (IsDistributed(controller))
  {
    controller->AllReduce(&value, &largest, 1, vtkCommunicator::MAX_OP);
  }
  return largest;
}
