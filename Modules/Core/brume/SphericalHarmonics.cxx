// SPDX-License-Identifier: BSD-3-Clause
#include "brume/SphericalHarmonics.h"

#include "brume/Sampling.h"

#include <algorithm>

namespace brume
{

namespace
{
float LegendreP(int l, float x)
{
  switch (l)
  {
    case 0:
      return 1.f;
    case 1:
      return x;
    case 2:
      return 0.5f * (3.f * x * x - 1.f);
    default:
      return 0.5f * x * (5.f * x * x - 3.f);
  }
}
}

void EvaluateSh(int order, const Vec3& d, float* y)
{
  const float x = d.x, yy = d.y, z = d.z;
  y[0] = ShY00;
  if (order < 1)
  {
    return;
  }
  y[1] = 0.488602512f * yy;
  y[2] = 0.488602512f * z;
  y[3] = 0.488602512f * x;
  if (order < 2)
  {
    return;
  }
  y[4] = 1.092548431f * x * yy;
  y[5] = 1.092548431f * yy * z;
  y[6] = 0.315391565f * (3.f * z * z - 1.f);
  y[7] = 1.092548431f * x * z;
  y[8] = 0.546274215f * (x * x - yy * yy);
  if (order < 3)
  {
    return;
  }
  y[9] = 0.590043589f * yy * (3.f * x * x - yy * yy);
  y[10] = 2.890611442f * x * yy * z;
  y[11] = 0.457045799f * yy * (5.f * z * z - 1.f);
  y[12] = 0.373176333f * z * (5.f * z * z - 3.f);
  y[13] = 0.457045799f * x * (5.f * z * z - 1.f);
  y[14] = 1.445305721f * z * (x * x - yy * yy);
  y[15] = 0.590043589f * x * (x * x - 3.f * yy * yy);
}

float EvaluateHgFromSh(
  int order, float g, const float* coefficients, int stride, const Vec3& d, bool tail)
{
  float y[ShCoefficients(MaxShOrder)];
  EvaluateSh(order, d, y);
  float sum = 0.f, gl = 1.f;
  for (int l = 0; l <= order; ++l)
  {
    float band = 0.f;
    for (int k = l * l; k < (l + 1) * (l + 1); ++k)
    {
      band += coefficients[k * stride] * y[k];
    }
    sum += gl * band;
    gl *= g;
  }
  if (!tail || order < 1)
  {
    return sum;
  }
  // The lost bands l > order, from a model of the incident light: an
  // isotropic part plus a Henyey-Greenstein lobe of weight b, mean direction
  // mu and mean cosine gL. Its first moment b gL mu is band 1; with order
  // >= 2 its second, b gL^2 = sum Phi P_2(w . mu), is band 2 along mu, which
  // separates the lobe from the isotropic part (order 1: all light in the
  // lobe). Convolved with HG(g) the lobe is b HG(g gL); its bands up to the
  // order are already in the sum.
  const float total = coefficients[0] / ShY00;
  const Vec3 moment =
    Vec3(coefficients[3 * stride], coefficients[stride], coefficients[2 * stride]) / 0.488602512f;
  const float length = Length(moment);
  if (!(total > 0.f) || !(length > 0.f))
  {
    return sum;
  }
  const Vec3 axis = moment / length;
  float weight = total, meanCosine = std::min(length / total, 0.999f);
  if (order >= 2)
  {
    float band2[ShCoefficients(MaxShOrder)];
    EvaluateSh(2, axis, band2);
    float zonal = 0.f;
    for (int k = 4; k < 9; ++k)
    {
      zonal += coefficients[k * stride] * band2[k];
    }
    const float second = zonal * 4.f * Pi / 5.f; // b gL^2
    if (!(second > 1e-4f * length))
    {
      return sum; // no lobe: nothing beyond the bands
    }
    meanCosine = std::min(second / length, 0.999f);
    weight = std::min(length / meanCosine, total);
  }
  const float gg = g * meanCosine;
  const float mu = Dot(axis, d);
  float truncated = 0.f, power = 1.f;
  for (int l = 0; l <= order; ++l)
  {
    truncated += power * (2 * l + 1) * Inv4Pi * LegendreP(l, mu);
    power *= gg;
  }
  return sum + weight * (HenyeyGreenstein(gg).Evaluate(mu) - truncated);
}

} // namespace brume
