// SPDX-License-Identifier: BSD-3-Clause
#include "BrumeView.h"
#include "BrumeProgress.h"

#include "vtkBrumeDisplayPass.h"
#include "vtkBrumeLightTracer.h"
#include "vtkBrumePipeline.h"
#include "vtkBrumeRadianceReconstruction.h"
#include "vtkBrumeSceneActors.h"
#include "vtkBrumeSliceVolumeMapper.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkInteractorStyleTrackballCamera.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPolyData.h"
#include "vtkPropCollection.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"
#include "vtkTextActor.h"
#include "vtkTextProperty.h"
#include "vtkVolume.h"
#include "vtkWindowToImageFilter.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <vector>

namespace
{
using Clock = std::chrono::steady_clock;

double Milliseconds(Clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// The q-quantile of the values (nearest rank).
double Quantile(std::vector<double> values, double q)
{
  if (values.empty())
  {
    return 0.0;
  }
  std::sort(values.begin(), values.end());
  const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(values.size())));
  return values[std::min(values.size() - 1, rank > 0 ? rank - 1 : 0)];
}

std::string Thousands(long long n)
{
  std::string digits = std::to_string(n), out;
  for (std::size_t i = 0; i < digits.size(); ++i)
  {
    if (i > 0 && (digits.size() - i) % 3 == 0)
    {
      out += ',';
    }
    out += digits[i];
  }
  return out;
}

// The three phases behind a window: tracing once (and progressively more),
// reconstruction before every frame, rendering.
class Viewer
{
public:
  // `pipeline`: configured (ConfigurePipeline), with a display installed.
  Viewer(const ViewOptions& options, vtkBrumePipeline* pipeline)
    : Options(options)
    , Pipeline(pipeline)
  {
  }

  // The pipeline, configured from the options; phases 1 and 2, then the
  // window around the scene's props.
  bool Start()
  {
    this->Pipeline->ProgressiveOn(); // p adds particles to the histograms
    this->Reconstruction->SetDirectionalRadiance(this->Options.Directional);
    this->Reconstruction->SetDirectionalOrder(this->Options.Order);
    BrumeShowProgress(this->Pipeline->GetTracer(), "particle tracing");
    // A volume the GPU cannot hold at its own resolution is coarsened to
    // fit (where the driver says what it has free), asked, as brume render
    // asks, of the pipeline's offscreen window: the viewer's own is made
    // after the first trace, on the same driver.
    this->Pipeline->LimitToGPUMemory(this->Pipeline->GetImageWindow());
    if (!this->Pipeline->Update())
    {
      std::cerr << "brume: " << this->Pipeline->GetFailedPhase() << " failed.\n";
      return false;
    }
    this->LastTrace = 1000.0 * this->Pipeline->GetTracingSeconds();
    this->FirstReconstruction = 1000.0 * this->Pipeline->GetReconstructionSeconds();

    this->Renderer->SetBackground(0, 0, 0);
    this->Display->SetExposure(this->Pipeline->GetExposure());
    this->Renderer->SetPass(this->Display);
    this->Window->SetMultiSamples(0);
    this->Window->SetSize(this->Pipeline->GetSize());
    this->Window->SetWindowName("Brume");
    this->Window->AddRenderer(this->Renderer);
    if (!this->Pipeline->AddToRenderer(this->Renderer))
    {
      return false;
    }
    vtkPropCollection* props = this->Actors->GetProps();
    props->InitTraversal();
    while (vtkProp* prop = props->GetNextProp())
    {
      if (auto* volume = vtkVolume::SafeDownCast(prop))
      {
        vtkBrumeSliceVolumeMapper::SafeDownCast(volume->GetMapper())
          ->SetDirectionalEvaluation(this->Options.PerFragment
              ? vtkBrumeSliceVolumeMapper::PerFragment
              : vtkBrumeSliceVolumeMapper::PerVoxel);
      }
    }
    this->Overlay->GetTextProperty()->SetFontSize(12);
    this->Overlay->GetTextProperty()->SetColor(1.0, 1.0, 0.6);
    this->Overlay->SetDisplayPosition(8, 8);
    this->Overlay->SetVisibility(this->Options.Overlay);
    this->Renderer->AddActor2D(this->Overlay);
    this->Renderer->ResetCameraClippingRange();
    this->ShowOverlay(true);
    return true;
  }

  long long Particles() const
  {
    return static_cast<long long>(this->Pipeline->GetTracer()->GetNumberOfParticles());
  }

