// SPDX-License-Identifier: BSD-3-Clause
#include "BrumeRender.h"
#include "BrumeProgress.h"

#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeDefaultSceneSource.h"
#include "vtkBrumeFloatImageCapture.h"
#include "vtkBrumeLightTracer.h"
#include "vtkBrumePipeline.h"
#include "vtkBrumeProcesses.h"
#include "vtkBrumeRadianceReconstruction.h"
#include "vtkBrumeReferencePathTracer.h"
#include "vtkBrumeRenderWindowSelection.h"
#include "vtkBrumeSceneReader.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkSmartPointer.h"
#include "vtkXMLImageDataWriter.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

namespace
{
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

namespace
{
// Sets `value` through `set` where the user gave it.
template <typename T, typename Set>
void IfGiven(const std::optional<T>& value, Set set)
{
  if (value)
  {
    set(*value);
  }
}

vtkSmartPointer<vtkAlgorithm> SceneSource(const std::string& scene)
{
  if (scene.empty() || scene == "default")
  {
    return vtkSmartPointer<vtkBrumeDefaultSceneSource>::New();
  }
  auto reader = vtkSmartPointer<vtkBrumeSceneReader>::New();
  reader->SetFileName(scene.c_str());
  return reader;
}
}

bool ConfigurePipeline(vtkBrumePipeline* pipeline, const RenderOptions& options)
{
  const vtkSmartPointer<vtkAlgorithm> source = SceneSource(options.Scene);
  pipeline->SetInputConnection(source->GetOutputPort());
  // The scene's render settings, then what the user gave.
  if (!pipeline->ApplySceneSettings())
  {
    std::cerr << "brume: cannot load the scene '" << options.Scene << "' (see the error above).\n";
    return false;
  }
  vtkBrumeLightTracer* tracer = pipeline->GetTracer();
  vtkBrumeRadianceReconstruction* reconstruction = pipeline->GetReconstruction();
  // --timings prints the steady frame's time too: a second frame, timed only.
  pipeline->SetMeasureFrame(options.Timings);
  IfGiven(options.Particles, [&](long long n) { tracer->SetNumberOfParticles(n); });
  // At most 2^63 - 1 (the option's range).
  IfGiven(options.Seed, [&](std::uint64_t s) { tracer->SetSeed(static_cast<vtkIdType>(s)); });
  IfGiven(options.MaxDepth, [&](int depth) { tracer->SetMaximumDepth(depth); });
  IfGiven(options.MediumAim, [&](double aim) { tracer->SetMediumAimFraction(aim); });
  IfGiven(options.SplitHeavy, [&](bool split) { tracer->SetSplitHeavyParticles(split); });
  IfGiven(options.MemoryLimit,
    [&](double gib) { tracer->SetMemoryLimit(static_cast<vtkTypeInt64>(gib * 1073741824.0)); });
  IfGiven(options.NativeMemory,
    [&](double gib)
    { reconstruction->SetNativeMemoryLimit(static_cast<vtkTypeInt64>(gib * 1073741824.0)); });
  IfGiven(options.Threshold, [&](double t) { reconstruction->SetRadiosityThreshold(t); });
  IfGiven(options.DirectLight, [&](bool direct) { reconstruction->SetDirectLighting(direct); });
  IfGiven(
    options.CentroidMatching, [&](bool match) { reconstruction->SetCentroidMatching(match); });
  IfGiven(
    options.Size, [&](const std::array<int, 2>& size) { pipeline->SetSize(size[0], size[1]); });
  IfGiven(options.Exposure, [&](double exposure) { pipeline->SetExposure(exposure); });
  IfGiven(options.Batch, [&](long long batch) { pipeline->SetBatchSize(batch); });
  return true;
}

namespace
{
// Writes next to the output under a temporary name and renames it on
// success, so that a failure never leaves a partial image behind.
int WriteImage(vtkImageData* radiance, vtkBrumePipeline* pipeline, const std::string& output)
{
  const std::string partial = output + ".partial";
  bool ok = false;
  if (EndsWith(output, ".png"))
  {
    vtkNew<vtkPNGWriter> writer;
    writer->SetFileName(partial.c_str());
    writer->SetInputData(pipeline->ToneMap(radiance));
    writer->Write();
    ok = writer->GetErrorCode() == 0;
  }
  else
  {
    vtkNew<vtkXMLImageDataWriter> writer;
    writer->SetFileName(partial.c_str());
    writer->SetInputData(radiance);
    writer->SetDataModeToBinary(); // inline: VTK 9.2 misreads appended data under expat 2.5
    ok = writer->Write() != 0;
  }
  std::error_code error;
  if (ok)
  {
    std::filesystem::rename(partial, output, error);
    ok = !error;
  }
  if (!ok)
  {
    std::filesystem::remove(partial, error);
    std::cerr << "brume: could not write " << output << "\n";
    return 1;
  }
  return 0;
}

// The time steps to render: --time-step's alone, else every one; a scene
// that does not change has one, -1 (no time asked for). False (with the
// message on stderr) when --time-step names none of the scene's steps.
bool StepsToRender(
  vtkBrumePipeline* pipeline, const RenderOptions& options, std::vector<int>& steps)
{
  const int count = pipeline->GetNumberOfTimeSteps();
  steps.clear();
  if (options.TimeStep)
  {
    if (*options.TimeStep >= count)
    {
      std::cerr << "brume: --time-step " << *options.TimeStep << ": "
                << (count == 0 ? std::string("the scene does not change over time (no medium "
                                             "lists its files per time step)")
                               : "the scene has " + std::to_string(count) + " time steps, 0 to " +
                         std::to_string(count - 1))
                << "\n";
      return false;
    }
    steps.push_back(*options.TimeStep);
  }
  for (int k = 0; !options.TimeStep && k < count; ++k)
  {
    steps.push_back(k);
  }
  if (steps.empty())
  {
    steps.push_back(-1);
  }
  return true;
}

// Step K's image of a series: OUTPUT with K before its suffix
// (out.0003.png); --time-step's, or a scene that does not change, OUTPUT.
std::string StepOutput(const std::string& output, int step, const RenderOptions& options)
{
  if (step < 0 || options.TimeStep)
  {
    return output;
  }
  char number[16];
  std::snprintf(number, sizeof(number), ".%04d", step);
  const std::size_t dot = output.size() - 4; // ".png" or ".vti"
  return output.substr(0, dot) + number + output.substr(dot);
}

// The line each time step of a series prints: where it went and its time.
void PrintStep(vtkBrumePipeline* pipeline, int step, const std::string& output, double seconds,
  const char* phases)
{
  std::printf("time step %d of %d (t = %g): %s in %.3f s%s\n", step,
    pipeline->GetNumberOfTimeSteps(), pipeline->GetTimeStep(step), output.c_str(), seconds, phases);
  std::fflush(stdout);
}

// The reference image: the unbiased path tracer (no display needed), with
// the pipeline's scene, size, seed, depth and camera.
int RunReference(const RenderOptions& options)
{
  vtkNew<vtkBrumePipeline> pipeline;
  std::vector<int> steps;
  if (!ConfigurePipeline(pipeline, options))
  {
    return 1;
  }
  if (!StepsToRender(pipeline, options, steps))
  {
    return 2;
  }
  vtkNew<vtkBrumeReferencePathTracer> reference;
  reference->SetInputConnection(pipeline->GetInputConnection());
  reference->SetSize(pipeline->GetSize());
  reference->SetSamplesPerPixel(options.SamplesPerPixel);
  reference->SetSeed(pipeline->GetTracer()->GetSeed());
  reference->SetMaximumDepth(pipeline->GetTracer()->GetMaximumDepth());
  BrumeShowProgress(reference, "path tracing");
  for (const int step : steps)
  {
    const auto start = std::chrono::steady_clock::now();
    if (!(step < 0 ? reference->GetExecutive()->Update()
                   : reference->UpdateTimeStep(pipeline->GetTimeStep(step))))
    {
      std::cerr << "brume: reference rendering failed.\n";
      return 1;
    }
    const double seconds = Seconds(start);
    if (options.Timings)
    {
      std::printf("reference path tracing %8.3f s   %d samples per pixel at %dx%d\n", seconds,
        options.SamplesPerPixel, pipeline->GetSize()[0], pipeline->GetSize()[1]);
    }
    const std::string output = StepOutput(options.Output, step, options);
    if (const int rc = WriteImage(reference->GetOutput(), pipeline, output))
    {
      return rc;
    }
    if (step >= 0)
    {
      PrintStep(pipeline, step, output, Seconds(start), "");
    }
  }
  return 0;
}

// What `--timings` prints: each phase's time (the paper's Table 1), then
// the memory of every radiance texture.
void PrintTextureMemory(vtkPartitionedDataSetCollection* textures)
{
  // A row per texture, the first MaxRows of them: a scene of thousands of
  // objects gets one line for the rest.
  constexpr int MaxRows = 32;
  int rows = 0, more = 0;
  double total = 0.0, moreMegabytes = 0.0;
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
      if (++rows > MaxRows)
      {
        ++more;
        moreMegabytes += megabytes;
        continue;
      }
      std::printf("  %-28s %-18s %5d x %5d x %5d %9.2f", name ? name : "(unnamed)",
        k == 0 ? (volume ? "source radiance" : "radiance") : "extinction (own)",
        volume ? dims[0] - 1 : dims[0], volume ? dims[1] - 1 : dims[1], volume ? dims[2] - 1 : 1,
        megabytes);
      // A sparse grid: the bricks it stores of those its box holds.
      vtkFieldData* fd = image->GetFieldData();
      const bool source = fd->GetArray(vtkBrumeNames::SourceBrickSlots) != nullptr;
      vtkDataArray* slots = fd->GetArray(
        source ? vtkBrumeNames::SourceBrickSlots : vtkBrumeNames::ExtinctionBrickSlots);
      vtkDataArray* samples = fd->GetArray(
        source ? vtkBrumeNames::SourceRadianceBrickSamples : vtkBrumeNames::ExtinctionBrickSamples);
      if (slots && (samples || fd->GetArray(vtkBrumeNames::ExtinctionCellValues)))
      {
        // Bricks read in place from the field's cells store no samples here.
        long long stored = 0;
        for (vtkIdType b = 0; !samples && b < slots->GetNumberOfTuples(); ++b)
        {
          stored += slots->GetTuple1(b) >= 0 ? 1 : 0;
        }
        std::printf("   sparse: %lld of %lld bricks%s",
          samples ? static_cast<long long>(samples->GetNumberOfTuples() / 512) : stored,
          static_cast<long long>(slots->GetNumberOfTuples()),
          samples ? "" : " (field's own values)");
      }
      std::printf("\n");
    }
  }
  if (more > 0)
  {
    const std::string others = std::to_string(more) + " more textures";
    std::printf("  %-28s %-18s %23s %9.2f\n", others.c_str(), "", "", moreMegabytes);
  }
  std::printf("  %-28s %-18s %23s %9.2f\n", "all textures", "", "", total);
}

