// SPDX-License-Identifier: BSD-3-Clause
// End-to-end image regression of the built-in scene through the three phases.
//
// The image compared is the one `brume render` writes to PNG (float
// framebuffer, tone mapped). VTK's regression test (vtkTesting, threshold
// 0.15) forgives per-pixel differences below 105 (sum over RGB): measured, it
// does not see a missing medium (error 0) although it sees a missing wall
// (error 304). So the test adds VTK's vtkImageDifference with a per-pixel
// tolerance of 16, no shift and no averaging, whose thresholded error was
// measured at 0 for the same render, 70.8 with the medium removed, 2915 with
// the left wall removed and 6054 with the back wall removed; it must stay
// below 10. The render is deterministic (fixed seed, any thread count), so
// the tolerance only absorbs rasterization differences between machines.
// The test proves on every run that both mistakes are caught.
#include "vtkBrumeDefaultSceneSource.h"
#include "vtkBrumeFloatImageCapture.h"
#include "vtkBrumeLightTracer.h"
#include "vtkBrumeRadianceReconstruction.h"
#include "vtkBrumeSceneActors.h"
#include "vtkCamera.h"
#include "vtkCompositeDataSet.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkImageDifference.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkPNGReader.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkTesting.h"
#include "vtkTrivialProducer.h"

#include <cstdlib>
#include <iostream>
#include <sstream>
#include <string>

namespace
{
constexpr double VTKThreshold = 0.15; // VTK's default image-test threshold
constexpr int PixelTolerance = 16;    // per pixel, sum of the RGB differences
constexpr double StrictThreshold = 10.0;
constexpr double Exposure = 1.0;

struct Frame
{
  vtkSmartPointer<vtkRenderWindow> Window;
  vtkSmartPointer<vtkBrumeSceneActors> Actors;
  vtkSmartPointer<vtkBrumeFloatImageCapture> Capture;
};

// Where the camera is: the scene's own viewpoint, or inside the medium.
struct View
{
  double Position[3];
  double FocalPoint[3];
};
constexpr View Outside{ { 0, 0, 4 }, { 0, 0, 0 } };
constexpr View Inside{ { 0.2, -0.3, 0.45 }, { -0.6, 0.7, -1.0 } };

// Renders the default scene, optionally without its medium or one object.
Frame Render(bool medium, const std::string& dropObject, const View& view = Outside)
{
  vtkNew<vtkBrumeDefaultSceneSource> source;
  source->SetIncludeMedium(medium);
  source->Update();
  vtkNew<vtkPartitionedDataSetCollection> scene;
  scene->CopyStructure(source->GetOutput());
  scene->SetNumberOfPartitionedDataSets(0);
  scene->GetFieldData()->ShallowCopy(source->GetOutput()->GetFieldData());
  for (unsigned int i = 0; i < source->GetOutput()->GetNumberOfPartitionedDataSets(); ++i)
  {
    const char* name = source->GetOutput()->GetMetaData(i)->Get(vtkCompositeDataSet::NAME());
    if (dropObject == name)
    {
      continue;
    }
    const unsigned int k = scene->GetNumberOfPartitionedDataSets();
    scene->SetPartitionedDataSet(k, source->GetOutput()->GetPartitionedDataSet(i));
    scene->GetMetaData(k)->Set(vtkCompositeDataSet::NAME(), name);
  }

  vtkNew<vtkBrumeLightTracer> tracer;
  tracer->SetInputData(scene);
  tracer->SetNumberOfParticles(200000);
  tracer->SetSeed(1);
  vtkNew<vtkBrumeRadianceReconstruction> reconstruction;
  reconstruction->SetInputDataObject(0, scene);
  reconstruction->SetInputConnection(1, tracer->GetOutputPort());
  reconstruction->SetEyePosition(view.Position[0], view.Position[1], view.Position[2]);
  reconstruction->Update();

  Frame frame;
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0, 0, 0);
  frame.Window = vtkSmartPointer<vtkRenderWindow>::New();
  frame.Window->SetOffScreenRendering(1);
  frame.Window->SetMultiSamples(0);
  frame.Window->SetSize(256, 256);
  frame.Window->AddRenderer(renderer);
  frame.Actors = vtkSmartPointer<vtkBrumeSceneActors>::New();
  frame.Actors->SetInputData(reconstruction->GetOutput());
  frame.Actors->AddToRenderer(renderer);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(view.Position[0], view.Position[1], view.Position[2]);
  camera->SetFocalPoint(view.FocalPoint[0], view.FocalPoint[1], view.FocalPoint[2]);
  camera->SetViewUp(0, 1, 0);
  camera->SetViewAngle(40);
  renderer->ResetCameraClippingRange();
  frame.Capture = vtkSmartPointer<vtkBrumeFloatImageCapture>::New();
  frame.Capture->Attach(renderer);
  frame.Window->Render();
  return frame;
}

