// SPDX-License-Identifier: BSD-3-Clause
// vtkBrumeRadianceReconstruction models no more than the scene needs:
// turning the camera recomputes only the view-dependent textures (a glossy
// floor and the anisotropic fog), the others stay the same objects with the
// same bits; objects without particles are reported, not fatal.
#include "BrumeTestScenes.h"
#include "vtkBrumeLightTracer.h"
#include "vtkBrumeRadianceReconstruction.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCellData.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"

#include <cstdlib>
#include <cstring>
#include <iostream>
#include <map>
#include <string>

namespace
{
vtkDataArray* TextureArray(vtkDataObject* texture)
{
  auto* image = vtkImageData::SafeDownCast(texture);
  return image->GetPointData()->GetScalars() ? image->GetPointData()->GetScalars()
                                             : image->GetCellData()->GetScalars();
}

bool SameBits(vtkDataArray* a, vtkDataArray* b)
{
  return a->GetNumberOfValues() == b->GetNumberOfValues() &&
    std::memcmp(a->GetVoidPointer(0), b->GetVoidPointer(0),
      a->GetNumberOfValues() * a->GetDataTypeSize()) == 0;
}

struct Snapshot
{
  std::map<std::string, vtkSmartPointer<vtkDataObject>> Textures;
  std::map<std::string, vtkSmartPointer<vtkDataArray>> Copies;
};

Snapshot Take(vtkPartitionedDataSetCollection* out)
{
  Snapshot s;
  for (unsigned int i = 0; i < out->GetNumberOfPartitionedDataSets(); ++i)
  {
    const std::string name = out->GetMetaData(i)->Get(vtkCompositeDataSet::NAME());
    vtkDataObject* texture = out->GetPartitionedDataSet(i)->GetPartition(0);
    s.Textures[name] = texture;
    auto copy = vtkSmartPointer<vtkDataArray>::Take(TextureArray(texture)->NewInstance());
    copy->DeepCopy(TextureArray(texture));
    s.Copies[name] = copy;
  }
  return s;
}
}

int TestReconstructionViews(int, char*[])
{
  // The default scene with a glossy floor (view dependent, like the fog).
  const auto scene = DefaultSceneWithGlossyFloor();
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
  reconstruction->Update();
  const Snapshot first = Take(reconstruction->GetOutput());
  const vtkIdType objects = static_cast<vtkIdType>(first.Textures.size());
  if (reconstruction->GetNumberOfTextureBuilds() != objects)
  {
    std::cerr << "Expected " << objects << " texture builds, got "
              << reconstruction->GetNumberOfTextureBuilds() << "\n";
    return EXIT_FAILURE;
  }

  // Turn the camera 10 degrees.
  camera->Azimuth(10.0);
  reconstruction->Update();
  const Snapshot second = Take(reconstruction->GetOutput());
  bool ok = reconstruction->GetNumberOfTextureBuilds() == objects &&
    reconstruction->GetNumberOfViewUpdates() == 2;
  for (const auto& entry : first.Textures)
  {
    const std::string& name = entry.first;
    const bool viewDependent = name == "floor" || name == "fog";
    const bool same = second.Textures.at(name) == entry.second;
    const bool sameBits = SameBits(first.Copies.at(name), TextureArray(second.Textures.at(name)));
    if (viewDependent == same || viewDependent == sameBits)
    {
      std::cerr << name << ": " << (same ? "same object" : "new object") << ", "
                << (sameBits ? "same bits" : "new bits") << "\n";
      ok = false;
    }
  }
  std::cout << "after a 10 degree turn: " << reconstruction->GetNumberOfTextureBuilds()
            << " builds, " << reconstruction->GetNumberOfViewUpdates() << " view updates\n";

  // The same viewpoint again: nothing to do.
  reconstruction->Modified();
  reconstruction->Update();
  ok = ok && reconstruction->GetNumberOfTextureBuilds() == objects &&
    reconstruction->GetNumberOfViewUpdates() == 2;

  // Without the incremental update, the two view-dependent textures are
  // rebuilt from the hits, to the same bits.
  vtkNew<vtkBrumeRadianceReconstruction> full;
  full->SetInputDataObject(0, scene);
  full->SetInputConnection(1, tracer->GetOutputPort());
  full->SetCamera(camera);
  full->IncrementalUpdateOff();
  camera->Azimuth(-10.0);
  full->Update();
  camera->Azimuth(10.0);
  full->Update();
  ok = ok && full->GetNumberOfTextureBuilds() == objects + 2 && full->GetNumberOfViewUpdates() == 0;
  const Snapshot rebuilt = Take(full->GetOutput());
  for (const char* name : { "floor", "fog" })
  {
    if (!SameBits(second.Copies.at(name), rebuilt.Copies.at(name)))
    {
      std::cerr << name << ": the incremental update differs from a rebuild\n";
      ok = false;
    }
  }

  // An object no particle reaches: a warning, and a texture of its emission.
  vtkNew<vtkBrumeLightTracer> few;
  few->SetInputData(scene);
  few->SetNumberOfParticles(1);
  vtkNew<vtkBrumeRadianceReconstruction> sparse;
  sparse->SetInputDataObject(0, scene);
  sparse->SetInputConnection(1, few->GetOutputPort());
  int warnings = 0;
  vtkNew<vtkCallbackCommand> counter;
  counter->SetClientData(&warnings);
  counter->SetCallback(
    [](vtkObject*, unsigned long, void* data, void*) { ++*static_cast<int*>(data); });
  sparse->AddObserver(vtkCommand::WarningEvent, counter);
  if (!sparse->GetExecutive()->Update() || warnings < 1)
  {
    std::cerr << "Objects without particles: expected warnings and success, got " << warnings
              << " warnings\n";
    ok = false;
  }
  std::cout << "1 particle: " << warnings << " objects reported without particles\n";
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