  // Brings the textures up to date with the camera and the settings; false
  // on failure. Only what changed is recomputed and uploaded.
  bool Update()
  {
    const auto start = Clock::now();
    this->Renderer->ResetCameraClippingRange();
    if (!this->Pipeline->UpdateView())
    {
      std::cerr << "brume: reconstruction failed.\n";
      return false;
    }
    this->LastUpdate = Milliseconds(start);
    return true;
  }

  // A frame: update, then render to completion; the times are kept.
  bool Frame()
  {
    if (!this->Update())
    {
      return false;
    }
    const auto start = Clock::now();
    this->Window->Render();
    this->Window->WaitForCompletion();
    this->LastRender = Milliseconds(start);
    return true;
  }

  // The viewer's keys; false if the key is not one of them.
  bool Key(char key)
  {
    switch (key)
    {
      case 'p':
      case '+':
        // Progressive: the next particles are added to the histograms (at
        // once: the reconstruction holds the hits of one step at a time).
        this->MoreParticles();
        break;
      case 'd':
        this->Reconstruction->SetDirectionalRadiance(
          !this->Reconstruction->GetDirectionalRadiance());
        break;
      case 'm':
        this->MediaVisible = !this->MediaVisible;
        this->Actors->SetMediaVisibility(this->MediaVisible);
        break;
      case 's':
        this->Screenshot();
        break;
      case 'n':
      case 'b':
        this->StepTime(key == 'n' ? 1 : -1);
        break;
      default:
        return false;
    }
    this->ShowOverlay(true);
    return true;
  }

  // Doubles the particles; on failure the viewer keeps the textures it has.
  void MoreParticles()
  {
    const long long total = this->Particles();
    if (total > 5000000000LL)
    {
      std::cerr << "brume: already " << Thousands(total) << " particles; not adding more.\n";
      return;
    }
    const auto start = Clock::now();
    this->Renderer->ResetCameraClippingRange();
    if (this->Pipeline->AddParticles(total))
    {
      this->LastTrace = 1000.0 * this->Pipeline->GetTracingSeconds();
      this->LastUpdate = Milliseconds(start) - this->LastTrace;
      return;
    }
    std::cerr << "brume: cannot add particles; keeping " << Thousands(total) << ".\n";
  }

  // A scene that changes over time: the next (+1) or previous (-1) time
  // step, traced with the particles the view has and reconstructed (what
  // does not change is not read again); on failure the viewer keeps the
  // step it shows.
  void StepTime(int direction)
  {
    const int steps = this->Pipeline->GetNumberOfTimeSteps();
    if (steps == 0)
    {
      std::cerr << "brume: the scene does not change over time (no medium lists its files per "
                   "time step).\n";
      return;
    }
    const int step = std::max(0, std::min(steps - 1, this->TimeStep + direction));
    if (step == this->TimeStep)
    {
      return;
    }
    const auto start = Clock::now();
    this->Pipeline->SetTime(this->Pipeline->GetTimeStep(step));
    if (!this->Pipeline->Update())
    {
      std::cerr << "brume: " << this->Pipeline->GetFailedPhase() << " failed at time step " << step
                << "; showing step " << this->TimeStep << ".\n";
      this->Pipeline->SetTime(this->Pipeline->GetTimeStep(this->TimeStep));
      this->Pipeline->Update();
      return;
    }
    this->TimeStep = step;
    this->LastTrace = 1000.0 * this->Pipeline->GetTracingSeconds();
    std::printf("time step %d of %d (t = %g): traced in %.3f s, reconstructed in %.3f s (%.3f s "
                "in all)\n",
      step, steps, this->Pipeline->GetTimeStep(step), this->Pipeline->GetTracingSeconds(),
      this->Pipeline->GetReconstructionSeconds(), Milliseconds(start) / 1000.0);
    std::fflush(stdout);
  }

  bool Save(const std::string& file)
  {
    vtkNew<vtkWindowToImageFilter> grab;
    grab->SetInput(this->Window);
    grab->ReadFrontBufferOff();
    vtkNew<vtkPNGWriter> writer;
    writer->SetFileName(file.c_str());
    writer->SetInputConnection(grab->GetOutputPort());
    writer->Write();
    if (writer->GetErrorCode() != 0)
    {
      std::cerr << "brume: could not write " << file << "\n";
      return false;
    }
    return true;
  }

