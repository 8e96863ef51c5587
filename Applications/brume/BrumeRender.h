// SPDX-License-Identifier: BSD-3-Clause
// `brume render`, and what render and view share: the options a user gives
// and how they set the pipeline (vtkBrumePipeline).
#ifndef BrumeRender_h
#define BrumeRender_h

#include <array>
#include <cstdint>
#include <optional>
#include <string>

class vtkBrumePipeline;

/**
 * What the command line gave. A setting left unset is the scene file's
 * (its `render` block) where it has one, else the default of the filter
 * that owns it (vtkBrumeLightTracer, vtkBrumeRadianceReconstruction,
 * vtkBrumePipeline): no default is repeated here. Only the command's own
 * choices have values here.
 */
struct RenderOptions
{
  std::string Scene;  // empty or "default": the built-in default scene
  std::string Output; // .png or .vti
  std::optional<long long> Particles;
  std::optional<std::uint64_t> Seed;
  std::optional<std::array<int, 2>> Size; // width, height
  std::optional<double> Exposure;
  std::optional<double> Threshold;
  std::optional<bool> DirectLight;      // deterministic single scattering
  std::optional<bool> CentroidMatching; // media textures matched to their estimates' centroids
  std::optional<double> MediumAim;      // directional lights' particles aimed at the media
  std::optional<bool> SplitHeavy;       // heavy particles split where they head into a medium
  std::optional<long long> Batch;       // particles per batch
  std::optional<double> MemoryLimit;    // GiB the hits of one trace may take
  std::optional<double> NativeMemory;   // GiB each medium's own-resolution grids may take
  std::optional<int> MaxDepth;          // interactions after which a particle or a path stops
  // The command's own choices.
  int Supersample = 1;         // render K x K pixels per output pixel and average them
  bool Timings = false;        // print each phase's time
  bool Reference = false;      // the unbiased path tracer instead of the three phases
  int SamplesPerPixel = 64;    // of --reference
  std::optional<int> TimeStep; // of a scene that changes over time: this step alone
};

/**
 * Points `pipeline` at the options' scene, loads it (a bad file is
 * reported on stderr, false), takes its render settings and camera, then
 * sets what the options give.
 */
bool ConfigurePipeline(vtkBrumePipeline* pipeline, const RenderOptions& options);

/// Runs the pipeline and writes the image; returns the process exit code.
int RunRender(const RenderOptions& options);

/// True when `what` can render: through X when DISPLAY names a display,
/// else through EGL (vtkBrumeRenderWindowSelection); with `window`, only
/// on X (a window on a screen). Otherwise says why on stderr.
bool HasDisplay(const char* what, bool window = false);

#endif
