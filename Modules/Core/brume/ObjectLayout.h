// SPDX-License-Identifier: BSD-3-Clause
// What an object's radiance texture covers, fixed when its reconstruction
// (brume::ObjectRadiance) is made: the surface or medium, the texture's and
// the histogram's resolutions, the surface's chart, and how a medium
// scatters once its phase function's forward peak is set apart. Every part
// of the reconstruction (binning, estimation, direct light, the native
// grid, the directional projection) reads it; none changes it.
#ifndef brume_ObjectLayout_h
#define brume_ObjectLayout_h

#include "brume/Sampling.h"
#include "brume/Scene.h"
#include "brume/SurfaceChart.h"
#include "brume/Vec3.h"

#include <array>
#include <cstddef>
#include <vector>

namespace brume
{

/**
 * Strongly forward-scattering media: the part of the phase function's peak
 * a representation cannot resolve is set apart (brume/Sampling.h). Per-view
 * textures (directional false) keep HG(g) itself wherever it is below what
 * HG(ResolvedG) reaches forward, HG(ResolvedG)(1), and set apart only what
 * rises above that (TruncateForwardPeak): light scattered backward and
 * sideways is in-scattered exactly. The directional representation (true)
 * keeps a Henyey-Greenstein remainder HG(DirectionalResolvedG)
 * (SplitForwardPeak), whose Legendre series its three bands project, at
 * the cost of that remainder's own backward lobe. The texture then holds
 * the light in-scattered by the remainder, GetPeak(directional).Remainder(),
 * which rests on many particles where HG(g) rests on the few travelling
 * almost straight at the eye, and the peak is drawn as transport: a
 * renderer multiplies the medium's sigma_t by
 * GetExtinctionFactor(directional) (1 - Forward albedo per channel), and
 * the source radiance is per unit of that reduced extinction. Without a
 * split (HG(g) resolved, surfaces) the factor is 1.
 *
 * A medium whose albedo varies (Medium::AlbedoFactor) cannot fold it into
 * its texture: the albedo may step inside a texel where the light does not.
 * Its texture then holds the source radiance X of an albedo of 1 with no
 * peak set apart, and a renderer applies the albedo a(x) where it draws:
 * the emission is sigma_t a X and the extinction sigma_t (1 - a Forward),
 * Forward being GetPeak(directional).Forward; GetExtinctionFactor() is then
 * 1. SourceAt() gives the source radiance S per unit of that extinction and
 * its factor, for any medium.
 */
class MediumScattering
{
public:
  static constexpr float ResolvedG = 0.7f;
  static constexpr float DirectionalResolvedG = 0.6f;

  /// Surfaces: no peak, albedo 1.
  MediumScattering() = default;
  explicit MediumScattering(const Medium& medium);

  const ForwardPeak& GetPeak(bool directional) const { return this->Peaks[directional ? 1 : 0]; }
  const Vec3& GetExtinctionFactor(bool directional) const
  {
    return this->ExtinctionFactors[directional ? 1 : 0];
  }
  bool HasVaryingAlbedo() const { return this->AlbedoVaries; }
  /// sigma_s / sigma_t folded into the texture (1 where the albedo varies).
  const Vec3& GetAlbedo() const { return this->Albedo; }
  Vec3 SourceAt(const Vec3& albedo, const Vec3& texel, bool directional, Vec3& factor) const;

private:
  bool AlbedoVaries = false;
  Vec3 Albedo = Vec3(1.f);
  ForwardPeak Peaks[2];
  Vec3 ExtinctionFactors[2] = { Vec3(1.f), Vec3(1.f) };
};

/**
 * The texture's extent and resolutions. A surface's texture is a 2D image
 * over its chart (Resolution[2] = 1); a medium's a 3D grid over its bounds.
 * The histogram behind it has Refinement cells per texel along every used
 * axis (Dims). Plain data: made once, then read.
 */
struct ObjectLayout
{
  ObjectLayout(
    const Surface& surface, SurfaceChart chart, std::array<int, 2> resolution, int refinement);
  ObjectLayout(const Medium& medium, std::array<int, 3> resolution, int refinement);

  const Surface* SurfaceRef = nullptr; // exactly one of the two is set
  const Medium* MediumRef = nullptr;
  SurfaceChart Chart;            // surfaces
  std::array<int, 3> Resolution; // texels
  std::array<int, 3> Dims;       // histogram cells
  int Refinement;
  /// Glossy surfaces and anisotropic media change with the viewpoint.
  bool ViewDependent = false;
  double CellVolume = 0.0; // media: one histogram cell's volume
  // Surfaces: each triangle's winding normal (not normalized), which the
  // binning tests every hit against (light on the back is not shown).
  std::vector<Vec3> TriangleNormals;
  MediumScattering Scattering;

  std::size_t Texels() const
  {
    return static_cast<std::size_t>(this->Resolution[0]) * this->Resolution[1] *
      this->Resolution[2];
  }
  std::size_t Cells() const
  {
    return static_cast<std::size_t>(this->Dims[0]) * this->Dims[1] * this->Dims[2];
  }
  /// The triangles' unit normals.
  std::vector<Vec3> UnitNormals() const;
  /**
   * What estimating the texture costs, about, in units of one homogeneous
   * medium's histogram cell: the summed-area tables (and a surface's
   * areas) per cell, a region per texel (AssignOwners() shares the objects
   * out by it). It depends on the resolutions alone, which every process
   * of a run chooses alike.
   */
  double EstimateCost() const;
};

} // namespace brume

#endif
