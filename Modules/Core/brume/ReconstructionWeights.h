// SPDX-License-Identifier: BSD-3-Clause
// Internal to the reconstruction's sources, not part of the API: the weight
// of a hit toward an eye, inline in the two loops that call it for every hit
// (ObjectRadiance::WeighCells() re-weighting kept hits, and the binning of
// a fixed view, ObjectRadiance::AddTerms()), which live in two sources.
#ifndef brume_ReconstructionWeights_h
#define brume_ReconstructionWeights_h

#include "brume/Material.h"
#include "brume/Reconstruction.h"
#include "brume/Reflection.h"
#include "brume/Sampling.h"

#include <cmath>

namespace brume
{

inline void ObjectRadiance::WeighHit(const Vec3& eye, const float* position, const float* direction,
  const float* flux, std::uint32_t triangle, const std::vector<Vec3>& normals, double* value) const
{
  if (this->MediumRef)
  {
    // The remainder of the phase function once its peak is set apart, from
    // the direction of travel to the eye: WeighCells() evaluates the same
    // expression in vectorized blocks.
    const HenyeyGreenstein phase(this->Peaks[0].G);
    const float remainder = static_cast<float>(1.0 - this->Peaks[0].Forward);
    const float dx = eye.x - position[0], dy = eye.y - position[1], dz = eye.z - position[2];
    const float cosine = (direction[0] * dx + direction[1] * dy + direction[2] * dz) /
      std::sqrt(dx * dx + dy * dy + dz * dz);
    const float p = remainder * phase.Evaluate(cosine);
    for (int c = 0; c < 3; ++c)
    {
      value[c] = static_cast<double>(p) * flux[c];
    }
    return;
  }
  const Vec3 pos(position[0], position[1], position[2]);
  const Vec3 dir(direction[0], direction[1], direction[2]);
  // The BRDF from the incoming direction to the eye.
  Material coloured; // where the surface's reflectance varies over it
  const Material& m = this->SurfaceRef->VertexReflectance.empty()
    ? this->SurfaceRef->MaterialOf(triangle)
    : (coloured = this->SurfaceRef->MaterialAt(triangle, pos));
  // A cast lobe is left out: the diffuse part alone.
  const bool diffuseOnly =
    this->LobeCast && m.Type == MaterialType::Phong && MirrorReflection::Casts(m);
  Vec3 n = normals[triangle];
  if (Dot(n, dir) > 0.f)
  {
    n = -n;
  }
  const Vec3 toEye = Normalize(eye - pos);
  const Vec3 f =
    diffuseOnly ? EvaluateDiffuseBrdf(m, n, -dir, toEye) : EvaluateBrdf(m, n, -dir, toEye);
  for (int c = 0; c < 3; ++c)
  {
    value[c] = static_cast<double>(f[c]) * flux[c];
  }
}

} // namespace brume

#endif
