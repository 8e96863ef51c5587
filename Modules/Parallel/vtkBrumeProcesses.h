// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeProcesses
 * @brief   the processes of a distributed run and their agreements
 *
 * Brume runs under MPI (`mpirun -np R brume render`, or pvbatch with the
 * plugin): every process traces its share of the particles, the histograms
 * are summed across processes (vtkBrumeHistogramReduction), process 0
 * renders.
 * Every step that can fail is followed by an agreement (Agree), so that a
 * failure on any process stops all of them at the same point and no process
 * is left waiting in a collective call. Without MPI, or with one process,
 * every function here is the trivial single-process answer.
 *
 * @sa vtkBrumeHistogramReduction vtkBrumeRadianceReconstruction
 */
#ifndef vtkBrumeProcesses_h
#define vtkBrumeProcesses_h

#include "vtkBrumeParallelModule.h" // For export macro
#include "vtkType.h"                // For vtkTypeInt64

#include <vector>

class vtkMultiProcessController;

class VTKBRUMEPARALLEL_EXPORT vtkBrumeProcesses
{
public:
  /**
   * The program's MPI session: when an MPI launcher (Open MPI, MPICH, PMIx)
   * started the program, a vtkMPIController becomes VTK's global controller
   * for the session's lifetime; otherwise nothing happens. Create one at the
   * start of main(). When Open MPI started every process on this machine,
   * the session chooses Open MPI's shared-memory messaging layer
   * (`OMPI_MCA_pml=ob1`) unless the environment or `mpirun --mca pml`
   * names one: the default selection's probing of network fabrics took
   * 0.25 s of each process's start.
   */
  class VTKBRUMEPARALLEL_EXPORT Session
  {
  public:
    Session(int* argc, char*** argv);
    ~Session();
    Session(const Session&) = delete;
    Session& operator=(const Session&) = delete;

  private:
    vtkMultiProcessController* Controller = nullptr;
  };

  /// VTK's global controller (null without one).
  static vtkMultiProcessController* GetGlobalController();

  ///@{
  /// This process and the number of processes (0 and 1 without a controller).
  static int GetRank(vtkMultiProcessController* controller);
  static int GetSize(vtkMultiProcessController* controller);
  ///@}

  /// Whether `controller` holds more than one process.
  static bool IsDistributed(vtkMultiProcessController* controller);

  /**
   * Collective: true when `ok` holds on every process. Every process must
   * call it, in the same order.
   */
  static bool Agree(vtkMultiProcessController* controller, bool ok);

  /**
   * Agree() on the global controller for a program: when any process
   * failed at `step`, each says so on stderr (the failing one that it
   * failed, the others that they stop because of it) before any returns.
   */
  static bool AllSucceeded(bool ok, const char* step);
  /// The same over `controller`'s processes (null: this one alone).
  static bool AllSucceeded(vtkMultiProcessController* controller, bool ok, const char* step);

  ///@{
  /// Collective sums and maxima (in place) over the processes.
  static void Sum(vtkMultiProcessController* controller, std::vector<vtkTypeInt64>& values);
  static vtkTypeInt64 Sum(vtkMultiProcessController* controller, vtkTypeInt64 value);
  static double Max(vtkMultiProcessController* controller, double value);
  ///@}
};

#endif
