// SPDX-License-Identifier: BSD-3-Clause
#include "brume/Material.h"

#include "brume/Sampling.h"

#include <cmath>
#include <sstream>

namespace brume
{

namespace
{
bool InUnitInterval(const Vec3& v)
{
  return IsFinite(v) && MinComponent(v) >= 0.f && MaxComponent(v) <= 1.f;
}

// Probability of choosing the diffuse lobe in a Phong material.
float DiffuseProbability(const Material& m)
{
  const float d = Average(m.Reflectance), s = Average(m.Specular);
  return d + s > 0.f ? d / (d + s) : 1.f;
}

// Density of the normalized cosine-power lobe around r: (e + 1)/(2 pi) cos^e.
float LobePdf(float exponent, float cosAlpha)
{
  return cosAlpha > 0.f ? (exponent + 1.f) * 0.5f * InvPi * std::pow(cosAlpha, exponent) : 0.f;
}
}

std::string Material::Validate() const
{
  if (!InUnitInterval(this->Reflectance) || !InUnitInterval(this->Specular))
  {
    return "has a reflectance outside [0, 1]";
  }
  if (!InUnitInterval(this->Reflectance + this->Specular))
  {
    return "reflects more than it receives (diffuse + specular reflectance > 1)";
  }
  if (!(this->Exponent > 0.f) || !std::isfinite(this->Exponent))
  {
    return "has a Phong exponent that is not positive and finite";
  }
  if (!IsFinite(this->Emission) || MinComponent(this->Emission) < 0.f)
  {
    return "has a negative or non-finite emission";
  }
  return {};
}

Vec3 EvaluateDiffuseBrdf(const Material& m, const Vec3& n, const Vec3& wi, const Vec3& wo)
{
  if (Dot(wi, n) <= 0.f || Dot(wo, n) <= 0.f || m.Type == MaterialType::Mirror)
  {
    return Vec3(0.f);
  }
  return m.Reflectance * InvPi;
}

Vec3 EvaluateBrdf(const Material& m, const Vec3& n, const Vec3& wi, const Vec3& wo)
{
  if (Dot(wi, n) <= 0.f || Dot(wo, n) <= 0.f)
  {
    return Vec3(0.f);
  }
  switch (m.Type)
  {
    case MaterialType::Lambertian:
      return m.Reflectance * InvPi;
    case MaterialType::Phong:
    {
      const float cosAlpha = Dot(Reflect(wi, n), wo);
      const float lobe =
        cosAlpha > 0.f ? (m.Exponent + 2.f) * 0.5f * InvPi * std::pow(cosAlpha, m.Exponent) : 0.f;
      return m.Reflectance * InvPi + m.Specular * lobe;
    }
    case MaterialType::Mirror:
      return Vec3(0.f);
  }
  return Vec3(0.f);
}

float BrdfPdf(const Material& m, const Vec3& n, const Vec3& wi, const Vec3& wo)
{
  const float cosO = Dot(wo, n);
  if (Dot(wi, n) <= 0.f || cosO <= 0.f)
  {
    return 0.f;
  }
  switch (m.Type)
  {
    case MaterialType::Lambertian:
      return cosO * InvPi;
    case MaterialType::Phong:
    {
      const float pd = DiffuseProbability(m);
      return pd * cosO * InvPi + (1.f - pd) * LobePdf(m.Exponent, Dot(Reflect(wi, n), wo));
    }
    case MaterialType::Mirror:
      return 0.f;
  }
  return 0.f;
}

bool SampleBrdf(
  const Material& m, const Vec3& n, const Vec3& wi, Random& rng, Vec3& wo, Vec3& weight)
{
  switch (m.Type)
  {
    case MaterialType::Lambertian:
    {
      if (!(MaxComponent(m.Reflectance) > 0.f))
      {
        return false;
      }
      // f cos / pdf = rho_d for cosine-weighted sampling.
      wo = Normalize(Frame(n).ToWorld(SampleCosineHemisphere(rng.NextFloat(), rng.NextFloat())));
      weight = m.Reflectance;
      return true;
    }
    case MaterialType::Mirror:
    {
      if (!(MaxComponent(m.Specular) > 0.f))
      {
        return false;
      }
      wo = Normalize(Reflect(wi, n));
      weight = m.Specular;
      return true;
    }
    case MaterialType::Phong:
    {
      if (!(MaxComponent(m.Reflectance) > 0.f) && !(MaxComponent(m.Specular) > 0.f))
      {
        return false;
      }
      // One-sample mixture of the cosine lobe and the cosine-power lobe;
      // the weight uses the mixture's density.
      const float u = rng.NextFloat(), u1 = rng.NextFloat(), u2 = rng.NextFloat();
      if (u < DiffuseProbability(m))
      {
        wo = Normalize(Frame(n).ToWorld(SampleCosineHemisphere(u1, u2)));
      }
      else
      {
        const float cosAlpha = std::pow(u1, 1.f / (m.Exponent + 1.f));
        const float sinAlpha = std::sqrt(std::max(0.f, 1.f - cosAlpha * cosAlpha));
        const float phi = 2.f * Pi * u2;
        wo =
          Normalize(Frame(Normalize(Reflect(wi, n)))
                      .ToWorld({ sinAlpha * std::cos(phi), sinAlpha * std::sin(phi), cosAlpha }));
      }
      const float pdf = BrdfPdf(m, n, wi, wo);
      if (!(pdf > 0.f))
      {
        return false; // sampled below the surface
      }
      weight = EvaluateBrdf(m, n, wi, wo) * (Dot(wo, n) / pdf);
      return true;
    }
  }
  return false;
}

} // namespace brume
