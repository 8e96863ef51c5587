// SPDX-License-Identifier: BSD-3-Clause
// The surfaces' BVH is built again only when they change
// (vtkBrumeSceneConversion::SharedRayCaster). The default scene with a
// point light, whose direct light the reconstruction computes with shadow
// rays (its textures keep their BVH; the tracer keeps none: a filter may
// outlive Embree):
// - a first run: the tracer's BVH, then the shadow rays' (the tracer's is
//   gone);
// - another seed, a run in four batches: none, the textures' one is found;
// - a surface moved: the tracer's and the shadow rays' again, and the
//   image is the one of a pipeline that never saw the old surfaces.
#include "vtkBrumeDefaultSceneSource.h"
#include "vtkBrumeLightTracer.h"
#include "vtkBrumePipeline.h"
#include "vtkBrumeRadianceReconstruction.h"
#include "vtkBrumeSceneConversion.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <cstring>
#include <iostream>
#include <string>

namespace
{
int Failures = 0;

void Check(bool ok, const std::string& what)
{
  std::cout << (ok ? "ok: " : "FAILED: ") << what << "\n";
  Failures += ok ? 0 : 1;
}

std::size_t Builds()
{
  return vtkBrumeSceneConversion::GetNumberOfRayCasterBuilds();
}

// Updates `pipeline`; checks that it succeeded with `expected` BVHs built.
void UpdateBuilding(vtkBrumePipeline* pipeline, std::size_t expected, const std::string& what)
{
  const std::size_t before = Builds();
  const bool updated = pipeline->Update();
  const std::size_t built = Builds() - before;
  Check(updated && built == expected, what + ": " + std::to_string(built) + " built");
}

bool Same(vtkImageData* a, vtkImageData* b)
{
  auto* x = a ? vtkFloatArray::SafeDownCast(a->GetPointData()->GetArray("Radiance")) : nullptr;
  auto* y = b ? vtkFloatArray::SafeDownCast(b->GetPointData()->GetArray("Radiance")) : nullptr;
  return x && y && x->GetNumberOfValues() == y->GetNumberOfValues() &&
    std::memcmp(x->GetPointer(0), y->GetPointer(0),
      static_cast<std::size_t>(x->GetNumberOfValues()) * sizeof(float)) == 0;
}

void Configure(vtkBrumePipeline* pipeline)
{
  vtkNew<vtkLight> lamp;
  lamp->SetPositional(true);
  lamp->SetConeAngle(180.0);
  lamp->SetPosition(0.0, 0.3, 0.2);
  lamp->SetIntensity(0.5);
  pipeline->GetTracer()->AddLight(lamp);
  pipeline->GetTracer()->SetNumberOfParticles(20000);
  pipeline->GetReconstruction()->SetFixedView(true);
  pipeline->SetSize(24, 24);
}
}

int TestSharedRayCaster(int, char*[])
{
  vtkNew<vtkBrumeDefaultSceneSource> source;
  vtkNew<vtkBrumePipeline> pipeline;
  pipeline->SetInputConnection(source->GetOutputPort());
  Configure(pipeline);
  UpdateBuilding(pipeline, 2, "a first run: the tracer's BVH and the shadow rays'");
  pipeline->GetTracer()->SetSeed(7);
  UpdateBuilding(pipeline, 0, "another seed: no BVH");
  pipeline->SetBatchSize(5000);
  pipeline->GetTracer()->SetSeed(8);
  UpdateBuilding(pipeline, 0, "four batches: no BVH");
  pipeline->SetBatchSize(0);

  // The scene again, one surface's points moved up by 1 cm.
  source->Update();
  vtkNew<vtkPartitionedDataSetCollection> moved;
  moved->DeepCopy(source->GetOutput());
  auto* surface = vtkPolyData::SafeDownCast(moved->GetPartitionedDataSet(0)->GetPartition(0));
  Check(surface != nullptr && surface->GetNumberOfPoints() > 0,
    "the scene's first object is a surface");
  for (vtkIdType i = 0; surface && i < surface->GetNumberOfPoints(); ++i)
  {
    double p[3];
    surface->GetPoint(i, p);
    p[1] += 0.01;
    surface->GetPoints()->SetPoint(i, p);
  }
  pipeline->SetInputData(moved);
  UpdateBuilding(pipeline, 2, "a surface moved: two BVHs again");
  const vtkSmartPointer<vtkImageData> image = pipeline->RenderImage();

  vtkNew<vtkBrumePipeline> fresh;
  fresh->SetInputData(moved);
  Configure(fresh);
  fresh->GetTracer()->SetSeed(8);
  Check(fresh->Update(), "a fresh pipeline of the moved scene");
  const vtkSmartPointer<vtkImageData> expected = fresh->RenderImage();
  Check(Same(image, expected),
    "the moved scene's image is that of a pipeline that never saw the old surfaces");
  return Failures == 0 ? 0 : 1;
}
