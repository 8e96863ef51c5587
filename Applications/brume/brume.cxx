// SPDX-License-Identifier: BSD-3-Clause
// `brume`: the command line front end of the Brume toolkit. Its commands and
// their options are declared in BrumeCommandLine.cxx.
#include "BrumeCommandLine.h"
#include "BrumeOutputWindow.h"

#include "vtkBrumeProcesses.h"
#include "vtkBrumeRenderWindowSelection.h"
#include "vtkBrumeSMP.h"
#include "vtkVersion.h"

#include <cstdlib>
#include <exception>
#include <iostream>
#include <new>

namespace
{
int RunCommand(BrumeCommandLine& line)
{
  using Command = BrumeCommandLine::Command;
  switch (line.Run)
  {
    case Command::Version:
      std::cout << "brume " << BRUME_VERSION << " (VTK " << vtkVersion::GetVTKVersionFull()
                << ")\n";
      return 0;
    case Command::Render:
      return RunRender(line.Render);
    case Command::View:
      return RunView(line.View);
    case Command::ValidateSlab:
      return RunValidateSlab(line.Slab);
    case Command::Bench:
      return RunBench(line.Bench);
    case Command::Chart:
      return RunChart(line.Chart);
    case Command::None:
      break;
  }
  return 2;
}
}

int main(int argc, char* argv[])
{
  const vtkBrumeProcesses::Session processes(&argc, &argv); // MPI, when mpirun started brume
  BrumeCommandLine line;
  const int rc = ParseCommandLine(argc, argv, line);
  if (rc >= 0)
  {
    return rc;
  }
  vtkBrumeSMP::UseAllCores(line.Threads);
  BrumeOutputWindow::Install();
  // --window chooses the render window before anything renders; without it
  // the first render chooses (BRUME_RENDER_WINDOW, else X or EGL).
  if (!line.Window.empty() && !vtkBrumeRenderWindowSelection::Install(line.Window.c_str()))
  {
    std::cerr << "brume: " << vtkBrumeRenderWindowSelection::GetLastError() << ".\n";
    return 1;
  }
  // Memory that cannot be had (an image or a run too large for this
  // machine) ends the command with a message, not an abort. Under mpirun
  // the other processes may be waiting for this one in a collective: a
  // clean exit would leave them waiting, an abort ends the run.
  const bool distributed =
    vtkBrumeProcesses::IsDistributed(vtkBrumeProcesses::GetGlobalController());
  try
  {
    return RunCommand(line);
  }
  catch (const std::bad_alloc&)
  {
    std::cerr << "brume: out of memory: this machine cannot hold what the command asks for "
                 "(a smaller --size, or fewer --particles).\n";
  }
  catch (const std::exception& e)
  {
    std::cerr << "brume: " << e.what() << ".\n";
  }
  if (distributed)
  {
    std::abort();
  }
  return 1;
}
