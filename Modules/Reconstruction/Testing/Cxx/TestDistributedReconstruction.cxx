// SPDX-License-Identifier: BSD-3-Clause
// Run with mpirun -np 2 (or more): every process traces its piece of the
// run and the reconstruction sums the histograms across processes. On
// process 0 the textures must be bitwise those of one process tracing and
// reconstructing every particle: after the build, after a camera turn (the
// view-dependent histograms summed again), and with directional media.
#include "BrumeTestScenes.h"

#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeLightTracer.h"
#include "vtkBrumeRadianceReconstruction.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCommunicator.h"
#include "vtkExecutive.h"
#include "vtkMPIController.h"
#include "vtkPolyData.h"
#include "vtkUnsignedShortArray.h"

#include <cstdlib>

int TestDistributedReconstruction(int argc, char* argv[])
{
  vtkNew<vtkMPIController> controller;
  controller->Initialize(&argc, &argv, 0);
  const int rank = controller->GetLocalProcessId(), size = controller->GetNumberOfProcesses();
  bool ok = size > 1;
  if (!ok && rank == 0)
  {
    std::cerr << "run this test with mpirun -np 2 or more\n";
  }
  const auto scene = DefaultSceneWithGlossyFloor();
  vtkNew<vtkCamera> camera;
  camera->SetPosition(0, 0, 4);
  camera->SetFocalPoint(0, 0, 0);

  vtkNew<vtkBrumeLightTracer> tracer;
  tracer->SetInputData(scene);
  tracer->SetNumberOfParticles(50000);
  vtkNew<vtkBrumeRadianceReconstruction> distributed;
  distributed->SetController(controller);
  distributed->SetInputDataObject(0, scene);
  distributed->SetInputConnection(1, tracer->GetOutputPort());
  distributed->SetCamera(camera);

  // The one-process run, on every process.
  vtkNew<vtkBrumeLightTracer> allTracer;
  allTracer->SetInputData(scene);
  allTracer->SetNumberOfParticles(50000);
  vtkNew<vtkBrumeRadianceReconstruction> single;
  single->SetController(nullptr);
  single->SetInputDataObject(0, scene);
  single->SetInputConnection(1, allTracer->GetOutputPort());
  single->SetCamera(camera);

  // Every process gives the textures (renderers that composite draw on
  // each): those of one process holding every hit.
  auto compare = [&](const char* what)
  {
    ok = distributed->UpdatePiece(rank, size, 0) != 0 && ok;
    single->Update();
    ok = SameTextures(distributed->GetOutput(), single->GetOutput(), what) && ok;
    if (rank == 0)
    {
      std::cout << what << ": " << distributed->GetLastReductionBytes()
                << " bytes sent and received by process 0\n";
    }
  };
  compare("after the build");
  camera->Azimuth(20.0);
  compare("after a camera turn");
  distributed->DirectionalRadianceOn();
  single->DirectionalRadianceOn();
  compare("directional media");

  // Process 1's hits name an object the scene lacks: every process fails
  // (none waits forever for it), each with an error.
  {
    tracer->UpdatePiece(rank, size, 0);
    vtkNew<vtkPolyData> hits;
    hits->DeepCopy(tracer->GetOutput());
    if (rank == 1 && hits->GetNumberOfPoints() > 0)
    {
      vtkUnsignedShortArray::SafeDownCast(hits->GetPointData()->GetArray(vtkBrumeNames::ObjectId))
        ->SetValue(0, 999);
    }
    vtkNew<vtkBrumeRadianceReconstruction> broken;
    broken->SetController(controller);
    broken->SetInputDataObject(0, scene);
    broken->SetInputDataObject(1, hits);
    vtkNew<vtkCallbackCommand> silence;
    broken->AddObserver(vtkCommand::ErrorEvent, silence);
    broken->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, silence);
    if (broken->UpdatePiece(rank, size, 0) != 0)
    {
      std::cerr << "process " << rank << " went on although process 1's hits were bad\n";
      ok = false;
    }
  }

  // Every process agrees on the result.
  int local = ok ? 1 : 0, all = 0;
  controller->AllReduce(&local, &all, 1, vtkCommunicator::MIN_OP);
  controller->Finalize();
  return all ? EXIT_SUCCESS : EXIT_FAILURE;
}
