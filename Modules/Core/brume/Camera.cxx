// SPDX-License-Identifier: BSD-3-Clause
#include "brume/Camera.h"

#include "brume/Sampling.h"

#include <cmath>

namespace brume
{

void PinholeCamera::Ray(float x, float y, Vec3& origin, Vec3& direction) const
{
  const Vec3 forward = Normalize(this->FocalPoint - this->Position);
  const Vec3 right = Normalize(Cross(forward, this->ViewUp));
  const Vec3 up = Cross(right, forward);
  const float tanHalf = std::tan(0.5f * this->ViewAngle * Pi / 180.f);
  const float aspect = static_cast<float>(this->Width) / static_cast<float>(this->Height);
  const float u = (2.f * x / this->Width - 1.f) * tanHalf * aspect;
  const float v = (2.f * y / this->Height - 1.f) * tanHalf;
  origin = this->Position;
  direction = Normalize(forward + right * u + up * v);
}

} // namespace brume
