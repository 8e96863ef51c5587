// SPDX-License-Identifier: BSD-3-Clause
// vtkBrumePipeline: the three phases wired once.
// - Its image is bitwise the image of the filters wired by hand (tracer,
//   reconstruction, scene actors, float capture), as `brume render` wired
//   them before it.
// - A scene's render settings reach the filters, and what is set after
//   them wins.
// - Batches and a progressive step (the count doubled) give bitwise the
//   image of one run.
// - Without a scene, or a progressive step not asked for, it fails and
//   says which phase.
#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeDefaultSceneSource.h"
#include "vtkBrumeFloatImageCapture.h"
#include "vtkBrumeLightTracer.h"
#include "vtkBrumePipeline.h"
#include "vtkBrumeRadianceReconstruction.h"
#include "vtkBrumeSceneActors.h"
#include "vtkBrumeSceneCamera.h"
#include "vtkCamera.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"

#include <cstring>
#include <iostream>
#include <string>

namespace
{
constexpr vtkTypeInt64 Particles = 40000;
constexpr int Size = 48;

int Failures = 0;

void Check(bool ok, const std::string& what)
{
  if (!ok)
  {
    std::cerr << "FAILED: " << what << "\n";
    ++Failures;
  }
}

// Bitwise equality of two radiance images.
bool Same(vtkImageData* a, vtkImageData* b)
{
  if (!a || !b)
  {
    return false;
  }
  auto* x = vtkFloatArray::SafeDownCast(a->GetPointData()->GetArray("Radiance"));
  auto* y = vtkFloatArray::SafeDownCast(b->GetPointData()->GetArray("Radiance"));
  if (!x || !y || x->GetNumberOfValues() != y->GetNumberOfValues())
  {
    return false;
  }
  return std::memcmp(x->GetPointer(0), y->GetPointer(0),
           static_cast<std::size_t>(x->GetNumberOfValues()) * sizeof(float)) == 0;
}

// Not black: the test compares images of something.
bool Lit(vtkImageData* image)
{
  auto* x =
    image ? vtkFloatArray::SafeDownCast(image->GetPointData()->GetArray("Radiance")) : nullptr;
  double sum = 0.0;
  for (vtkIdType i = 0; x && i < x->GetNumberOfValues(); ++i)
  {
    sum += x->GetValue(i);
  }
  return sum > 0.0;
}

// The phases wired by hand, as `brume render` wired them before the
// pipeline object: the scene's camera, one image from one viewpoint.
vtkSmartPointer<vtkImageData> ByHand(vtkAlgorithm* scene)
{
  double position[3], focal[3], up[3], angle;
  vtkBrumeSceneCamera::GetSceneCamera(scene->GetOutputDataObject(0), position, focal, up, angle);
  vtkNew<vtkBrumeLightTracer> tracer;
  tracer->SetInputConnection(scene->GetOutputPort());
  tracer->SetNumberOfParticles(Particles);
  tracer->SetSeed(3);
  vtkNew<vtkBrumeRadianceReconstruction> reconstruction;
  reconstruction->SetInputConnection(0, scene->GetOutputPort());
  reconstruction->SetInputConnection(1, tracer->GetOutputPort());
  reconstruction->SetEyePosition(position);
  reconstruction->SetFixedView(true);
  reconstruction->Update();
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0, 0, 0);
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->SetSize(Size, Size);
  window->AddRenderer(renderer);
  vtkNew<vtkBrumeSceneActors> actors;
  actors->SetInputData(reconstruction->GetOutput());
  if (!actors->AddToRenderer(renderer))
  {
    return nullptr;
  }
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(position);
  camera->SetFocalPoint(focal);
  camera->SetViewUp(up);
  camera->SetViewAngle(angle);
  renderer->ResetCameraClippingRange();
  vtkNew<vtkBrumeFloatImageCapture> capture;
  capture->Attach(renderer);
  window->Render();
  window->Render();
  return capture->Capture();
}

vtkSmartPointer<vtkBrumePipeline> MakePipeline(vtkAlgorithm* scene)
{
  auto pipeline = vtkSmartPointer<vtkBrumePipeline>::New();
  pipeline->SetInputConnection(scene->GetOutputPort());
  pipeline->SetSize(Size, Size);
  pipeline->GetTracer()->SetNumberOfParticles(Particles);
  pipeline->GetTracer()->SetSeed(3);
  pipeline->GetReconstruction()->SetFixedView(true);
  return pipeline;
}

