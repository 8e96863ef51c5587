// SPDX-License-Identifier: BSD-3-Clause
// Ray casting against the scene's surfaces through Embree 3.
#ifndef brume_RayCaster_h
#define brume_RayCaster_h

#include "brume/Scene.h"

#include <memory>
#include <string>

namespace brume
{

struct SurfaceHit
{
  float T = 0.f;
  /// Index of the surface in Scene::Surfaces.
  unsigned int Surface = 0;
  unsigned int Triangle = 0;
  /// Unnormalized geometric normal (orientation: Embree's convention, do not rely on it).
  Vec3 Ng;
};

class RayCaster
{
public:
  /// Builds Embree's BVH over every surface of the scene (the scene must be valid).
  explicit RayCaster(const Scene& scene);
  ~RayCaster();
  RayCaster(const RayCaster&) = delete;
  RayCaster& operator=(const RayCaster&) = delete;

  /// Empty when the BVH was built, otherwise Embree's error.
  const std::string& GetError() const { return this->Error; }

  /// Closest hit of the ray o + t d with t in (tnear, tfar); false when none.
  bool Intersect(const Vec3& o, const Vec3& d, float tnear, float tfar, SurfaceHit& hit) const;

  /// Cheap axis-aligned bounds of every surface (for epsilons and resolutions).
  const Box& GetBounds() const { return this->Bounds; }

private:
  struct Internals;
  std::unique_ptr<Internals> Impl;
  std::string Error;
  Box Bounds;
};

} // namespace brume

#endif
