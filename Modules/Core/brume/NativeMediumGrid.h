// SPDX-License-Identifier: BSD-3-Clause
// A heterogeneous medium's density at its own resolution, for one object's
// reconstruction (brume::ObjectRadiance) and the renderers that draw it.
#ifndef brume_NativeMediumGrid_h
#define brume_NativeMediumGrid_h

#include "brume/BrickedGrid.h"
#include "brume/CentroidMatching.h"
#include "brume/DensityEstimation.h"
#include "brume/Medium.h"
#include "brume/Parallel.h"
#include "brume/SummedAreaTable.h"

#include <array>
#include <cstddef>
#include <memory>
#include <vector>

namespace brume
{
class GridDensity;
class OpacityTransferFunction;

/**
 * The density per cell of the medium's own grid
 * (brume::DensityField::NativeResolution over NativeBox, whose cell centres
 * are the field's own samples), independent of the texture's resolution,
 * so that a renderer draws the medium's structure (sigma_t = the medium's
 * SigmaT() times the density) at its own resolution with the smooth source
 * radiance of the texture. Each cell holds the density at its centre:
 * interpolated trilinearly, the grid is the field (an OpenVDB grid's
 * trilinear sampler, a point-valued image), not a smoothed copy. Stored in
 * bricks (brume::BrickedGrid): bricks where the density's majorant is 0 are
 * not evaluated and, with bricks of one value, not stored, so memory
 * follows the medium's occupied bricks, not its box. A grid is coarsened
 * by one integer factor on every axis (the smallest that fits; a coarsened
 * cell averages 2^3 samples) only where its grids would take more memory
 * than Sample() is given, or its box more than MaxAxis cells along an axis.
 *
 * From this grid come the tables a texture is normalized by: the integral
 * of the density over each histogram cell and its first moments
 * (BuildTables()), and so each region's integral and sigma_t-weighted
 * centroid.
 */
class NativeMediumGrid
{
public:
  /// The memory a grid may take where none is given: what the grids were
  /// held to before their budget came from the machine.
  static constexpr std::size_t DefaultMemory = std::size_t(32) << 20;
  static constexpr int MaxAxis = 2048;
  /// The lines per axis across which a classified density's cell is
  /// integrated where its function bends inside the cell (see Sample()).
  static constexpr int BendSamples = 4;

