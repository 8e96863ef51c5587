// SPDX-License-Identifier: BSD-3-Clause
// Anisotropic media: per voxel, the spherical-harmonics projection of the
// directions of travel of the light received (ObjectRadiance::
// BuildDirectional()), normalized as the source radiance, so that the
// source radiance toward any direction w_o is sum_lm g^l c_lm Y_lm(w_o)
// (brume/SphericalHarmonics.h) without reconstructing again; past
// MediumScattering::DirectionalResolvedG, g is the remainder's
// (MediumScattering::GetPeak(true).G) and the source radiance is per unit
// of the reduced extinction.
#ifndef brume_DirectionalRadiance_h
#define brume_DirectionalRadiance_h

#include "brume/ObjectLayout.h"

#include <array>
#include <cstddef>
#include <vector>

namespace brume
{

class DirectionalRadiance
{
public:
  explicit DirectionalRadiance(const ObjectLayout& layout);

  /// -1 before a projection is built.
  int GetOrder() const { return this->Order; }
  /// (order + 1)^2 RGB coefficients per voxel: [voxel][coefficient][channel].
  const std::vector<float>& GetCoefficients() const { return this->Coefficients; }
  /// The source radiance toward `eye`, evaluated at voxel centres (clamped
  /// at zero), RGB per voxel; zero without a projection.
  void Evaluate(const Vec3& eye, std::vector<float>& radiance) const;

  /// No projection.
  void Clear();
  /// A projection of `order`: its coefficients, zeroed, for the caller to
  /// fill.
  std::vector<float>& Start(int order, std::size_t floats);

private:
  std::array<int, 3> Resolution;
  Box Bounds; // media
  bool IsMedium;
  float G; // the asymmetry the coefficients are evaluated with
  int Order = -1;
  std::vector<float> Coefficients;
};

} // namespace brume

#endif
