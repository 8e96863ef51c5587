// SPDX-License-Identifier: BSD-3-Clause
// A dense ball's visible skin against the reference path tracer, with the
// reconstruction's CentroidMatching on and off: a ball of constant density
// (optical radius 5.7, albedo 0.99) in sunlight, whose image is mostly
// multiply scattered light from its first mean free path. Twice: isotropic
// with per-view textures, and with g = 0.5 as spherical harmonics
// (DirectionalRadiance), whose coefficients are matched the same way.
//   TestDenseEdge [OUTPUT_DIR]
//
// A texel's estimate is the sigma_t-weighted mean of the source over its
// region; across the ball's edge that belongs to a point inside the ball.
// Interpolated as though it belonged to the texel's centre, the interior's
// brighter source reaches the skin. The same particles (one seed) are
// reconstructed both ways, so the two images differ by the matching alone;
// the reference's standard error gives the test its scale:
// - without matching the image must be brighter than the reference by more
//   than 4 standard errors of the total (what the matching corrects is
//   there to be seen at this budget);
// - with it, the excess must be less than half, by more than 4 standard
//   errors, and the block error lower;
// - with it, every block of the ball (at least a tenth as bright as the
//   brightest, the limb's included) within 5 % of the reference's beyond
//   4 of its standard errors.
#include "EvaluationTestScenes.h"

#include "vtkBrumeReferencePathTracer.h"
#include "vtkBrumeRenderWindowSelection.h"
#include "vtkBrumeTimedPipeline.h"
#include "vtkExecutive.h"
#include "vtkImageData.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>