  void Screenshot()
  {
    char name[64];
    std::snprintf(name, sizeof(name), "brume-view-%04d.png", this->Screenshots++);
    if (this->Save(name))
    {
      std::cout << "saved " << name << "\n";
    }
  }

  // The overlay's text; the frame times at most four times a second
  // (redrawing the text costs 4 ms a frame under llvmpipe, and faster
  // changes cannot be read), anything else (`force`) at once.
  void ShowOverlay(bool force = false)
  {
    if (!force && Milliseconds(this->OverlayShown) < 250.0)
    {
      return;
    }
    this->OverlayShown = Clock::now();
    char time[96] = "";
    const int steps = this->Pipeline->GetNumberOfTimeSteps();
    if (steps > 0)
    {
      std::snprintf(time, sizeof(time), "time step %d of %d (t = %g)   n / b next / previous\n",
        this->TimeStep, steps, this->Pipeline->GetTimeStep(this->TimeStep));
    }
    char text[640];
    std::snprintf(text, sizeof(text),
      "%s particles (traced in %.2f s)   media: %s\n"
      "%slast frame: update %.1f ms, render %.1f ms\n"
      "p more particles   d paper / SH   m medium   s screenshot   q quit",
      Thousands(this->Particles()).c_str(), this->LastTrace / 1000.0,
      this->Reconstruction->GetDirectionalRadiance() ? "spherical harmonics" : "per view (paper)",
      time, this->LastUpdate, this->LastRender);
    this->Overlay->SetInput(text);
  }

  // The first image on screen: how long since `start` (the command's
  // start), and its phases (`brume bench` times the line from outside).
  void PrintFirstImage(Clock::time_point start) const
  {
    std::printf("first image: %.3f s after the command started (tracing %.3f s, reconstruction "
                "%.3f s, first frame %.3f s with texture upload and shader compilation)\n",
      Milliseconds(start) / 1000.0, this->LastTrace / 1000.0, this->FirstReconstruction / 1000.0,
      (this->LastUpdate + this->LastRender) / 1000.0);
    std::fflush(stdout);
  }

  const ViewOptions& Options;
  double LastUpdate = 0.0, LastRender = 0.0, LastTrace = 0.0, FirstReconstruction = 0.0;
  Clock::time_point OverlayShown;
  bool MediaVisible = true;
  int Screenshots = 0;
  int TimeStep = 0; // of a scene that changes over time: the step shown
  vtkSmartPointer<vtkBrumePipeline> Pipeline;
  vtkBrumeRadianceReconstruction* Reconstruction = Pipeline->GetReconstruction();
  vtkBrumeSceneActors* Actors = Pipeline->GetActors();
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkRenderWindow> Window;
  vtkNew<vtkBrumeDisplayPass> Display;
  vtkNew<vtkTextActor> Overlay;
};

