// SPDX-License-Identifier: BSD-3-Clause
// Run with mpirun -np 2 on one machine, with the messaging layer the
// session must leave to Open MPI as argv[1]: the session starts MPI, and
// Open MPI's processes on one machine take its shared-memory layer (ob1)
// unless the user named one (`mpirun --mca pml ...`, which reaches the
// processes as OMPI_MCA_pml), which the session keeps.
#include "vtkBrumeProcesses.h"
#include "vtkMultiProcessController.h"

#include <cstdlib>
#include <iostream>
#include <string>

int TestProcessesSession(int argc, char* argv[])
{
  if (argc < 2)
  {
    std::cerr << "usage: TestProcessesSession EXPECTED_PML\n";
    return EXIT_FAILURE;
  }
  const std::string expected = argv[1];
  const vtkBrumeProcesses::Session session(&argc, &argv);
  vtkMultiProcessController* controller = vtkBrumeProcesses::GetGlobalController();
  bool ok = true;
  if (vtkBrumeProcesses::GetSize(controller) != 2)
  {
    std::cerr << "run this test with mpirun -np 2: " << vtkBrumeProcesses::GetSize(controller)
              << " processes\n";
    ok = false;
  }
  const char* pml = std::getenv("OMPI_MCA_pml");
  if (!pml || expected != pml)
  {
    std::cerr << "OMPI_MCA_pml is " << (pml ? pml : "(unset)") << ", expected " << expected << "\n";
    ok = false;
  }
  return vtkBrumeProcesses::Agree(controller, ok) ? EXIT_SUCCESS : EXIT_FAILURE;
}
