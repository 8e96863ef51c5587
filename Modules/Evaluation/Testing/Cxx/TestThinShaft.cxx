// SPDX-License-Identifier: BSD-3-Clause
// A thin shaft: sunlight through a slit in the ceiling of a hazy box. The
// pipeline's image (direct light computed, pixels area-sampled) and the
// reference path tracer's must show the same shaft: its cross-section
// profile (the mean over the rows where it crosses the haze) agrees column
// by column within the Monte Carlo error band, and its width (at half its
// height above the background) within one pixel.
//
// With `sheet`: a sheet one voxel thick, a plane of points of scalar 200 in
// a 64^3 grid of 0 classified by a transfer function (opacity 0 up to 50,
// 0.5 a voxel at 200), seen edge-on under a point light, a voxel about a
// pixel wide: drawn where the reference draws it (its profile's centroid
// within half a pixel) and as wide (within one pixel).
//   TestThinShaft [sheet] [OUTPUT_DIR]
#include "EvaluationTestScenes.h"

#include "vtkBrumeReferencePathTracer.h"
#include "vtkBrumeRenderWindowSelection.h"
#include "vtkBrumeTimedPipeline.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPointData.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

namespace
{
constexpr int Size = 64;
constexpr int FirstRow = 16, LastRow = 47; // where the shaft crosses the haze

vtkSmartPointer<vtkPartitionedDataSetCollection> SlitScene(double halfWidth)
{
  auto scene = vtkSmartPointer<vtkPartitionedDataSetCollection>::New();
  // The ceiling y = 1 in two parts, facing down, the slit |x| < halfWidth between.
  const double a0[3] = { -1, 1, -1 }, a1[3] = { -halfWidth, 1, -1 }, a2[3] = { -halfWidth, 1, 1 },
               a3[3] = { -1, 1, 1 };
  AddQuad(scene, "ceiling left", a0, a1, a2, a3);
  const double b0[3] = { halfWidth, 1, -1 }, b1[3] = { 1, 1, -1 }, b2[3] = { 1, 1, 1 },
               b3[3] = { halfWidth, 1, 1 };
  AddQuad(scene, "ceiling right", b0, b1, b2, b3);
  const double lower[3] = { -1, -1, -1 }, upper[3] = { 1, 1, 1 };
  AddMedium(scene, "haze", lower, upper);
  const double down[3] = { 0, -1, 0 };
  AddDirectionalLight(scene, down, 20.0);
  const double eye[3] = { 0, 0, 4 }, target[3] = { 0, 0, 0 };
  SetSceneCamera(scene, eye, target, 30);
  return scene;
}

// The one-voxel sheet: points i = 32 of 64 along x over [-1, 1]^3.
vtkSmartPointer<vtkPartitionedDataSetCollection> SheetScene()
{
  auto scene = vtkSmartPointer<vtkPartitionedDataSetCollection>::New();
  const double sigmaA[3] = { 0.1, 0.1, 0.1 }, sigmaS[3] = { 0.9, 0.9, 0.9 };
  constexpr int Points = 64;
  const double sheetX = -1.0 + 32.0 * 2.0 / (Points - 1);
  AddDensityGrid(
    scene, "sheet", Points,
    [&](double x, double, double) { return std::abs(x - sheetX) < 1e-6 ? 200.0 : 0.0; }, sigmaA,
    sigmaS, 0.0);
  vtkFieldData* fd = scene->GetPartitionedDataSet(0)->GetPartition(0)->GetFieldData();
  vtkNew<vtkDoubleArray> opacity;
  opacity->SetName(vtkBrumeNames::ScalarOpacity);
  opacity->SetNumberOfComponents(2);
  opacity->InsertNextTuple2(0.0, 0.0);
  opacity->InsertNextTuple2(50.0, 0.0);
  opacity->InsertNextTuple2(200.0, 0.5);
  fd->AddArray(opacity);
  const double unit = 2.0 / (Points - 1); // a voxel
  vtkBrumeSceneConversion::AppendTuple(fd, vtkBrumeNames::ScalarOpacityUnitDistance, &unit, 1);
  const double lamp[3] = { 2.0, 1.0, 3.0 };
  AddPointLight(scene, lamp, 20.0);
  const double eye[3] = { 0, 0, 4 }, target[3] = { 0, 0, 0 };
  SetSceneCamera(scene, eye, target, 30);
  return scene;
}

// The profile's centroid in pixels (its excess over the background, the
// mean of the outer eight columns).
double Centroid(const std::vector<double>& p)
{
  double background = 0.0;
  for (int x = 0; x < 4; ++x)
  {
    background += (p[x] + p[Size - 1 - x]) / 8.0;
  }
  double sum = 0.0, moment = 0.0;
  for (int x = 0; x < Size; ++x)
  {
    const double excess = std::max(0.0, p[x] - background);
    sum += excess;
    moment += excess * x;
  }
  return sum > 0.0 ? moment / sum : -1.0;
}

// The shaft's width in pixels: where the profile crosses half its height
// above the background (the mean of the outer eight columns), interpolated.
double Width(const std::vector<double>& p)
{
  double background = 0.0;
  for (int x = 0; x < 4; ++x)
  {
    background += (p[x] + p[Size - 1 - x]) / 8.0;
  }
  const int peak = static_cast<int>(std::max_element(p.begin(), p.end()) - p.begin());
  const double half = background + 0.5 * (p[peak] - background);
  double left = peak, right = peak;
  for (int x = peak; x > 0; --x)
  {
    if (p[x - 1] < half)
    {
      left = x - (half - p[x - 1]) / (p[x] - p[x - 1]);
      break;
    }
  }
  for (int x = peak; x < Size - 1; ++x)
  {
    if (p[x + 1] < half)
    {
      right = x + (p[x] - half) / (p[x] - p[x + 1]);
      break;
    }
  }
  return right - left;
}
}

