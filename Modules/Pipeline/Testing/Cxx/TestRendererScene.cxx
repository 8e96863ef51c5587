// SPDX-License-Identifier: BSD-3-Clause
// vtkBrumeRendererScene: what a vtkRenderer holds, as a Brume scene.
// - Opaque actors become surfaces in world coordinates with their
//   property's material (diffuse x colour; a Phong lobe where Specular > 0,
//   scaled to conserve energy); translucent actors are left out.
// - Volumes become media classified by their volume property, placed by
//   their translation and scale; a rotated volume is refused.
// - Lights come scaled by LightScale; a renderer without one gets a
//   headlight.
// - Scalar colouring: cells coloured through the mapper's colour map have
//   those colours, times Diffuse, as their reflectance.
// - Brume shows a surface's front side: an open one is turned toward the
//   camera, a closed one outward; each block of a composite input is a
//   surface; an empty renderer gives an empty scene where allowed; a scene
//   built again without a change keeps its content signature.
// - Nothing is rebuilt when only the camera moves; a property edit is.
// - The scene renders through vtkBrumePipeline to a lit, finite image.
#include "VtkSceneTesting.h"
#include "vtkActor.h"
#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeLightTracer.h"
#include "vtkBrumePipeline.h"
#include "vtkBrumeRendererScene.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkColorTransferFunction.h"
#include "vtkCompositeDataSet.h"
#include "vtkCompositePolyDataMapper2.h"
#include "vtkCubeSource.h"
#include "vtkDataArray.h"
#include "vtkDataSetMapper.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkFixedPointVolumeRayCastMapper.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMath.h"
#include "vtkMultiBlockDataSet.h"
#include "vtkNew.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRTAnalyticSource.h"
#include "vtkRenderer.h"
#include "vtkReverseSense.h"
#include "vtkStringArray.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <cmath>
#include <iostream>
#include <string>

namespace
{
int Failures = 0;

void Check(bool ok, const std::string& what)
{
  if (!ok)
  {
    std::cerr << "FAILED: " << what << "\n";
    ++Failures;
  }
}

bool Near(double a, double b)
{
  return std::abs(a - b) <= 1e-6 * std::max(1.0, std::abs(b));
}

// The object named `name` of a scene, or null.
vtkDataObject* Object(vtkPartitionedDataSetCollection* scene, const std::string& name)
{
  for (unsigned int i = 0; i < scene->GetNumberOfPartitionedDataSets(); ++i)
  {
    if (scene->HasMetaData(i) && name == scene->GetMetaData(i)->Get(vtkCompositeDataSet::NAME()))
    {
      return scene->GetPartitionedDataSet(i)->GetPartition(0);
    }
  }
  return nullptr;
}

double Component(vtkDataObject* object, const char* name, int c)
{
  vtkDataArray* a = object ? object->GetFieldData()->GetArray(name) : nullptr;
  return a ? a->GetComponent(0, c) : -1.0;
}

std::string Material(vtkDataObject* object)
{
  auto* a = object ? vtkStringArray::SafeDownCast(
                       object->GetFieldData()->GetAbstractArray(vtkBrumeNames::Material))
                   : nullptr;
  return a && a->GetNumberOfValues() > 0 ? a->GetValue(0) : std::string();
}

void TestCellColours()
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(3, 3, 1);
  vtkNew<vtkFloatArray> values;
  values->SetName("values");
  for (int c = 0; c < 4; ++c)
  {
    values->InsertNextValue(static_cast<float>(c));
  }
  image->GetCellData()->SetScalars(values);
  vtkNew<vtkColorTransferFunction> colours;
  colours->AddRGBPoint(0.0, 1.0, 0.0, 0.0);
  colours->AddRGBPoint(3.0, 0.0, 0.0, 1.0);
  vtkNew<vtkDataSetMapper> mapper;
  mapper->SetInputData(image);
  mapper->SetLookupTable(colours);
  mapper->SetScalarRange(0.0, 3.0);
  mapper->SetScalarModeToUseCellData();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetDiffuse(0.5);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  vtkNew<vtkBrumeRendererScene> source;
  source->SetRenderer(renderer);
  source->Update();
  auto* surface = vtkPolyData::SafeDownCast(Object(source->GetOutput(), "actor 0"));
  vtkDataArray* reflectance =
    surface ? surface->GetCellData()->GetArray(vtkBrumeNames::Reflectance) : nullptr;
  bool right = reflectance && reflectance->GetNumberOfTuples() == 4;
  for (vtkIdType k = 0; right && k < 4; ++k)
  {
    double bounds[6];
    surface->GetCellBounds(k, bounds);
    const int cell = static_cast<int>(bounds[0] + 0.5) + 2 * static_cast<int>(bounds[2] + 0.5);
    double rgb[3];
    colours->GetColor(cell, rgb);
    for (int c = 0; c < 3; ++c)
    {
      // Mapped to 8 bits, as VTK draws them.
      right = right && std::abs(reflectance->GetComponent(k, c) - 0.5 * rgb[c]) < 0.5 / 255 + 1e-6;
    }
  }
  Check(right, "cell colours follow their cells through the surface filter, times Diffuse");
}