// N frames around the focal point, each timed; prints medians and 95th
// percentiles and the work the reconstruction did during the orbit.
int Orbit(Viewer& viewer, const ViewOptions& options, Clock::time_point commandStart)
{
  if (!options.FramesOut.empty())
  {
    std::error_code error;
    std::filesystem::create_directories(options.FramesOut, error);
    if (error)
    {
      std::cerr << "brume: cannot create " << options.FramesOut << ": " << error.message() << "\n";
      return 1;
    }
  }
  // The first image, at full resolution as the interactive viewer's, then
  // a frame at the moving sample distance (the camera moves all along):
  // they compile shaders and upload every texture, and are not counted.
  if (!viewer.Frame())
  {
    return 1;
  }
  viewer.PrintFirstImage(commandStart);
  viewer.Actors->SetImageSampleDistance(options.MovingSampleDistance);
  if (!viewer.Frame())
  {
    return 1;
  }
  viewer.ShowOverlay(); // each frame shows the previous frame's times
  vtkBrumeRadianceReconstruction* reconstruction = viewer.Reconstruction;
  const vtkIdType builds = reconstruction->GetNumberOfTextureBuilds();
  const vtkIdType updates = reconstruction->GetNumberOfViewUpdates();
  std::vector<double> update, render, total;
  std::ofstream csv;
  if (!options.Csv.empty())
  {
    csv.open(options.Csv);
    if (!csv)
    {
      std::cerr << "brume: cannot write " << options.Csv << "\n";
      return 1;
    }
    csv << "frame,update_ms,render_ms\n";
  }
  for (int k = 0; k < options.Orbit; ++k)
  {
    viewer.Renderer->GetActiveCamera()->Azimuth(360.0 / options.Orbit);
    viewer.Renderer->GetActiveCamera()->OrthogonalizeViewUp();
    if (!viewer.Frame())
    {
      return 1;
    }
    update.push_back(viewer.LastUpdate);
    render.push_back(viewer.LastRender);
    total.push_back(viewer.LastUpdate + viewer.LastRender);
    if (csv)
    {
      csv << k << ',' << viewer.LastUpdate << ',' << viewer.LastRender << '\n';
    }
    if (!options.FramesOut.empty())
    {
      char name[32];
      std::snprintf(name, sizeof(name), "/frame_%04d.png", k);
      if (!viewer.Save(options.FramesOut + name))
      {
        return 1;
      }
    }
    viewer.ShowOverlay();
  }
  std::printf("orbit: %d frames at %dx%d, media %s at image sample distance %g, %s particles\n",
    options.Orbit, viewer.Pipeline->GetSize()[0], viewer.Pipeline->GetSize()[1],
    !reconstruction->GetDirectionalRadiance() ? "per view (paper)"
      : options.PerFragment                   ? "spherical harmonics (per fragment)"
                                              : "spherical harmonics (per voxel)",
    viewer.Actors->GetLastImageSampleDistance(), Thousands(viewer.Particles()).c_str());
  std::printf("per frame        median (ms)   95th percentile (ms)\n");
  std::printf("update           %11.2f   %20.2f\n", Quantile(update, 0.5), Quantile(update, 0.95));
  std::printf("render           %11.2f   %20.2f\n", Quantile(render, 0.5), Quantile(render, 0.95));
  std::printf("update + render  %11.2f   %20.2f\n", Quantile(total, 0.5), Quantile(total, 0.95));
  std::printf("texture builds during the orbit: %lld\n",
    static_cast<long long>(reconstruction->GetNumberOfTextureBuilds() - builds));
  std::printf("view-dependent texture updates during the orbit: %lld\n",
    static_cast<long long>(reconstruction->GetNumberOfViewUpdates() - updates));
  return 0;
}

// While the camera moves the media are drawn coarser; the style renders
// once more at full resolution when the button is released.
void CoarserWhileMoving(Viewer& viewer, vtkInteractorStyle* style)
{
  vtkNew<vtkCallbackCommand> moving, still;
  moving->SetClientData(&viewer);
  moving->SetCallback(
    [](vtkObject*, unsigned long, void* data, void*)
    {
      auto* view = static_cast<Viewer*>(data);
      view->Actors->SetImageSampleDistance(view->Options.MovingSampleDistance);
    });
  still->SetClientData(&viewer);
  still->SetCallback([](vtkObject*, unsigned long, void* data, void*)
    { static_cast<Viewer*>(data)->Actors->SetImageSampleDistance(1.0); });
  style->AddObserver(vtkCommand::StartInteractionEvent, moving);
  style->AddObserver(vtkCommand::EndInteractionEvent, still);
}

// --exit-after N: a timer presses the --keys through the interactor, then
// turns the camera 5 degrees a frame for N frames and quits (for tests and
// demonstrations of the interactive path itself).
struct Script
{
  Viewer* View;
  vtkRenderWindowInteractor* Interactor;
  std::string Keys;
  int Frames, Done;
  vtkIdType Builds, Updates;
};

void InstallScript(Script& script, vtkRenderWindowInteractor* interactor, vtkCallbackCommand* tick)
{
  tick->SetClientData(&script);
  tick->SetCallback(
    [](vtkObject*, unsigned long, void* data, void*)
    {
      auto* run = static_cast<Script*>(data);
      for (const char key : run->Keys)
      {
        run->Interactor->SetKeyCode(key);
        run->Interactor->InvokeEvent(vtkCommand::CharEvent, nullptr);
      }
      if (run->Done == 0)
      {
        // The keys' own renders are not counted.
        run->Builds = run->View->Reconstruction->GetNumberOfTextureBuilds();
        run->Updates = run->View->Reconstruction->GetNumberOfViewUpdates();
      }
      run->Keys.clear();
      if (run->Done++ == run->Frames)
      {
        run->Interactor->TerminateApp();
        return;
      }
      run->View->Renderer->GetActiveCamera()->Azimuth(5.0);
      run->Interactor->Render();
    });
  interactor->AddObserver(vtkCommand::TimerEvent, tick);
  interactor->CreateRepeatingTimer(1);
}

