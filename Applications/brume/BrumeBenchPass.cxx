// SPDX-License-Identifier: BSD-3-Clause
// `brume bench`: a VTK program's renderer lit by Brume through its render
// pass (vtkBrumePass): the first frame, the progressive frames to the
// budget against the budget at once, a new view, the frame after an edit,
// and edits of the volume's transfer functions.
#include "BrumeBench.h"

#include "vtkActor.h"
#include "vtkBrumePass.h"
#include "vtkBrumePipeline.h"
#include "vtkBrumeRadianceReconstruction.h"
#include "vtkBrumeRenderWindowSelection.h"
#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkFixedPointVolumeRayCastMapper.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPlaneSource.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRTAnalyticSource.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

namespace BrumeBench
{
namespace
{
// What the bench edits.
struct Scene
{
  vtkSmartPointer<vtkActor> Ground;
  vtkSmartPointer<vtkPiecewiseFunction> Opacity;
  vtkSmartPointer<vtkColorTransferFunction> Colour;
};

// The program of Examples/Python/vtk_scene_pass.py: a ground, a sphere,
// VTK's Wavelet as a volume (`points` per axis, the same size in the
// scene whatever their number), one positional light of VTK intensity 1.
Scene BuildScene(vtkRenderer* renderer, int points)
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-4, -1, 4);
  plane->SetPoint1(4, -1, 4);
  plane->SetPoint2(-4, -1, -4);
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(1.3, -0.35, 0.3);
  sphere->SetRadius(0.65);
  sphere->SetThetaResolution(64);
  sphere->SetPhiResolution(48);
  vtkSmartPointer<vtkActor> ground;
  for (vtkAlgorithm* source :
    { static_cast<vtkAlgorithm*>(plane), static_cast<vtkAlgorithm*>(sphere) })
  {
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(source->GetOutputPort());
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->GetProperty()->SetColor(0.7, 0.7, 0.7);
    renderer->AddActor(actor);
    ground = ground ? ground : vtkSmartPointer<vtkActor>(actor);
  }
  vtkNew<vtkRTAnalyticSource> wavelet;
  const int half = (points - 1) / 2;
  wavelet->SetWholeExtent(
    -half, points - 1 - half, -half, points - 1 - half, -half, points - 1 - half);
  vtkNew<vtkFixedPointVolumeRayCastMapper> mapper;
  mapper->SetInputConnection(wavelet->GetOutputPort());
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(90, 0.0);
  opacity->AddPoint(170, 0.15);
  opacity->AddPoint(280, 0.7);
  vtkNew<vtkColorTransferFunction> colour;
  colour->AddRGBPoint(90, 0.4, 0.6, 1.0);
  colour->AddRGBPoint(280, 1.0, 0.85, 0.7);
  vtkNew<vtkVolumeProperty> property;
  property->SetScalarOpacity(opacity);
  property->SetColor(colour);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  volume->SetProperty(property);
  volume->SetScale(0.08 * 20.0 / (points - 1));
  volume->SetPosition(-1.0, -0.1, 0.0);
  renderer->AddVolume(volume);
  vtkNew<vtkLight> light;
  light->SetLightTypeToSceneLight();
  light->SetPositional(true);
  light->SetConeAngle(180);
  light->SetPosition(1.5, 4, 3);
  renderer->AddLight(light);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(0, 2.2, 8);
  camera->SetFocalPoint(0, -0.3, 0);
  camera->SetViewAngle(35);
  renderer->ResetCameraClippingRange();
  return { ground, opacity, colour };
}

double Frame(vtkRenderWindow* window)
{
  const auto start = std::chrono::steady_clock::now();
  window->Render();
  window->WaitForCompletion();
  return Seconds(start);
}
}

// Renders until the pass holds its whole budget; the seconds it took.
double Converge(vtkRenderWindow* window, vtkBrumePass* pass)
{
  double seconds = 0.0;
  for (int k = 0; k < 64 && !pass->IsConverged(); ++k)
  {
    seconds += Frame(window);
  }
  return seconds;
}

