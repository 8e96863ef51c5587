// SPDX-License-Identifier: BSD-3-Clause
// A mirror through vtkBrumeRadianceReconstruction: its texture is the
// reflection cast at MirrorResolution texels (the particles alone leave it
// black), recast when the camera turns; the anisotropic fog it reflects is
// looked up from the mirrored eye and turned back, so that turning back to
// the first viewpoint gives the first textures' bits, incremental or
// rebuilt; out-of-range resolutions fail the request.
#include "BrumeTestScenes.h"
#include "vtkBrumeLightTracer.h"
#include "vtkBrumeRadianceReconstruction.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkExecutive.h"

#include <cstdlib>
#include <iostream>

namespace
{
vtkImageData* Texture(vtkPartitionedDataSetCollection* out, const std::string& name)
{
  for (unsigned int i = 0; i < out->GetNumberOfPartitionedDataSets(); ++i)
  {
    if (name == out->GetMetaData(i)->Get(vtkCompositeDataSet::NAME()))
    {
      return vtkImageData::SafeDownCast(out->GetPartitionedDataSet(i)->GetPartition(0));
    }
  }
  return nullptr;
}

vtkSmartPointer<vtkPartitionedDataSetCollection> Copy(vtkPartitionedDataSetCollection* out)
{
  auto copy = vtkSmartPointer<vtkPartitionedDataSetCollection>::New();
  copy->DeepCopy(out);
  return copy;
}
}

int TestMirrorReconstruction(int, char*[])
{
  const auto scene = DefaultSceneWithMirrorFloor();
  vtkNew<vtkBrumeLightTracer> tracer;
  tracer->SetInputData(scene);
  tracer->SetNumberOfParticles(100000);
  vtkNew<vtkCamera> camera;
  camera->SetPosition(0, 0, 4);
  camera->SetFocalPoint(0, 0, 0);
  vtkNew<vtkBrumeRadianceReconstruction> reconstruction;
  reconstruction->SetInputDataObject(0, scene);
  reconstruction->SetInputConnection(1, tracer->GetOutputPort());
  reconstruction->SetCamera(camera);
  reconstruction->SetMirrorResolution(48);
  bool ok = reconstruction->GetExecutive()->Update() == 1;
  const auto first = Copy(reconstruction->GetOutput());
  vtkImageData* floor = Texture(first, "floor");
  int dims[3] = { 0, 0, 0 };
  if (floor)
  {
    floor->GetDimensions(dims);
  }
  double mean = 0.0;
  if (ok && floor)
  {
    vtkDataArray* radiance = floor->GetPointData()->GetScalars();
    for (vtkIdType t = 0; t < radiance->GetNumberOfTuples(); ++t)
    {
      mean += radiance->GetComponent(t, 0) / radiance->GetNumberOfTuples();
    }
  }
  std::cout << "mirror floor: " << dims[0] << " x " << dims[1] << " texels, mean " << mean << "\n";
  // The room reflected: walls of about 0.1 to 0.4 W/m^2/sr times 0.9.
  if (!ok || dims[0] != 48 || dims[1] != 48 || !(mean > 0.05 && mean < 1.0))
  {
    std::cerr << "FAILED: the mirror's texture is not the cast reflection\n";
    ok = false;
  }

  // A turn recasts it; the fog follows the eye.
  camera->Azimuth(10.0);
  ok = reconstruction->GetExecutive()->Update() == 1 && ok;
  if (SameTextures(first, reconstruction->GetOutput(), "after a turn"))
  {
    std::cerr << "FAILED: nothing changed after a turn\n";
    ok = false;
  }
  // Back: the first bits, the fog turned back from the mirrored eye.
  camera->Azimuth(-10.0);
  ok = reconstruction->GetExecutive()->Update() == 1 && ok;
  ok = SameTextures(first, reconstruction->GetOutput(), "incremental, turned back") && ok;

  // Rebuilt from the hits at each view: the same bits.
  vtkNew<vtkBrumeRadianceReconstruction> full;
  full->SetInputDataObject(0, scene);
  full->SetInputConnection(1, tracer->GetOutputPort());
  full->SetCamera(camera);
  full->SetMirrorResolution(48);
  full->IncrementalUpdateOff();
  camera->Azimuth(10.0);
  ok = full->GetExecutive()->Update() == 1 && ok;
  camera->Azimuth(-10.0);
  ok = full->GetExecutive()->Update() == 1 && ok;
  ok = SameTextures(first, full->GetOutput(), "rebuilt") && ok;

  // Out of range: a failed request, not a crash.
  for (const int resolution : { 0, 4097 })
  {
    vtkNew<vtkBrumeRadianceReconstruction> bad;
    bad->SetInputDataObject(0, scene);
    bad->SetInputConnection(1, tracer->GetOutputPort());
    bad->SetMirrorResolution(resolution);
    int errors = 0;
    vtkNew<vtkCallbackCommand> counter;
    counter->SetClientData(&errors);
    counter->SetCallback(
      [](vtkObject*, unsigned long, void* data, void*) { ++*static_cast<int*>(data); });
    bad->AddObserver(vtkCommand::ErrorEvent, counter);
    bad->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, counter);
    if (bad->GetExecutive()->Update() != 0 || errors < 1)
    {
      std::cerr << "FAILED: MirrorResolution " << resolution << " was accepted\n";
      ok = false;
    }
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
