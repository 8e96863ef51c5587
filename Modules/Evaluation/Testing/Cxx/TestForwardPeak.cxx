// SPDX-License-Identifier: BSD-3-Clause
// Strongly forward scattering: a slab of mist with g = 0.99 in front of a
// large emitter, seen through it. Almost all the light the eye receives
// from the mist was scattered by a few tenths of a degree, which per-view
// textures can only estimate from the few particles travelling straight at
// the eye, unless the phase function's peak is set apart and drawn as
// transport (brume::TruncateForwardPeak per view, brume::SplitForwardPeak
// as spherical harmonics). Over blocks of 4 x 4 pixels covering
// the mist, the pipeline's image, with per-view textures and with
// directional (spherical-harmonics) media, and the reference path tracer's
// agree within four standard errors of the reference plus 3 % for the
// pipeline's own noise and smoothing (the same allowance as the thin
// shaft's).
//   TestForwardPeak [OUTPUT_DIR]
#include "EvaluationTestScenes.h"

#include "vtkBrumeDataModelNames.h"
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

namespace
{
constexpr int Size = 32;
constexpr int Block = 4;
constexpr int First = 8, Last = 23; // the pixels the mist covers, both axes

vtkSmartPointer<vtkPartitionedDataSetCollection> SlabScene()
{
  auto scene = vtkSmartPointer<vtkPartitionedDataSetCollection>::New();
  // A window of light behind the mist, facing the eye, wider than the view.
  const double w0[3] = { -3, -3, -1.2 }, w1[3] = { 3, -3, -1.2 }, w2[3] = { 3, 3, -1.2 },
               w3[3] = { -3, 3, -1.2 };
  AddQuad(scene, "window", w0, w1, w2, w3, 1.0);
  vtkNew<vtkImageData> box;
  box->SetOrigin(-0.8, -0.8, -0.5);
  box->SetSpacing(1.6, 1.6, 1.0);
  box->SetDimensions(2, 2, 2);
  const double sigmaA[3] = { 0.2, 0.2, 0.2 }, sigmaS[3] = { 1.8, 1.8, 1.8 }, g = 0.99;
  vtkBrumeSceneConversion::AppendTuple(box->GetFieldData(), vtkBrumeNames::SigmaA, sigmaA, 3);
  vtkBrumeSceneConversion::AppendTuple(box->GetFieldData(), vtkBrumeNames::SigmaS, sigmaS, 3);
  vtkBrumeSceneConversion::AppendTuple(box->GetFieldData(), vtkBrumeNames::G, &g, 1);
  vtkBrumeSceneConversion::AddObject(scene, box, "forward mist");
  const double eye[3] = { 0, 0, 4 }, target[3] = { 0, 0, 0 };
  SetSceneCamera(scene, eye, target, 30);
  return scene;
}

}

int TestForwardPeak(int argc, char* argv[])
{
  if (!*vtkBrumeRenderWindowSelection::GetInstalled())
  {
    std::cerr << "no render window (no X display and no EGL): skipped\n";
    return 125;
  }
  const auto scene = SlabScene();
  vtkNew<vtkBrumeReferencePathTracer> reference;
  reference->SetInputData(scene);
  reference->SetSize(Size, Size);
  reference->SetSamplesPerPixel(256);
  reference->SetSeed(5);
  if (reference->GetExecutive()->Update() != 1)
  {
    std::cerr << "FAILED: the reference was not made\n";
    return EXIT_FAILURE;
  }
  if (argc > 1)
  {
    SaveImage(argv[1], "forward-peak-reference", reference->GetOutput());
  }
  bool ok = true;
  for (const bool directional : { false, true })
  {
    const char* mode = directional ? "directional" : "per-view";
    const auto pipeline = MakePipeline(scene, Size, 1000000, directional);
    if (pipeline->GetExecutive()->Update() != 1)
    {
      std::cerr << "FAILED: the " << mode << " image was not made\n";
      return EXIT_FAILURE;
    }
    if (argc > 1)
    {
      SaveImage(argv[1], std::string("forward-peak-") + mode, pipeline->GetOutput());
    }
    double worst = 0.0;
    std::printf("%s\n%6s %6s %12s %12s %12s\n", mode, "x", "y", "reference", "pipeline", "band");
    for (int by = First; by <= Last; by += Block)
    {
      for (int bx = First; bx <= Last; bx += Block)
      {
        double error = 0.0;
        const double want = BlockMean(reference->GetOutput(), bx, by, Block, &error);
        const double got = BlockMean(pipeline->GetOutput(), bx, by, Block, nullptr);
        const double band = 4.0 * error + 0.03 * want;
        const bool pass = std::abs(got - want) <= band;
        ok = ok && pass;
        worst = std::max(worst, std::abs(got - want) / want);
        std::printf(
          "%6d %6d %12.5g %12.5g %12.3g%s\n", bx, by, want, got, band, pass ? "" : "  FAIL");
      }
    }
    std::printf("%s: largest block difference %.2f %%\n", mode, 100.0 * worst);
  }
  if (!ok)
  {
    std::cerr << "FAILED: a block of the mist is outside the reference's band\n";
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
