// SPDX-License-Identifier: BSD-3-Clause
// The camera of the core: the reference path tracer's pinhole, and the
// default view of every Brume scene.
#ifndef brume_Camera_h
#define brume_Camera_h

#include "brume/Vec3.h"

namespace brume
{

/**
 * A pinhole camera as vtkCamera describes it (vertical view angle). Its
 * initial values are Brume's default view, the one used wherever a scene
 * names no camera: from (0, 0, 4) toward the origin, +y up, 40 degrees.
 */
struct PinholeCamera
{
  Vec3 Position{ 0.f, 0.f, 4.f };
  Vec3 FocalPoint{ 0.f };
  Vec3 ViewUp{ 0.f, 1.f, 0.f };
  float ViewAngle = 40.f; // degrees
  int Width = 512;
  int Height = 512;

  /// The ray through image point (x, y), pixel units, row 0 at the bottom.
  void Ray(float x, float y, Vec3& origin, Vec3& direction) const;
};

} // namespace brume

#endif
