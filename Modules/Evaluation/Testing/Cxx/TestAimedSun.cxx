// SPDX-License-Identifier: BSD-3-Clause
// A small cloud over a wide ground in sunlight against the reference path
// tracer, with the light tracer's MediumAimFraction at 0 and at its
// default: the sun's beam covers the whole ground (24 x 24), and the ball
// (radius 0.7, optical radius 2.1, albedo 0.99) covers under 1 % of it.
//   TestAimedSun [OUTPUT_DIR]
//
// Uniform, the ball gets about 1 % of the particles and its multiply
// scattered light is noisy; aimed, it gets about half of them, the ground
// the rest, every flux weighted so that the light is the same. Both images
// come from the same number of particles and are compared with the
// reference block by block:
// - aimed, the block error must be lower (by a quarter at least: the
//   particles the ball gets are about 40 times more);
// - aiming must not bias the image: the totals of the two images must
//   agree within 4 standard errors of the uniform one's total, estimated
//   from the spread of its blocks' errors;
// - nor must splitting the particles emitted beside the aimed disk where
//   they head into the ball (vtkBrumeLightTracer::SplitHeavyParticles):
//   the aimed image's total with and without it agree the same way.
#include "EvaluationTestScenes.h"

#include "vtkBrumeReferencePathTracer.h"
#include "vtkBrumeRenderWindowSelection.h"
#include "vtkBrumeTimedPipeline.h"
#include "vtkExecutive.h"
#include "vtkImageData.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

namespace
{
constexpr int Size = 64;
constexpr int Block = 8;

vtkSmartPointer<vtkPartitionedDataSetCollection> CloudOverPlain()
{
  auto scene = vtkSmartPointer<vtkPartitionedDataSetCollection>::New();
  const double g0[3] = { -12, -1, -12 }, g1[3] = { -12, -1, 12 }, g2[3] = { 12, -1, 12 },
               g3[3] = { 12, -1, -12 };
  AddQuad(scene, "plain", g0, g1, g2, g3);
  auto ball = [](double x, double y, double z) { return x * x + y * y + z * z < 0.49 ? 1.0 : 0.0; };
  const double sigmaA[3] = { 0.03, 0.03, 0.03 }, sigmaS[3] = { 3.0, 3.0, 3.0 };
  AddDensityGrid(scene, "cloud", 33, ball, sigmaA, sigmaS, 0.0);
  const double sun[3] = { -0.5, -0.8, -0.35 };
  AddDirectionalLight(scene, sun, 4.0);
  const double eye[3] = { 2.5, 1.0, 3.5 }, target[3] = { 0, -0.3, 0 };
  SetSceneCamera(scene, eye, target, 45);
  return scene;
}

struct Comparison
{
  double Ratio;      // the image's total over the reference's
  double BlockError; // mean |block difference| / mean block
  double RatioError; // standard error of Ratio from the blocks' scatter
};

Comparison Compare(vtkImageData* image, vtkImageData* reference)
{
  double got = 0.0, want = 0.0, differences = 0.0;
  std::vector<double> errors;
  for (int by = 0; by < Size; by += Block)
  {
    for (int bx = 0; bx < Size; bx += Block)
    {
      const double w = BlockMean(reference, bx, by, Block, nullptr);
      const double g = BlockMean(image, bx, by, Block, nullptr);
      got += g;
      want += w;
      differences += std::abs(g - w);
      errors.push_back(g - w);
    }
  }
  // The blocks' errors taken as independent: the spread of their sum.
  double mean = 0.0;
  for (double e : errors)
  {
    mean += e / errors.size();
  }
  double spread = 0.0;
  for (double e : errors)
  {
    spread += (e - mean) * (e - mean);
  }
  return { got / want, differences / want, std::sqrt(spread) / want };
}
}

int TestAimedSun(int argc, char* argv[])
{
  if (!*vtkBrumeRenderWindowSelection::GetInstalled())
  {
    std::cerr << "no render window (no X display and no EGL): skipped\n";
    return 125;
  }
  const auto scene = CloudOverPlain();
  vtkNew<vtkBrumeReferencePathTracer> reference;
  reference->SetInputData(scene);
  reference->SetSize(Size, Size);
  reference->SetSamplesPerPixel(256);
  reference->SetSeed(5);
  const auto pipeline = MakePipeline(scene, Size, 300000, false);
  pipeline->SetMediumAimFraction(0.0);
  if (reference->GetExecutive()->Update() != 1 || pipeline->GetExecutive()->Update() != 1)
  {
    std::cerr << "FAILED: the images were not made\n";
    return EXIT_FAILURE;
  }
  vtkNew<vtkImageData> uniform;
  uniform->DeepCopy(pipeline->GetOutput());
  const double fraction = vtkSmartPointer<vtkBrumeTimedPipeline>::New()->GetMediumAimFraction();
  pipeline->SetMediumAimFraction(fraction);
  pipeline->SplitHeavyParticlesOff();
  vtkNew<vtkImageData> unsplit;
  if (pipeline->GetExecutive()->Update() != 1)
  {
    std::cerr << "FAILED: the aimed image was not made\n";
    return EXIT_FAILURE;
  }
  unsplit->DeepCopy(pipeline->GetOutput());
  pipeline->SplitHeavyParticlesOn();
  if (pipeline->GetExecutive()->Update() != 1)
  {
    std::cerr << "FAILED: the aimed image was not made\n";
    return EXIT_FAILURE;
  }
  if (argc > 1)
  {
    SaveImage(argv[1], "aimed-sun-reference", reference->GetOutput());
    SaveImage(argv[1], "aimed-sun-uniform", uniform);
    SaveImage(argv[1], "aimed-sun-aimed", pipeline->GetOutput());
    SaveImage(argv[1], "aimed-sun-unsplit", unsplit);
  }
  const Comparison u = Compare(uniform, reference->GetOutput());
  const Comparison a = Compare(pipeline->GetOutput(), reference->GetOutput());
  const Comparison w = Compare(unsplit, reference->GetOutput());
  std::printf("uniform: block error %.2f %%, total %.4f (+- %.4f); aimed (%.2f): block error "
              "%.2f %%, total %.4f (+- %.4f); aimed, heavy particles unsplit: block error "
              "%.2f %%, total %.4f (+- %.4f)\n",
    100.0 * u.BlockError, u.Ratio, u.RatioError, fraction, 100.0 * a.BlockError, a.Ratio,
    a.RatioError, 100.0 * w.BlockError, w.Ratio, w.RatioError);
  bool ok = true;
  if (!(a.BlockError < 0.75 * u.BlockError))
  {
    std::cerr << "FAILED: aimed, the block error is not a quarter lower\n";
    ok = false;
  }
  if (std::abs(a.Ratio - u.Ratio) > 4.0 * u.RatioError)
  {
    std::cerr << "FAILED: the aimed image's total differs from the uniform one's beyond "
                 "its noise\n";
    ok = false;
  }
  if (std::abs(a.Ratio - w.Ratio) > 4.0 * w.RatioError)
  {
    std::cerr << "FAILED: splitting the heavy particles changed the image's total beyond "
                 "its noise\n";
    ok = false;
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
