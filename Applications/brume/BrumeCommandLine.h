// SPDX-License-Identifier: BSD-3-Clause
// `brume`'s command line: its commands and their options (CLI11), parsed
// into the options of the command to run, which runs nothing.
#ifndef BrumeCommandLine_h
#define BrumeCommandLine_h

#include "BrumeCommands.h"
#include "BrumeRender.h"
#include "BrumeView.h"

#include <iostream>
#include <string>

struct BrumeCommandLine
{
  enum class Command
  {
    None, // help was printed, or a usage error
    Version,
    Render,
    View,
    ValidateSlab,
    Bench,
    Chart
  };
  Command Run = Command::None;
  std::string Window; // --window: the render window's kind, "" for BRUME_RENDER_WINDOW
  int Threads = 0;    // --threads: 0 for VTK_SMP_MAX_THREADS, else every core
  RenderOptions Render;
  ViewOptions View;
  SlabOptions Slab;
  BenchOptions Bench;
  ChartOptions Chart;
};

/**
 * Parses `brume COMMAND [arguments]` into `line`. Returns -1 when
 * `line.Run` is to run; otherwise the exit code: 0 after printing help on
 * `out`, 2 after a usage error (`brume: MESSAGE` and where to find the usage,
 * on `err`).
 */
int ParseCommandLine(int argc, char** argv, BrumeCommandLine& line, std::ostream& out = std::cout,
  std::ostream& err = std::cerr);

#endif
