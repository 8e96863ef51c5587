// SPDX-License-Identifier: BSD-3-Clause
// The data the phases exchange: the scene's camera, the hit schema and the
// radiance-texture schema round-trip, and malformed data fails cleanly.
#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeDefaultSceneSource.h"
#include "vtkBrumeHitConversion.h"
#include "vtkBrumeRadianceConversion.h"
#include "vtkBrumeSceneCamera.h"
#include "vtkBrumeSceneConversion.h"
#include "vtkCamera.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"

#include "brume/Reconstruction.h"

#include <cmath>
#include <cstring>
#include <iostream>

namespace
{
int failures = 0;

void Check(bool condition, const char* what)
{
  if (!condition)
  {
    std::cerr << "FAILED: " << what << "\n";
    ++failures;
  }
}

bool Near(const double* a, const double* b, int n)
{
  for (int i = 0; i < n; ++i)
  {
    if (std::abs(a[i] - b[i]) > 1e-12)
    {
      return false;
    }
  }
  return true;
}

void TestCamera()
{
  // The default scene names the default view.
  vtkNew<vtkBrumeDefaultSceneSource> source;
  source->Update();
  vtkNew<vtkCamera> fromScene, byDefault;
  Check(vtkBrumeSceneCamera::SetFromScene(source->GetOutputDataObject(0), fromScene),
    "the default scene names its camera");
  vtkBrumeSceneCamera::SetToDefault(byDefault);
  Check(Near(fromScene->GetPosition(), byDefault->GetPosition(), 3) &&
      Near(fromScene->GetFocalPoint(), byDefault->GetFocalPoint(), 3) &&
      Near(fromScene->GetViewUp(), byDefault->GetViewUp(), 3) &&
      fromScene->GetViewAngle() == byDefault->GetViewAngle(),
    "the default scene's camera is the default view");

  // A scene without a camera gets the default view; a written one reads back.
  vtkNew<vtkPartitionedDataSetCollection> bare;
  vtkNew<vtkCamera> camera;
  camera->SetPosition(1, 2, 3);
  Check(!vtkBrumeSceneCamera::SetFromScene(bare, camera), "a bare scene names no camera");
  Check(Near(camera->GetPosition(), byDefault->GetPosition(), 3), "a bare scene: default view");
  camera->SetPosition(1, 2, 3);
  camera->SetFocalPoint(0, 1, 0);
  camera->SetViewUp(0, 0, 1);
  camera->SetViewAngle(25);
  vtkBrumeSceneCamera::WriteToScene(camera, bare->GetFieldData());
  vtkBrumeSceneCamera::WriteToScene(camera, bare->GetFieldData()); // replaces, no duplicates
  vtkNew<vtkCamera> back;
  Check(vtkBrumeSceneCamera::SetFromScene(bare, back), "a written camera is named");
  Check(Near(back->GetPosition(), camera->GetPosition(), 3) &&
      Near(back->GetFocalPoint(), camera->GetFocalPoint(), 3) && back->GetViewAngle() == 25,
    "a written camera reads back");
  Check(bare->GetFieldData()->GetNumberOfArrays() == 4, "writing twice keeps four arrays");
}

void TestHits()
{
  std::vector<brume::Hit> hits(3);
  for (std::size_t i = 0; i < hits.size(); ++i)
  {
    brume::Hit& h = hits[i];
    std::memset(&h, 0, sizeof(h));
    for (int c = 0; c < 3; ++c)
    {
      h.Position[c] = 0.5f * static_cast<float>(i + c);
      h.Direction[c] = c == 2 ? -1.f : 0.f;
      h.Flux[c] = 1e-3f * static_cast<float>(i + 1);
    }
    h.Object = static_cast<std::uint16_t>(i);
    h.Emitter = 7;
    h.Depth = static_cast<std::uint8_t>(i);
    h.Triangle = static_cast<std::uint32_t>(10 * i);
  }
  auto data = vtkBrumeHitConversion::HitsToPolyData(hits, brume::Vec3(1.f, 2.f, 3.f), 1000);
  std::vector<brume::Hit> back;
  Check(vtkBrumeHitConversion::HitsFromPolyData(data, back).empty(), "hits read back");
  Check(back.size() == hits.size() &&
      std::memcmp(back.data(), hits.data(), hits.size() * sizeof(brume::Hit)) == 0,
    "hits round-trip bitwise");

  brume::HitArrays view;
  vtkBrumeHitConversion::RunInfo run;
  std::vector<float> copy;
  Check(vtkBrumeHitConversion::ReadHits(data, view, run, copy).empty(), "hits viewed in place");
  Check(view.Count == 3 && view.Object[2] == 2 && view.Triangle && view.Triangle[1] == 10 &&
      view.Flux[3] == hits[1].Flux[0] && copy.empty(),
    "the in-place view sees the arrays (float points are not copied)");
  Check(run.Particles == 1000 && run.TotalPower[2] == 3.0 && run.FirstParticle == 0.0,
    "the run's field data");

  Check(!vtkBrumeHitConversion::ReadHits(nullptr, view, run, copy).empty(), "no hits: an error");
  vtkNew<vtkPolyData> noPower;
  noPower->ShallowCopy(data);
  noPower->GetFieldData()->RemoveArray(vtkBrumeHitConversion::TotalPowerName);
  Check(vtkBrumeHitConversion::ReadHits(noPower, view, run, copy).find(vtkBrumeNames::TotalPower) !=
      std::string::npos,
    "missing TotalPower is named");
  vtkNew<vtkPolyData> noFlux;
  noFlux->DeepCopy(data);
  noFlux->GetPointData()->RemoveArray(vtkBrumeHitConversion::FluxName);
  Check(vtkBrumeHitConversion::ReadHits(noFlux, view, run, copy).find(vtkBrumeNames::Flux) !=
      std::string::npos,
    "a missing Flux array is named");

  // An aimed run's classes and weights (emitter 7 is the hits' light).
  Check(!view.Aim && view.GrowthScale(0) == 1.0, "unaimed hits grow by their flux");
  vtkNew<vtkPolyData> aimed;
  aimed->DeepCopy(data);
  vtkNew<vtkUnsignedCharArray> aim;
  aim->SetName(vtkBrumeHitConversion::AimName);
  for (unsigned char a : { 0, 1, 2 })
  {
    aim->InsertNextValue(a);
  }
  aimed->GetPointData()->AddArray(aim);
  Check(vtkBrumeHitConversion::ReadHits(aimed, view, run, copy).find(vtkBrumeNames::AimWeights) !=
      std::string::npos,
    "an Aim array without AimWeights is named");
  vtkNew<vtkDoubleArray> weights;
  weights->SetName(vtkBrumeHitConversion::AimWeightsName);
  weights->SetNumberOfComponents(3);
  for (int e = 0; e < 8; ++e)
  {
    weights->InsertNextTuple3(1.0, e == 7 ? 1.25 : 1.0, e == 7 ? 0.05 : 1.0);
  }
  aimed->GetFieldData()->AddArray(weights);
  Check(vtkBrumeHitConversion::ReadHits(aimed, view, run, copy).empty() && view.Aim &&
      view.GrowthScale(0) == 1.0 && std::abs(view.GrowthScale(1) - 0.8) < 1e-12 &&
      std::abs(view.GrowthScale(2) - 20.0) < 1e-9,
    "each hit grows by its class's inverse weight");
  std::vector<brume::Hit> aimedBack;
  Check(vtkBrumeHitConversion::HitsFromPolyData(aimed, aimedBack).empty() &&
      aimedBack.size() == 3 && aimedBack[2].Aim == 2,
    "hits read back with their classes");
  weights->SetComponent(7, 2, 0.0);
  Check(vtkBrumeHitConversion::ReadHits(aimed, view, run, copy).find(vtkBrumeNames::AimWeights) !=
      std::string::npos,
    "a weight of 0 is refused");
  weights->SetComponent(7, 2, 0.05);
  aim->SetValue(1, 3);
  Check(
    !vtkBrumeHitConversion::ReadHits(aimed, view, run, copy).empty(), "a class of 3 is refused");
  aim->SetValue(1, 1);
  weights->SetNumberOfTuples(7);
  Check(!vtkBrumeHitConversion::ReadHits(aimed, view, run, copy).empty(),
    "an emitter without weights is refused");
}

void TestTextures()
{
  vtkNew<vtkBrumeDefaultSceneSource> source;
  source->Update();
  brume::Scene scene;
  std::vector<vtkBrumeSceneConversion::ObjectSource> sources;
  Check(vtkBrumeSceneConversion::ToScene(source->GetOutput(), scene, &sources).empty(),
    "the default scene converts");
  Check(!scene.Surfaces.empty() && !scene.Media.empty(), "the default scene has both kinds");

  // A surface with no hits: its texture is its emission alone.
  const brume::Surface& wall = scene.Surfaces[0];
  brume::ObjectRadiance surface(wall, brume::MakeChart(wall, nullptr), { 8, 4 }, 2);
  const brume::HitArrays none;
  Check(
    surface.Build(none, nullptr, 0, brume::Vec3(0.f, 0.f, 4.f), 1.0, brume::SerialFor()).empty(),
    "an empty surface texture builds");
  auto* sceneSurface = vtkPolyData::SafeDownCast(
    source->GetOutput()->GetPartitionedDataSet(sources[0].CollectionIndex)->GetPartition(0));
  auto pds = vtkBrumeRadianceConversion::FromSurface(surface, wall, sceneSurface);
  auto* texture = vtkImageData::SafeDownCast(pds->GetPartition(0));
  auto* mapped = vtkPolyData::SafeDownCast(pds->GetPartition(1));
  int dims[3];
  texture->GetDimensions(dims);
  Check(dims[0] == 8 && dims[1] == 4 && dims[2] == 1, "surface texture dimensions");
  vtkDataArray* radiance = texture->GetPointData()->GetArray(vtkBrumeNames::Radiance);
  Check(radiance && radiance->GetNumberOfComponents() == 3 && radiance->GetNumberOfTuples() == 32,
    "surface Radiance array");
  Check(radiance && radiance->GetComponent(0, 0) == wall.Mat.Emission.x,
    "an unlit texel holds the emission");
  auto* kind = vtkStringArray::SafeDownCast(
    texture->GetFieldData()->GetAbstractArray(vtkBrumeNames::ObjectKind));
  Check(kind && kind->GetValue(0) == "surface", "surface kind");
  vtkDataArray* tcoords = mapped ? mapped->GetPointData()->GetTCoords() : nullptr;
  Check(tcoords && tcoords->GetNumberOfTuples() == mapped->GetNumberOfPoints(),
    "the mapped surface has texture coordinates");
  for (vtkIdType i = 0; tcoords && i < tcoords->GetNumberOfTuples(); ++i)
  {
    const double u = tcoords->GetComponent(i, 0), v = tcoords->GetComponent(i, 1);
    Check(u > -1e-5 && u < 1 + 1e-5 && v > -1e-5 && v < 1 + 1e-5, "planar (u, v) in [0, 1]");
  }

  // A medium: a grid of cells over its box, with its extinction.
  const brume::Medium& fog = scene.Media[0];
  brume::ObjectRadiance medium(fog, { 4, 3, 2 }, 1);
  Check(medium.Build(none, nullptr, 0, brume::Vec3(0.f, 0.f, 4.f), 1.0, brume::SerialFor()).empty(),
    "an empty medium texture builds");
  auto volumePds = vtkBrumeRadianceConversion::FromMedium(medium, fog, false);
  auto* volume = vtkImageData::SafeDownCast(volumePds->GetPartition(0));
  volume->GetDimensions(dims);
  Check(dims[0] == 5 && dims[1] == 4 && dims[2] == 3, "medium grid: one cell per voxel");
  vtkDataArray* extinction = volume->GetCellData()->GetArray(vtkBrumeNames::Extinction);
  Check(extinction && extinction->GetNumberOfTuples() == 24 &&
      std::abs(extinction->GetComponent(0, 0) - (fog.SigmaA.x + fog.SigmaS.x)) < 1e-6,
    "medium Extinction is sigma_a + sigma_s");
  Check(volume->GetCellData()->GetArray(vtkBrumeNames::SourceRadiance) != nullptr,
    "medium SourceRadiance");
  double bounds[6];
  volume->GetBounds(bounds);
  Check(std::abs(bounds[0] - fog.Bounds.lower.x) < 1e-6 &&
      std::abs(bounds[5] - fog.Bounds.upper.z) < 1e-6,
    "the grid spans the medium's box");
}
}

int TestDataModelSchemas(int, char*[])
{
  TestCamera();
  TestHits();
  TestTextures();
  if (failures == 0)
  {
    std::cout << "Brume::DataModel schemas: all checks passed\n";
  }
  return failures == 0 ? 0 : 1;
}
