// SPDX-License-Identifier: BSD-3-Clause
// Beyond the paper, through the pipeline: progressively added particles give
// the textures of one run with all of them (bitwise), and so do batches of
// one run traced one after the other; a run that does not continue the
// textures' is refused, and directional media follow the
// camera without any reconstruction, then return to per-view textures that
// equal a fresh reconstruction's; with its build state released, the
// output stays and a later execution rebuilds it in full.
#include "BrumeTestScenes.h"
#include "vtkBrumeDataModelNames.h"
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
#include "vtkStringArray.h"

#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>

namespace
{
vtkDataObject* Fog(vtkPartitionedDataSetCollection* out)
{
  for (unsigned int i = 0; i < out->GetNumberOfPartitionedDataSets(); ++i)
  {
    if (std::string(out->GetMetaData(i)->Get(vtkCompositeDataSet::NAME())) == "fog")
    {
      return out->GetPartitionedDataSet(i)->GetPartition(0);
    }
  }
  return nullptr;
}

// Runs `algorithm`; true if it failed with an error (which is silenced).
bool FailsWithError(vtkAlgorithm* algorithm)
{
  int errors = 0;
  vtkNew<vtkCallbackCommand> counter;
  counter->SetClientData(&errors);
  counter->SetCallback(
    [](vtkObject*, unsigned long, void* data, void*) { ++*static_cast<int*>(data); });
  vtkNew<vtkCallbackCommand> silence;
  const unsigned long tag = algorithm->AddObserver(vtkCommand::ErrorEvent, counter);
  const unsigned long executiveTag =
    algorithm->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, silence);
  const int rc = algorithm->GetExecutive()->Update();
  algorithm->RemoveObserver(tag);
  algorithm->GetExecutive()->RemoveObserver(executiveTag);
  return rc == 0 && errors > 0;
}
}

