// SPDX-License-Identifier: BSD-3-Clause
// The three-phase pipeline behind `brume render`.
#ifndef BrumeRender_h
#define BrumeRender_h

#include "vtkAlgorithm.h"
#include "vtkSmartPointer.h"

#include <cstdint>
#include <string>

struct RenderOptions
{
  std::string Scene;  // empty: the built-in default scene
  std::string Output; // .png or .vti
  long long Particles = 1000000;
  std::uint64_t Seed = 0;
  int Width = 512;
  int Height = 512;
  double Exposure = 1.0;
  double Threshold = 128.0;
  bool DirectLight = true;      // deterministic single scattering (vtkBrumeRadianceReconstruction)
  bool CentroidMatching = true; // media textures matched to their estimates' centroids
  double MediumAim = 0.2;       // directional lights' particles aimed at the media
  bool SplitHeavy = true;       // heavy particles split where they head into a medium
  int Supersample = 1;          // render K x K pixels per output pixel and average them
  bool Timings = false;
  long long Batch = 0;    // particles per batch (0: all at once)
  double MemoryLimit = 8.0; // GiB the hits of one trace may take (vtkBrumeLightTracer)
  bool Reference = false; // the unbiased path tracer instead of the three phases
  int SamplesPerPixel = 64;
  int MaxDepth = 1024; // interactions after which a particle or a path stops
  // Which settings the command line gave (a scene file's render settings
  // give the others).
  bool ParticlesSet = false, SizeSet = false, ThresholdSet = false, SeedSet = false,
       ExposureSet = false;
};

/// Runs the pipeline and writes the image; returns the process exit code.
int RunRender(RenderOptions options);

/**
 * The scene: the built-in one (empty or "default"), or a scene file, loaded
 * and validated; its render settings fill the options the command line did
 * not give. Null, with the reason on stderr, when it cannot be loaded.
 */
vtkSmartPointer<vtkAlgorithm> LoadScene(RenderOptions& options);

/// True when `what` can render: through X when DISPLAY names a display,
/// else through EGL (vtkBrumeRenderWindowSelection); with `window`, only
/// on X (a window on a screen). Otherwise says why on stderr.
bool HasDisplay(const char* what, bool window = false);

#endif
