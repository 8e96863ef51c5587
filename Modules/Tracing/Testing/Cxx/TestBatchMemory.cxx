// SPDX-License-Identifier: BSD-3-Clause
// Batches of one run, and new runs, write where the last output's hits
// were, unless someone still holds them: an array a consumer keeps is never
// written again, and every batch's and run's hits are those of a fresh
// tracer.
#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeDefaultSceneSource.h"
#include "vtkBrumeLightTracer.h"
#include "vtkDataArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <cstring>
#include <iostream>
#include <vector>

namespace
{
constexpr vtkTypeInt64 Particles = 60000;

bool SameBytes(vtkDataArray* a, vtkDataArray* b)
{
  return a && b && a->GetDataType() == b->GetDataType() &&
    a->GetNumberOfValues() == b->GetNumberOfValues() &&
    std::memcmp(a->GetVoidPointer(0), b->GetVoidPointer(0),
      a->GetNumberOfValues() * a->GetDataTypeSize()) == 0;
}

// The hits of particles [first, end) of a run (end 0: all), from a tracer
// of its own.
vtkSmartPointer<vtkPolyData> FreshRun(vtkBrumeDefaultSceneSource* scene, vtkTypeInt64 particles,
  vtkIdType seed, vtkTypeInt64 first = 0, vtkTypeInt64 end = 0)
{
  vtkNew<vtkBrumeLightTracer> tracer;
  tracer->SetInputConnection(scene->GetOutputPort());
  tracer->SetNumberOfParticles(particles);
  tracer->SetSeed(seed);
  tracer->SetFirstParticle(first);
  tracer->SetEndParticle(end);
  tracer->Update();
  auto copy = vtkSmartPointer<vtkPolyData>::New();
  copy->DeepCopy(tracer->GetOutput());
  return copy;
}

// The hits of batch [first, end) of the run of Particles.
vtkSmartPointer<vtkPolyData> FreshBatch(
  vtkBrumeDefaultSceneSource* scene, vtkTypeInt64 first, vtkTypeInt64 end)
{
  return FreshRun(scene, Particles, 0, first, end);
}

bool SameHits(vtkPolyData* a, vtkPolyData* b, const char* what)
{
  bool ok = SameBytes(a->GetPoints()->GetData(), b->GetPoints()->GetData());
  for (int i = 0; i < a->GetPointData()->GetNumberOfArrays(); ++i)
  {
    vtkDataArray* x = a->GetPointData()->GetArray(i);
    ok = SameBytes(x, b->GetPointData()->GetArray(x->GetName())) && ok;
  }
  if (!ok)
  {
    std::cerr << what << ": the hits differ from a fresh tracer's\n";
  }
  return ok;
}
}

