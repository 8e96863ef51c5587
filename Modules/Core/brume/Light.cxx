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
  if (!(this->AimFraction >= 0.f && this->AimFraction < 1.f) || !(this->AimRadius >= 0.f) ||
    !std::isfinite(this->AimRadius) || !IsFinite(this->AimCenter))
  {
    return "has an aimed disk that is not a fraction in [0, 1) of a finite disk";
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

bool Light::Aims() const
{
  return this->Type == LightType::Directional && this->AimFraction > 0.f &&
    this->AimFraction < 1.f && this->AimRadius > 0.f;
}

float Light::EmissionWeight(std::uint8_t aim) const
{
  if (aim == 0 || !this->Aims())
  {
    return 1.f;
  }
  // The beam's uniform density over the mixture's: (1/A) / ((1 - p)/A + p/a)
  // inside the aimed disk, (1/A) / ((1 - p)/A) outside it.
  const double p = this->AimFraction;
  if (aim == 1)
  {
    return static_cast<float>(1.0 / (1.0 - p));
  }
  const double areas = static_cast<double>(this->BeamRadius) * this->BeamRadius /
    (static_cast<double>(this->AimRadius) * this->AimRadius);
  return static_cast<float>(1.0 / ((1.0 - p) + p * areas));
}

float Light::SampleEmission(Random& rng, Vec3& origin, Vec3& direction, std::uint8_t& aim) const
{
  if (!this->Aims())
  {
    aim = 0;
    this->SampleEmission(rng, origin, direction);
    return 1.f;
  }
  const bool aimed = rng.NextFloat() < this->AimFraction;
  const float u1 = rng.NextFloat(), u2 = rng.NextFloat();
  const Vec3& centre = aimed ? this->AimCenter : this->BeamCenter;
  const float r = (aimed ? this->AimRadius : this->BeamRadius) * std::sqrt(u1);
  const float phi = 2.f * Pi * u2;
  const Frame frame(this->Direction);
  origin = centre + frame.s * (r * std::cos(phi)) + frame.t * (r * std::sin(phi));
  direction = this->Direction;
  // Which density the point has follows from where it is, whichever disk it
  // was drawn from (a point drawn from the aimed disk is inside it).
  const Vec3 fromAim = origin - this->AimCenter;
  aim = aimed || Dot(fromAim, fromAim) <= this->AimRadius * this->AimRadius ? 2 : 1;
  if (aimed)
  {
    const Vec3 fromBeam = origin - this->BeamCenter;
    if (Dot(fromBeam, fromBeam) > this->BeamRadius * this->BeamRadius)
    {
      return 0.f; // where the beam does not reach
    }
  }
  return this->EmissionWeight(aim);
}

} // namespace brume