void BenchPass(long long particles, int volumePoints, Report& report)
{
  if (!vtkBrumeRenderWindowSelection::Install())
  {
    std::printf("render pass        skipped: %s\n", vtkBrumeRenderWindowSelection::GetLastError());
    return;
  }
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->SetSize(512, 512);
  window->AddRenderer(renderer);
  const Scene scene = BuildScene(renderer, volumePoints);
  const vtkSmartPointer<vtkActor>& ground = scene.Ground;
  vtkNew<vtkBrumePass> pass;
  pass->SetNumberOfParticles(particles);
  renderer->SetPass(pass);
  // Progressive (the default): the first frame, then frames to the budget.
  const double first = Frame(window);
  const double full = first + Converge(window, pass);
  const int steps = pass->GetNumberOfSteps();
  // New views once converged: a 2 degree turn a frame, the median of 10.
  std::vector<double> views;
  for (int k = 0; k < 10; ++k)
  {
    renderer->GetActiveCamera()->Azimuth(2.0);
    views.push_back(Frame(window));
  }
  std::sort(views.begin(), views.end());
  const double view = 0.5 * (views[4] + views[5]);
  // An edit: the ground's colour, traced and reconstructed again.
  ground->GetProperty()->SetColor(0.6, 0.7, 0.8);
  const double edit = Frame(window);
  Converge(window, pass);
  // The budget at once (as brume render traces it), after another edit.
  pass->ProgressiveOff();
  ground->GetProperty()->SetColor(0.7, 0.7, 0.7);
  const double once = Frame(window);
  std::printf("render pass        %8.3f s first frame, %.3f s to the budget in %d more frames "
              "(%.3f s at once: x%.2f), %.1f ms a new view (median of 10), %.3f s the frame after "
              "a colour edit, 512x512, a VTK program's scene\n",
    first, full, steps, once, full / once, 1e3 * view, edit);
  report.Add("pass_first_frame", first, "s", "<= 0.3",
    "vtkBrumePass, a VTK program's first frame (progressive: its first step)");
  report.Add("pass_full_budget", full / once, "x", "<= 1.1",
    "progressive frames to the budget over the budget traced at once");
  report.Add("pass_new_view", 1e3 * view, "ms", "<= 17", "a 2 degree turn, median of 10");
  report.Add("pass_edit_frame", edit, "s", "<= 0.3", "after a vtkProperty colour edit");

  // Edits of the volume's transfer functions, progressive: an opacity
  // point between two of the function's (the extinction's bricks whose
  // scalars lie elsewhere are kept), then a colour point (the extinction
  // and the shadow rays kept): the first frame after each, and the frames
  // to the budget.
  pass->ProgressiveOn();
  Converge(window, pass);
  vtkBrumeRadianceReconstruction* reconstruction = pass->GetPipeline()->GetReconstruction();
  const vtkIdType sampled = reconstruction->GetNumberOfNativeBricksSampled();
  const vtkIdType reused = reconstruction->GetNumberOfNativeBricksReused();
  scene.Opacity->AddPoint(220, 0.45);
  const double opacityFirst = Frame(window);
  const double opacityFull = opacityFirst + Converge(window, pass);
  const vtkIdType resampled = reconstruction->GetNumberOfNativeBricksSampled() - sampled;
  const vtkIdType kept = reconstruction->GetNumberOfNativeBricksReused() - reused;
  scene.Colour->AddRGBPoint(220, 1.0, 0.5, 0.3);
  const double colourFirst = Frame(window);
  const double colourFull = colourFirst + Converge(window, pass);
  // A later opacity edit, as a user makes them one after another: the
  // extinction is sampled again into memory the grid before the last one
  // held, not into fresh pages (brume::FloatBuffer).
  scene.Opacity->AddPoint(200, 0.3);
  const double againFirst = Frame(window);
  const double againFull = againFirst + Converge(window, pass);
  std::printf("transfer functions %8.3f s the first frame after an opacity edit, %.3f s to the "
              "budget (%lld bricks of extinction sampled again, %lld kept); %.3f s and %.3f s "
              "after a colour edit; %.3f s and %.3f s after a second opacity edit (the Wavelet "
              "at %d^3, 512x512)\n",
    opacityFirst, opacityFull, static_cast<long long>(resampled), static_cast<long long>(kept),
    colourFirst, colourFull, againFirst, againFull, volumePoints);
  // The edits' targets are a 512^3 volume's (--volume-size 512).
  const bool large = volumePoints >= 512;
  const std::string size = " (Wavelet " + std::to_string(volumePoints) + "^3)";
  report.Add("pass_opacity_edit_first", opacityFirst, "s", large ? "<= 0.3" : "",
    "the first frame after an opacity edit" + size);
  report.Add("pass_opacity_edit_full", opacityFull, "s", large ? "<= 3" : "",
    "an opacity edit to the budget" + size);
  report.Add("pass_colour_edit_first", colourFirst, "s", large ? "<= 0.3" : "",
    "the first frame after a colour edit of the volume" + size);
  report.Add("pass_colour_edit_full", colourFull, "s", large ? "<= 3" : "",
    "a colour edit of the volume to the budget" + size);
  report.Add("pass_opacity_edit_again_first", againFirst, "s", large ? "<= 0.3" : "",
    "the first frame after a second opacity edit" + size);
  report.Add("pass_opacity_edit_again_full", againFull, "s", large ? "<= 3" : "",
    "a second opacity edit to the budget" + size);

  // The same edits previewed (PreviewEdits): the first frame draws the
  // last light under the new functions; the trace follows.
  pass->PreviewEditsOn();
  scene.Opacity->AddPoint(240, 0.6);
  const double opacityPreview = Frame(window);
  const int previews = pass->GetNumberOfPreviews();
  Converge(window, pass);
  scene.Colour->AddRGBPoint(240, 1.0, 0.8, 0.4);
  const double colourPreview = Frame(window);
  Converge(window, pass);
  std::printf("previewed edits    %8.3f s the preview after an opacity edit, %.3f s after a "
              "colour edit (%d of 2 previewed)\n",
    opacityPreview, colourPreview, pass->GetNumberOfPreviews());
  if (previews == 1 && pass->GetNumberOfPreviews() == 2)
  {
    report.Add("pass_opacity_edit_preview", opacityPreview, "s", large ? "<= 0.3" : "",
      "the previewed frame after an opacity edit" + size);
    report.Add("pass_colour_edit_preview", colourPreview, "s", large ? "<= 0.3" : "",
      "the previewed frame after a colour edit" + size);
  }
}
}
