// SPDX-License-Identifier: BSD-3-Clause
// Surfaces coloured by scalars through a colour map, lit by Brume.
// - vtkBrumeRendererScene gives each vertex its mapped colour times Diffuse
//   as its reflectance, interpolated over the triangles.
// - Colour bleeding: a ground coloured red to blue along x by a point
//   scalar, a white ball above it, a light overhead. The ball's lower
//   left, facing the red end, is redder than its lower right: over both
//   regions the pipeline's red and blue radiances agree with the reference
//   path tracer's within four of its standard errors plus 3 % (the
//   pipeline's own noise and smoothing, the allowance of the evaluation
//   tests), and both images show the same bleeding. 4 x 10^7 particles:
//   the scene is open (about 9 % of the light's particles reach the
//   ground), and the ball's underside, lit only by the ground, is where
//   the curved surface's texture converges last (4 % dark at 2 x 10^7).
// - Through vtkBrumePass, an edit of the colour map traces once more.
//   TestScalarColouring [OUTPUT_DIR]
#include "VtkSceneTesting.h"
#include "vtkActor.h"
#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeLightTracer.h"
#include "vtkBrumePass.h"
#include "vtkBrumePipeline.h"
#include "vtkBrumeReferencePathTracer.h"
#include "vtkBrumeRendererScene.h"
#include "vtkCamera.h"
#include "vtkCellData.h"
#include "vtkColorTransferFunction.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArray.h"
#include "vtkElevationFilter.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkXMLImageDataWriter.h"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>

namespace
{
constexpr int Size = 64;
constexpr double ViewAngle = 30.0;
const double Eye[3] = { 0.0, -0.2, 6.0 };
const double Centre[3] = { 0.0, -0.2, 0.0 };
constexpr double Radius = 0.8;

int Failures = 0;

void Check(bool ok, const std::string& what)
{
  if (!ok)
  {
    std::cerr << "FAILED: " << what << "\n";
    ++Failures;
  }
}

// Which part of the ball pixel (i, j) sees: -1 its lower left, +1 its lower
// right (more than 0.25 from the middle, below its centre), 0 otherwise.
int Region(int i, int j)
{
  const double t = std::tan(vtkMath::RadiansFromDegrees(ViewAngle / 2.0));
  const double d[3] = { (2.0 * (i + 0.5) / Size - 1.0) * t, (2.0 * (j + 0.5) / Size - 1.0) * t,
    -1.0 };
  const double o[3] = { Eye[0] - Centre[0], Eye[1] - Centre[1], Eye[2] - Centre[2] };
  const double a = vtkMath::Dot(d, d), b = vtkMath::Dot(o, d);
  const double disc = b * b - a * (vtkMath::Dot(o, o) - Radius * Radius);
  if (disc <= 0.0)
  {
    return 0;
  }
  const double s = (-b - std::sqrt(disc)) / a;
  const double x = o[0] + s * d[0], y = o[1] + s * d[1];
  if (y > -0.2 * Radius || std::abs(x) < 0.25 * Radius)
  {
    return 0;
  }
  return x < 0.0 ? -1 : 1;
}

struct RegionMeans
{
  double Value[2][3] = {};    // [left, right][r, g, b]
  double Variance[2][3] = {}; // of the means, where given
  int Pixels[2] = {};
};

RegionMeans Measure(vtkImageData* image)
{
  RegionMeans m;
  vtkDataArray* radiance = image ? image->GetPointData()->GetArray("Radiance") : nullptr;
  vtkDataArray* variance = image ? image->GetPointData()->GetArray("Variance") : nullptr;
  for (int j = 0; radiance && j < Size; ++j)
  {
    for (int i = 0; i < Size; ++i)
    {
      const int r = Region(i, j);
      if (r == 0)
      {
        continue;
      }
      const int k = r < 0 ? 0 : 1;
      ++m.Pixels[k];
      for (int c = 0; c < 3; ++c)
      {
        m.Value[k][c] += radiance->GetComponent(j * Size + i, c);
        m.Variance[k][c] += variance ? variance->GetComponent(j * Size + i, c) : 0.0;
      }
    }
  }
  for (int k = 0; k < 2; ++k)
  {
    for (int c = 0; c < 3; ++c)
    {
      const double n = std::max(1, m.Pixels[k]);
      m.Value[k][c] /= n;
      m.Variance[k][c] /= n * n;
    }
  }
  return m;
}

// Red over blue on the left over the same on the right: > 1 where the red
// end bleeds onto the left.
double Bleeding(const RegionMeans& m)
{
  return (m.Value[0][0] / m.Value[0][2]) / (m.Value[1][0] / m.Value[1][2]);
}

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
}

