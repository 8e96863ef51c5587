// SPDX-License-Identifier: BSD-3-Clause
// Many small surfaces drawn through few actors. Private to Brume::Rendering.
#ifndef vtkBrumeSurfaceAtlas_h
#define vtkBrumeSurfaceAtlas_h

#include "vtkImageData.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <cstddef>
#include <vector>

namespace vtkBrumeSceneActorsInternals
{
/// One surface drawn through an atlas.
struct AtlasMember
{
  unsigned int Index;                   // the object's place in the input collection
  vtkSmartPointer<vtkImageData> Image;  // its radiance texture, as shown
  vtkSmartPointer<vtkPolyData> Surface; // its surface, as shown
  int X = 0;                            // the corner of its slot in the atlas, in texels
  int Y = 0;
};

/**
 * A scene of thousands of objects made thousands of actors, each with its
 * texture, mapper and buffers: VTK draws each with its own calls, and
 * finding and releasing their buffers grows with their number squared
 * (16,000 tiles: 7 s to the first frame, 1 s a frame, 20 s to let them go).
 * An atlas packs the radiance textures of many surfaces into one image
 * (shelves, tallest first), each texture in a slot one texel wider on every
 * side that repeats its edge, so linear filtering inside a slot reads what
 * the texture alone clamped to its edge gives; their surfaces become one
 * polygonal data set whose texture coordinates point into the slots.
 */
class SurfaceAtlas
{
public:
  /// The largest side of an atlas image, in texels (every OpenGL 4
  /// implementation allows at least 16,384).
  static constexpr int MaxSide = 4096;

  /**
   * Whether a surface can share an atlas: a 2D float RGB texture no larger
   * than MaxSide - 2 texels a side, and polygons only with 2D texture
   * coordinates at every point.
   */
  static bool Accepts(vtkImageData* image, vtkPolyData* surface);

  /// Packs the members (each accepted) into as few atlases as hold them, and builds them.
  static std::vector<SurfaceAtlas> Pack(std::vector<AtlasMember> members);

  const std::vector<AtlasMember>& GetMembers() const { return this->Members; }
  vtkImageData* GetImage() const { return this->Image; }
  vtkPolyData* GetGeometry() const { return this->Geometry; }

  /**
   * Shows `image` (of the dimensions member k had) for member k: its texels
   * are copied into its slot, and the atlas image is marked modified.
   */
  void SetTexels(std::size_t k, vtkImageData* image);

private:
  int Width = 0;
  int Height = 0;
  std::vector<AtlasMember> Members;
  vtkSmartPointer<vtkImageData> Image;
  vtkSmartPointer<vtkPolyData> Geometry;

  void Build();
  void CopyTexels(const AtlasMember& member);
};
}

#endif
