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
  /// How a volume's extinction is read (the shader's BRUME_EXTINCTION).
  enum ExtinctionRead
  {
    ExtinctionTexture = 0, ///< a dense 3D texture (the source's grid, or its own)
    ExtinctionBricks = 1,  ///< a sparse grid's atlas of bricks and its table
    ExtinctionConstant = 2 ///< one value (a homogeneous medium): no texture read
  };

  /// What one fragment shader is compiled for: volumes differing in any of
  /// these are drawn by different programs.
  struct Kind
  {
    int Order = 0; ///< directional radiance's order (0: none)
    ExtinctionRead Extinction = ExtinctionTexture;
    bool SourceIsRadiance = false; ///< the source texture holds S, not J
    bool Classified = false;       ///< the bricks hold scalars a transfer function classifies
    bool Albedo = false;           ///< and its table gives an albedo, applied per fragment
    bool Slabs = false;            ///< slabs take several extinction samples along each ray
    bool Bends = false; ///< and four for each in bricks the transfer function bends within
    bool operator==(const Kind& other) const
    {
      return this->Order == other.Order && this->Extinction == other.Extinction &&
        this->SourceIsRadiance == other.SourceIsRadiance && this->Classified == other.Classified &&
        this->Albedo == other.Albedo && this->Slabs == other.Slabs && this->Bends == other.Bends;
    }
  };

  /// The fragment shader for volumes of this kind.
  static std::string Fragment(const Kind& kind);
};

#endif