int TestScalarColouring(int argc, char* argv[])
{
  vtkNew<vtkRenderer> renderer;
  // The ground, coloured by x through a red-to-blue colour map.
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-3, -1, 3);
  plane->SetPoint1(3, -1, 3);
  plane->SetPoint2(-3, -1, -3);
  plane->SetResolution(24, 24);
  vtkNew<vtkElevationFilter> byX;
  byX->SetInputConnection(plane->GetOutputPort());
  byX->SetLowPoint(-3, 0, 0);
  byX->SetHighPoint(3, 0, 0);
  vtkNew<vtkColorTransferFunction> colours;
  colours->AddRGBPoint(0.0, 0.9, 0.05, 0.05);
  colours->AddRGBPoint(1.0, 0.05, 0.05, 0.9);
  vtkNew<vtkPolyDataMapper> groundMapper;
  groundMapper->SetInputConnection(byX->GetOutputPort());
  groundMapper->SetLookupTable(colours);
  groundMapper->SetScalarRange(0.0, 1.0);
  vtkNew<vtkActor> ground;
  ground->SetMapper(groundMapper);
  renderer->AddActor(ground);
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(Centre);
  sphere->SetRadius(Radius);
  sphere->SetThetaResolution(48);
  sphere->SetPhiResolution(24);
  AddActor(renderer, sphere, 0.9, 0.9, 0.9);
  const double above[3] = { 0, 4, 1 };
  AddPointLight(renderer, above, 1.0);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(Eye);
  camera->SetFocalPoint(Centre);
  camera->SetViewUp(0, 1, 0);
  camera->SetViewAngle(ViewAngle);

  // The scene: each triangle of the ground has its cell's mean colour.
  vtkNew<vtkBrumeRendererScene> scene;
  scene->SetRenderer(renderer);
  scene->Update();
  auto* floor = vtkPolyData::SafeDownCast(Object(scene->GetOutput(), "actor 0"));
  vtkDataArray* reflectance =
    floor ? floor->GetPointData()->GetArray(vtkBrumeNames::Reflectance) : nullptr;
  // Every vertex has its scalar's colour (8-bit, as VTK maps it): red at
  // x = -3, blue at x = 3, interpolated over the triangles.
  bool mapped = reflectance && reflectance->GetNumberOfTuples() == floor->GetNumberOfPoints();
  for (vtkIdType i = 0; mapped && i < floor->GetNumberOfPoints(); ++i)
  {
    double rgb[3];
    colours->GetColor((floor->GetPoint(i)[0] + 3.0) / 6.0, rgb);
    for (int c = 0; c < 3; ++c)
    {
      mapped = mapped && std::abs(reflectance->GetComponent(i, c) - rgb[c]) < 0.5 / 255 + 1e-6;
    }
  }
  Check(mapped, "the ground's vertices have their mapped colours as reflectance");

  // The pipeline's image and the reference's.
  vtkNew<vtkBrumePipeline> pipeline;
  pipeline->SetInputConnection(scene->GetOutputPort());
  pipeline->SetCamera(camera);
  pipeline->SetSize(Size, Size);
  pipeline->GetTracer()->SetNumberOfParticles(40000000);
  pipeline->GetTracer()->SetSeed(7);
  Check(pipeline->Update(), "the pipeline runs on the coloured scene");
  vtkSmartPointer<vtkImageData> image = pipeline->RenderImage();
  vtkNew<vtkBrumeReferencePathTracer> reference;
  reference->SetInputConnection(scene->GetOutputPort());
  reference->SetCamera(camera);
  reference->SetSize(Size, Size);
  reference->SetSamplesPerPixel(1024);
  reference->SetSeed(3);
  reference->Update();
  const RegionMeans got = Measure(image);
  const RegionMeans want = Measure(reference->GetOutput());
  const char* side[2] = { "left (red end)", "right (blue end)" };
  bool within = got.Pixels[0] > 20 && got.Pixels[1] > 20;
  for (int k = 0; k < 2; ++k)
  {
    for (int c : { 0, 2 })
    {
      const double band = 4.0 * std::sqrt(want.Variance[k][c]) + 0.03 * want.Value[k][c];
      const bool ok = std::abs(got.Value[k][c] - want.Value[k][c]) <= band;
      within = within && ok;
      std::printf("%-18s %s: pipeline %.5g, reference %.5g, band %.3g%s\n", side[k],
        c == 0 ? "red " : "blue", got.Value[k][c], want.Value[k][c], band, ok ? "" : "  FAIL");
    }
  }
  std::printf("bleeding (red/blue left over right): pipeline %.3f, reference %.3f\n", Bleeding(got),
    Bleeding(want));
  Check(within, "the ball's lower sides agree with the reference within its band");
  Check(Bleeding(want) > 1.2 && Bleeding(got) > 1.2,
    "the side facing the red end is redder than the side facing the blue end");
  if (argc > 1)
  {
    vtkNew<vtkXMLImageDataWriter> writer;
    writer->SetInputData(image);
    writer->SetFileName((std::string(argv[1]) + "/scalar-colouring.vti").c_str());
    writer->Write();
    writer->SetInputData(reference->GetOutput());
    writer->SetFileName((std::string(argv[1]) + "/scalar-colouring-reference.vti").c_str());
    writer->Write();
  }

  // Through the pass: a colour-map edit traces once more.
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetSize(Size, Size);
  window->AddRenderer(renderer);
  vtkNew<vtkBrumePass> pass;
  pass->SetNumberOfParticles(20000);
  renderer->SetPass(pass);
  window->Render();
  window->Render();
  const int traces = pass->GetNumberOfTraces();
  colours->AddRGBPoint(0.5, 0.1, 0.8, 0.1);
  window->Render();
  window->Render();
  Check(traces == 1 && pass->GetNumberOfTraces() == 2,
    "the first frames trace once; a colour-map edit traces once more");
  if (Failures == 0)
  {
    std::cout << "scalar colouring: per-vertex reflectance, bleeding as the reference's: ok\n";
  }
  return Failures == 0 ? 0 : 1;
}
