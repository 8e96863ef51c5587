// SPDX-License-Identifier: BSD-3-Clause
// The light scattered or reflected once, against the reference path tracer:
// a cloud of two overlapping blobs with ripples (a density grid of point
// values) in sunlight, casting its shadow on a floor. With the tracers'
// MaximumDepth at 1 the pipeline keeps only the particles' first
// interactions, which the direct light replaces (shadow rays through the
// native density), and the path tracer stops after its first vertex's
// light sample; both images are then the single-scattered light.
//   TestSingleScattering [OUTPUT_DIR]
//
// Per 8x8 block, the difference over the reference's standard error (its
// 'Variance') is z. Were the pipeline exact, z would be a standard normal
// per block: mean |z| is sqrt(2/pi) = 0.80 with a standard deviation of
// sqrt(1 - 2/pi) / 8 = 0.075 over 64 blocks, and the images' totals differ
// by a z of the same law. Both must stay within four of those deviations.
#include "EvaluationTestScenes.h"

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

namespace
{
constexpr int Size = 64;
constexpr int Block = 8;
constexpr int Points = 41; // density samples per axis over [-1, 1]
constexpr double Rounding = 1e-5;

vtkSmartPointer<vtkPartitionedDataSetCollection> CloudScene()
{
  auto scene = vtkSmartPointer<vtkPartitionedDataSetCollection>::New();
  auto cloud = [](double x, double y, double z)
  {
    auto blob = [&](double cx, double cy, double cz, double r)
    {
      const double d2 = (x - cx) * (x - cx) + (y - cy) * (y - cy) + (z - cz) * (z - cz);
      return std::exp(-d2 / (r * r));
    };
    const double ripples = 0.75 + 0.25 * std::sin(9.0 * x) * std::cos(7.0 * y + 3.0 * z);
    return 3.0 * (blob(-0.3, 0.1, 0.0, 0.45) + 0.8 * blob(0.35, -0.1, 0.1, 0.35)) * ripples;
  };
  const double sigmaA[3] = { 0.2, 0.2, 0.2 }, sigmaS[3] = { 1.8, 1.6, 1.4 };
  AddDensityGrid(scene, "cloud", Points, cloud, sigmaA, sigmaS, 0.4);
  const double f0[3] = { -3, -1.2, -3 }, f1[3] = { -3, -1.2, 3 }, f2[3] = { 3, -1.2, 3 },
               f3[3] = { 3, -1.2, -3 };
  AddQuad(scene, "floor", f0, f1, f2, f3);
  const double sun[3] = { -0.5, -0.8, -0.35 };
  AddDirectionalLight(scene, sun, 4.0);
  const double eye[3] = { 0.4, 0.6, 4.2 }, target[3] = { 0, -0.4, 0 };
  SetSceneCamera(scene, eye, target, 45);
  return scene;
}
}

int TestSingleScattering(int argc, char* argv[])
{
  if (!*vtkBrumeRenderWindowSelection::GetInstalled())
  {
    std::cerr << "no render window (no X display and no EGL): skipped\n";
    return 125;
  }
  const auto scene = CloudScene();
  vtkNew<vtkBrumeReferencePathTracer> reference;
  reference->SetInputData(scene);
  reference->SetSize(Size, Size);
  reference->SetSamplesPerPixel(256);
  reference->SetSeed(11);
  reference->SetMaximumDepth(1);
  vtkNew<vtkBrumeTimedPipeline> pipeline;
  pipeline->SetInputData(scene);
  pipeline->SetSize(Size, Size);
  pipeline->SetNumberOfParticles(20000);
  pipeline->SetMaximumDepth(1);
  pipeline->MeasureNewViewOff();
  if (reference->GetExecutive()->Update() != 1 || pipeline->GetExecutive()->Update() != 1)
  {
    std::cerr << "FAILED: the images were not made\n";
    return EXIT_FAILURE;
  }
  if (argc > 1)
  {
    SaveImage(argv[1], "single-scattering-reference", reference->GetOutput());
    SaveImage(argv[1], "single-scattering-pipeline", pipeline->GetOutput());
  }
  double absZ = 0.0, sumGot = 0.0, sumWant = 0.0, variance = 0.0;
  int blocks = 0, litBlocks = 0;
  double darkGot = 0.0;    // the largest block the reference never saw lit
  double worstExact = 0.0; // blocks without noise: their difference over the rounding
  for (int by = 0; by < Size; by += Block)
  {
    for (int bx = 0; bx < Size; bx += Block)
    {
      double error = 0.0, unused = 0.0;
      const double want = BlockMean(reference->GetOutput(), bx, by, Block, &error);
      const double got = BlockMean(pipeline->GetOutput(), bx, by, Block, &unused);
      sumGot += got;
      sumWant += want;
      variance += error * error;
      ++blocks;
      // The pipeline's own rounding (32-bit float textures and targets,
      // slices blended): a few parts in a million of the block's value.
      const double rounding = Rounding * want;
      if (want == 0.0 && error == 0.0)
      {
        darkGot = std::max(darkGot, std::abs(got));
      }
      else if (error == 0.0)
      {
        // Lit by the sun alone, in view of it: the reference has no noise.
        worstExact = std::max(worstExact, std::abs(got - want) / rounding);
      }
      else
      {
        absZ += std::abs(got - want) / std::sqrt(error * error + rounding * rounding);
        ++litBlocks;
      }
    }
  }
  const double meanAbsZ = litBlocks > 0 ? absZ / litBlocks : 0.0;
  const double spread = std::sqrt(1.0 - 2.0 / M_PI) / std::sqrt(static_cast<double>(litBlocks));
  const double totalZ = (sumGot - sumWant) / std::sqrt(variance);
  std::printf("%d of %d blocks noisy (the others dark, or exact within %.1f roundings); mean |z| "
              "%.3f (noise alone: %.3f +- %.3f); totals %.6g / %.6g "
              "(%+.3f %%, z %.2f)\n",
    litBlocks, blocks, worstExact, meanAbsZ, std::sqrt(2.0 / M_PI), spread, sumGot, sumWant,
    100.0 * (sumGot / sumWant - 1.0), totalZ);
  // Where no sample of the reference met light (the sky, where the blobs'
  // tails are all there is) the pipeline may show what the reference
  // missed, but not a thousandth of the lit blocks' mean.
  if (darkGot > 1e-3 * sumWant / litBlocks)
  {
    std::cerr << "FAILED: a block dark in the reference is " << darkGot
              << " in the pipeline's image\n";
    return EXIT_FAILURE;
  }
  if (worstExact > 4.0)
  {
    std::cerr << "FAILED: a block without noise in the reference differs by " << worstExact
              << " times the rounding\n";
    return EXIT_FAILURE;
  }
  bool ok = litBlocks >= blocks / 4;
  if (!ok)
  {
    std::cerr << "FAILED: fewer than a quarter of the blocks have noise to compare with\n";
  }
  if (meanAbsZ > std::sqrt(2.0 / M_PI) + 4.0 * spread)
  {
    std::cerr << "FAILED: the blocks differ by more than the reference's noise\n";
    ok = false;
  }
  if (std::abs(totalZ) > 4.0)
  {
    std::cerr << "FAILED: the image's total differs from the reference's beyond its noise\n";
    ok = false;
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