  /**
   * Samples the density of `medium` (which has one) at its own resolution
   * where its grids fit `memory` bytes: the stored bricks and the brick
   * tables of the density and, for a classified density, of its scalars.
   * Otherwise coarsened by the smallest integer factor that fits
   * (GetCoarsening()).
   *
   * A classified density's cell whose scalars span one of its function's
   * points is its mean extinction (ClassifiedDensity::NativeMean(): exact
   * along the axis the scalars change most along, on BendSamples^2 lines
   * across the other two), which the tables integrate, the direct light's
   * shadow rays march and the slice mapper draws (the function at the
   * cell's own scalar would put a sheet one cell thin, whose scalar peaks
   * at the grid's points, at its peak extinction across the whole cell:
   * 14 % too dark an image of Data/scenes/shells.json; a mean of 4^3
   * samples left its shadows 10 to 15 % too light). Other cells take the
   * field's value there.
   */
  void Sample(const Medium& medium, std::size_t memory, const ParallelFor& parallelFor);
  /**
   * Sample(), taking what it would compute again from `previous`, a grid
   * sampled earlier of the same density (the same object: an edit of the
   * medium's albedo), or of the same scalar field (the same object)
   * classified by another function (an edit of the function): the whole
   * grid where the density or the function is the same (a colour-only
   * edit), else each brick whose
   * scalars lie where the two functions give the same floats
   * (OpacityFunctionEdit::SameOver()). The result is bitwise what
   * Sample() gives without it; `previous` may be null, or of another
   * field (then it is not read). GetReusedBricks() counts what was taken.
   */
  void Sample(const Medium& medium, std::size_t memory, const ParallelFor& parallelFor,
    const NativeMediumGrid* previous);
  /**
   * Sample() taking from `previous` as above, and, for an edit of the
   * function that classifies the same field, sampling the extinction again
   * in `previous`'s own memory where no one else holds it
   * (BrickedGrid::ResampleInPlace(): the bricks the edit left are not even
   * copied), so that a 512^3 field's 0.78 GB grid and its successor are
   * not held at once. The same floats; `previous` is left empty.
   */
  void Sample(const Medium& medium, std::size_t memory, const ParallelFor& parallelFor,
    NativeMediumGrid&& previous);
  /// Whether Sample(medium, ..., this) could take from this grid: both a
  /// classified density of the same scalars, this one at their own resolution.
  bool SameField(const Medium& medium) const;
  /// Whether this grid was sampled from `medium`'s density itself (the same object).
  bool SameDensity(const Medium& medium) const
  {
    return this->Source && this->Source == medium.Density;
  }
  /**
   * Of the extinction's bricks the last Sample() evaluated (those its
   * majorants did not leave out), how many it took from the previous grid
   * and how many it sampled (a whole grid kept counts all its bricks as taken).
   */
  std::size_t GetReusedBricks() const { return this->ReusedBricks; }
  std::size_t GetSampledBricks() const { return this->SampledBricks; }
  /// The integer factor the field's own grid was coarsened by (1: none).
  int GetCoarsening() const { return this->Coarsening; }
  /// The field's own resolution (DensityField::NativeResolution()).
  const std::array<int, 3>& GetFieldResolution() const { return this->FieldResolution; }
  bool Empty() const { return this->Density.Empty(); }
  const BrickedGrid& GetDensity() const { return this->Density; }
  /**
   * A density classified by a transfer function (ClassifiedDensity) also
   * keeps its scalars at the same centres, for a renderer that
   * interpolates them and classifies after, as the tracer does: bricks
   * whose extinction the majorants make 0 hold a scalar the function takes
   * to 0. Empty otherwise, and when the grid is coarsened (a mean of
   * scalars is not what the function classified). GetClassification() is
   * then the function, else null.
   *
   * Scalars that are a grid's own values (a brume::GridDensity of the
   * grid's cells, read in place from its array) are not copied: the grid
   * is then an outline (BrickedGrid::Outline(), the same slots and
   * constants, no samples; ScalarsInPlace()), and a stored brick's
   * samples are the field's values at its cells (ScalarAt(), or
   * GetScalarField()'s values, x fastest): a 512^3 float field's 0.78 GB
   * held once.
   */
  const BrickedGrid& GetScalars() const { return this->Scalars; }
  /// Whether GetScalars() is an outline over the field's own values.
  bool ScalarsInPlace() const { return this->ScalarField != nullptr; }
  /// The grid whose values those are (null when not in place).
  const GridDensity* GetScalarField() const { return this->ScalarField; }
  /// The scalar of cell (i, j, k): GetScalars().At(), read from the field
  /// where the scalars are in place (a brick left out holds its constant).
  float ScalarAt(int i, int j, int k) const;
  const OpacityTransferFunction* GetClassification() const { return this->Classification; }
  const std::array<int, 3>& GetResolution() const { return this->Density.GetDims(); }
  /// The box of the grid's cells (DensityField::NativeBox(), grown to whole
  /// coarsened cells): it holds the medium's bounds.
  const Box& GetBox() const { return this->Density.GetBox(); }

