// SPDX-License-Identifier: BSD-3-Clause
// Phase 2 of Jimenez & Pueyo (2003), section 3: radiance textures from the
// stored particle hits, per object, through a histogram, its summed-area
// table and adaptive nearest-neighbour density estimation.
//
// Radiometric normalization (units agree with a path tracer's radiance):
//  - Surface texel, Lambertian reflectance rho, region of area A holding hits
//    of incident flux Phi_p:  L_o = rho/pi * sum(Phi_p) / A  +  L_e.
//  - Medium voxel, region of volume V holding the hits stored at real
//    collisions (flux before the albedo weighting), phase function p, direction
//    of travel w_p, direction toward the eye w_o:
//      J = (sigma_s/sigma_t) * sum(p(w_p, w_o) Phi_p) / V   (W m^-3 sr^-1)
//    and the texture holds the slab source radiance S = J / sigma_t
//    (W m^-2 sr^-1), which the slice renderer composites with
//    alpha = 1 - exp(-sigma_t * Delta).
//  - The growth threshold is a flux (W): the region grows until the incident
//    flux it holds (mean over channels) reaches it.
#ifndef brume_Reconstruction_h
#define brume_Reconstruction_h

#include "brume/DensityEstimation.h"
#include "brume/LightTracer.h"
#include "brume/Scene.h"

#include <array>
#include <vector>

namespace brume
{

/**
 * Texture resolution along each axis of an object of the given extent (zero
 * along unused axes) so that a texel holds about `hitsPerTexel` of the object's
 * `hitCount` hits, clamped to [minimum, maximum] per axis.
 */
std::array<int, 3> ChooseResolution(
  const Vec3& extent, std::size_t hitCount, double hitsPerTexel, int minimum, int maximum);

/// Outgoing radiance texture of a planar Lambertian surface (view independent).
class SurfaceRadiance
{
public:
  /// resolution: texels along the frame's U and V axes; refinement: histogram
  /// cells per texel along each axis.
  SurfaceRadiance(const Surface& surface, const PlanarFrame& frame, std::array<int, 2> resolution,
    int refinement);

  /// Bins the hits of this surface (hits of other objects must be filtered out).
  void AddHits(const Hit* hits, std::size_t count);
  /// Builds the summed-area table; call once after the hits are added.
  void Finalize();

  /// Radiance (RGB) of texels [begin, end) in row-major order (U fastest).
  void Estimate(std::size_t begin, std::size_t end, double thresholdFlux, float* rgb) const;

  std::array<int, 2> GetResolution() const { return this->Resolution; }

private:
  const Surface& SurfaceRef;
  PlanarFrame Frame;
  std::array<int, 2> Resolution;
  int Refinement;
  Histogram Cells;
  SummedAreaTable Table;
};

/// Source radiance texture of a homogeneous medium toward an eye point.
class MediumRadiance
{
public:
  MediumRadiance(const Medium& medium, std::array<int, 3> resolution, int refinement);

  /// Bins the hits of this medium, weighting each by the phase function
  /// toward `eye` (view dependent unless the medium is isotropic).
  void AddHits(const Hit* hits, std::size_t count, const Vec3& eye);
  void Finalize();

  /// Source radiance S (RGB) and extinction sigma_t (RGB, the mean over the
  /// voxel for heterogeneous media) of voxels [begin, end) in x-fastest order.
  void Estimate(
    std::size_t begin, std::size_t end, double thresholdFlux, float* rgb, float* extinction) const;

  std::array<int, 3> GetResolution() const { return this->Resolution; }

private:
  const Medium& MediumRef;
  std::array<int, 3> Resolution;
  int Refinement;
  Histogram Cells;
  SummedAreaTable Table;
};

} // namespace brume

#endif