int TestThinShaft(int argc, char* argv[])
{
  if (!*vtkBrumeRenderWindowSelection::GetInstalled())
  {
    std::cerr << "no render window (no X display and no EGL): skipped\n";
    return 125;
  }
  const bool sheet = argc > 1 && std::string(argv[1]) == "sheet";
  if (sheet)
  {
    --argc;
    ++argv;
  }
  const auto scene = sheet ? SheetScene() : SlitScene(0.15);

  vtkNew<vtkBrumeReferencePathTracer> reference;
  reference->SetInputData(scene);
  reference->SetSize(Size, Size);
  reference->SetSamplesPerPixel(256);
  reference->SetSeed(7);
  vtkNew<vtkBrumeTimedPipeline> pipeline;
  pipeline->SetInputData(scene);
  pipeline->SetSize(Size, Size);
  pipeline->SetNumberOfParticles(1000000);
  pipeline->MeasureNewViewOff();
  if (reference->GetExecutive()->Update() != 1 || pipeline->GetExecutive()->Update() != 1)
  {
    std::cerr << "FAILED: the images were not made\n";
    return EXIT_FAILURE;
  }
  const std::string name = sheet ? "thin-sheet" : "thin-shaft";
  if (argc > 1)
  {
    SaveImage(argv[1], name + "-reference", reference->GetOutput());
    SaveImage(argv[1], name + "-pipeline", pipeline->GetOutput());
  }

  std::vector<double> expected, error, got;
  RowProfile(reference->GetOutput(), Size, FirstRow, LastRow, expected, &error);
  RowProfile(pipeline->GetOutput(), Size, FirstRow, LastRow, got, nullptr);
  if (sheet)
  {
    // Place and width only: its brightness is not resolved yet (seen
    // edge-on, a one-voxel sheet's lit skin comes out about 10 % bright).
    const double wantAt = Centroid(expected), gotAt = Centroid(got);
    const double wantWidth = Width(expected), gotWidth = Width(got);
    double wantSum = 0.0, gotSum = 0.0;
    for (int x = 0; x < Size; ++x)
    {
      wantSum += expected[x];
      gotSum += got[x];
    }
    std::printf("sheet: centroid reference %.3f px, pipeline %.3f px; width reference %.2f px, "
                "pipeline %.2f px; profile sum pipeline / reference %.3f\n",
      wantAt, gotAt, wantWidth, gotWidth, gotSum / wantSum);
    bool ok = true;
    if (!(std::abs(wantAt - gotAt) <= 0.5))
    {
      std::cerr << "FAILED: the sheet is drawn at " << gotAt << " px, the reference's at " << wantAt
                << "\n";
      ok = false;
    }
    if (!(std::abs(wantWidth - gotWidth) <= 1.0))
    {
      std::cerr << "FAILED: the sheet is " << gotWidth << " pixels wide, the reference's "
                << wantWidth << "\n";
      ok = false;
    }
    return ok ? EXIT_SUCCESS : EXIT_FAILURE;
  }
  // The band: four standard errors of the reference, and 3 % of the peak
  // for the pipeline's own noise and smoothing of the multiply scattered
  // light (the shaft itself is computed, not estimated).
  bool ok = WithinBand(expected, error, got, 0.03);
  const double wantWidth = Width(expected), gotWidth = Width(got);
  std::printf("shaft width: reference %.2f px, pipeline %.2f px\n", wantWidth, gotWidth);
  if (!(std::abs(wantWidth - gotWidth) <= 1.0))
  {
    std::cerr << "FAILED: the shaft is " << gotWidth << " pixels wide, the reference's "
              << wantWidth << "\n";
    ok = false;
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
