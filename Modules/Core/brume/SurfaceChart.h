// SPDX-License-Identifier: BSD-3-Clause
// How a surface maps to its radiance texture's [0, 1]^2: its plane, its own
// texture coordinates, or an automatic atlas; and the world area that each
// histogram cell of the texture covers.
#ifndef brume_SurfaceChart_h
#define brume_SurfaceChart_h

#include "brume/Scene.h"

#include <array>
#include <vector>

namespace brume
{

class Histogram;

/// How a surface maps to its texture's [0, 1]^2.
struct SurfaceChart
{
  enum class Kind
  {
    Planar,             // the plane's own (u, v): PlanarFrame
    TextureCoordinates, // the mesh's texture coordinates
    Atlas               // one chart per triangle, made automatically
  };
  Kind Type = Kind::Planar;
  PlanarFrame Frame;
  /// (u, v) of the three corners of every triangle.
  std::vector<std::array<float, 6>> TriangleUV;
  /// Aspect (u extent / v extent in the world) for choosing resolutions.
  float Width = 1.f, Height = 1.f;
};

/**
 * The chart of a surface: planar surfaces use their plane, others the given
 * per-vertex texture coordinates (if any, with non-degenerate triangles),
 * others an automatic per-triangle atlas.
 */
SurfaceChart MakeChart(
  const Surface& surface, const std::vector<std::array<float, 2>>* vertexTextureCoordinates);

/**
 * Adds to `area` (a one-component histogram over the chart's [0, 1]^2) the
 * world area of the surface inside each cell: every triangle's exact (u, v)
 * overlap with the cell times its world/texture area ratio.
 */
void AddChartAreas(const Surface& surface, const SurfaceChart& chart, Histogram& area);

} // namespace brume

#endif
