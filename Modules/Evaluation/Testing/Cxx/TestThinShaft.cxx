// SPDX-License-Identifier: BSD-3-Clause
// A thin shaft: sunlight through a slit in the ceiling of a hazy box. The
// pipeline's image (direct light computed, pixels area-sampled) and the
// reference path tracer's must show the same shaft: its cross-section
// profile (the mean over the rows where it crosses the haze) agrees column
// by column within the Monte Carlo error band, and its width (at half its
// height above the background) within one pixel.
//   TestThinShaft [OUTPUT_DIR]
#include "EvaluationTestScenes.h"

#include "vtkBrumeReferencePathTracer.h"
#include "vtkBrumeRenderWindowSelection.h"
#include "vtkBrumeTimedPipeline.h"
#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkImageData.h"
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
  const auto scene = SlitScene(0.15);

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
  if (argc > 1)
  {
    SaveImage(argv[1], "thin-shaft-reference", reference->GetOutput());
    SaveImage(argv[1], "thin-shaft-pipeline", pipeline->GetOutput());
  }

  std::vector<double> expected, error, got;
  RowProfile(reference->GetOutput(), Size, FirstRow, LastRow, expected, &error);
  RowProfile(pipeline->GetOutput(), Size, FirstRow, LastRow, got, nullptr);
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
