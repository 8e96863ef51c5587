// SPDX-License-Identifier: BSD-3-Clause
// The slice mapper's fragment shader, assembled from the module's .glsl
// files (private to Brume::RenderingOpenGL2): the slab shader, and for
// directional media of order > 0 the spherical-harmonics evaluation toward
// the eye, with its textures, fetch and constants filled in.
#ifndef vtkBrumeSliceVolumeShader_h
#define vtkBrumeSliceVolumeShader_h

#include <string>

class vtkBrumeSliceVolumeShader
{
public:
  /// The fragment shader for directional radiance of `order` (0: none).
  static std::string Fragment(int order);
};

#endif
