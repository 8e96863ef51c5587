// SPDX-License-Identifier: BSD-3-Clause
// Bad input gets a clear error and a failed RequestData, never a crash.
#include "BrumeExpectFailure.h"
#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeDefaultSceneSource.h"
#include "vtkBrumeLightTracer.h"
#include "vtkBrumeRadianceReconstruction.h"
#include "vtkCallbackCommand.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <string>

namespace
{
vtkSmartPointer<vtkPartitionedDataSetCollection> DefaultScene()
{
  vtkNew<vtkBrumeDefaultSceneSource> source;
  source->Update();
  auto scene = vtkSmartPointer<vtkPartitionedDataSetCollection>::New();
  scene->DeepCopy(source->GetOutput());
  return scene;
}

vtkDataObject* Object(vtkPartitionedDataSetCollection* scene, const std::string& name)
{
  for (unsigned int i = 0; i < scene->GetNumberOfPartitionedDataSets(); ++i)
  {
    if (name == scene->GetMetaData(i)->Get(vtkCompositeDataSet::NAME()))
    {
      return scene->GetPartitionedDataSet(i)->GetPartition(0);
    }
  }
  return nullptr;
}

void AddString(vtkDataObject* object, const char* name, const std::string& value)
{
  vtkNew<vtkStringArray> a;
  a->SetName(name);
  a->InsertNextValue(value);
  object->GetFieldData()->AddArray(a);
}

std::string TemporaryPath(const std::string& name)
{
  return (std::filesystem::temp_directory_path() / ("brume-test-" + name)).string();
}

void SetField(vtkDataObject* object, const char* name, double x, double y, double z)
{
  vtkDataArray* a = object->GetFieldData()->GetArray(name);
  a->SetTuple3(0, x, y, z);
}

bool TracerFails(const std::string& what, vtkPartitionedDataSetCollection* scene,
  const std::string& expected, const std::function<void(vtkBrumeLightTracer*)>& configure = {})
{
  vtkNew<vtkBrumeLightTracer> tracer;
  tracer->SetInputData(scene);
  tracer->SetNumberOfParticles(1000);
  if (configure)
  {
    configure(tracer);
  }
  return ExpectFailure(what, tracer, expected);
}
}

