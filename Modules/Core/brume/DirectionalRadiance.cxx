// SPDX-License-Identifier: BSD-3-Clause
#include "brume/DirectionalRadiance.h"

#include "brume/Medium.h"
#include "brume/SphericalHarmonics.h"

#include <algorithm>

namespace brume
{

DirectionalRadiance::DirectionalRadiance(const ObjectLayout& layout)
  : Resolution(layout.Resolution)
  , Bounds(layout.MediumRef ? layout.MediumRef->Bounds : Box())
  , IsMedium(layout.MediumRef != nullptr)
  , G(layout.Scattering.GetPeak(true).G)
{
}

void DirectionalRadiance::Clear()
{
  this->Coefficients.clear();
  this->Order = -1;
}

std::vector<float>& DirectionalRadiance::Start(int order, std::size_t floats)
{
  this->Coefficients.assign(floats, 0.f);
  this->Order = order;
  return this->Coefficients;
}

void DirectionalRadiance::Evaluate(const Vec3& eye, std::vector<float>& radiance) const
{
  const std::size_t texels =
    static_cast<std::size_t>(this->Resolution[0]) * this->Resolution[1] * this->Resolution[2];
  radiance.assign(3 * texels, 0.f);
  if (this->Order < 0 || !this->IsMedium)
  {
    return;
  }
  const int nk = ShCoefficients(this->Order);
  const Box box = this->Bounds;
  const Vec3 voxel = box.Extent() /
    Vec3(static_cast<float>(this->Resolution[0]), static_cast<float>(this->Resolution[1]),
      static_cast<float>(this->Resolution[2]));
  const std::size_t nx = this->Resolution[0], nxy = nx * this->Resolution[1];
  for (std::size_t t = 0; t < texels; ++t)
  {
    const Vec3 centre = box.lower +
      (Vec3(static_cast<float>(t % nx), static_cast<float>((t % nxy) / nx),
         static_cast<float>(t / nxy)) +
        Vec3(0.5f)) *
        voxel;
    const Vec3 toEye = Normalize(eye - centre);
    for (int c = 0; c < 3; ++c)
    {
      radiance[3 * t + c] = std::max(
        0.f, EvaluateHgFromSh(this->Order, this->G, &this->Coefficients[t * nk * 3 + c], 3, toEye));
    }
  }
}

} // namespace brume
