// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeSMP
 * @brief   the physics core's parallel loop on vtkSMPTools; the machine's memory
 *
 * The core takes its thread primitive from its caller (brume/Parallel.h);
 * Brume's VTK modules give it vtkSMPTools, so that VTK's backend and thread
 * count (VTK_SMP_BACKEND_IN_USE, VTK_SMP_MAX_THREADS) apply to every phase.
 */
#ifndef vtkBrumeSMP_h
#define vtkBrumeSMP_h

#include "vtkBrumeConversionModule.h" // For export macro

#include "brume/Parallel.h" // For brume::ParallelFor

class VTKBRUMECONVERSION_EXPORT vtkBrumeSMP
{
public:
  /// A brume::ParallelFor that runs on vtkSMPTools::For.
  static brume::ParallelFor ParallelFor();

  /**
   * ParaView's VTK defaults vtkSMPTools to its Sequential backend: Brume's
   * programs and tests use the STDThread one on every core, unless the user
   * chose a backend with VTK_SMP_BACKEND_IN_USE; on `threads` threads when
   * above 0 (brume's --threads), else VTK_SMP_MAX_THREADS's, else every core.
   */
  static void UseAllCores(int threads = 0);

  /**
   * For libraries (the Python package, the ParaView plugin), which share
   * the process with their user: UseAllCores() only when the user has not
   * chosen (no VTK_SMP_BACKEND_IN_USE) and the backend is still VTK's
   * Sequential default, which would run every phase on one core. Returns
   * whether it switched.
   */
  static bool UseAllCoresUnlessChosen();

  /**
   * What sizes a file or a request announces may ask of this machine: half
   * of its physical memory, in bytes (0 when it cannot be told). Brume's
   * checks compare announced sizes with it before anything is allocated.
   */
  static double UsableMemory();
};

#endif
