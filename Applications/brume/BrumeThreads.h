// SPDX-License-Identifier: BSD-3-Clause
// ParaView's VTK defaults vtkSMPTools to its Sequential backend: Brume's
// programs use the STDThread one on every core unless the user chose a
// backend with VTK_SMP_BACKEND_IN_USE (and a count with VTK_SMP_MAX_THREADS).
#ifndef BrumeThreads_h
#define BrumeThreads_h

#include "vtkSMPTools.h"

#include <cstdlib>

inline void BrumeUseAllCores()
{
  if (!std::getenv("VTK_SMP_BACKEND_IN_USE"))
  {
    vtkSMPTools::SetBackend("STDThread");
  }
  const char* max = std::getenv("VTK_SMP_MAX_THREADS");
  vtkSMPTools::Initialize(max ? std::atoi(max) : 0);
}

#endif
