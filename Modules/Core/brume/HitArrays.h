// SPDX-License-Identifier: BSD-3-Clause
// The hits phase 2 reads, as arrays (the tracer's output viewed in place),
// and grouped by object (part of the reconstruction, brume/Reconstruction.h).
#ifndef brume_HitArrays_h
#define brume_HitArrays_h

#include "brume/Grouping.h"
#include "brume/Parallel.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace brume
{
/// Hits in structure-of-arrays form (e.g. the arrays of a vtkPolyData).
struct HitArrays
{
  const float* Position = nullptr;  // 3 per hit
  const float* Direction = nullptr; // 3 per hit, direction of travel
  const float* Flux = nullptr;      // 3 per hit
  const std::uint16_t* Object = nullptr;
  const std::uint32_t* Triangle = nullptr; // may be null: planar surfaces need none
  const std::uint16_t* Emitter = nullptr;  // may be null unless direct light is computed
  const std::uint8_t* Depth = nullptr;     // may be null unless direct light is computed
  /**
   * May be null: every particle weighed alike. Where lights were aimed
   * (Light::AimAtMedia), each hit's class (Hit::Aim) and, three per emitter
   * id, the inverse of each class's emission weight: what a hit counts for
   * when its region grows (GrowthScale), so that regions grow to the
   * threshold's number of particles, not its flux, and a medium that aimed
   * particles reach gets their noise down and its regions small, as if
   * every particle had been traced toward it.
   */
  const std::uint8_t* Aim = nullptr;
  const double* GrowthScales = nullptr;
  std::size_t Count = 0;

  double GrowthScale(std::size_t i) const
  {
    return this->Aim ? this->GrowthScales[3 * std::size_t(this->Emitter[i]) + this->Aim[i]] : 1.0;
  }
};

/// Hit indices grouped by object, in hit order within each object.
struct ObjectHits
{
  std::vector<std::uint32_t, UninitializedAllocator<std::uint32_t>> Index;
  std::vector<std::size_t> Offset; // objects + 1
};
/// Empty on success, otherwise what is wrong (an object id out of range).
std::string GroupHitsByObject(const HitArrays& hits, std::size_t objects, ObjectHits& groups,
  const ParallelFor& parallelFor = SerialFor());
}

#endif
