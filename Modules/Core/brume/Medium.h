// SPDX-License-Identifier: BSD-3-Clause
// Participating media and unbiased free-flight sampling through them.
#ifndef brume_Medium_h
#define brume_Medium_h

#include "brume/Density.h"
#include "brume/Random.h"
#include "brume/Vec3.h"

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace brume
{

/**
 * A factor on a medium's single-scattering albedo that varies in space:
 * per channel, in [0, 1] (a transfer function's colour, ClassifiedAlbedo
 * in brume/TransferFunction.h). Must be thread safe.
 */
class AlbedoField
{
public:
  virtual ~AlbedoField() = default;
  virtual Vec3 Evaluate(const Vec3& p) const = 0;
  /**
   * Whether NativeValue() reads the samples of `density`'s native grid
   * (DensityField::NativeResolution() cells over NativeBox()): a colour of
   * the scalars the density classifies, whose samples are those cells'.
   */
  virtual bool SharesNativeCells(const DensityField& density) const
  {
    (void)density;
    return false;
  }
  /**
   * The factor at the centre of native cell (i, j, k), which lies at world
   * point `centre`: Evaluate(centre), or from the cell's own sample where
   * SharesNativeCells() (at a 512^3 grid's every cell, interpolating
   * generically took seconds).
   */
  virtual Vec3 NativeValue(int i, int j, int k, const Vec3& centre) const
  {
    (void)i;
    (void)j;
    (void)k;
    return this->Evaluate(centre);
  }
  /**
   * Where SharesNativeCells(), NativeValue() of the `count` native cells
   * from `lower` (x fastest) into `out`, through `scratch`, read at once
   * (a brick of a grid's values); false, with nothing written, where the
   * field cannot.
   */
  virtual bool NativeValues(const std::array<int, 3>& lower, const std::array<int, 3>& count,
    std::vector<float>& scratch, Vec3* out) const
  {
    (void)lower;
    (void)count;
    (void)scratch;
    (void)out;
    return false;
  }
};

struct Medium
{
  std::string Name;
  /// Extent of a homogeneous medium; for a heterogeneous one, the density's
  /// bounds (set by SetDensity). The boundary is index-matched.
  Box Bounds;
  /// Coefficients (m^-1) per channel; heterogeneous media scale them by the density.
  Vec3 SigmaA{ 0.1f };
  Vec3 SigmaS{ 1.f };
  /// Henyey-Greenstein asymmetry, -1 < g < 1.
  float G = 0.f;
  /// Null for a homogeneous medium.
  std::shared_ptr<const DensityField> Density;
  /**
   * Null for an albedo alike everywhere. Otherwise the albedo at p is
   * Albedo() times the field's value there: sigma_s(p) = AlbedoAt(p)
   * sigma_t(p), sigma_t unchanged.
   */
  std::shared_ptr<const AlbedoField> AlbedoFactor;

  void SetDensity(std::shared_ptr<const DensityField> density)
  {
    this->Density = std::move(density);
    if (this->Density)
    {
      this->Bounds = this->Density->GetBounds();
    }
  }
  bool IsHomogeneous() const { return !this->Density; }
  Vec3 SigmaT() const { return this->SigmaA + this->SigmaS; }
  /// Extinction at a point inside Bounds.
  Vec3 SigmaTAt(const Vec3& p) const
  {
    return this->Density ? this->SigmaT() * this->Density->Evaluate(p) : this->SigmaT();
  }
  /// Single-scattering albedo sigma_s / sigma_t per channel (0 where sigma_t is 0).
  Vec3 Albedo() const;
  /// Whether the albedo varies in space (AlbedoFactor).
  bool HasVaryingAlbedo() const { return this->AlbedoFactor != nullptr; }
  /// The albedo at a point inside Bounds.
  Vec3 AlbedoAt(const Vec3& p) const
  {
    return this->AlbedoFactor ? this->Albedo() * this->AlbedoFactor->Evaluate(p) : this->Albedo();
  }
  /// Empty when valid, otherwise what is wrong.
  std::string Validate() const;
};

/**
 * A heterogeneous medium's varying albedo taken once per cell of its
 * density's own grid (DensityField::NativeResolution() cells over
 * NativeBox()): the albedo's factor at the centre of the cell holding a
 * point. A region's estimate weighs its hits by it and divides by the
 * density's integral weighted by the same cells' factors
 * (NativeMediumGrid::BuildAlbedoTable()): the light X where the albedo is
 * high counts for more, as the albedo a renderer multiplies X by makes it,
 * and a region of even light reads that light whatever the albedo does
 * inside a cell (a sheet one cell thin, whose colour at its peak is not
 * the colour where most of its extinction lies).
 */
class CellAlbedo
{
public:
  /// Requires medium.Density and medium.AlbedoFactor.
  explicit CellAlbedo(const Medium& medium);
  /// The factor at the centre of the cell holding p (clamped to the grid).
  Vec3 At(const Vec3& p) const;
  /// The factor at the centre of cell (i, j, k).
  Vec3 AtCell(int i, int j, int k) const
  {
    return this->Native ? this->Field->NativeValue(i, j, k, this->Centre(i, j, k))
                        : this->Field->Evaluate(this->Centre(i, j, k));
  }
  /// AtCell() of the `count` cells from `lower` (x fastest) into `out`,
  /// batched where the field can (`scratch` its working memory).
  void AtCells(const std::array<int, 3>& lower, const std::array<int, 3>& count,
    std::vector<float>& scratch, Vec3* out) const;
  /// The centre of cell (i, j, k).
  Vec3 Centre(int i, int j, int k) const;

private:
  const AlbedoField* Field;
  bool Native; // Field->SharesNativeCells(the density)
  Vec3 Lower, Cell;
  int Dims[3];
};

/**
 * Delta tracking of one medium along one ray segment: tentative collisions
 * are exponential steps with the local majorant, block by block (a 3D DDA
 * over the density's majorant grid), so empty blocks cost nothing. For a
 * homogeneous medium the majorant is sigma_t itself and every tentative
 * collision of a colourless medium is real.
 */
class MediumTracker
{
public:
  /// Starts tracking the ray o + t d, t in [0, tMax]; false when it misses the medium.
  bool Begin(const Medium& medium, const Vec3& o, const Vec3& d, float tMax);
  /// Moves to the next tentative collision; false when the segment ends first.
  bool Next(Random& rng);

  // Plain data, set by Begin(): trackers live on the tracer's hot path.
  /// Distance of the current tentative collision.
  float T;
  /// Majorant (max over channels) at T.
  float Majorant;
  const Medium* Tracked;

private:
  bool Advance();
  float BlockMajorant() const;

  float TEnd;
  float TBlockEnd;
  float ScaleMax; // max over channels of sigma_t
  const MajorantGrid* Grid;
  int Cell[3];
  int Step[3];
  float TNext[3];
  float TDelta[3];
};

/**
 * Free-flight sampling along o + t d, t in [0, tMax], through every medium:
 * each medium's delta tracking, events taken in distance order (superposed
 * Poisson processes), spectral-tracking weights applied to `weight` (a flux
 * or a path throughput). Returns the medium of the first real collision and
 * its distance in `t`, or nullptr. `trackers` has room for media.size().
 */
const Medium* SampleCollision(const std::vector<Medium>& media, const Vec3& o, const Vec3& d,
  float tMax, Random& rng, Vec3& weight, float& t, MediumTracker* trackers);

/**
 * Transmittance (per channel) along o + t d, t in [0, distance], through
 * every medium: exact for homogeneous media, ratio tracking (unbiased) for
 * heterogeneous ones.
 */
Vec3 Transmittance(const std::vector<Medium>& media, const Vec3& o, const Vec3& d, float distance,
  Random& rng, MediumTracker& tracker);

} // namespace brume

#endif