// The interactive window: before each frame the textures follow the camera;
// after it the overlay shows what the frame cost.
int Interact(Viewer& viewer, const ViewOptions& options, Clock::time_point commandStart)
{
  vtkNew<vtkRenderWindowInteractor> interactor;
  vtkNew<vtkInteractorStyleTrackballCamera> style;
  interactor->SetInteractorStyle(style);
  interactor->SetRenderWindow(viewer.Window);
  Clock::time_point frameStart;
  bool failed = false;
  vtkNew<vtkCallbackCommand> before, after, keys;
  struct Hooks
  {
    Viewer* View;
    Clock::time_point* Start;
    bool* Failed;
  } hooks{ &viewer, &frameStart, &failed };
  before->SetClientData(&hooks);
  before->SetCallback(
    [](vtkObject*, unsigned long, void* data, void*)
    {
      auto* h = static_cast<Hooks*>(data);
      if (!h->View->Update())
      {
        *h->Failed = true;
        h->View->Window->GetInteractor()->TerminateApp();
      }
      *h->Start = Clock::now();
    });
  after->SetClientData(&hooks);
  after->SetCallback(
    [](vtkObject*, unsigned long, void* data, void*)
    {
      auto* h = static_cast<Hooks*>(data);
      h->View->LastRender = Milliseconds(*h->Start);
      h->View->ShowOverlay();
    });
  struct KeyHook
  {
    Viewer* View;
    vtkCallbackCommand* Command;
  } keyHook{ &viewer, keys };
  keys->SetClientData(&keyHook);
  keys->SetCallback(
    [](vtkObject* caller, unsigned long, void* data, void*)
    {
      auto* hook = static_cast<KeyHook*>(data);
      auto* source = static_cast<vtkRenderWindowInteractor*>(caller);
      if (hook->View->Key(source->GetKeyCode()))
      {
        hook->Command->SetAbortFlag(1); // the style's own meaning of the key is not wanted
        source->Render();
      }
    });
  viewer.Window->AddObserver(vtkCommand::StartEvent, before);
  viewer.Window->AddObserver(vtkCommand::EndEvent, after);
  CoarserWhileMoving(viewer, style);
  // Before the style's own keys (p picks, s shows surfaces).
  interactor->AddObserver(vtkCommand::CharEvent, keys, 1.0);
  interactor->Initialize();
  viewer.Window->Render();
  viewer.Window->WaitForCompletion();
  viewer.PrintFirstImage(commandStart);

  // --exit-after N: a timer presses the --keys, turns the camera and quits.
  Script script{ &viewer, interactor, options.Keys, options.ExitAfter, 0,
    viewer.Reconstruction->GetNumberOfTextureBuilds(),
    viewer.Reconstruction->GetNumberOfViewUpdates() };
  vtkNew<vtkCallbackCommand> tick;
  if (options.ExitAfter > 0)
  {
    InstallScript(script, interactor, tick);
  }
  interactor->Start();
  if (options.ExitAfter > 0)
  {
    std::printf("interactive: %d frames, %s particles, media %s\n", options.ExitAfter,
      Thousands(viewer.Particles()).c_str(),
      viewer.Reconstruction->GetDirectionalRadiance() ? "spherical harmonics" : "per view (paper)");
    std::printf("texture builds during the frames: %lld\n",
      static_cast<long long>(viewer.Reconstruction->GetNumberOfTextureBuilds() - script.Builds));
    std::printf("view-dependent texture updates during the frames: %lld\n",
      static_cast<long long>(viewer.Reconstruction->GetNumberOfViewUpdates() - script.Updates));
  }
  return failed ? 1 : 0;
}
}

int RunView(const ViewOptions& options)
{
  const auto commandStart = Clock::now();
  // The scene first: a bad file is reported with or without a display.
  vtkNew<vtkBrumePipeline> pipeline;
  if (!ConfigurePipeline(pipeline, options.Render))
  {
    return 1;
  }
  if (!HasDisplay("the viewer", options.Orbit == 0))
  {
    return 1;
  }
  Viewer viewer(options, pipeline);
  if (options.Orbit > 0)
  {
    viewer.Window->SetOffScreenRendering(1);
  }
  if (!viewer.Start())
  {
    return 1;
  }
  if (options.Orbit > 0)
  {
    for (const char key : options.Keys)
    {
      viewer.Key(key);
    }
    return Orbit(viewer, options, commandStart);
  }
  return Interact(viewer, options, commandStart);
}
