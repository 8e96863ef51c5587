// A downstream program: the built-in scene through Brume's pipeline object
// (tracing and reconstruction; vtkBrumePipeline::RenderImage would draw it).
#include "vtkBrumeDefaultSceneSource.h"
#include "vtkBrumeLightTracer.h"
#include "vtkBrumePipeline.h"
#include "vtkNew.h"
#include "vtkPartitionedDataSetCollection.h"

#include <cstdlib>
#include <iostream>

int main()
{
  vtkNew<vtkBrumeDefaultSceneSource> scene;
  vtkNew<vtkBrumePipeline> pipeline;
  pipeline->SetInputConnection(scene->GetOutputPort());
  pipeline->GetTracer()->SetNumberOfParticles(20000);
  if (!pipeline->Update())
  {
    std::cerr << "downstream: " << pipeline->GetFailedPhase() << " failed\n";
    return EXIT_FAILURE;
  }
  const auto hits = pipeline->GetNumberOfHits();
  const auto objects = pipeline->GetTextures()->GetNumberOfPartitionedDataSets();
  std::cout << "downstream: " << hits << " hits, " << objects << " textures\n";
  return hits > 0 && objects == 7 ? EXIT_SUCCESS : EXIT_FAILURE;
}
