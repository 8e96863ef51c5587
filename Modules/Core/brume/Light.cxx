// SPDX-License-Identifier: BSD-3-Clause
#include "brume/Light.h"

#include "brume/Sampling.h"

#include <cmath>

namespace brume
{

namespace
{
float CosCone(float degrees)
{
  return std::cos(degrees * Pi / 180.f);
}
}

Vec3 Light::Power() const
{
  switch (this->Type)
  {
    case LightType::Point:
      return this->Intensity * (4.f * Pi);
    case LightType::Spot:
      return this->Intensity * (2.f * Pi * (1.f - CosCone(this->ConeAngle)));
    case LightType::Directional:
      return this->Intensity * (Pi * this->BeamRadius * this->BeamRadius);
  }
  return Vec3(0.f);
}

std::string Light::Validate() const
{
  if (!IsFinite(this->Intensity) || MinComponent(this->Intensity) < 0.f)
  {
    return "has a negative or non-finite intensity";
  }
  if (!IsFinite(this->Position) || !IsFinite(this->BeamCenter))
  {
    return "has a non-finite position";
  }
  if (this->Type != LightType::Point &&
    (!IsFinite(this->Direction) || std::abs(Length(this->Direction) - 1.f) > 1e-3f))
  {
    return "has no unit direction";
  }
  if (this->Type == LightType::Spot && !(this->ConeAngle > 0.f && this->ConeAngle <= 180.f))
  {
    return "has a cone angle outside (0, 180] degrees";
  }
  if (this->Type == LightType::Directional &&
    (!(this->BeamRadius > 0.f) || !std::isfinite(this->BeamRadius)))
  {
    return "has a beam radius that is not positive";
  }
  if (!(MaxComponent(this->Power()) > 0.f))
  {
    return "has zero power";
  }
  return {};
}

void Light::SampleEmission(Random& rng, Vec3& origin, Vec3& direction) const
{
  const float u1 = rng.NextFloat(), u2 = rng.NextFloat();
  switch (this->Type)
  {
    case LightType::Point:
      origin = this->Position;
      direction = SampleUniformSphere(u1, u2);
      return;
    case LightType::Spot:
    {
      // Uniform in the cone's solid angle.
      const float cosTheta = 1.f - u1 * (1.f - CosCone(this->ConeAngle));
      const float sinTheta = std::sqrt(std::max(0.f, 1.f - cosTheta * cosTheta));
      const float phi = 2.f * Pi * u2;
      origin = this->Position;
      direction =
        Normalize(Frame(this->Direction)
                    .ToWorld({ sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta }));
      return;
    }
    case LightType::Directional:
    {
      // Uniform point on the emitting disk.
      const float r = this->BeamRadius * std::sqrt(u1);
      const float phi = 2.f * Pi * u2;
      const Frame frame(this->Direction);
      origin = this->BeamCenter + frame.s * (r * std::cos(phi)) + frame.t * (r * std::sin(phi));
      direction = this->Direction;
      return;
    }
  }
}

} // namespace brume
