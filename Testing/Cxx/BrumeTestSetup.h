// SPDX-License-Identifier: BSD-3-Clause
// Runs before every test of the driver: the threaded SMP backend, as `brume` uses.
#ifndef BrumeTestSetup_h
#define BrumeTestSetup_h

#include "BrumeThreads.h"

inline void BrumeTestSetup(int*, char***)
{
  BrumeUseAllCores();
}

#endif
