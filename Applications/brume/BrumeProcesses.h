// SPDX-License-Identifier: BSD-3-Clause
// `mpirun -np R brume ...`: one vtkMPIController for the whole program when
// an MPI launcher started it (VTK's global controller), and the agreement
// that makes a failure on any process stop every process.
#ifndef BrumeProcesses_h
#define BrumeProcesses_h

#include "vtkCommunicator.h"
#include "vtkMultiProcessController.h"
#ifdef BRUME_HAVE_MPI
#include "vtkMPIController.h"
#endif

#include <cstdio>
#include <cstdlib>
#include <string>

class BrumeProcesses
{
public:
  BrumeProcesses(int* argc, char*** argv)
  {
#ifdef BRUME_HAVE_MPI
    // Open MPI, MPICH and PMIx launchers set one of these.
    for (const char* name : { "OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK" })
    {
      if (std::getenv(name))
      {
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
  ~BrumeProcesses()
  {
    if (this->Controller)
    {
      this->Controller->Finalize();
      vtkMultiProcessController::SetGlobalController(nullptr);
      this->Controller->Delete();
    }
  }
  BrumeProcesses(const BrumeProcesses&) = delete;
  BrumeProcesses& operator=(const BrumeProcesses&) = delete;

private:
  vtkMultiProcessController* Controller = nullptr;
};

/// This process and the number of processes (0 and 1 without MPI).
inline int BrumeRank()
{
  vtkMultiProcessController* c = vtkMultiProcessController::GetGlobalController();
  return c ? c->GetLocalProcessId() : 0;
}
inline int BrumeSize()
{
  vtkMultiProcessController* c = vtkMultiProcessController::GetGlobalController();
  return c ? c->GetNumberOfProcesses() : 1;
}

/**
 * Whether every process succeeded at `step` (collective: every process must
 * call it, in the same order). The failing process has said why; the others
 * say that they stop because of it.
 */
inline bool BrumeAllSucceeded(bool ok, const char* step)
{
  if (BrumeSize() == 1)
  {
    return ok;
  }
  const int local = ok ? 1 : 0;
  int all = 0;
  vtkMultiProcessController::GetGlobalController()->AllReduce(
    &local, &all, 1, vtkCommunicator::MIN_OP);
  if (!all)
  {
    // One write per message (the launcher merges the processes' streams),
    // and every process says it before any exits: the launcher stops the
    // others as soon as one exits with an error.
    const std::string message = "brume: process " + std::to_string(BrumeRank()) +
      (ok ? " stops: another process failed at " : " failed at ") + step + ".\n";
    std::fputs(message.c_str(), stderr);
    std::fflush(stderr);
    vtkMultiProcessController::GetGlobalController()->Barrier();
  }
  return all != 0;
}

#endif