// The normal of a surface's first polygon, by its winding.
double NormalY(vtkPolyData* surface)
{
  if (!surface || surface->GetNumberOfCells() == 0)
  {
    return 0.0;
  }
  vtkNew<vtkIdList> ids;
  surface->GetCellPoints(0, ids);
  double p[3][3];
  for (int k = 0; k < 3; ++k)
  {
    surface->GetPoint(ids->GetId(k), p[k]);
  }
  double a[3], b[3], n[3];
  for (int c = 0; c < 3; ++c)
  {
    a[c] = p[1][c] - p[0][c];
    b[c] = p[2][c] - p[0][c];
  }
  vtkMath::Cross(a, b, n);
  return n[1];
}

// Which side a surface shows, composite inputs, empty renderers, and the
// content signature that tells a rebuilt scene from a changed one.
void TestSidesBlocksAndSignature()
{
  vtkNew<vtkRenderer> renderer;
  renderer->GetActiveCamera()->SetPosition(0, 5, 8);
  renderer->GetActiveCamera()->SetFocalPoint(0, 0, 0);
  vtkNew<vtkBrumeRendererScene> source;
  source->SetRenderer(renderer);
  source->AllowEmptyOn();
  source->Update();
  Check(source->GetOutput()->GetNumberOfPartitionedDataSets() == 0,
    "an empty renderer gives an empty scene where allowed");

  // A ground whose polygons face down, seen from above: turned up.
  vtkNew<vtkPlaneSource> down;
  down->SetOrigin(-3, -1, -3);
  down->SetPoint1(3, -1, -3);
  down->SetPoint2(-3, -1, 3);
  AddActor(renderer, down, 0.5, 0.5, 0.5);
  // Two blocks through a composite mapper: a closed box whose polygons
  // face inward becomes outward.
  vtkNew<vtkCubeSource> cube;
  cube->Update();
  vtkNew<vtkReverseSense> inward;
  inward->SetInputConnection(cube->GetOutputPort());
  inward->ReverseCellsOn();
  inward->Update();
  vtkNew<vtkMultiBlockDataSet> blocks;
  blocks->SetNumberOfBlocks(2);
  blocks->SetBlock(0, cube->GetOutput());
  blocks->SetBlock(1, inward->GetOutput());
  vtkNew<vtkCompositePolyDataMapper2> composite;
  composite->SetInputDataObject(blocks);
  vtkNew<vtkActor> boxes;
  boxes->SetMapper(composite);
  renderer->AddActor(boxes);
  source->Update();
  vtkPartitionedDataSetCollection* scene = source->GetOutput();
  auto* ground = vtkPolyData::SafeDownCast(Object(scene, "actor 0"));
  Check(NormalY(ground) > 0.0, "an open surface is turned toward the camera");
  auto* outer = vtkPolyData::SafeDownCast(Object(scene, "actor 1"));
  auto* inner = vtkPolyData::SafeDownCast(Object(scene, "actor 1 block 1"));
  double outerBounds[6] = { 0 }, innerBounds[6] = { 0 };
  if (outer && inner)
  {
    outer->GetBounds(outerBounds);
    inner->GetBounds(innerBounds);
  }
  // The box's top face (y = 0.5) must face +y in both blocks.
  auto topFacesUp = [](vtkPolyData* box)
  {
    vtkNew<vtkIdList> ids;
    for (vtkIdType k = 0; box && k < box->GetNumberOfCells(); ++k)
    {
      box->GetCellPoints(k, ids);
      bool top = true;
      for (vtkIdType i = 0; i < ids->GetNumberOfIds(); ++i)
      {
        top = top && box->GetPoint(ids->GetId(i))[1] > 0.49;
      }
      if (top)
      {
        vtkNew<vtkPolyData> one;
        one->SetPoints(box->GetPoints());
        vtkNew<vtkCellArray> cells;
        cells->InsertNextCell(ids);
        one->SetPolys(cells);
        return NormalY(one) > 0.0;
      }
    }
    return false;
  };
  Check(outer && inner && topFacesUp(outer) && topFacesUp(inner),
    "each block of a composite input is a surface, a closed one turned outward");

  // Built again unchanged: the same signature; a colour edit: another.
  const vtkTypeUInt64 first = source->GetContentSignature();
  composite->Modified();
  renderer->GetActiveCamera()->Azimuth(30); // the headlight follows; no matter
  source->Update();
  Check(source->GetContentSignature() == first,
    "a scene built again without a change has the same signature");
  boxes->GetProperty()->SetColor(0.9, 0.1, 0.1);
  source->Update();
  Check(source->GetContentSignature() != first, "a colour edit changes the signature");
}