int TestBadInput(int, char*[])
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  bool ok = true;

  auto scene = DefaultScene();
  SetField(Object(scene, "fog"), vtkBrumeNames::SigmaS, nan, 1, 1);
  ok &= TracerFails("NaN sigma_s", scene, "non-finite");

  scene = DefaultScene();
  SetField(Object(scene, "fog"), vtkBrumeNames::SigmaA, -0.1, -0.1, -0.1);
  ok &= TracerFails("negative sigma_a", scene, "negative");

  scene = DefaultScene();
  Object(scene, "fog")->GetFieldData()->GetArray(vtkBrumeNames::G)->SetTuple1(0, 1.0);
  ok &= TracerFails("g = 1", scene, "|g| >= 1");

  scene = DefaultScene();
  SetField(Object(scene, "light"), vtkBrumeNames::Emission, 0, 0, 0);
  ok &= TracerFails("no light", scene, "no light");

  scene = DefaultScene();
  SetField(Object(scene, "light"), vtkBrumeNames::Emission, 15, nan, 15);
  ok &= TracerFails("NaN emission", scene, "emission");

  scene = vtkSmartPointer<vtkPartitionedDataSetCollection>::New();
  ok &= TracerFails("empty scene", scene, "empty");

  scene = DefaultScene();
  {
    auto* floor = vtkPolyData::SafeDownCast(Object(scene, "floor"));
    vtkNew<vtkPoints> collapsed;
    for (int i = 0; i < 4; ++i)
    {
      collapsed->InsertNextPoint(0, -1, 0);
    }
    floor->SetPoints(collapsed);
  }
  ok &= TracerFails("degenerate floor", scene, "degenerate");

  scene = DefaultScene();
  AddString(Object(scene, "fog"), vtkBrumeNames::DensityArray, "density");
  ok &= TracerFails("medium naming a missing density array", scene, "no density array");

  scene = DefaultScene();
  {
    vtkNew<vtkFloatArray> density;
    density->SetName("density");
    density->SetNumberOfTuples(8);
    density->Fill(1.0);
    density->SetValue(3, -2.0);
    vtkImageData::SafeDownCast(Object(scene, "fog"))->GetPointData()->SetScalars(density);
  }
  ok &= TracerFails("negative density", scene, "negative or non-finite densities");

  scene = DefaultScene();
  {
    const std::string path = TemporaryPath("corrupt.vdb");
    std::ofstream(path) << "this is not an OpenVDB file";
    AddString(Object(scene, "fog"), vtkBrumeNames::VDBFile, path);
  }
  ok &= TracerFails("corrupt VDB file", scene, "is not a valid OpenVDB file");

  scene = DefaultScene();
  AddString(Object(scene, "fog"), vtkBrumeNames::VDBFile, "/nonexistent/fog.vdb");
  ok &= TracerFails("missing VDB file", scene, "cannot open OpenVDB file");

  scene = DefaultScene();
  ok &= TracerFails("zero-power light", scene, "zero power",
    [](vtkBrumeLightTracer* t)
    {
      vtkNew<vtkLight> light;
      light->SetPosition(0, 0.5, 0);
      light->SetIntensity(0.0);
      t->AddLight(light);
    });

  scene = DefaultScene();
  AddString(Object(scene, "floor"), vtkBrumeNames::Material, "velvet");
  ok &= TracerFails("unknown material", scene, vtkBrumeNames::Material);

  scene = DefaultScene();
  SetField(Object(scene, "floor"), vtkBrumeNames::Reflectance, 0.8, 0.8, 0.8);
  {
    vtkNew<vtkDoubleArray> specular;
    specular->SetName(vtkBrumeNames::Specular);
    specular->SetNumberOfComponents(3);
    specular->InsertNextTuple3(0.5, 0.5, 0.5);
    Object(scene, "floor")->GetFieldData()->AddArray(specular);
  }
  ok &= TracerFails("material reflecting more than it receives", scene, "reflects more");

  scene = DefaultScene();
  ok &= TracerFails("absurd particle count", scene, "NumberOfParticles",
    [](vtkBrumeLightTracer* t) { t->SetNumberOfParticles(100000000000LL); });
  ok &= TracerFails("particles beyond the memory limit", scene, "MemoryLimit",
    [](vtkBrumeLightTracer* t)
    {
      t->SetNumberOfParticles(1000000);
      t->SetMemoryLimit(1 << 20);
    });

  // Reconstruction.
  scene = DefaultScene();
  vtkNew<vtkBrumeLightTracer> tracer;
  tracer->SetInputData(scene);
  tracer->SetNumberOfParticles(2000);
  tracer->Update();
  auto reconstruct = [&](vtkDataObject* hits, const std::string& what, const std::string& expected,
                       const std::function<void(vtkBrumeRadianceReconstruction*)>& configure)
  {
    vtkNew<vtkBrumeRadianceReconstruction> r;
    r->SetInputDataObject(0, scene);
    r->SetInputDataObject(1, hits);
    if (configure)
    {
      configure(r);
    }
    return ExpectFailure(what, r, expected);
  };
  vtkNew<vtkPolyData> bare;
  bare->ShallowCopy(tracer->GetOutput());
  bare->GetPointData()->RemoveArray(vtkBrumeNames::Flux);
  ok &= reconstruct(bare, "hits without Flux", "lack", {});
  ok &= reconstruct(tracer->GetOutput(), "zero threshold", "RadiosityThreshold",
    [](vtkBrumeRadianceReconstruction* r) { r->SetRadiosityThreshold(0.0); });
  ok &= reconstruct(tracer->GetOutput(), "absurd resolution", "Resolution",
    [](vtkBrumeRadianceReconstruction* r) { r->SetMediumResolution(100000); });
  vtkNew<vtkPolyData> noPower;
  noPower->ShallowCopy(tracer->GetOutput());
  noPower->SetFieldData(nullptr);
  ok &= reconstruct(noPower, "hits without TotalPower", vtkBrumeNames::TotalPower, {});
  // A scene object asking for a texture beyond the limit.
  vtkNew<vtkPartitionedDataSetCollection> huge;
  huge->DeepCopy(scene);
  vtkNew<vtkDoubleArray> texels;
  texels->SetName(vtkBrumeNames::TextureResolution);
  texels->InsertNextValue(100000);
  huge->GetPartitionedDataSet(0)->GetPartition(0)->GetFieldData()->AddArray(texels);
  {
    vtkNew<vtkBrumeRadianceReconstruction> r;
    r->SetInputDataObject(0, huge);
    r->SetInputDataObject(1, tracer->GetOutput());
    ok &= ExpectFailure("absurd per-object resolution", r, vtkBrumeNames::TextureResolution);
  }

  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
