// SPDX-License-Identifier: BSD-3-Clause
// Scenes shared by the core's tests.
#ifndef brume_TestScenes_h
#define brume_TestScenes_h

#include "brume/Scene.h"

#include <string>
#include <vector>

namespace brume
{
namespace testing
{
/// The six faces of the closed box [-1, 1]^3 (inward normals), all of material m.
inline std::vector<Surface> ClosedBox(const Material& m)
{
  const Vec3 c[8] = { { -1, -1, -1 }, { 1, -1, -1 }, { -1, 1, -1 }, { 1, 1, -1 }, { -1, -1, 1 },
    { 1, -1, 1 }, { -1, 1, 1 }, { 1, 1, 1 } };
  // Quads counter-clockwise seen from inside.
  const int faces[6][4] = { { 0, 4, 5, 1 }, { 2, 3, 7, 6 }, { 0, 1, 3, 2 }, { 4, 6, 7, 5 },
    { 0, 2, 6, 4 }, { 1, 5, 7, 3 } };
  std::vector<Surface> walls;
  for (int f = 0; f < 6; ++f)
  {
    Surface s;
    s.Name = "wall" + std::to_string(f);
    for (int k = 0; k < 4; ++k)
    {
      s.Vertices.push_back(c[faces[f][k]]);
    }
    s.Triangles = { { 0, 1, 2 }, { 0, 2, 3 } };
    s.Mat = m;
    walls.push_back(s);
  }
  return walls;
}
} // namespace testing
} // namespace brume

#endif
