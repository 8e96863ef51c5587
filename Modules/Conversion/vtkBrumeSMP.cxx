// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeSMP.h"

#include "vtkSMPTools.h"

#include <vtksys/SystemInformation.hxx>

#include <cstdlib>
#include <cstring>

void vtkBrumeSMP::UseAllCores(int threads)
{
  if (!std::getenv("VTK_SMP_BACKEND_IN_USE"))
  {
    vtkSMPTools::SetBackend("STDThread");
  }
  const char* max = std::getenv("VTK_SMP_MAX_THREADS");
  vtkSMPTools::Initialize(threads > 0 ? threads : max ? std::atoi(max) : 0);
}

bool vtkBrumeSMP::UseAllCoresUnlessChosen()
{
  const char* backend = vtkSMPTools::GetBackend();
  if (std::getenv("VTK_SMP_BACKEND_IN_USE") || !backend || std::strcmp(backend, "Sequential") != 0)
  {
    return false;
  }
  vtkBrumeSMP::UseAllCores();
  return std::strcmp(vtkSMPTools::GetBackend(), "Sequential") != 0;
}

brume::ParallelFor vtkBrumeSMP::ParallelFor()
{
  return [](std::size_t begin, std::size_t end,
           const std::function<void(std::size_t, std::size_t)>& body)
  {
    vtkSMPTools::For(static_cast<vtkIdType>(begin), static_cast<vtkIdType>(end),
      [&](vtkIdType b, vtkIdType e)
      { body(static_cast<std::size_t>(b), static_cast<std::size_t>(e)); });
  };
}

double vtkBrumeSMP::UsableMemory()
{
  vtksys::SystemInformation system;
  system.RunMemoryCheck();
  return 0.5 * static_cast<double>(system.GetTotalPhysicalMemory()) * 1048576.0;
}