// The image as `brume render` writes it to PNG (float capture, tone mapped).
vtkSmartPointer<vtkTrivialProducer> DisplayImage(const Frame& frame)
{
  auto producer = vtkSmartPointer<vtkTrivialProducer>::New();
  producer->SetOutput(vtkBrumeFloatImageCapture::ToneMap(frame.Capture->Capture(), Exposure));
  return producer;
}

// The baseline given with -V, or an empty string.
std::string Baseline(int argc, char* argv[])
{
  for (int i = 0; i + 1 < argc; ++i)
  {
    if (std::string(argv[i]) == "-V")
    {
      return argv[i + 1];
    }
  }
  return {};
}

// Thresholded error of vtkImageDifference with the strict settings.
double StrictError(const std::string& baseline, const Frame& frame)
{
  vtkNew<vtkPNGReader> reader;
  reader->SetFileName(baseline.c_str());
  vtkNew<vtkImageDifference> difference;
  difference->SetInputConnection(DisplayImage(frame)->GetOutputPort());
  difference->SetImageConnection(reader->GetOutputPort());
  difference->SetThreshold(PixelTolerance);
  difference->AllowShiftOff();
  difference->AveragingOff();
  difference->Update();
  return difference->GetThresholdedError();
}
}

int TestDefaultScene(int argc, char* argv[])
{
  // `inside`: the camera inside the medium (its own baseline).
  bool inside = false;
  for (int i = 1; i < argc; ++i)
  {
    inside = inside || std::string(argv[i]) == "inside";
  }
  const Frame frame = Render(true, "", inside ? Inside : Outside);
  // VTK's regression test: reports, and writes the test image for a new baseline.
  vtkNew<vtkTesting> testing;
  for (int i = 0; i < argc; ++i)
  {
    testing->AddArgument(argv[i]);
  }
  if (testing->RegressionTest(DisplayImage(frame), VTKThreshold) != vtkTesting::PASSED)
  {
    return EXIT_FAILURE;
  }
  const std::string baseline = Baseline(argc, argv);
  const double error = StrictError(baseline, frame);
  std::cout << "strict image error " << error << " (limit " << StrictThreshold << ")\n";
  if (!(error <= StrictThreshold))
  {
    std::cerr << "Failed Image Test: strict image error " << error << " > " << StrictThreshold
              << "\n";
    return EXIT_FAILURE;
  }
  if (inside)
  {
    return EXIT_SUCCESS;
  }
  // The mistakes the comparison must catch.
  const double noMedium = StrictError(baseline, Render(false, ""));
  const double noWall = StrictError(baseline, Render(true, "left"));
  std::cout << "without the medium: " << noMedium << ", without the left wall: " << noWall << "\n";
  if (!(noMedium > StrictThreshold) || !(noWall > StrictThreshold))
  {
    std::cerr << "The image comparison does not catch a missing medium or wall.\n";
    return EXIT_FAILURE;
  }
  return EXIT_SUCCESS;
}