int TestProgressiveDirectional(int, char*[])
{
  // The default scene with a glossy floor (view dependent, like the fog).
  const auto scene = DefaultSceneWithGlossyFloor();
  vtkNew<vtkCamera> camera;
  camera->SetPosition(0, 0, 4);
  camera->SetFocalPoint(0, 0, 0);
  auto reconstructionOf = [&](vtkBrumeLightTracer* tracer)
  {
    auto r = vtkSmartPointer<vtkBrumeRadianceReconstruction>::New();
    r->SetInputDataObject(0, scene);
    r->SetInputConnection(1, tracer->GetOutputPort());
    r->SetCamera(camera);
    r->SetSurfaceResolution(24);
    r->SetMediumResolution(10);
    return r;
  };
  // The first half, [0, 20000), of a run of 40,000 particles, binned by an
  // accumulating reconstruction.
  auto firstHalf = [&](vtkSmartPointer<vtkBrumeLightTracer>& tracer)
  {
    tracer = vtkSmartPointer<vtkBrumeLightTracer>::New();
    tracer->SetInputData(scene);
    tracer->SetNumberOfParticles(40000);
    tracer->SetEndParticle(20000);
    auto r = reconstructionOf(tracer);
    r->AccumulateParticlesOn();
    r->Update();
    return r;
  };
  bool ok = true;

  // 1. Progressive: 20,000 particles, then 20,000 more, against 40,000.
  vtkNew<vtkBrumeLightTracer> progressiveTracer, singleTracer;
  progressiveTracer->SetInputData(scene);
  progressiveTracer->SetNumberOfParticles(20000);
  singleTracer->SetInputData(scene);
  singleTracer->SetNumberOfParticles(40000);
  auto progressive = reconstructionOf(progressiveTracer);
  progressive->AccumulateParticlesOn();
  auto single = reconstructionOf(singleTracer);
  progressive->Update();
  const vtkIdType objects = progressive->GetNumberOfTextureBuilds();
  progressiveTracer->SetFirstParticle(20000);
  progressiveTracer->SetNumberOfParticles(40000);
  progressive->Update();
  single->Update();
  ok = SameTextures(progressive->GetOutput(), single->GetOutput(), "added particles") && ok;
  if (progressive->GetNumberOfTextureBuilds() != objects ||
    progressive->GetNumberOfParticleAdditions() != objects)
  {
    std::cerr << "expected " << objects << " builds and additions, got "
              << progressive->GetNumberOfTextureBuilds() << " and "
              << progressive->GetNumberOfParticleAdditions() << "\n";
    ok = false;
  }
  camera->Azimuth(15.0);
  progressive->Update();
  single->Update();
  ok = SameTextures(progressive->GetOutput(), single->GetOutput(), "added, then turned") && ok;

  // The tracer running the same step again brings nothing new; a changed
  // setting cannot rebuild the textures from the last step's particles.
  progressiveTracer->Modified();
  if (!progressive->GetExecutive()->Update() ||
    progressive->GetNumberOfParticleAdditions() != objects ||
    progressive->GetNumberOfTextureBuilds() != objects)
  {
    std::cerr << "the same step traced again changed the textures\n";
    ok = false;
  }
  ok = SameTextures(progressive->GetOutput(), single->GetOutput(), "same step again") && ok;
  progressive->SetRadiosityThreshold(64.0);
  if (!FailsWithError(progressive))
  {
    std::cerr << "a setting change rebuilt the textures from part of the particles\n";
    ok = false;
  }
  progressive->SetRadiosityThreshold(128.0);

  // 2. Hits that do not continue the textures' run are refused.
  progressiveTracer->SetFirstParticle(50000);
  progressiveTracer->SetNumberOfParticles(60000);
  if (!FailsWithError(progressive))
  {
    std::cerr << "a run that skips particles was accepted\n";
    ok = false;
  }
  auto plain = reconstructionOf(progressiveTracer);
  if (!FailsWithError(plain))
  {
    std::cerr << "part of a run was accepted without AccumulateParticles\n";
    ok = false;
  }

  // 3. Batches of one run: [0, 13000), [13000, 26000), [26000, 40000) of
  // 40,000 particles, added one after the other, give the textures of the
  // single run (bitwise), per view and directional; only one batch's hits
  // exist at a time.
  for (const bool directionalMedia : { false, true })
  {
    vtkNew<vtkBrumeLightTracer> batchTracer;
    batchTracer->SetInputData(scene);
    batchTracer->SetNumberOfParticles(40000);
    auto batched = reconstructionOf(batchTracer);
    batched->AccumulateParticlesOn();
    batched->SetDirectionalRadiance(directionalMedia);
    const vtkTypeInt64 ends[3] = { 13000, 26000, 40000 };
    vtkTypeInt64 first = 0;
    for (const vtkTypeInt64 end : ends)
    {
      batchTracer->SetFirstParticle(first);
      batchTracer->SetEndParticle(end);
      batched->Update();
      first = end;
    }
    auto reference = reconstructionOf(singleTracer);
    reference->SetDirectionalRadiance(directionalMedia);
    reference->Update();
    const char* what = directionalMedia ? "batches, directional" : "batches";
    ok = SameTextures(batched->GetOutput(), reference->GetOutput(), what) && ok;
    if (batched->GetNumberOfTextureBuilds() != objects ||
      batched->GetNumberOfParticleAdditions() != 2 * objects)
    {
      std::cerr << what << ": expected " << objects << " builds and " << 2 * objects
                << " additions, got " << batched->GetNumberOfTextureBuilds() << " and "
                << batched->GetNumberOfParticleAdditions() << "\n";
      ok = false;
    }
    // A batch that skips particles, or one of another run, is refused.
    batchTracer->SetNumberOfParticles(80000);
    batchTracer->SetFirstParticle(50000);
    batchTracer->SetEndParticle(60000);
    if (!FailsWithError(batched))
    {
      std::cerr << what << ": a batch that skips particles was accepted\n";
      ok = false;
    }
  }
  {
    // Before the run is complete, a batch of a larger run cannot follow.
    vtkSmartPointer<vtkBrumeLightTracer> batchTracer;
    auto batched = firstHalf(batchTracer);
    batchTracer->SetNumberOfParticles(80000);
    batchTracer->SetFirstParticle(20000);
    batchTracer->SetEndParticle(40000);
    if (!FailsWithError(batched))
    {
      std::cerr << "a batch of another run continued an incomplete one\n";
      ok = false;
    }
    // EndParticle beyond the run, or not after FirstParticle: the tracer fails.
    batchTracer->SetEndParticle(90000);
    if (!FailsWithError(batchTracer))
    {
      std::cerr << "EndParticle beyond NumberOfParticles was accepted\n";
      ok = false;
    }
    batchTracer->SetEndParticle(20000);
    if (!FailsWithError(batchTracer))
    {
      std::cerr << "EndParticle at FirstParticle was accepted\n";
      ok = false;
    }
  }

  // 4. Directional media: projected once, then the camera moves freely.
  auto directional = reconstructionOf(singleTracer);
  directional->DirectionalRadianceOn();
  directional->Update();
  vtkDataObject* fog = Fog(directional->GetOutput());
  vtkDataArray* sh =
    vtkImageData::SafeDownCast(fog)->GetCellData()->GetArray(vtkBrumeNames::SourceRadianceSH);
  // Order 3: 3 x 16 components.
  if (!sh || sh->GetNumberOfComponents() != 48 ||
    directional->GetNumberOfDirectionalBuilds() != 1 ||
    !fog->GetFieldData()->GetArray(vtkBrumeNames::PhaseAsymmetry))
  {
    std::cerr << "the directional fog lacks its coefficients\n";
    ok = false;
  }
  const vtkIdType updates = directional->GetNumberOfViewUpdates();
  for (int k = 0; k < 3; ++k)
  {
    camera->Azimuth(20.0);
    directional->Update();
  }
  if (Fog(directional->GetOutput()) != fog || directional->GetNumberOfViewUpdates() != updates + 3)
  {
    std::cerr << "directional fog: expected the same texture and 3 floor updates, got "
              << directional->GetNumberOfViewUpdates() - updates << " updates\n";
    ok = false;
  }
  // Back to per-view textures: toward the current eye, as a fresh run's.
  directional->DirectionalRadianceOff();
  directional->Update();
  single->Update();
  ok =
    SameTextures(directional->GetOutput(), single->GetOutput(), "directional, then per view") && ok;
  // 5. The build state released, as by a program that draws its last
  // image: the output stays as it was; a later execution rebuilds every
  // object (toward a turned camera, as a fresh run's textures), and a run's
  // next batch cannot continue textures that are no longer held.
  {
    auto released = reconstructionOf(singleTracer);
    released->Update();
    vtkPartitionedDataSetCollection* output = released->GetOutput();
    vtkNew<vtkPartitionedDataSetCollection> before;
    before->DeepCopy(output);
    released->ReleaseBuildState();
    ok =
      released->GetOutput() == output && SameTextures(output, before, "released: the output") && ok;
    const vtkIdType builds = released->GetNumberOfTextureBuilds();
    camera->Azimuth(10.0);
    released->Update();
    single->Update();
    ok = SameTextures(released->GetOutput(), single->GetOutput(), "released, then turned") && ok;
    if (released->GetNumberOfTextureBuilds() != builds + objects)
    {
      std::cerr << "released, then turned: expected " << objects << " objects built again, got "
                << released->GetNumberOfTextureBuilds() - builds << "\n";
      ok = false;
    }
    vtkSmartPointer<vtkBrumeLightTracer> batchTracer;
    auto batched = firstHalf(batchTracer);
    batched->ReleaseBuildState();
    batchTracer->SetFirstParticle(20000);
    batchTracer->SetEndParticle(40000);
    if (!FailsWithError(batched))
    {
      std::cerr << "a batch continued textures whose build state was released\n";
      ok = false;
    }
  }
  std::cout << "progressive, batches, continuation checks and directional mode: "
            << (ok ? "ok" : "FAILED") << "\n";
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