namespace
{
constexpr int Size = 64;
constexpr int Block = 8;

vtkSmartPointer<vtkPartitionedDataSetCollection> BallScene(double g)
{
  auto scene = vtkSmartPointer<vtkPartitionedDataSetCollection>::New();
  auto ball = [](double x, double y, double z) { return x * x + y * y + z * z < 0.49 ? 1.0 : 0.0; };
  const double sigmaA[3] = { 0.08, 0.08, 0.08 }, sigmaS[3] = { 8.0, 8.0, 8.0 };
  AddDensityGrid(scene, "ball", 65, ball, sigmaA, sigmaS, g);
  const double sun[3] = { -0.5, -0.8, -0.35 };
  AddDirectionalLight(scene, sun, 4.0);
  const double eye[3] = { 2.5, 1.5, 3.5 }, target[3] = { 0, 0, 0 };
  SetSceneCamera(scene, eye, target, 40);
  return scene;
}

struct Comparison
{
  double Excess;     // the totals' ratio - 1
  double BlockError; // mean |block difference| / mean block
  // The block farthest from the reference's, in units of its own mean,
  // beyond 4 of its standard errors, among the blocks at least a tenth as
  // bright as the brightest (the ball's, its limb included).
  double WorstBlock = 0.0;
  int WorstX = -1, WorstY = -1;
};

Comparison Compare(vtkImageData* image, vtkImageData* reference, double* standardError)
{
  double got = 0.0, want = 0.0, differences = 0.0, variance = 0.0, brightest = 0.0;
  for (int by = 0; by < Size; by += Block)
  {
    for (int bx = 0; bx < Size; bx += Block)
    {
      brightest = std::max(brightest, BlockMean(reference, bx, by, Block, nullptr));
    }
  }
  Comparison c;
  for (int by = 0; by < Size; by += Block)
  {
    for (int bx = 0; bx < Size; bx += Block)
    {
      double error = 0.0, unused = 0.0;
      const double w = BlockMean(reference, bx, by, Block, &error);
      const double g = BlockMean(image, bx, by, Block, &unused);
      got += g;
      want += w;
      differences += std::abs(g - w);
      variance += error * error;
      const double beyond = (std::abs(g - w) - 4.0 * error) / w;
      if (w >= 0.1 * brightest && beyond > c.WorstBlock)
      {
        c.WorstBlock = beyond;
        c.WorstX = bx / Block;
        c.WorstY = by / Block;
      }
    }
  }
  if (standardError)
  {
    *standardError = std::sqrt(variance) / want;
  }
  c.Excess = got / want - 1.0;
  c.BlockError = differences / want;
  return c;
}

// One case: the reference, the pipeline with and without matching, the
// figures and the verdict.
bool Case(double g, bool directional, const char* name, int argc, char* argv[])
{
  const auto scene = BallScene(g);
  vtkNew<vtkBrumeReferencePathTracer> reference;
  reference->SetInputData(scene);
  reference->SetSize(Size, Size);
  reference->SetSamplesPerPixel(512);
  reference->SetSeed(5);
  const auto pipeline = MakePipeline(scene, Size, 1000000, directional);
  if (reference->GetExecutive()->Update() != 1 || pipeline->GetExecutive()->Update() != 1)
  {
    std::cerr << "FAILED: " << name << ": the images were not made\n";
    return false;
  }
  vtkNew<vtkImageData> matched;
  matched->DeepCopy(pipeline->GetOutput());
  pipeline->CentroidMatchingOff();
  if (pipeline->GetExecutive()->Update() != 1)
  {
    std::cerr << "FAILED: " << name << ": the image without matching was not made\n";
    return false;
  }
  if (argc > 1)
  {
    const std::string prefix = std::string("dense-edge-") + name;
    SaveImage(argv[1], prefix + "-reference", reference->GetOutput());
    SaveImage(argv[1], prefix + "-matched", matched);
    SaveImage(argv[1], prefix + "-unmatched", pipeline->GetOutput());
  }
  double se = 0.0;
  const Comparison with = Compare(matched, reference->GetOutput(), &se);
  const Comparison without = Compare(pipeline->GetOutput(), reference->GetOutput(), nullptr);
  std::printf("%s: the reference's total to %.3f %%; without matching %+.2f %% (block error "
              "%.2f %%), with it %+.2f %% (%.2f %%); the farthest block beyond 4 standard errors: "
              "%.2f %% (block %d, %d) without, %.2f %% (block %d, %d) with\n",
    name, 100.0 * se, 100.0 * without.Excess, 100.0 * without.BlockError, 100.0 * with.Excess,
    100.0 * with.BlockError, 100.0 * without.WorstBlock, without.WorstX, without.WorstY,
    100.0 * with.WorstBlock, with.WorstX, with.WorstY);
  bool ok = true;
  if (without.Excess < 4.0 * se)
  {
    std::cerr << "FAILED: " << name
              << ": without matching the ball is not brighter than the reference beyond "
                 "its noise: nothing to correct at this budget\n";
    ok = false;
  }
  if (std::abs(with.Excess) > 0.5 * without.Excess ||
    without.Excess - std::abs(with.Excess) < 4.0 * se)
  {
    std::cerr << "FAILED: " << name
              << ": matching does not halve the excess beyond the reference's noise\n";
    ok = false;
  }
  if (with.BlockError >= without.BlockError)
  {
    std::cerr << "FAILED: " << name << ": the block error is not lower with matching\n";
    ok = false;
  }
  if (with.WorstBlock > 0.05)
  {
    std::cerr << "FAILED: " << name << ": block (" << with.WorstX << ", " << with.WorstY
              << ") lies " << 100.0 * with.WorstBlock
              << " % of its mean beyond 4 standard errors of the reference's\n";
    ok = false;
  }
  return ok;
}
}

int TestDenseEdge(int argc, char* argv[])
{
  if (!*vtkBrumeRenderWindowSelection::GetInstalled())
  {
    std::cerr << "no render window (no X display and no EGL): skipped\n";
    return 125;
  }
  const bool isotropic = Case(0.0, false, "isotropic", argc, argv);
  const bool directional = Case(0.5, true, "spherical-harmonics", argc, argv);
  return isotropic && directional ? EXIT_SUCCESS : EXIT_FAILURE;
}
