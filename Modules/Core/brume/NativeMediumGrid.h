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
#include <vector>

namespace brume
{
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
 * follows the medium's occupied bricks, not its box. Grids whose occupied
 * bricks would store more than MaxSamples samples, or whose box holds more
 * than MaxBricks bricks or MaxAxis cells along an axis, are coarsened by
 * one integer factor on every axis (the smallest that fits; a coarsened
 * cell averages 2^3 samples).
 *
 * From this grid come the tables a texture is normalized by: the integral
 * of the density over each histogram cell and its first moments
 * (BuildTables()), and so each region's integral and sigma_t-weighted
 * centroid.
 */
class NativeMediumGrid
{
public:
  static constexpr std::size_t MaxSamples = std::size_t(1) << 23; // 32 MB
  static constexpr std::size_t MaxBricks = std::size_t(1) << 21;  // 16 MB of table
  static constexpr int MaxAxis = 2048;

  /// Samples the density of `medium` (which has one).
  void Sample(const Medium& medium, const ParallelFor& parallelFor);
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
   */
  const BrickedGrid& GetScalars() const { return this->Scalars; }
  const OpacityTransferFunction* GetClassification() const { return this->Classification; }
  const std::array<int, 3>& GetResolution() const { return this->Density.GetDims(); }
  /// The box of the grid's cells (DensityField::NativeBox(), grown to whole
  /// coarsened cells): it holds the medium's bounds.
  const Box& GetBox() const { return this->Density.GetBox(); }

  /// The density's integral over each of `dims` histogram cells over the
  /// medium's bounds `box`, and its first moments.
  void BuildTables(const Box& box, const std::array<int, 3>& dims);
  bool HasTables() const { return this->DensityTable.GetNumberOfChannels() != 0; }
  /// The density's integral over a region of histogram cells.
  double RegionIntegral(const Region& region) const;
  /// Regions whose integral is at most this hold no medium.
  double GetEmptyIntegral() const { return this->EmptyIntegral; }
  /// Where each texel's estimate belongs (its region's sigma_t-weighted
  /// centroid), for the texture whose interpolation meets it there.
  CentroidMatching Centroids(const std::vector<Region>& regions,
    const std::array<int, 3>& resolution, int refinement, const ParallelFor& parallelFor) const;

private:
  BrickedGrid Density; // the density's mean per cell
  BrickedGrid Scalars; // a classified density's scalars at the same centres
  const OpacityTransferFunction* Classification = nullptr;
  SummedAreaTable DensityTable;   // integral of the density per histogram cell
  SummedAreaTable DensityMoments; // and its first moments (histogram-cell coordinates)
  double EmptyIntegral = 0.0;
};

} // namespace brume

#endif