void TestSameAsByHand(vtkAlgorithm* scene)
{
  const vtkSmartPointer<vtkImageData> expected = ByHand(scene);
  auto pipeline = MakePipeline(scene);
  Check(pipeline->Update(), "the pipeline updates");
  Check(pipeline->GetNumberOfHits() > Particles && pipeline->GetNumberOfRays() > 0,
    "the pipeline counts its hits and rays");
  const vtkSmartPointer<vtkImageData> image = pipeline->RenderImage();
  Check(Lit(expected) && Same(image, expected),
    "the pipeline's image is bitwise that of the phases wired by hand");
  // A second image of the same view: nothing recomputed, the same pixels.
  Check(Same(pipeline->RenderImage(), expected), "a second RenderImage gives the same image");
  // The image is the frame that uploads the textures: none is drawn only to
  // be timed unless asked (MeasureFrameOn(), as brume render --timings
  // does), and one drawn then changes no pixel.
  Check(pipeline->GetFrameSeconds() == 0.0 && pipeline->GetFirstFrameSeconds() > 0.0,
    "one frame, timed, unless a second is asked for");
  pipeline->MeasureFrameOn();
  Check(Same(pipeline->RenderImage(), expected) && pipeline->GetFrameSeconds() > 0.0,
    "a frame drawn to be timed leaves the image as it was");
  pipeline->MeasureFrameOff();

  // One image, its build state freed first (brume render): the same image;
  // after a camera move the textures are rebuilt in full, bitwise those of
  // a fresh pipeline toward the new view.
  auto released = MakePipeline(scene);
  Check(released->Update(), "a pipeline to release updates");
  released->ReleaseBuildState();
  Check(Same(released->RenderImage(), expected),
    "the image after the build state is released is the same");
  released->GetCamera()->Azimuth(5.0);
  auto fresh = MakePipeline(scene);
  fresh->GetCamera()->Azimuth(5.0);
  Check(fresh->Update(), "a pipeline toward the turned view updates");
  const vtkSmartPointer<vtkImageData> turned = fresh->RenderImage();
  Check(Lit(turned) && !Same(turned, expected) && Same(released->RenderImage(), turned),
    "released, then turned: the image of a fresh pipeline toward the new view");

  // A camera moved between Update() and the first image: the view-dependent
  // textures follow it there too.
  auto moved = MakePipeline(scene);
  Check(moved->Update(), "a pipeline whose camera moves updates");
  moved->GetCamera()->Azimuth(5.0);
  Check(Same(moved->RenderImage(), turned),
    "a camera moved before the first image: the image toward the new view");

  // Batches of one run bin as they come: the same textures, the same image.
  auto batched = MakePipeline(scene);
  batched->SetBatchSize(Particles / 4);
  Check(batched->GetPlannedBatchSize() == Particles / 4 && !batched->IsBatchedForMemory(),
    "the batch size given is the one planned");
  Check(batched->Update(), "a batched run updates");
  Check(Same(batched->RenderImage(), expected), "four batches give the image of one run");

  // Batches chosen for memory where the run's hits would not fit.
  auto limited = MakePipeline(scene);
  limited->GetTracer()->SetMemoryLimit(
    static_cast<vtkTypeInt64>(vtkBrumeLightTracer::ExpectedHitBytes(Particles / 3)));
  Check(limited->IsBatchedForMemory() && limited->GetPlannedBatchSize() < Particles,
    "a run over the memory limit is planned in batches");
  Check(limited->Update() && Same(limited->RenderImage(), expected),
    "batches chosen for memory give the image of one run");

  // Progressive: half the particles, then the other half added, against
  // one run at the same texture resolutions (a progressive run keeps its
  // first step's).
  auto resolutions = [](vtkBrumePipeline* p)
  {
    p->GetReconstruction()->SetSurfaceResolution(24);
    p->GetReconstruction()->SetMediumResolution(10);
  };
  auto once = MakePipeline(scene);
  resolutions(once);
  Check(once->Update(), "one run at fixed resolutions updates");
  const vtkSmartPointer<vtkImageData> whole = once->RenderImage();
  auto progressive = MakePipeline(scene);
  resolutions(progressive);
  progressive->GetReconstruction()->SetFixedView(false);
  progressive->ProgressiveOn();
  progressive->GetTracer()->SetNumberOfParticles(Particles / 2);
  Check(progressive->Update(), "a progressive run updates");
  const vtkSmartPointer<vtkImageData> half = progressive->RenderImage();
  Check(progressive->AddParticles(Particles / 2), "particles are added");
  Check(progressive->GetTracer()->GetNumberOfParticles() == Particles,
    "the run counts the added particles");
  Check(Lit(whole) && !Same(half, whole) && Same(progressive->RenderImage(), whole),
    "a doubled progressive run gives the image of one run (and half of it does not)");
}

