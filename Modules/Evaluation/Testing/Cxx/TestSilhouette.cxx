// SPDX-License-Identifier: BSD-3-Clause
// A heterogeneous medium's silhouette: a dense ball given as a density
// grid (vtkImageData point values), lit from the front. In the pipeline's
// image (pixels area-sampled) and the reference path tracer's, the ball's
// edges along the middle rows, where the profile crosses half the ball's
// brightness, lie within one voxel of the density grid of each other.
//   TestSilhouette [OUTPUT_DIR]
#include "EvaluationTestScenes.h"

#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeReferencePathTracer.h"
#include "vtkBrumeRenderWindowSelection.h"
#include "vtkBrumeTimedPipeline.h"
#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkFloatArray.h"
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
constexpr int Points = 33;         // density samples per axis over [-1, 1]
constexpr double ViewAngle = 30.0; // degrees
constexpr double Distance = 4.0;   // eye to the ball's centre

vtkSmartPointer<vtkPartitionedDataSetCollection> BallScene()
{
  auto scene = vtkSmartPointer<vtkPartitionedDataSetCollection>::New();
  const double sigmaA[3] = { 0.1, 0.1, 0.1 }, sigmaS[3] = { 0.9, 0.9, 0.9 };
  AddDensityGrid(
    scene, "ball", Points,
    [](double x, double y, double z) { return std::sqrt(x * x + y * y + z * z) < 0.6 ? 8.0 : 0.0; },
    sigmaA, sigmaS, 0.3);
  const double light[3] = { 0.3, -0.4, -1.0 };
  AddDirectionalLight(scene, light, 5.0);
  const double eye[3] = { 0, 0, Distance }, target[3] = { 0, 0, 0 };
  SetSceneCamera(scene, eye, target, ViewAngle);
  return scene;
}

// The middle rows' profile (channels' mean).
std::vector<double> Profile(vtkImageData* image)
{
  vtkDataArray* radiance = image->GetPointData()->GetArray(vtkBrumeNames::Radiance);
  std::vector<double> p(Size, 0.0);
  for (int x = 0; x < Size; ++x)
  {
    for (int y = Size / 2 - 2; y < Size / 2 + 2; ++y)
    {
      const vtkIdType i = y * Size + x;
      p[x] += (radiance->GetComponent(i, 0) + radiance->GetComponent(i, 1) +
                radiance->GetComponent(i, 2)) /
        12.0;
    }
  }
  return p;
}

// Where the profile first rises through, and last falls through, half of
// its maximum (pixel centres at x + 0.5), interpolated.
void Edges(const std::vector<double>& p, double& left, double& right)
{
  const double half = 0.5 * *std::max_element(p.begin(), p.end());
  left = right = -1.0;
  for (int x = 0; x + 1 < Size; ++x)
  {
    if (p[x] < half && p[x + 1] >= half && left < 0.0)
    {
      left = x + 0.5 + (half - p[x]) / (p[x + 1] - p[x]);
    }
    if (p[x] >= half && p[x + 1] < half)
    {
      right = x + 0.5 + (p[x] - half) / (p[x] - p[x + 1]);
    }
  }
}
}

int TestSilhouette(int argc, char* argv[])
{
  if (!*vtkBrumeRenderWindowSelection::GetInstalled())
  {
    std::cerr << "no render window (no X display and no EGL): skipped\n";
    return 125;
  }
  const auto scene = BallScene();
  vtkNew<vtkBrumeReferencePathTracer> reference;
  reference->SetInputData(scene);
  reference->SetSize(Size, Size);
  reference->SetSamplesPerPixel(128);
  reference->SetSeed(3);
  vtkNew<vtkBrumeTimedPipeline> pipeline;
  pipeline->SetInputData(scene);
  pipeline->SetSize(Size, Size);
  pipeline->SetNumberOfParticles(500000);
  pipeline->MeasureNewViewOff();
  if (reference->GetExecutive()->Update() != 1 || pipeline->GetExecutive()->Update() != 1)
  {
    std::cerr << "FAILED: the images were not made\n";
    return EXIT_FAILURE;
  }
  if (argc > 1)
  {
    SaveImage(argv[1], "silhouette-reference", reference->GetOutput());
    SaveImage(argv[1], "silhouette-pipeline", pipeline->GetOutput());
  }
  double wantLeft, wantRight, gotLeft, gotRight;
  Edges(Profile(reference->GetOutput()), wantLeft, wantRight);
  Edges(Profile(pipeline->GetOutput()), gotLeft, gotRight);
  // One voxel of the density grid, in pixels at the ball's silhouette.
  const double pixel = 2.0 * Distance * std::tan(ViewAngle * M_PI / 360.0) / Size;
  const double voxel = 2.0 / (Points - 1) / pixel;
  std::printf("edges (pixels): reference %.2f, %.2f; pipeline %.2f, %.2f; one voxel %.2f px\n",
    wantLeft, wantRight, gotLeft, gotRight, voxel);
  const bool ok = wantLeft > 0.0 && wantRight > 0.0 && gotLeft > 0.0 && gotRight > 0.0 &&
    std::abs(gotLeft - wantLeft) <= voxel && std::abs(gotRight - wantRight) <= voxel;
  if (!ok)
  {
    std::cerr << "FAILED: a silhouette edge is more than one voxel from the reference's\n";
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