int TestBatchMemory(int, char*[])
{
  vtkNew<vtkBrumeDefaultSceneSource> scene;
  vtkNew<vtkBrumeLightTracer> tracer;
  tracer->SetInputConnection(scene->GetOutputPort());
  tracer->SetNumberOfParticles(Particles);
  bool ok = true;

  // Batch 1; its flux array is kept by a consumer, with a copy of its values.
  tracer->SetFirstParticle(0);
  tracer->SetEndParticle(20000);
  tracer->Update();
  vtkSmartPointer<vtkDataArray> held =
    tracer->GetOutput()->GetPointData()->GetArray(vtkBrumeNames::Flux);
  auto heldValues = vtkSmartPointer<vtkDataArray>::Take(held->NewInstance());
  heldValues->DeepCopy(held);
  const void* directionBuffer =
    tracer->GetOutput()->GetPointData()->GetArray(vtkBrumeNames::Direction)->GetVoidPointer(0);
  ok = SameHits(tracer->GetOutput(), FreshBatch(scene, 0, 20000), "batch 1") && ok;

  // Batch 2 reuses the arrays no one holds (Direction), not the one kept.
  tracer->SetFirstParticle(20000);
  tracer->SetEndParticle(40000);
  tracer->Update();
  ok = SameHits(tracer->GetOutput(), FreshBatch(scene, 20000, 40000), "batch 2") && ok;
  if (!SameBytes(held, heldValues))
  {
    std::cerr << "batch 2 wrote into the flux array a consumer still holds\n";
    ok = false;
  }
  if (tracer->GetOutput()->GetPointData()->GetArray(vtkBrumeNames::Flux) == held.GetPointer())
  {
    std::cerr << "batch 2's output still shows the kept flux array\n";
    ok = false;
  }
  // realloc may move a reused buffer; glibc keeps large ones where they are
  // when they shrink or grow in place, so this is informative only.
  const bool reusedInPlace =
    tracer->GetOutput()->GetPointData()->GetArray(vtkBrumeNames::Direction)->GetVoidPointer(0) ==
    directionBuffer;
  std::cout << "batch 2 wrote its directions "
            << (reusedInPlace ? "where batch 1's were" : "elsewhere (moved by realloc)") << "\n";

  // A consumer that gives an output array a buffer of its own (VTK does not
  // free it) must get it back untouched: the tracer takes back only the
  // buffers it handed out.
  vtkDataArray* emitter = tracer->GetOutput()->GetPointData()->GetArray(vtkBrumeNames::EmitterId);
  std::vector<unsigned short> own(static_cast<std::size_t>(emitter->GetNumberOfValues()), 7);
  emitter->SetVoidArray(own.data(), static_cast<vtkIdType>(own.size()), 1);

  // Batch 3 ends the run: its arrays are the output's alone afterwards, and
  // a run after it starts afresh.
  held = nullptr;
  tracer->SetFirstParticle(40000);
  tracer->SetEndParticle(Particles);
  tracer->Update();
  ok = SameHits(tracer->GetOutput(), FreshBatch(scene, 40000, Particles), "batch 3") && ok;
  for (const unsigned short v : own)
  {
    if (v != 7)
    {
      std::cerr << "batch 3 wrote into a buffer a consumer gave an output array\n";
      ok = false;
      break;
    }
  }
  vtkDataArray* last = tracer->GetOutput()->GetPointData()->GetArray(vtkBrumeNames::Direction);
  if (last->GetReferenceCount() != 1)
  {
    std::cerr << "after the run's last batch the tracer still holds its arrays ("
              << last->GetReferenceCount() << " references)\n";
    ok = false;
  }
  tracer->SetFirstParticle(0);
  tracer->SetEndParticle(20000);
  tracer->Update();
  ok = SameHits(tracer->GetOutput(), FreshBatch(scene, 0, 20000), "a new run's batch 1") && ok;

  // Whole runs: a new run (another seed) writes where the last run's hits
  // were, but never into a buffer still referenced: here the positions,
  // through the points object, and the flux, through an array that shares
  // its buffer (vtkDataArray::ShallowCopy shares the vtkBuffer, not the array).
  tracer->SetFirstParticle(0);
  tracer->SetEndParticle(0);
  tracer->SetNumberOfParticles(20000);
  tracer->Update();
  vtkSmartPointer<vtkPoints> heldPoints = tracer->GetOutput()->GetPoints();
  auto heldPositions = vtkSmartPointer<vtkDataArray>::Take(heldPoints->GetData()->NewInstance());
  heldPositions->DeepCopy(heldPoints->GetData());
  vtkDataArray* flux = tracer->GetOutput()->GetPointData()->GetArray(vtkBrumeNames::Flux);
  auto sharedFlux = vtkSmartPointer<vtkDataArray>::Take(flux->NewInstance());
  sharedFlux->ShallowCopy(flux);
  auto fluxValues = vtkSmartPointer<vtkDataArray>::Take(flux->NewInstance());
  fluxValues->DeepCopy(flux);
  tracer->SetSeed(5);
  tracer->Update();
  ok = SameHits(tracer->GetOutput(), FreshRun(scene, 20000, 5), "a run after a run") && ok;
  if (!SameBytes(heldPoints->GetData(), heldPositions))
  {
    std::cerr << "a new run wrote into the positions a consumer still holds\n";
    ok = false;
  }
  if (!SameBytes(sharedFlux, fluxValues))
  {
    std::cerr << "a new run wrote into the flux an array shares\n";
    ok = false;
  }
  // Five of the seven arrays came back (the aim array is absent here).
  const vtkTypeInt64 partlyReused = tracer->GetLastReusedBytes();
  heldPoints = nullptr;
  sharedFlux = nullptr;
  // Twice more, no one holding the hits: the second writes where the first's
  // were (every array), a run with more particles grows them.
  tracer->SetSeed(6);
  tracer->Update();
  ok = SameHits(tracer->GetOutput(), FreshRun(scene, 20000, 6), "a run after a run, reused") && ok;
  const vtkTypeInt64 hits = tracer->GetOutput()->GetNumberOfPoints();
  const vtkTypeInt64 unheld = tracer->GetLastReusedBytes();
  // The last run's arrays, all but the positions and the flux (24 bytes a
  // hit of 45), came back to it; this run's (as many hits) all of them.
  std::cout << "reused " << partlyReused << " bytes with the positions and flux held, " << unheld
            << " with nothing held\n";
  if (partlyReused <= 0 || unheld <= partlyReused || unheld < 45 * hits * 9 / 10)
  {
    std::cerr << "the runs did not write where the last run's hits were (" << partlyReused
              << " and " << unheld << " bytes reused)\n";
    ok = false;
  }
  tracer->SetNumberOfParticles(50000);
  tracer->Update();
  ok = SameHits(tracer->GetOutput(), FreshRun(scene, 50000, 6), "a larger run, reused") && ok;
  // A much smaller run keeps at most twice its expected hits of that memory.
  const vtkTypeInt64 larger = tracer->GetOutput()->GetNumberOfPoints();
  tracer->SetNumberOfParticles(2000);
  tracer->Update();
  ok = SameHits(tracer->GetOutput(), FreshRun(scene, 2000, 6), "a smaller run, reused") && ok;
  if (tracer->GetLastReusedBytes() != 45 * larger)
  {
    std::cerr << "the smaller run took back " << tracer->GetLastReusedBytes() << " bytes, not "
              << 45 * larger << "\n";
    ok = false;
  }
  tracer->SetNumberOfParticles(50000);
  tracer->Update();
  ok = SameHits(tracer->GetOutput(), FreshRun(scene, 50000, 6), "a larger run again") && ok;
  // The output released between runs (ReleaseDataFlag does so downstream):
  // its buffers were freed then, not kept, and the next run starts afresh.
  tracer->GetOutput()->ReleaseData();
  tracer->SetSeed(7);
  tracer->Update();
  ok = SameHits(tracer->GetOutput(), FreshRun(scene, 50000, 7), "a run after released data") && ok;
  if (tracer->GetLastReusedBytes() != 0)
  {
    std::cerr << "a run after released data reused " << tracer->GetLastReusedBytes()
              << " bytes: the tracer kept buffers the output had let go\n";
    ok = false;
  }
  // An output that outlives its tracer frees its buffers itself.
  vtkSmartPointer<vtkPolyData> orphan;
  {
    vtkNew<vtkBrumeLightTracer> shortLived;
    shortLived->SetInputConnection(scene->GetOutputPort());
    shortLived->SetNumberOfParticles(2000);
    shortLived->Update();
    orphan = shortLived->GetOutput();
  }
  ok = SameHits(orphan, FreshRun(scene, 2000, 0), "an output that outlived its tracer") && ok;
  orphan = nullptr;
  return ok ? 0 : 1;
}
