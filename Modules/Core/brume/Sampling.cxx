// SPDX-License-Identifier: BSD-3-Clause
#include "brume/Sampling.h"

#include <cmath>

namespace brume
{

Vec3 SampleCosineHemisphere(float u1, float u2)
{
  // Malley's method: uniform disk point lifted to the hemisphere.
  const float r = std::sqrt(u1);
  const float phi = 2.f * Pi * u2;
  const float z = std::sqrt(std::max(0.f, 1.f - u1));
  return { r * std::cos(phi), r * std::sin(phi), z };
}

float CosineHemispherePdf(float cosTheta)
{
  return cosTheta > 0.f ? cosTheta * InvPi : 0.f;
}

Vec3 SampleUniformSphere(float u1, float u2)
{
  const float z = 1.f - 2.f * u1;
  const float r = std::sqrt(std::max(0.f, 1.f - z * z));
  const float phi = 2.f * Pi * u2;
  return { r * std::cos(phi), r * std::sin(phi), z };
}

float HenyeyGreenstein::SampleCosTheta(float u) const
{
  const float g = this->G;
  if (std::abs(g) < 1e-3f)
  {
    return 1.f - 2.f * u;
  }
  // Inverse CDF of HG in cos(theta), written so that g > 0 is forward.
  const float sq = (1.f - g * g) / (1.f - g + 2.f * g * u);
  const float c = (1.f + g * g - sq * sq) / (2.f * g);
  return std::min(1.f, std::max(-1.f, c));
}

Vec3 HenyeyGreenstein::Sample(const Vec3& wi, float u1, float u2) const
{
  const float cosTheta = this->SampleCosTheta(u1);
  const float sinTheta = std::sqrt(std::max(0.f, 1.f - cosTheta * cosTheta));
  const float phi = 2.f * Pi * u2;
  const Frame frame(wi);
  return Normalize(frame.ToWorld({ sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta }));
}

ForwardPeak SplitForwardPeak(float g, float resolvedG)
{
  ForwardPeak peak;
  peak.G = g;
  if (g > resolvedG && resolvedG < 1.f)
  {
    peak.G = resolvedG;
    peak.Forward = (g - resolvedG) / (1.f - resolvedG);
    peak.Scale = 1.f - peak.Forward;
  }
  return peak;
}

ForwardPeak TruncateForwardPeak(float g, float cap)
{
  ForwardPeak peak;
  peak.G = g;
  if (!(g > 0.f && cap > 0.f) || HenyeyGreenstein(g).Evaluate(1.f) <= cap)
  {
    return peak;
  }
  // HG(g) equals the cap at cosTheta = c, where 1 + g^2 - 2 g c = d; above
  // it HG(g) holds (1 - g^2) / (2 g) (1 / (1 - g) - 1 / sqrt(d)), of which
  // the cap keeps 2 pi cap (1 - c).
  constexpr double pi = 3.14159265358979323846;
  const double gd = g, capd = cap;
  const double d = std::pow((1.0 - gd * gd) / (4.0 * pi * capd), 2.0 / 3.0);
  const double c = (1.0 + gd * gd - d) / (2.0 * gd);
  const double above = (1.0 - gd * gd) / (2.0 * gd) * (1.0 / (1.0 - gd) - 1.0 / std::sqrt(d));
  peak.Forward = static_cast<float>(std::max(0.0, above - 2.0 * pi * capd * (1.0 - c)));
  peak.Cap = cap;
  return peak;
}

} // namespace brume
