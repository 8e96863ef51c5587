// SPDX-License-Identifier: BSD-3-Clause
// Runs before every test of a Brume test driver: the threaded SMP backend,
// as `brume` uses.
#ifndef BrumeTestSetup_h
#define BrumeTestSetup_h

#include "vtkBrumeSMP.h"
#ifdef BRUME_TEST_RENDERING
#include "vtkBrumeRenderWindowSelection.h"
#endif

inline void BrumeTestSetup(int*, char***)
{
  vtkBrumeSMP::UseAllCores();
#ifdef BRUME_TEST_RENDERING
  // X when DISPLAY names a display, else EGL (BRUME_RENDER_WINDOW chooses).
  vtkBrumeRenderWindowSelection::Install();
#endif
}

#endif
