// SPDX-License-Identifier: BSD-3-Clause
// `brume view`: the interactive viewer and its scripted orbit.
#ifndef BrumeView_h
#define BrumeView_h

#include "BrumeRender.h"

#include <string>

struct ViewOptions
{
  RenderOptions Render;     // scene, particles, seed, size, exposure, threshold
  bool Directional = false; // spherical-harmonics media instead of per-view textures
  int Order = 3;            // their order
  bool PerFragment = false; // evaluated in the slice shader rather than per voxel
  int Orbit = 0;            // frames of a scripted orbit (0: interactive)
  std::string FramesOut;    // with Orbit: where frame_NNNN.png go
  std::string Csv;          // with Orbit: per-frame timings
  std::string Keys;         // keys pressed before the orbit or the interaction
  bool Overlay = true;      // the text overlay
  int ExitAfter = 0;        // interactive: quit after so many timer-driven frames (0: never)
  double MovingSampleDistance = 2.0; // the media's image sample distance while the camera moves
};

/// Runs the viewer; returns the process exit code.
int RunView(const ViewOptions& options);

#endif