// A point light outside the scene's bounding sphere becomes a spot of the
// same intensity aimed at its centre, its cone just holding the sphere.
void TestAimedPointLight()
{
  vtkNew<vtkRenderer> renderer;
  AddGround(renderer, 0.5, 0.5, 0.5); // [-3, 3] x {-1} x [-3, 3]
  const double above[3] = { 0, 20, 0 };
  AddPointLight(renderer, above, 1.0);
  vtkNew<vtkBrumeRendererScene> source;
  source->SetRenderer(renderer);
  source->PhysicalLightsOn();
  source->Update();
  vtkFieldData* fd = source->GetOutput()->GetFieldData();
  auto* types = vtkStringArray::SafeDownCast(fd->GetAbstractArray(vtkBrumeNames::LightType));
  vtkDataArray* cone = fd->GetArray(vtkBrumeNames::LightConeAngle);
  vtkDataArray* direction = fd->GetArray(vtkBrumeNames::LightDirection);
  vtkDataArray* intensity = fd->GetArray(vtkBrumeNames::LightIntensity);
  const double radius = 1.001 * std::sqrt(72.0) / 2.0;
  const double expected = vtkMath::DegreesFromRadians(std::asin(radius / 21.0));
  Check(types && types->GetNumberOfValues() == 1 && types->GetValue(0) == "spot" && cone &&
      std::abs(cone->GetTuple1(0) - expected) < 1e-3 && direction &&
      Near(direction->GetComponent(0, 1), -1.0) && intensity &&
      Near(intensity->GetComponent(0, 0), 1.0),
    "a point light above the scene is a spot of the same intensity holding it");
  renderer->GetLights()->InitTraversal();
  renderer->GetLights()->GetNextItem()->SetPosition(0, 0, 0); // inside the sphere
  source->Update();
  types = vtkStringArray::SafeDownCast(
    source->GetOutput()->GetFieldData()->GetAbstractArray(vtkBrumeNames::LightType));
  Check(types && types->GetValue(0) == "point", "a point light inside the scene stays one");
}

}