// `reconstruction`: Update()'s time (a later frame's view update resets
// the pipeline's figure).
void PrintTimings(vtkBrumePipeline* pipeline, int processes, double reconstruction)
{
  vtkBrumeLightTracer* tracer = pipeline->GetTracer();
  const long long particles = tracer->GetNumberOfParticles();
  const long long batch = pipeline->GetPlannedBatchSize();
  std::printf("phase                time (s)\n");
  std::printf("particle tracing     %8.3f   %lld particles, %lld hits, %lld rays",
    pipeline->GetTracingSeconds(), particles, static_cast<long long>(pipeline->GetNumberOfHits()),
    static_cast<long long>(pipeline->GetNumberOfRays()));
  if (batch < particles)
  {
    std::printf(" in batches of %lld", batch);
  }
  std::printf(processes > 1 ? " (process 0 of %d; time: the slowest)\n" : "\n", processes);
  std::printf("reconstruction       %8.3f", reconstruction);
  if (processes > 1)
  {
    std::printf("   histograms summed across processes: %.1f MB sent and received in all, "
                "%.3f s in the reduction (the slowest process)\n",
      static_cast<double>(pipeline->GetReductionBytes()) / 1e6, pipeline->GetReductionSeconds());
  }
  else
  {
    std::printf("\n");
  }
  std::printf("rendering            %8.3f   per frame at %dx%d (first frame %.3f s, with "
              "texture upload and shader compilation)\n",
    pipeline->GetFrameSeconds(), pipeline->GetSize()[0], pipeline->GetSize()[1],
    pipeline->GetFirstFrameSeconds());
  PrintTextureMemory(pipeline->GetTextures());
}
}

