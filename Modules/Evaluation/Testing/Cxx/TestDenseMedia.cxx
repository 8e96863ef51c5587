// SPDX-License-Identifier: BSD-3-Clause
// A dense medium against the reference path tracer: the shared dragon
// (OpenVDB, sigma_s 25 per unit density, albedo 0.98) in sunlight with a
// fill light from the other side, over a ground. Nearly all the light the
// eye receives from it was scattered many times within a mean free path
// (about 4 cm, under half a voxel) of its skin, where a texture averages the
// lit skin with the dark inside.
//
// At 2 * 10^6 particles, 64 x 64, the pipeline area-sampled as the path
// tracer integrates pixels:
// - the block error (the relative MAE of 8 x 8-block means) at most 3 %
//   plus twice the reference's own block noise (what an image equal to the
//   truth would score: sqrt(2 / pi) times each block's standard error, over
//   the mean block; the sum over 64 blocks strays far less than that from
//   its mean);
// - the mean brightness within 2 % of the reference's, plus four of its
//   standard errors.
// Skipped (125) without the shared volumes or a render window.
//   TestDenseMedia SCENE_FILE SHARED_VDB_DIR [OUTPUT_DIR]
#include "EvaluationTestScenes.h"

#include "vtkBrumeImageError.h"
#include "vtkBrumeReferencePathTracer.h"
#include "vtkBrumeRenderWindowSelection.h"
#include "vtkBrumeSceneReader.h"
#include "vtkBrumeTimedPipeline.h"
#include "vtkExecutive.h"
#include "vtkImageData.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>

namespace
{
constexpr int Size = 64;
constexpr int Block = 8;
}

int TestDenseMedia(int argc, char* argv[])
{
  if (argc < 3)
  {
    std::cerr << "usage: TestDenseMedia SCENE_FILE SHARED_VDB_DIR [OUTPUT_DIR]\n";
    return EXIT_FAILURE;
  }
  if (!std::filesystem::exists(std::filesystem::path(argv[2]) / "dragon.vdb"))
  {
    std::cout << "no shared sample volumes: skipped\n";
    return 125;
  }
  if (!*vtkBrumeRenderWindowSelection::GetInstalled())
  {
    std::cerr << "no render window (no X display and no EGL): skipped\n";
    return 125;
  }
  vtkNew<vtkBrumeSceneReader> reader;
  reader->SetFileName(argv[1]);
  vtkNew<vtkBrumeReferencePathTracer> reference;
  reference->SetInputConnection(reader->GetOutputPort());
  reference->SetSize(Size, Size);
  reference->SetSamplesPerPixel(1024);
  reference->SetSeed(7);
  vtkNew<vtkBrumeTimedPipeline> pipeline;
  pipeline->SetInputConnection(reader->GetOutputPort());
  pipeline->SetSize(Size, Size);
  pipeline->SetNumberOfParticles(2000000);
  pipeline->SetSeed(1);
  pipeline->MeasureNewViewOff();
  if (reference->GetExecutive()->Update() != 1 || pipeline->GetExecutive()->Update() != 1)
  {
    std::cerr << "FAILED: the images were not made\n";
    return EXIT_FAILURE;
  }
  if (argc > 3)
  {
    SaveImage(argv[3], "dense-media-reference", reference->GetOutput());
    SaveImage(argv[3], "dense-media-pipeline", pipeline->GetOutput());
  }
  vtkNew<vtkBrumeImageError> error;
  error->SetBlockSize(Block);
  if (!error->Compare(pipeline->GetOutput(), reference->GetOutput()))
  {
    std::cerr << "FAILED: the images could not be compared\n";
    return EXIT_FAILURE;
  }
  // The reference's own noise: per block, sqrt(2 / pi) times its standard
  // error; and the standard error of its mean.
  double want = 0.0, got = 0.0, noise = 0.0, variance = 0.0;
  for (int by = 0; by < Size; by += Block)
  {
    for (int bx = 0; bx < Size; bx += Block)
    {
      double se = 0.0;
      want += BlockMean(reference->GetOutput(), bx, by, Block, &se);
      got += BlockMean(pipeline->GetOutput(), bx, by, Block, nullptr);
      noise += std::sqrt(2.0 / M_PI) * se;
      variance += se * se;
    }
  }
  noise /= want;
  const double ratio = got / want, meanError = std::sqrt(variance) / want;
  const double allowedBlock = 0.03 + 2.0 * noise, allowedMean = 0.02 + 4.0 * meanError;
  std::printf("block error %.2f %% (allowed %.2f %%: the reference's own block noise %.2f %%); "
              "mean %.4f of the reference's (allowed 1 +- %.4f)\n",
    100.0 * error->GetBlockError(), 100.0 * allowedBlock, 100.0 * noise, ratio, allowedMean);
  bool ok = true;
  if (!(error->GetBlockError() <= allowedBlock))
  {
    std::cerr << "FAILED: the block error is " << 100.0 * error->GetBlockError() << " %\n";
    ok = false;
  }
  if (!(std::abs(ratio - 1.0) <= allowedMean))
  {
    std::cerr << "FAILED: the mean brightness is " << ratio << " of the reference's\n";
    ok = false;
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
