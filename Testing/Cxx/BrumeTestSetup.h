// SPDX-License-Identifier: BSD-3-Clause
// Runs before every test of a Brume test driver: the threaded SMP backend,
// as `brume` uses.
#ifndef BrumeTestSetup_h
#define BrumeTestSetup_h

#include "vtkBrumeSMP.h"
#ifdef BRUME_TEST_RENDERING
#include "vtkBrumeRenderWindowSelection.h"

#include <cstdlib>
#include <iostream>
#endif

inline void BrumeTestSetup(int*, char***)
{
  vtkBrumeSMP::UseAllCores();
#ifdef BRUME_TEST_RENDERING
  // X when DISPLAY names a display, else EGL (BRUME_RENDER_WINDOW chooses);
  // with neither, the test cannot render: skipped (125), not crashed.
  if (!vtkBrumeRenderWindowSelection::Install())
  {
    std::cerr << "no render window: " << vtkBrumeRenderWindowSelection::GetLastError()
              << ": skipped\n";
    std::exit(125);
  }
#endif
}

#endif
