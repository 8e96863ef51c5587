// A downstream program: traces the built-in scene and reconstructs its textures.
#include "vtkBrumeDefaultSceneSource.h"
#include "vtkBrumeLightTracer.h"
#include "vtkBrumeRadianceReconstruction.h"
#include "vtkNew.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPolyData.h"

#include <cstdlib>
#include <iostream>

int main()
{
  vtkNew<vtkBrumeDefaultSceneSource> scene;
  vtkNew<vtkBrumeLightTracer> tracer;
  tracer->SetInputConnection(scene->GetOutputPort());
  tracer->SetNumberOfParticles(20000);
  vtkNew<vtkBrumeRadianceReconstruction> reconstruction;
  reconstruction->SetInputConnection(0, scene->GetOutputPort());
  reconstruction->SetInputConnection(1, tracer->GetOutputPort());
  reconstruction->Update();
  const auto hits = tracer->GetOutput()->GetNumberOfPoints();
  const auto objects = reconstruction->GetOutput()->GetNumberOfPartitionedDataSets();
  std::cout << "downstream: " << hits << " hits, " << objects << " textures\n";
  return hits > 0 && objects == 7 ? EXIT_SUCCESS : EXIT_FAILURE;
}
