// SPDX-License-Identifier: BSD-3-Clause
#include "BrumeRender.h"
#include "BrumeProgress.h"

#include "vtkBrumeDefaultSceneSource.h"
#include "vtkBrumeFloatImageCapture.h"
#include "vtkBrumeLightTracer.h"
#include "vtkBrumeProcesses.h"
#include "vtkBrumeRadianceReconstruction.h"
#include "vtkBrumeReferencePathTracer.h"
#include "vtkBrumeRenderWindowSelection.h"
#include "vtkBrumeSceneActors.h"
#include "vtkBrumeSceneCamera.h"
#include "vtkBrumeSceneReader.h"
#include "vtkCamera.h"
#include "vtkCommunicator.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"
#include "vtkXMLImageDataWriter.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>

namespace
{
// Particles per batch of a run too large for one, at most (about 1.3 GB of
// hits in the default scene; larger batches were no faster).
constexpr long long LargestAutomaticBatch = 10000000;

double Seconds(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

bool EndsWith(const std::string& s, const std::string& suffix)
{
  return s.size() >= suffix.size() &&
    s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}

bool HasDisplay(const char* what, bool window)
{
  // X when DISPLAY names a display, else EGL (BRUME_RENDER_WINDOW chooses).
  if (!vtkBrumeRenderWindowSelection::Install())
  {
    std::cerr << "brume: " << what << ": " << vtkBrumeRenderWindowSelection::GetLastError()
              << ".\n";
    return false;
  }
  if (window && std::string(vtkBrumeRenderWindowSelection::GetInstalled()) != "x")
  {
    std::cerr << "brume: " << what
              << " shows a window and needs an X display (none is set in DISPLAY).\n";
    return false;
  }
  return true;
}

vtkSmartPointer<vtkAlgorithm> LoadScene(RenderOptions& options)
{
  vtkSmartPointer<vtkAlgorithm> source;
  if (options.Scene.empty() || options.Scene == "default")
  {
    source = vtkSmartPointer<vtkBrumeDefaultSceneSource>::New();
  }
  else
  {
    auto reader = vtkSmartPointer<vtkBrumeSceneReader>::New();
    reader->SetFileName(options.Scene.c_str());
    source = reader;
  }
  if (!source->GetExecutive()->Update())
  {
    std::cerr << "brume: cannot load the scene '" << options.Scene << "' (see the error above).\n";
    return nullptr;
  }
  vtkFieldData* fd = source->GetOutputDataObject(0)->GetFieldData();
  auto value = [&](const char* name, int component, double& out)
  {
    vtkDataArray* a = fd->GetArray(name);
    if (a && a->GetNumberOfTuples() > 0 && component < a->GetNumberOfComponents())
    {
      out = a->GetComponent(0, component);
      return true;
    }
    return false;
  };
  double v = 0;
  if (!options.ParticlesSet && value("BrumeRenderParticles", 0, v))
  {
    options.Particles = static_cast<long long>(v);
  }
  if (!options.SizeSet && value("BrumeRenderSize", 0, v))
  {
    options.Width = static_cast<int>(v);
    value("BrumeRenderSize", 1, v);
    options.Height = static_cast<int>(v);
  }
  if (!options.ThresholdSet && value("BrumeRenderThreshold", 0, v))
  {
    options.Threshold = v;
  }
  if (!options.SeedSet && value("BrumeRenderSeed", 0, v))
  {
    options.Seed = static_cast<std::uint64_t>(v);
  }
  if (!options.ExposureSet && value("BrumeRenderExposure", 0, v))
  {
    options.Exposure = v;
  }
  return source;
}

namespace
{
// Writes next to the output under a temporary name and renames it on
// success, so that a failure never leaves a partial image behind.
int WriteImage(vtkImageData* radiance, const RenderOptions& options, bool png)
{
  const std::string partial = options.Output + ".partial";
  bool ok = false;
  if (png)
  {
    vtkNew<vtkPNGWriter> writer;
    writer->SetFileName(partial.c_str());
    writer->SetInputData(vtkBrumeFloatImageCapture::ToneMap(radiance, options.Exposure));
    writer->Write();
    ok = writer->GetErrorCode() == 0;
  }
  else
  {
    vtkNew<vtkXMLImageDataWriter> writer;
    writer->SetFileName(partial.c_str());
    writer->SetInputData(radiance);
    writer->SetDataModeToBinary(); // readable despite expat reparse deferral (see README)
    ok = writer->Write() != 0;
  }
  std::error_code error;
  if (ok)
  {
    std::filesystem::rename(partial, options.Output, error);
    ok = !error;
  }
  if (!ok)
  {
    std::filesystem::remove(partial, error);
    std::cerr << "brume: could not write " << options.Output << "\n";
    return 1;
  }
  return 0;
}

// The reference image: the unbiased path tracer (no display needed).
int RunReference(RenderOptions options, bool png)
{
  const vtkSmartPointer<vtkAlgorithm> scene = LoadScene(options);
  if (!scene)
  {
    return 1;
  }
  vtkNew<vtkBrumeReferencePathTracer> reference;
  reference->SetInputConnection(scene->GetOutputPort());
  reference->SetSize(options.Width, options.Height);
  reference->SetSamplesPerPixel(options.SamplesPerPixel);
  reference->SetSeed(options.Seed);
  reference->SetMaximumDepth(options.MaxDepth);
  BrumeShowProgress(reference, "path tracing");
  const auto start = std::chrono::steady_clock::now();
  if (!reference->GetExecutive()->Update())
  {
    std::cerr << "brume: reference rendering failed.\n";
    return 1;
  }
  const double seconds = Seconds(start);
  if (options.Timings)
  {
    std::printf("reference path tracing %8.3f s   %d samples per pixel at %dx%d\n", seconds,
      options.SamplesPerPixel, options.Width, options.Height);
  }
  return WriteImage(reference->GetOutput(), options, png);
}
// What `--timings` prints: each phase's time (the paper's Table 1), then
// the memory of every radiance texture.
struct PhaseTimes
{
  double Tracing, Reconstructing, FirstFrame, Frame, ReductionSeconds;
  vtkTypeInt64 ReductionBytes;
  long long Hits, Rays; // this process's, over every batch
};

void PrintTextureMemory(vtkPartitionedDataSetCollection* textures)
{
  double total = 0.0;
  std::printf("texture memory (MB, VTK's count of the arrays' bytes)\n");
  for (unsigned int i = 0; i < textures->GetNumberOfPartitionedDataSets(); ++i)
  {
    vtkPartitionedDataSet* pds = textures->GetPartitionedDataSet(i);
    const char* name = textures->HasMetaData(i)
      ? textures->GetMetaData(i)->Get(vtkCompositeDataSet::NAME())
      : nullptr;
    for (unsigned int k = 0; pds && k < pds->GetNumberOfPartitions(); ++k)
    {
      auto* image = vtkImageData::SafeDownCast(pds->GetPartition(k));
      if (!image)
      {
        continue; // the surfaces' geometry is the scene's
      }
      int dims[3];
      image->GetDimensions(dims);
      const bool volume = dims[2] > 1;
      const double megabytes = static_cast<double>(image->GetActualMemorySize()) / 1024.0;
      total += megabytes;
      std::printf("  %-28s %-18s %5d x %5d x %5d %9.2f", name ? name : "(unnamed)",
        k == 0 ? (volume ? "source radiance" : "radiance") : "extinction (own)",
        volume ? dims[0] - 1 : dims[0], volume ? dims[1] - 1 : dims[1], volume ? dims[2] - 1 : 1,
        megabytes);
      // A sparse grid: the bricks it stores of those its box holds.
      vtkFieldData* fd = image->GetFieldData();
      const bool source = fd->GetArray("SourceBrickSlots") != nullptr;
      vtkDataArray* slots = fd->GetArray(source ? "SourceBrickSlots" : "ExtinctionBrickSlots");
      vtkDataArray* samples =
        fd->GetArray(source ? "SourceRadianceBrickSamples" : "ExtinctionBrickSamples");
      if (slots && samples)
      {
        std::printf("   sparse: %lld of %lld bricks",
          static_cast<long long>(samples->GetNumberOfTuples() / 512),
          static_cast<long long>(slots->GetNumberOfTuples()));
      }
      std::printf("\n");
    }
  }
  std::printf("  %-28s %-18s %23s %9.2f\n", "all textures", "", "", total);
}

void PrintTimings(const RenderOptions& options, vtkPartitionedDataSetCollection* textures,
  const PhaseTimes& t, int processes)
{
  std::printf("phase                time (s)\n");
  std::printf("particle tracing     %8.3f   %lld particles, %lld hits, %lld rays", t.Tracing,
    options.Particles, t.Hits, t.Rays);
  if (options.Batch > 0 && options.Batch < options.Particles)
  {
    std::printf(" in batches of %lld", options.Batch);
  }
  std::printf(processes > 1 ? " (process 0 of %d; time: the slowest)\n" : "\n", processes);
  std::printf("reconstruction       %8.3f", t.Reconstructing);
  if (processes > 1)
  {
    std::printf("   histograms summed across processes: %.1f MB sent and received in all, "
                "%.3f s in the reduction (the slowest process)\n",
      static_cast<double>(t.ReductionBytes) / 1e6, t.ReductionSeconds);
  }
  else
  {
    std::printf("\n");
  }
  std::printf("rendering            %8.3f   per frame at %dx%d (first frame %.3f s, with "
              "texture upload and shader compilation)\n",
    t.Frame, options.Width, options.Height, t.FirstFrame);
  PrintTextureMemory(textures);
}
}

int RunRender(RenderOptions options)
{
  const bool png = EndsWith(options.Output, ".png");
  if (!png && !EndsWith(options.Output, ".vti"))
  {
    std::cerr << "brume: the output must end in .png or .vti: " << options.Output << "\n";
    return 2;
  }
  if (options.Reference)
  {
    return RunReference(options, png);
  }
  // Under mpirun every process traces its share of the particles, the
  // histograms are summed across processes, process 0 renders and writes.
  // Any process failing stops all of them at the next agreement.
  vtkMultiProcessController* controller = vtkBrumeProcesses::GetGlobalController();
  const int rank = vtkBrumeProcesses::GetRank(controller);
  const int processes = vtkBrumeProcesses::GetSize(controller);

  // The scene first: a bad file is reported with or without a display.
  const vtkSmartPointer<vtkAlgorithm> scene = LoadScene(options);
  if (!vtkBrumeProcesses::AllSucceeded(scene != nullptr, "loading the scene"))
  {
    return 1;
  }
  if (!vtkBrumeProcesses::AllSucceeded(rank != 0 || HasDisplay("rendering"), "finding a display"))
  {
    return 1;
  }

  if (options.Batch > 0 && processes > 1)
  {
    if (rank == 0)
    {
      std::cerr << "brume: --batch runs in one process only (under mpirun, every process "
                   "traces its share at once).\n";
    }
    return 2;
  }
  vtkNew<vtkBrumeLightTracer> tracer;
  tracer->SetMemoryLimit(static_cast<vtkTypeInt64>(options.MemoryLimit * 1073741824.0));
  // A run whose hits would not fit the tracer's memory at once is traced in
  // batches that do, as --batch does: the particle count is bounded by time.
  const double limit = static_cast<double>(tracer->GetMemoryLimit());
  if (options.Batch == 0 && processes == 1 &&
    vtkBrumeLightTracer::ExpectedHitBytes(options.Particles) > limit)
  {
    const auto fit = static_cast<long long>(limit / vtkBrumeLightTracer::ExpectedHitBytes(1));
    options.Batch = std::max(1LL, std::min(LargestAutomaticBatch, fit));
    std::printf("%lld particles: traced in batches of %lld, their hits exceeding the memory "
                "limit (%g GiB) at once (--batch sets the size, --memory-limit the limit)\n",
      options.Particles, options.Batch, options.MemoryLimit);
  }
  tracer->SetInputConnection(scene->GetOutputPort());
  tracer->SetNumberOfParticles(options.Particles);
  tracer->SetSeed(options.Seed);
  tracer->SetMaximumDepth(options.MaxDepth);
  tracer->SetMediumAimFraction(options.MediumAim);
  tracer->SetSplitHeavyParticles(options.SplitHeavy);
  double position[3], focal[3], up[3], angle;
  vtkBrumeSceneCamera::GetSceneCamera(scene->GetOutputDataObject(0), position, focal, up, angle);
  vtkNew<vtkBrumeRadianceReconstruction> reconstruction;
  reconstruction->SetInputConnection(0, scene->GetOutputPort());
  reconstruction->SetInputConnection(1, tracer->GetOutputPort());
  reconstruction->SetEyePosition(position);
  reconstruction->SetRadiosityThreshold(options.Threshold);
  reconstruction->SetDirectLighting(options.DirectLight);
  reconstruction->SetCentroidMatching(options.CentroidMatching);
  // One image, one viewpoint: view-dependent objects bin toward it and keep
  // no hits, so that a run in batches holds one batch's hits at a time.
  reconstruction->SetFixedView(true);
  if (rank == 0)
  {
    BrumeShowProgress(tracer, "particle tracing");
    BrumeShowProgress(reconstruction, "reconstruction");
  }
  // Phases 1 and 2, at once or batch by batch (each batch's hits binned,
  // then released when the next is traced).
  const long long batch = options.Batch > 0 ? options.Batch : options.Particles;
  reconstruction->SetAccumulateParticles(batch < options.Particles);
  double tracing = 0.0, reconstructing = 0.0;
  long long hits = 0, rays = 0;
  for (long long first = 0; first < options.Particles; first += batch)
  {
    tracer->SetFirstParticle(first);
    tracer->SetEndParticle(std::min(first + batch, options.Particles));
    auto start = std::chrono::steady_clock::now();
    const bool traced = tracer->UpdatePiece(rank, processes, 0) != 0;
    if (!traced)
    {
      std::cerr << "brume: particle tracing failed.\n";
    }
    if (!vtkBrumeProcesses::AllSucceeded(traced, "particle tracing"))
    {
      return 1;
    }
    // The slowest process's tracing time.
    tracing += vtkBrumeProcesses::Max(controller, Seconds(start));
    hits += tracer->GetOutput()->GetNumberOfPoints();
    rays += tracer->GetLastRayCount();
    start = std::chrono::steady_clock::now();
    const bool reconstructed = reconstruction->UpdatePiece(rank, processes, 0) != 0;
    if (!reconstructed)
    {
      std::cerr << "brume: reconstruction failed.\n";
    }
    if (!vtkBrumeProcesses::AllSucceeded(reconstructed, "reconstruction"))
    {
      return 1;
    }
    reconstructing += Seconds(start);
  }
  const vtkTypeInt64 reductionBytes =
    vtkBrumeProcesses::Sum(controller, reconstruction->GetLastReductionBytes());
  const double reductionSeconds =
    vtkBrumeProcesses::Max(controller, reconstruction->GetLastReductionSeconds());
  if (rank != 0)
  {
    return 0; // process 0 renders
  }

  // Phase 3: textured surfaces, then the media as slices.
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0, 0, 0);
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  const int k = options.Supersample;
  window->SetSize(options.Width, options.Height);
  window->AddRenderer(renderer);
  vtkNew<vtkBrumeSceneActors> actors;
  actors->SetInputData(reconstruction->GetOutput());
  if (!actors->AddToRenderer(renderer))
  {
    return 1;
  }
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(position);
  camera->SetFocalPoint(focal);
  camera->SetViewUp(up);
  camera->SetViewAngle(angle);
  renderer->ResetCameraClippingRange();
  vtkNew<vtkBrumeFloatImageCapture> capture;
  capture->Attach(renderer);
  auto start = std::chrono::steady_clock::now();
  window->Render();
  const double firstFrame = Seconds(start);
  // The steady per-view cost (textures already resident): a second frame,
  // or the mean of the k^2 frames whose mean is each pixel's area.
  start = std::chrono::steady_clock::now();
  double frame = 0.0;
  vtkSmartPointer<vtkImageData> radiance;
  if (k == 1)
  {
    window->Render();
    frame = Seconds(start);
    radiance = capture->Capture();
  }
  else
  {
    radiance = capture->CaptureSupersampled(k);
    frame = Seconds(start) / (k * k);
  }
  if (!radiance)
  {
    return 1;
  }

  if (const int rc = WriteImage(radiance, options, png))
  {
    return rc;
  }

  if (options.Timings)
  {
    PhaseTimes times{ tracing, reconstructing, firstFrame, frame, reductionSeconds, reductionBytes,
      hits, rays };
    PrintTimings(options, reconstruction->GetOutput(), times, processes);
  }
  return 0;
}
