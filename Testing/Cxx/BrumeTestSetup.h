// SPDX-License-Identifier: BSD-3-Clause
// Runs before every test of a Brume test driver: the threaded SMP backend,
// as `brume` uses.
#ifndef BrumeTestSetup_h
#define BrumeTestSetup_h

#include "vtkBrumeSMP.h"

inline void BrumeTestSetup(int*, char***)
{
  vtkBrumeSMP::UseAllCores();
}

#endif