int RunRender(const RenderOptions& options)
{
  if (!EndsWith(options.Output, ".png") && !EndsWith(options.Output, ".vti"))
  {
    std::cerr << "brume: the output must end in .png or .vti: " << options.Output << "\n";
    return 2;
  }
  if (options.Reference)
  {
    return RunReference(options);
  }
  // Under mpirun every process traces its share of the particles, the
  // histograms are summed across processes, process 0 renders and writes.
  // Any process failing stops all of them at the next agreement.
  vtkMultiProcessController* controller = vtkBrumeProcesses::GetGlobalController();
  const int rank = vtkBrumeProcesses::GetRank(controller);
  const int processes = vtkBrumeProcesses::GetSize(controller);

  // The scene first: a bad file is reported with or without a display.
  vtkNew<vtkBrumePipeline> pipeline;
  if (!vtkBrumeProcesses::AllSucceeded(ConfigurePipeline(pipeline, options), "loading the scene"))
  {
    return 1;
  }
  if (!vtkBrumeProcesses::AllSucceeded(rank != 0 || HasDisplay("rendering"), "finding a display"))
  {
    return 1;
  }
  if (options.Batch && processes > 1)
  {
    if (rank == 0)
    {
      std::cerr << "brume: --batch runs in one process only (under mpirun, every process "
                   "traces its share at once).\n";
    }
    return 2;
  }
  vtkBrumeLightTracer* tracer = pipeline->GetTracer();
  // A run whose hits would not fit the tracer's memory at once is traced in
  // batches that do, as --batch does: the particle count is bounded by time.
  if (pipeline->IsBatchedForMemory())
  {
    std::printf("%lld particles: traced in batches of %lld, their hits exceeding the memory "
                "limit (%g GiB) at once (--batch sets the size, --memory-limit the limit)\n",
      static_cast<long long>(tracer->GetNumberOfParticles()),
      static_cast<long long>(pipeline->GetPlannedBatchSize()),
      options.MemoryLimit ? *options.MemoryLimit
                          : static_cast<double>(tracer->GetMemoryLimit()) / 1073741824.0);
  }
  std::vector<int> steps;
  if (!StepsToRender(pipeline, options, steps))
  {
    return 2;
  }
  // One image, one viewpoint: view-dependent objects bin toward it and keep
  // no hits, so that a run in batches holds one batch's hits at a time.
  pipeline->GetReconstruction()->SetFixedView(true);
  // A volume the GPU cannot hold at its own resolution is coarsened to fit
  // (where the driver says what it has free; every process alike).
  pipeline->LimitToGPUMemory(rank == 0 ? pipeline->GetImageWindow() : nullptr);
  if (rank == 0)
  {
    BrumeShowProgress(tracer, "particle tracing");
    BrumeShowProgress(pipeline->GetReconstruction(), "reconstruction");
  }
  // Step by step through a scene that changes over time: what does not
  // change (surfaces, constant media) is not read again.
  for (const int step : steps)
  {
    const auto start = std::chrono::steady_clock::now();
    if (step >= 0)
    {
      pipeline->SetTime(pipeline->GetTimeStep(step));
    }
    // Phases 1 and 2, on every process.
    if (!pipeline->Update())
    {
      std::cerr << "brume: " << pipeline->GetFailedPhase() << " failed"
                << (step >= 0 ? " at time step " + std::to_string(step) : std::string()) << ".\n";
      return 1;
    }
    const double tracing = pipeline->GetTracingSeconds();
    const double reconstruction = pipeline->GetReconstructionSeconds();
    if (step == steps.back())
    {
      // No rebuild follows the last image: what the reconstruction keeps
      // for one (a large volume's extinction at its own resolution) is
      // freed before the GPU takes its copy of the textures.
      pipeline->ReleaseBuildState();
    }
    if (rank != 0)
    {
      continue; // process 0 renders
    }
    // Phase 3: textured surfaces, then the media as slices.
    const vtkSmartPointer<vtkImageData> radiance = pipeline->RenderImage(options.Supersample);
    if (!radiance)
    {
      return 1;
    }
    const std::string output = StepOutput(options.Output, step, options);
    if (step >= 0)
    {
      // A step's .vti records its time (VTK's TimeValue field, as the path
      // tracer's output does): ParaView reads the files as a time series.
      radiance->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), pipeline->GetTimeStep(step));
    }
    if (const int rc = WriteImage(radiance, pipeline, output))
    {
      return rc;
    }
    if (step >= 0)
    {
      char phases[160];
      std::snprintf(phases, sizeof(phases),
        " (tracing %.3f s, reconstruction %.3f s, first frame %.3f s)", tracing, reconstruction,
        pipeline->GetFirstFrameSeconds());
      PrintStep(pipeline, step, output, Seconds(start), phases);
    }
    if (options.Timings)
    {
      PrintTimings(pipeline, processes, reconstruction);
    }
  }
  return 0;
}