int TestRendererScene(int, char*[])
{
  vtkNew<vtkRenderer> renderer;
  // A ground facing +y, a shiny box moved by its actor, a translucent box.
  auto ground = AddGround(renderer, 0.6, 0.5, 0.4);
  vtkNew<vtkCubeSource> cube;
  auto box = AddActor(renderer, cube, 0.8, 0.2, 0.2);
  box->SetPosition(0.5, 0, 0);
  box->GetProperty()->SetSpecular(0.3);
  box->GetProperty()->SetSpecularPower(40);
  auto glass = AddActor(renderer, cube, 0.2, 0.2, 0.8);
  glass->GetProperty()->SetOpacity(0.5);
  // VTK's wavelet as a volume, scaled and moved.
  const double up[3] = { 0, 1, 0 };
  auto volume = AddWavelet(renderer, 4, 100, 250, 0.5, 0.1, up);
  const double lightPosition[3] = { 0, 3, 2 };
  AddPointLight(renderer, lightPosition, 20);
  renderer->GetActiveCamera()->SetPosition(0, 1, 8);

  vtkNew<vtkBrumeRendererScene> source;
  source->SetRenderer(renderer);
  source->SetLightScale(2);
  source->Update();
  vtkPartitionedDataSetCollection* scene = source->GetOutput();
  Check(scene->GetNumberOfPartitionedDataSets() == 3,
    "three objects: the ground, the box and the volume (the translucent box left out)");
  vtkDataObject* floor = Object(scene, "actor 0");
  Check(Material(floor) == "lambertian" &&
      Near(Component(floor, vtkBrumeNames::Reflectance, 0), 0.6) &&
      Near(Component(floor, vtkBrumeNames::Reflectance, 2), 0.4),
    "the ground: Lambertian, Diffuse x DiffuseColor");
  auto* shiny = vtkPolyData::SafeDownCast(Object(scene, "actor 1"));
  // vtkProperty::SetColor sets the specular colour too: rho_s = 0.3 x colour,
  // and the red channel's 0.8 + 0.24 scaled to 1.
  Check(Material(shiny) == "phong" &&
      Near(Component(shiny, vtkBrumeNames::Specular, 0), 0.24 / 1.04) &&
      Near(Component(shiny, vtkBrumeNames::Reflectance, 0), 0.8 / 1.04) &&
      Near(Component(shiny, vtkBrumeNames::Reflectance, 1), 0.2 / 1.04) &&
      Near(Component(shiny, vtkBrumeNames::Exponent, 0), 40),
    "the box: a Phong lobe, rho_d + rho_s scaled to 1 where they exceeded it");
  double bounds[6] = { 0, 0, 0, 0, 0, 0 };
  if (shiny)
  {
    shiny->GetBounds(bounds);
  }
  Check(
    Near(bounds[0], 0.0) && Near(bounds[1], 1.0), "the box in world coordinates (moved by 0.5)");
  Check(!Object(scene, "actor 2"), "the translucent box is left out");
  auto* medium = vtkImageData::SafeDownCast(Object(scene, "volume 0"));
  double extent[6] = { 0, 0, 0, 0, 0, 0 };
  if (medium)
  {
    medium->GetBounds(extent);
  }
  Check(medium && Near(extent[0], -0.4) && Near(extent[1], 0.4) && Near(extent[2], 0.6) &&
      Near(extent[3], 1.4) && medium->GetFieldData()->GetArray(vtkBrumeNames::ScalarOpacity),
    "the volume: a classified medium, scaled by 0.1 and moved by 1 along y");
  auto* types =
    vtkStringArray::SafeDownCast(scene->GetFieldData()->GetAbstractArray(vtkBrumeNames::LightType));
  // VTK's units: Intensity 1 an irradiance of pi at the focal point, the
  // origin, 13 m^2 away squared: 20 x 2 x pi x 13 W/sr.
  Check(types && types->GetNumberOfValues() == 1 && types->GetValue(0) == "point" &&
      std::abs(scene->GetFieldData()->GetArray(vtkBrumeNames::LightIntensity)->GetComponent(0, 1) /
          (40.0 * vtkMath::Pi() * 13.0) -
        1.0) < 1e-6,
    "the point light in VTK's units, times LightScale");
  source->PhysicalLightsOn();
  source->Update();
  Check(Near(source->GetOutput()
               ->GetFieldData()
               ->GetArray(vtkBrumeNames::LightIntensity)
               ->GetComponent(0, 1),
          40),
    "the point light in W/sr with PhysicalLights, times LightScale");
  scene = source->GetOutput();

  // A camera move rebuilds nothing; a property edit does.
  const vtkMTimeType built = scene->GetMTime();
  renderer->GetActiveCamera()->Azimuth(20);
  source->Update();
  Check(source->GetOutput()->GetMTime() == built, "a camera move rebuilds nothing");
  ground->GetProperty()->SetColor(0.2, 0.7, 0.3);
  source->Update();
  Check(source->GetOutput()->GetMTime() > built &&
      Near(Component(Object(source->GetOutput(), "actor 0"), vtkBrumeNames::Reflectance, 1), 0.7),
    "a colour edit rebuilds the scene");

  // An image coloured by cell scalars through a vtkDataSetMapper: its
  // surface's cells (made by a surface filter, in its own order) have the
  // colours of the cells they come from.
  TestCellColours();

  TestSidesBlocksAndSignature();
  TestAimedPointLight();

  // Through the pipeline: a lit, finite image.
  vtkNew<vtkBrumePipeline> pipeline;
  pipeline->SetInputConnection(source->GetOutputPort());
  pipeline->SetCamera(renderer->GetActiveCamera());
  pipeline->SetSize(48, 48);
  pipeline->GetTracer()->SetNumberOfParticles(30000);
  Check(pipeline->Update(), "the renderer's scene traces and reconstructs");
  vtkSmartPointer<vtkImageData> image = pipeline->RenderImage();
  auto* radiance =
    image ? vtkFloatArray::SafeDownCast(image->GetPointData()->GetArray("Radiance")) : nullptr;
  double sum = 0.0;
  bool finite = radiance != nullptr;
  for (vtkIdType i = 0; radiance && i < radiance->GetNumberOfValues(); ++i)
  {
    finite = finite && std::isfinite(radiance->GetValue(i));
    sum += radiance->GetValue(i);
  }
  Check(finite && sum > 0.0, "its image is lit and finite");

  // Without lights: a headlight; a rotated volume: refused.
  renderer->RemoveAllLights();
  source->Modified();
  source->Update();
  types = vtkStringArray::SafeDownCast(
    source->GetOutput()->GetFieldData()->GetAbstractArray(vtkBrumeNames::LightType));
  Check(types && types->GetNumberOfValues() == 1 && types->GetValue(0) == "directional",
    "a renderer without lights gets a headlight");
  volume->RotateY(30);
  std::cerr << "(an error expected below)\n";
  Check(source->GetExecutive()->Update() == 0, "a rotated volume is refused");
  if (Failures == 0)
  {
    std::cout << "vtkBrumeRendererScene: surfaces, materials, volumes, lights, rebuilds: ok\n";
  }
  return Failures == 0 ? 0 : 1;
}
