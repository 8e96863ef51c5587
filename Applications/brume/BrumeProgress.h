// SPDX-License-Identifier: BSD-3-Clause
// A progress bar on stderr for long phases, only when stderr is a terminal.
#ifndef BrumeProgress_h
#define BrumeProgress_h

#include "vtkAlgorithm.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkNew.h"

#include <cstdio>
#include <unistd.h>

inline void BrumeShowProgress(vtkAlgorithm* algorithm, const char* label)
{
  if (!isatty(STDERR_FILENO))
  {
    return;
  }
  vtkNew<vtkCallbackCommand> bar;
  bar->SetClientData(const_cast<char*>(label));
  bar->SetCallback(
    [](vtkObject*, unsigned long, void* clientData, void* callData)
    {
      const double progress = *static_cast<double*>(callData);
      const int filled = static_cast<int>(progress * 30.0 + 0.5);
      std::fprintf(stderr, "\r%-18s [%.*s%*s] %3d%%", static_cast<const char*>(clientData), filled,
        "##############################", 30 - filled, "",
        static_cast<int>(progress * 100.0 + 0.5));
      if (progress >= 1.0)
      {
        std::fputc('\n', stderr);
      }
      std::fflush(stderr);
    });
  algorithm->AddObserver(vtkCommand::ProgressEvent, bar);
}

#endif
