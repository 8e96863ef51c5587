// SPDX-License-Identifier: BSD-3-Clause
// Real spherical harmonics up to order 3 (16 functions), orthonormal on the
// unit sphere, in the usual order k = l (l + 1) + m (Sloan, "Stupid
// spherical harmonics tricks", 2008).
//
// Directional radiance: a medium voxel stores c_lm = sum_p Y_lm(w_p) Phi_p
// (times its normalization), the projection of the directions of travel of
// the light it received. Henyey-Greenstein is a zonal kernel with Legendre
// coefficients g^l, p(w . w') = sum_l g^l sum_m Y_lm(w) Y_lm(w'), so the
// phase-weighted sum toward any direction w_o is
//   sum_p p(w_p . w_o) Phi_p = sum_lm g^l c_lm Y_lm(w_o),
// exact up to the truncation: the terms l > order, which weigh g^l, are lost.
#ifndef brume_SphericalHarmonics_h
#define brume_SphericalHarmonics_h

#include "brume/Vec3.h"

namespace brume
{

constexpr int MaxShOrder = 3;

/// Y_00 = 1 / (2 sqrt(pi)): the constant band; c_00 Y_00 is the mean over directions.
constexpr float ShY00 = 0.282094792f;

/// Number of coefficients of an expansion up to `order`: (order + 1)^2.
constexpr int ShCoefficients(int order)
{
  return (order + 1) * (order + 1);
}

/// The (order + 1)^2 basis functions at the unit direction d.
void EvaluateSh(int order, const Vec3& d, float* y);

/**
 * sum_lm g^l c_lm Y_lm(d) for one channel: `coefficients` holds the
 * (order + 1)^2 values of that channel, `stride` floats apart.
 *
 * With `tail` (and order >= 1), the bands l > order are added from the
 * Henyey-Greenstein lobe with the projection's first moment (mean direction
 * mu, mean cosine gL = |c_1| / c_0 scaled): the convolution of two HG lobes
 * is the HG lobe of g gL, so the tail is
 *   c_0/Y_00 (p_{g gL}(mu . d) - sum_{l<=order} (g gL)^l (2l+1)/(4 pi) P_l(mu . d)).
 * It is exact for light from one direction and for isotropic light, and
 * restores most of the forward peak that truncation loses.
 */
float EvaluateHgFromSh(
  int order, float g, const float* coefficients, int stride, const Vec3& d, bool tail = true);

} // namespace brume

#endif