void TestSceneSettings(vtkAlgorithm* source)
{
  vtkNew<vtkPartitionedDataSetCollection> scene;
  scene->ShallowCopy(source->GetOutputDataObject(0));
  vtkNew<vtkFieldData> fields;
  fields->ShallowCopy(scene->GetFieldData());
  auto add = [&](const char* name, std::initializer_list<double> values)
  {
    vtkNew<vtkDoubleArray> a;
    a->SetName(name);
    a->SetNumberOfComponents(static_cast<int>(values.size()));
    a->InsertNextTuple(std::data(values));
    fields->AddArray(a);
  };
  add(vtkBrumeNames::RenderParticles, { 1234 });
  add(vtkBrumeNames::RenderSeed, { 9 });
  add(vtkBrumeNames::RenderThreshold, { 32 });
  add(vtkBrumeNames::RenderSize, { 40, 24 });
  add(vtkBrumeNames::RenderExposure, { 2.5 });
  add(vtkBrumeNames::CameraPosition, { 0.5, 1, 9 });
  scene->SetFieldData(fields);

  vtkNew<vtkBrumePipeline> defaults;
  vtkNew<vtkBrumePipeline> pipeline;
  pipeline->SetInputData(scene);
  pipeline->GetTracer()->SetNumberOfParticles(777); // before: the scene's setting wins
  Check(pipeline->ApplySceneSettings(), "the scene's settings are applied");
  Check(pipeline->GetTracer()->GetNumberOfParticles() == 1234 &&
      pipeline->GetTracer()->GetSeed() == 9 &&
      pipeline->GetReconstruction()->GetRadiosityThreshold() == 32.0 &&
      pipeline->GetSize()[0] == 40 && pipeline->GetSize()[1] == 24 &&
      pipeline->GetExposure() == 2.5,
    "particles, seed, threshold, size and exposure come from the scene");
  Check(pipeline->GetCamera()->GetPosition()[2] == 9.0, "the camera comes from the scene");
  Check(pipeline->GetTracer()->GetMaximumDepth() == defaults->GetTracer()->GetMaximumDepth(),
    "what the scene does not set keeps the filter's default");
  pipeline->GetTracer()->SetNumberOfParticles(2000); // after: the user's wins
  Check(pipeline->GetTracer()->GetNumberOfParticles() == 2000, "a setting after the scene's wins");

  // Without ApplySceneSettings the scene's camera is still the default view.
  vtkNew<vtkBrumePipeline> plain;
  plain->SetInputData(scene);
  plain->GetTracer()->SetNumberOfParticles(2000);
  Check(plain->Update(), "a pipeline without the scene's settings updates");
  Check(plain->GetCamera()->GetPosition()[2] == 9.0 &&
      plain->GetTracer()->GetNumberOfParticles() == 2000 &&
      plain->GetSize()[0] == defaults->GetSize()[0],
    "Update takes the scene's camera, not its render settings");
}

void TestFailures(vtkAlgorithm* scene)
{
  vtkNew<vtkBrumePipeline> empty;
  Check(!empty->Update() && std::string(empty->GetFailedPhase()) == "the scene",
    "no scene: Update fails at the scene");
  auto pipeline = MakePipeline(scene);
  pipeline->GetTracer()->SetNumberOfParticles(2000);
  Check(pipeline->Update(), "a small run updates");
  Check(!pipeline->AddParticles(1000) &&
      std::string(pipeline->GetFailedPhase()) == "particle tracing" &&
      pipeline->GetTracer()->GetNumberOfParticles() == 2000,
    "AddParticles without Progressive fails and keeps the run");
  pipeline->SetSize(0, 10);
  Check(!pipeline->RenderImage() && std::string(pipeline->GetFailedPhase()) == "rendering",
    "an empty size fails at rendering");
  auto invalid = MakePipeline(scene);
  invalid->GetTracer()->SetNumberOfParticles(0);
  Check(!invalid->Update() && std::string(invalid->GetFailedPhase()) == "particle tracing",
    "no particles: Update fails at particle tracing");
}
}

int TestPipeline(int, char*[])
{
  vtkNew<vtkBrumeDefaultSceneSource> scene;
  scene->Update();
  TestSameAsByHand(scene);
  TestSceneSettings(scene);
  std::cerr << "(errors expected below)\n";
  TestFailures(scene);
  if (Failures == 0)
  {
    std::cout << "vtkBrumePipeline: wiring, scene settings, batches, progressive, failures: ok\n";
  }
  return Failures == 0 ? 0 : 1;
}
