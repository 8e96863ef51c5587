// SPDX-License-Identifier: BSD-3-Clause
// The phases whose instruction counts guard against regressions
// (CheckInstructions.cmake runs this under callgrind): the default scene
// traced on a small budget, its full reconstruction, the view update after
// a 2 degree turn, and one 128 x 128 frame through OSMesa after a first
// frame that uploads textures and compiles shaders. Each phase's counts are
// zeroed before it and dumped after it under the phase's name; run outside
// callgrind it only runs the phases.
#include "vtkBrumeDefaultSceneSource.h"
#include "vtkBrumeLightTracer.h"
#include "vtkBrumeRadianceReconstruction.h"
#include "vtkBrumeRenderWindowSelection.h"
#include "vtkBrumeSceneActors.h"
#include "vtkBrumeSceneCamera.h"
#include "vtkCamera.h"
#include "vtkNew.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"

#include <valgrind/callgrind.h>

#include <cstdio>
#include <cstdlib>

namespace
{
template <typename Phase>
void Count(const char* name, Phase&& phase)
{
  CALLGRIND_ZERO_STATS;
  phase();
  CALLGRIND_DUMP_STATS_AT(name);
}
}

int main(int argc, char* argv[])
{
  const long long particles = argc > 1 ? std::atoll(argv[1]) : 20000;
  if (particles < 1)
  {
    std::fprintf(stderr, "usage: BrumeInstructionPhases [PARTICLES]\n");
    return 2;
  }
  vtkNew<vtkBrumeDefaultSceneSource> source;
  source->Update();
  vtkNew<vtkBrumeLightTracer> tracer;
  tracer->SetInputConnection(source->GetOutputPort());
  tracer->SetNumberOfParticles(particles);
  Count("tracing", [&] { tracer->Update(); });

  vtkNew<vtkCamera> camera;
  vtkBrumeSceneCamera::SetToDefault(camera);
  vtkNew<vtkBrumeRadianceReconstruction> reconstruction;
  reconstruction->SetInputConnection(0, source->GetOutputPort());
  reconstruction->SetInputConnection(1, tracer->GetOutputPort());
  reconstruction->SetCamera(camera);
  Count("reconstruction", [&] { reconstruction->Update(); });
  camera->Azimuth(2.0);
  Count("view-update", [&] { reconstruction->Update(); });

  if (!vtkBrumeRenderWindowSelection::Install("osmesa"))
  {
    std::fprintf(stderr, "BrumeInstructionPhases: no OSMesa window: %s\n",
      vtkBrumeRenderWindowSelection::GetLastError());
    return 1;
  }
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->SetSize(128, 128);
  window->AddRenderer(renderer);
  renderer->SetActiveCamera(camera);
  vtkNew<vtkBrumeSceneActors> actors;
  actors->SetInputData(reconstruction->GetOutput());
  actors->AddToRenderer(renderer);
  window->Render();
  camera->Azimuth(0.5);
  renderer->ResetCameraClippingRange();
  Count("frame", [&] {
    window->Render();
    window->WaitForCompletion();
  });
  std::printf("BrumeInstructionPhases: %lld particles, %lld hits\n", particles,
    static_cast<long long>(tracer->GetOutput()->GetNumberOfPoints()));
  return 0;
}