  /// The density's integral over each of `dims` histogram cells over the
  /// medium's bounds `box`, and its first moments.
  void BuildTables(
    const Box& box, const std::array<int, 3>& dims, const ParallelFor& parallelFor = SerialFor());
  bool HasTables() const { return this->DensityTable.GetNumberOfChannels() != 0; }
  /// Tables built (or kept with the grid) for `dims` histogram cells over `box`.
  bool HasTables(const Box& box, const std::array<int, 3>& dims) const;
  /// The density's integral over a region of histogram cells.
  double RegionIntegral(const Region& region) const;
  /**
   * Where `medium`'s albedo varies (Medium::AlbedoFactor, its density this
   * grid's): the integral over each histogram cell of the density times
   * each channel of the albedo's factor, taken per cell of the grid
   * (CellAlbedo). A region's scattered light, binned with each hit's
   * cell's albedo (HitBinning), is normalized by it: the light where the
   * albedo is high counts for more, as the renderer's albedo, applied
   * point by point, makes it. A texel across a step of the albedo so keeps
   * the covariance of the albedo and the light, which a mean of the light
   * alone (times the albedo) loses. Kept with the grid for the same albedo
   * field; a colour edit builds it again.
   */
  void BuildAlbedoTable(const Box& box, const std::array<int, 3>& dims, const Medium& medium,
    const ParallelFor& parallelFor = SerialFor());
  /// Whether BuildAlbedoTable() was made for these cells and this field.
  bool HasAlbedoTable(
    const Box& box, const std::array<int, 3>& dims, const AlbedoField* albedo) const;
  /// The albedo-weighted density's integral over a region, per channel.
  void RegionAlbedoIntegral(const Region& region, double integral[3]) const;
  /// Regions whose integral is at most this hold no medium.
  double GetEmptyIntegral() const { return this->EmptyIntegral; }
  /// Where each texel's estimate belongs (the mean of its two regions'
  /// sigma_t-weighted centroids: the estimate is the mean of theirs), for
  /// the texture whose interpolation meets it there.
  CentroidMatching Centroids(const std::vector<std::array<Region, 2>>& regions,
    const std::array<int, 3>& resolution, int refinement, const ParallelFor& parallelFor) const;

private:
  // Sample() from `previous`; `owned` is `previous` where its extinction
  // may be sampled again in its own memory, else null.
  void SampleFrom(const Medium& medium, std::size_t memory, const ParallelFor& parallelFor,
    const NativeMediumGrid* previous, NativeMediumGrid* owned);

  BrickedGrid Density;                      // the density's mean per cell
  BrickedGrid Scalars;                      // a classified density's scalars at the same centres
  const GridDensity* ScalarField = nullptr; // whose values they are, when in place
  const OpacityTransferFunction* Classification = nullptr;
  SummedAreaTable DensityTable;   // integral of the density per histogram cell
  SummedAreaTable DensityMoments; // and its first moments (histogram-cell coordinates)
  double EmptyIntegral = 0.0;
  std::array<int, 3> TableDims{ 0, 0, 0 };
  Box TableBox;
  SummedAreaTable AlbedoTable; // integral of the density times the albedo's factor, RGB
  std::shared_ptr<const AlbedoField> TableAlbedo; // the field it was made for
  std::array<int, 3> AlbedoDims{ 0, 0, 0 };
  Box AlbedoBox;
  // The density the grid was sampled from (it holds the function
  // Classification points to, and the scalars), and per brick of the
  // extinction the range of the scalars its samples were computed from
  // (ClassifiedDensity::NativeBrickRange(), NaN where not known): what the
  // next Sample() compares the functions over.
  std::shared_ptr<const DensityField> Source;
  std::vector<float> BrickRanges;
  // Which bricks were sampled (the scalars' and a classified extinction's),
  // and what the scalars' others hold.
  std::vector<char> Candidates;
  float ScalarSkipped = 0.f;
  std::size_t ReusedBricks = 0, SampledBricks = 0;
  int Coarsening = 1;
  // Whether the density is the trilinear interpolation of Density's values
  // (an OpenVDB grid, a grid of point values, not coarsened nor
  // classified): the tables then integrate that field, which the tracer's
  // hits sample, not cells of constant density.
  bool Trilinear = false;
  std::array<int, 3> FieldResolution{ 0, 0, 0 };
};

} // namespace brume

#endif
