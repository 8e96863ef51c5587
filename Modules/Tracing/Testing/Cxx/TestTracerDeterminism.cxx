// SPDX-License-Identifier: BSD-3-Clause
// The same seed gives identical particle hits with 1 and with 2 threads.
#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeDefaultSceneSource.h"
#include "vtkBrumeLightTracer.h"
#include "vtkBrumeReferencePathTracer.h"
#include "vtkConvertToMultiBlockDataSet.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"

#include <cstdlib>
#include <cstring>
#include <iostream>

namespace
{
vtkSmartPointer<vtkPolyData> Trace(int threads, vtkTypeUInt64 seed)
{
  vtkSMPTools::Initialize(threads);
  vtkNew<vtkBrumeDefaultSceneSource> scene;
  vtkNew<vtkBrumeLightTracer> tracer;
  tracer->SetInputConnection(scene->GetOutputPort());
  tracer->SetNumberOfParticles(50000);
  tracer->SetSeed(seed);
  tracer->Update();
  auto hits = vtkSmartPointer<vtkPolyData>::New();
  hits->DeepCopy(tracer->GetOutput());
  return hits;
}

vtkSmartPointer<vtkImageData> Reference(int threads)
{
  vtkSMPTools::Initialize(threads);
  vtkNew<vtkBrumeDefaultSceneSource> scene;
  vtkNew<vtkBrumeReferencePathTracer> reference;
  reference->SetInputConnection(scene->GetOutputPort());
  reference->SetSize(32, 32);
  reference->SetSamplesPerPixel(8);
  reference->Update();
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->DeepCopy(reference->GetOutput());
  return image;
}

bool SameBytes(vtkDataArray* a, vtkDataArray* b)
{
  if (!a || !b || a->GetDataType() != b->GetDataType() ||
    a->GetNumberOfValues() != b->GetNumberOfValues())
  {
    return false;
  }
  return std::memcmp(a->GetVoidPointer(0), b->GetVoidPointer(0),
           a->GetNumberOfValues() * a->GetDataTypeSize()) == 0;
}
}

int TestTracerDeterminism(int, char*[])
{
  vtkSMPTools::Initialize(2);
  if (vtkSMPTools::GetEstimatedNumberOfThreads() != 2)
  {
    std::cerr << "The SMP backend " << vtkSMPTools::GetBackend() << " does not run 2 threads.\n";
    return EXIT_FAILURE;
  }
  auto one = Trace(1, 7);
  auto two = Trace(2, 7);
  auto otherSeed = Trace(2, 8);
  if (one->GetNumberOfPoints() < 50000)
  {
    std::cerr << "Too few hits: " << one->GetNumberOfPoints() << "\n";
    return EXIT_FAILURE;
  }
  if (!SameBytes(one->GetPoints()->GetData(), two->GetPoints()->GetData()))
  {
    std::cerr << "Hit positions differ between 1 and 2 threads.\n";
    return EXIT_FAILURE;
  }
  for (const char* name : { vtkBrumeNames::Direction, vtkBrumeNames::Flux, vtkBrumeNames::ObjectId,
         vtkBrumeNames::EmitterId, vtkBrumeNames::Depth })
  {
    if (!SameBytes(one->GetPointData()->GetArray(name), two->GetPointData()->GetArray(name)))
    {
      std::cerr << "Array " << name << " differs between 1 and 2 threads.\n";
      return EXIT_FAILURE;
    }
  }
  // The comparison can fail: another seed gives other hits.
  if (SameBytes(one->GetPoints()->GetData(), otherSeed->GetPoints()->GetData()))
  {
    std::cerr << "Seeds 7 and 8 gave the same hits.\n";
    return EXIT_FAILURE;
  }
  std::cout << one->GetNumberOfPoints() << " hits, identical with 1 and 2 threads.\n";
  // The same scene as a multiblock (as ParaView's Group Datasets makes it).
  {
    vtkNew<vtkBrumeDefaultSceneSource> scene;
    vtkNew<vtkConvertToMultiBlockDataSet> multiblock;
    multiblock->SetInputConnection(scene->GetOutputPort());
    vtkNew<vtkBrumeLightTracer> tracer;
    tracer->SetInputConnection(multiblock->GetOutputPort());
    tracer->SetNumberOfParticles(50000);
    tracer->SetSeed(7);
    tracer->Update();
    if (!SameBytes(one->GetPoints()->GetData(), tracer->GetOutput()->GetPoints()->GetData()))
    {
      std::cerr << "A multiblock scene gives other hits than the collection.\n";
      return EXIT_FAILURE;
    }
  }
  // The reference renderer too.
  auto a = Reference(1), b = Reference(2);
  for (const char* name : { vtkBrumeNames::Radiance, vtkBrumeNames::Variance })
  {
    if (!SameBytes(a->GetPointData()->GetArray(name), b->GetPointData()->GetArray(name)))
    {
      std::cerr << "Reference " << name << " differs between 1 and 2 threads.\n";
      return EXIT_FAILURE;
    }
  }
  std::cout << "Reference image identical with 1 and 2 threads.\n";
  return EXIT_SUCCESS;
}
