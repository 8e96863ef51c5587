// SPDX-License-Identifier: BSD-3-Clause
// A medium defined by a scalar field and a transfer function, as VTK's
// volume properties define how a field looks: the scalar-opacity function
// gives the extinction, classified after interpolation (as VTK's ray caster
// does), and its block majorants follow the function over each block's
// scalar range, so a function that is 0 over most of the range costs no
// dense majorant.
#ifndef brume_TransferFunction_h
#define brume_TransferFunction_h

#include "brume/Density.h"
#include "brume/Medium.h"

#include <algorithm>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace brume
{

/**
 * Opacity per unit distance as a piecewise-linear function of a scalar
 * (vtkPiecewiseFunction with its midpoints at 0.5 and sharpness 0), clamped
 * to its end values outside its range, and the extinction it stands for.
 *
 * VTK's ray caster composites a step of length dt with the opacity
 * 1 - (1 - alpha)^(dt / unit), alpha the function's value and `unit` the
 * volume property's ScalarOpacityUnitDistance. That is the transmittance of
 * the extinction
 *
 *     sigma_t(s) = -ln(1 - alpha(s)) / unit,
 *
 * which this class returns. alpha = 1 would be infinite: opacity is held
 * below MaxOpacity (a unit distance then lets 10^-6 through).
 *
 * Extinction() costs a table lookup: TableCells cells evenly over the
 * points' scalar range, linear between sigma_t at their ends. Within a
 * cell where alpha is linear (no point of the function in the cell, its
 * ends included) sigma_t is a convex function of the scalar, so the chord
 * lies above it, and its largest distance is found in closed form when the
 * table is made: cells where it exceeds TableTolerance of sigma_t there,
 * and cells holding a point, are evaluated exactly (ExactExtinction()).
 * Every value is thus within TableTolerance (relative) of the exact one
 * (above it but for the float rounding of the exact one, which near alpha
 * = 1 reaches 10^-5), and MaxExtinction() bounds both: a block's majorant
 * is the largest of either over its scalars, as tight as before.
 */
class OpacityTransferFunction
{
public:
  struct Node
  {
    float Scalar;
    float Opacity;
  };
  static constexpr float MaxOpacity = 1.f - 1e-6f;

  /**
   * Empty when `nodes` (at least one, scalars finite and non-decreasing,
   * opacities in [0, 1]) and `unitDistance` (finite, > 0) make a function;
   * otherwise what is wrong.
   */
  static std::string Validate(const std::vector<Node>& nodes, double unitDistance);

  /// Requires Validate(nodes, unitDistance) to be empty.
  OpacityTransferFunction(std::vector<Node> nodes, float unitDistance);

  /// alpha(s), linear between nodes; a scalar at two nodes takes the later one.
  float Opacity(float s) const;
  /// Cells of the extinction's table, and the relative error it may make.
  static constexpr int TableCells = 4096;
  static constexpr double TableTolerance = 1e-4;

  /// sigma_t(s) = -ln(1 - alpha(s)) / unit, in inverse units of length,
  /// from the table: at most TableTolerance above ExactExtinction(s).
  float Extinction(float s) const
  {
    const float x = (s - this->TableLow) * this->TableScale;
    if (x >= 0.f && x < static_cast<float>(TableCells))
    {
      const int c = static_cast<int>(x);
      if (!this->TableExact[static_cast<std::size_t>(c)])
      {
        const float a = this->Table[static_cast<std::size_t>(c)];
        const float b = this->Table[static_cast<std::size_t>(c) + 1];
        // Between a and b, rounding included (MaxExtinction() bounds them).
        return std::min(a + (b - a) * (x - static_cast<float>(c)), std::max(a, b));
      }
      // A scalar at a point of the function (a scan's or a generated
      // field's whole numbers at a point): its exact value, made once.
      if (s == this->CellPoint[static_cast<std::size_t>(c)])
      {
        return this->CellPointExtinction[static_cast<std::size_t>(c)];
      }
    }
    return this->ExactExtinction(s);
  }
  /// Extinction() of each of `n` scalars, in place: the same floats, a
  /// cell's samples at a time (brume::ClassifiedDensity::NativeBrick()).
  void Extinctions(float* values, int n) const;
  /// sigma_t(s) evaluated from the function's points.
  float ExactExtinction(float s) const;
  /// The largest extinction Extinction() or ExactExtinction() gives over
  /// the scalars in [lo, hi].
  float MaxExtinction(float lo, float hi) const;
  /// The largest relative error of the table's cells, as made (at most TableTolerance).
  double GetTableError() const { return this->TableError; }
  /// The table's cells evaluated from the points instead.
  int NumberOfExactCells() const
  {
    return static_cast<int>(std::count(this->TableExact.begin(), this->TableExact.end(), 1));
  }

  const std::vector<Node>& GetNodes() const { return this->Nodes; }
  float GetUnitDistance() const { return this->UnitDistance; }

  /// The same points and unit distance: the same function everywhere.
  bool SameAs(const OpacityTransferFunction& other) const;

  /**
   * The mean of the extinction over scalars that run linearly from `a` to
   * `b` (either order): (1 / (b - a)) times the integral of the function
   * Extinction() evaluates (the table's chord where it is linear, the
   * function itself where it is exact) from a to b, integrated in closed
   * form; Extinction(a) where a == b. Along a line the trilinear
   * interpolation of a grid is linear between two points, so this is the
   * exact mean of the interpolated field classified along such a segment,
   * to the table's tolerance: a function that steps within a fraction of
   * a cell (a sheet one voxel thick) is integrated, not sampled.
   *
   * The result reads the function only over [min(a, b), max(a, b)]: an
   * edit that leaves the function as it was there (OpacityFunctionEdit::
   * SameOver()) leaves the result the same float.
   */
  float MeanExtinction(float a, float b) const
  {
    // Inline, the common run: inside the table, its end cells linear.
    const float lo = std::min(a, b), hi = std::max(a, b);
    const float x0 = (lo - this->TableLow) * this->TableScale;
    const float x1 = (hi - this->TableLow) * this->TableScale;
    if (lo < hi && x0 >= 0.f && x1 < static_cast<float>(TableCells))
    {
      const int c0 = static_cast<int>(x0), c1 = static_cast<int>(x1);
      const std::size_t i0 = static_cast<std::size_t>(c0), i1 = static_cast<std::size_t>(c1);
      const bool exact0 = this->TableExact[i0] != 0, exact1 = this->TableExact[i1] != 0;
      const float f0 = x0 - static_cast<float>(c0), f1 = x1 - static_cast<float>(c1);
      if (c0 == c1 && !exact0)
      {
        // One cell of the chord: its value at the run's middle.
        const float ta = this->Table[i0], tb = this->Table[i0 + 1];
        return ta + (tb - ta) * (0.5f * (f0 + f1));
      }
      // Ends in cells evaluated exactly: where the run ends at the cell's
      // point of the function (a scan's whole numbers), integrals made once.
      if (c0 != c1 && (!exact0 || lo == this->CellPoint[i0]) &&
        (!exact1 || hi == this->CellPoint[i1]))
      {
        // The chord's integral over each end cell's part (in table units)
        // and the whole cells between; over the run's length in table units.
        auto chord = [&](std::size_t c, double u0, double u1)
        {
          const double ta = this->Table[c], tb = this->Table[c + 1];
          return (u1 - u0) * (ta + (tb - ta) * 0.5 * (u0 + u1));
        };
        const double between =
          static_cast<double>(this->CellPrefix[i1] - this->CellPrefix[i0 + 1]) *
          this->IntegralQuantum * static_cast<double>(this->TableScale);
        const double sum = (exact0 ? this->PointToEnd[i0] : chord(i0, f0, 1.0)) + between +
          (exact1 ? this->StartToPoint[i1] : chord(i1, 0.0, f1));
        return static_cast<float>(sum / (static_cast<double>(x1) - x0));
      }
    }
    return this->MeanExtinctionElsewhere(a, b);
  }
  /// The integral of ExactExtinction() over [a, b] (a <= b), in closed form.
  double ExactIntegral(double a, double b) const;

private:
  friend class OpacityFunctionEdit;
  float ExtinctionOfOpacity(float alpha) const;
  void MakeTable();
  void MakeIntegrals();
  float TableRangeMax(int first, int last) const;
  // MeanExtinction() where a run is not inside the table with linear end cells.
  float MeanExtinctionElsewhere(float a, float b) const;
  // The integral of the table's function over [x0, x1] of table cell c's
  // [0, 1], part of the run of scalars [a, b].
  double CellPartial(int c, float x0, float x1, double a, double b) const;
  // The integral of the table's function over cells [first, last).
  double CellsIntegral(int first, int last) const;

  std::vector<Node> Nodes;
  float UnitDistance;
  // The table: TableCells + 1 values over [TableLow, TableLow +
  // TableCells / TableScale]; cells marked exact are evaluated from the
  // points (all of them without a range).
  float TableLow = 0.f;
  float TableScale = 0.f;
  std::vector<float> Table;
  std::vector<char> TableExact = std::vector<char>(TableCells, 1);
  // Per cell, the scalar of a point of the function in it (NaN: none) and
  // ExactExtinction() there.
  std::vector<float> CellPoint, CellPointExtinction;
  std::vector<std::vector<float>> TableMax; // maxima of 2^l consecutive values
  double TableError = 0.0;
  // Integrals of the table's function (MeanExtinction()): per cell, over
  // the cell, and over the cells before each in whole IntegralQuantum, so
  // that a sum over a range of cells reads the cells in that range only.
  std::vector<double> CellIntegrals;
  std::vector<std::int64_t> CellPrefix;
  // Per cell holding a point of the function, the integrals (in table
  // units) from the cell's start to the point and from the point to its end.
  std::vector<double> StartToPoint, PointToEnd;
  double IntegralQuantum = 0.0;
};

/**
 * Where an edit of an opacity function left it as it was: which ranges of
 * scalars the function after the edit classifies into the same floats as
 * the one before (Extinction() and ExactExtinction() alike), with the same
 * points inside them. What was computed from scalars in such a range
 * (brume::NativeMediumGrid's bricks) stays as it was. Made once per edit
 * (the table cells compared, counted for a lookup per range); both
 * functions must outlive it.
 */
class OpacityFunctionEdit
{
public:
  OpacityFunctionEdit(const OpacityTransferFunction& before, const OpacityTransferFunction& after);
  /**
   * Whether, for every scalar s in [lo, hi], Extinction(s) and
   * ExactExtinction(s) are the same floats before and after, and the
   * points strictly between lo and hi are the same (where a classified
   * cell bends): the same unit distance, the table cells those scalars
   * fall in alike (placed alike, the same values where linear, exact
   * in both where exact), and the points Opacity() reads for them alike.
   * False for a range that is not finite.
   */
  bool SameOver(float lo, float hi) const;

private:
  const OpacityTransferFunction& Before;
  const OpacityTransferFunction& After;
  bool Comparable = false;       // the same unit distance and table placement
  std::vector<int> ChangedCells; // per table cell: cells before it whose table differs
};

/**
 * A density that is the extinction of a transfer function applied to a
 * scalar field after interpolation: density(x) = sigma_t(s(x)), s(x)
 * interpolated as the field interpolates (a grid: trilinear between point
 * values, constant per cell, or the nearest value; an OpenVDB grid:
 * trilinear between voxels). A medium with this density and
 * sigma_a + sigma_s = 1 per channel has exactly the function's extinction.
 *
 * Majorants: each block's is the function's largest extinction over the
 * range of the field's values in the block (DensityField::ValueRanges).
 */
class ClassifiedDensity : public DensityField
{
public:
  /// `scalars` should know its ValueRanges (a GridDensity, a VdbDensity loaded as scalars).
  ClassifiedDensity(std::shared_ptr<const DensityField> scalars, OpacityTransferFunction opacity,
    const ParallelFor& parallelFor = SerialFor());
  /**
   * The same after an edit of `previous`'s function over the same scalars:
   * a grid of floats keeps `previous`'s occupancy of each chunk of values
   * (GridDensity::GetChunkRanges()) over whose range the edit left the
   * function as it was (OpacityFunctionEdit::SameOver()), and counts the
   * others, so that its totals are those counted afresh, to the bit.
   */
  ClassifiedDensity(std::shared_ptr<const DensityField> scalars, OpacityTransferFunction opacity,
    const ParallelFor& parallelFor, const ClassifiedDensity* previous);
  float Evaluate(const Vec3& p) const override
  {
    return this->Opacity.Extinction(this->Scalars->Evaluate(p));
  }
  std::array<int, 3> NativeResolution() const override { return this->Scalars->NativeResolution(); }
  Box NativeBox() const override { return this->Scalars->NativeBox(); }
  float NativeValue(int i, int j, int k, const Vec3& centre) const override
  {
    return this->Opacity.Extinction(this->Scalars->NativeValue(i, j, k, centre));
  }
  /**
   * The mean of the function over native cell (i, j, k), the scalars
   * interpolated from their points and classified after: along the axis the
   * scalars change most along through the cell's point, integrated exactly
   * (OpacityTransferFunction::MeanExtinction(): the interpolated scalar is
   * linear there between two points), on s x s lines evenly across the other
   * two axes. Scalars of nearest or cell values, or a field without points,
   * the mean of s^3 samples (DensityField::NativeMean()).
   */
  double NativeMean(int i, int j, int k, const Box& cell, const Box& bounds, int s) const override;

  /**
   * Whether one of the function's points lies strictly inside the range of
   * the scalars interpolated over `region` (the values that define it): where
   * the extinction may bend or step inside the region, so that one sample
   * does not give its mean.
   */
  bool BendsWithin(const Box& region) const;
  /**
   * BendsWithin(cell) for the native cell (i, j, k) whose box is `cell`:
   * over a grid of point values, from the 27 points around point (i, j, k)
   * directly (10^8 cells of a 512^3 field ask it).
   */
  bool BendsWithinNativeCell(int i, int j, int k, const Box& cell) const;
  /**
   * The samples brume::NativeMediumGrid takes of the size^3 native cells
   * from `lower` (x fastest; cells past the grid's last take the last's):
   * NativeMean() on s x s lines where BendsWithinNativeCell(), else the
   * function at the cell's point; the same floats as cell by cell, from
   * the brick's points read once. A grid of nearest or cell values: each
   * cell's own value classified (every sample of a cell reads it). False,
   * with nothing written, where the scalars are neither such a grid nor
   * one of points interpolated linearly (or an OpenVDB grid), or size
   * exceeds 8.
   */
  bool NativeBrick(
    const std::array<int, 3>& lower, int size, int s, float* out, float* range = nullptr) const;
  /**
   * The smallest and largest of the scalars NativeBrick() reads for the
   * same cells (`range`: two floats; what it writes there too), or, over a
   * grid read otherwise (nearest values, cell values), of the values its
   * cells and their neighbours hold, which the cells' samples read
   * (BendsWithinNativeCell(), NativeMean()): the cells' samples depend on
   * the function over that range only (OpacityFunctionEdit::SameOver()).
   * NaN where a value is not finite; false for other fields whose
   * NativeBrick() is false.
   */
  bool NativeBrickRange(const std::array<int, 3>& lower, int size, float* range) const;

  const DensityField& GetScalars() const { return *this->Scalars; }
  /// The scalars' owner (for one that keeps them alive with the function).
  const std::shared_ptr<const DensityField>& GetScalarsPointer() const { return this->Scalars; }
  const OpacityTransferFunction& GetOpacity() const { return this->Opacity; }
  /// The chunks of values whose occupancy was kept from the previous function.
  std::size_t GetNumberOfKeptChunks() const { return this->KeptChunks; }

private:
  bool BendsWithinBlocks(const Box& region) const;
  /// The points NativeBrick() reads for the size^3 cells from `lower`
  /// (into `points`, (size + 2)^3 at most), their first point and counts.
  bool NativeBrickPoints(const std::array<int, 3>& lower, int size, float* points,
    std::array<int, 3>& first, std::array<int, 3>& count) const;
  /// NativeBrickRange() over the grid's own values, with the cells' neighbours.
  void GridWindowRange(const std::array<int, 3>& lower, int size, float* range) const;
  /// Whether one of the function's points lies strictly between lo and hi.
  bool PointBetween(float lo, float hi) const
  {
    const auto next = std::upper_bound(this->Points.begin(), this->Points.end(), lo);
    return next != this->Points.end() && *next < hi;
  }

  std::shared_ptr<const DensityField> Scalars;
  const GridDensity* Grid = nullptr; // Scalars, when a grid
  std::vector<float> Points;         // the function's points' scalars, ascending, once each
  // Per majorant block, the field's value range (empty when it cannot say).
  std::vector<float> RangeLow, RangeHigh;
  OpacityTransferFunction Opacity;
  // A grid of floats: per chunk of values, the occupied count and sum
  // (DensityField::CountOccupiedChunks()), and how many came from a previous
  // function.
  std::vector<double> ChunkOccupied, ChunkSums;
  std::size_t KeptChunks = 0;
};

/**
 * Colour as a piecewise-linear function of a scalar, RGB per point
 * (vtkColorTransferFunction in RGB space, its midpoints at 0.5 and
 * sharpness 0, clamped to its end colours outside its range).
 */
class ColorTransferFunction
{
public:
  struct Node
  {
    float Scalar;
    Vec3 Color;
  };

  /**
   * Empty when `nodes` (at least one, scalars finite and non-decreasing,
   * colours in [0, 1]) make a function; otherwise what is wrong.
   */
  static std::string Validate(const std::vector<Node>& nodes);

  /// Requires Validate(nodes) to be empty.
  explicit ColorTransferFunction(std::vector<Node> nodes);

  /// The colour at s, linear between points; a scalar at two points takes the later one.
  Vec3 Color(float s) const;
  /// Color() of each of `n` scalars into `out`: the same colours, the
  /// last pair of points tried before a search (neighbouring samples
  /// mostly fall between the same two).
  void Colors(const float* s, std::size_t n, Vec3* out) const;
  const std::vector<Node>& GetNodes() const { return this->Nodes; }

private:
  std::vector<Node> Nodes;
};

/**
 * The colour of a transfer function applied to a scalar field after
 * interpolation, as a factor on a medium's albedo (Medium::AlbedoFactor):
 * the albedo at x is the medium's Albedo() times colour(s(x)). With the
 * extinction a ClassifiedDensity of the same scalars gives, this is how a
 * VTK volume property's colour transfer function colours the light a
 * medium scatters: sigma_s(x) = Albedo() colour(s(x)) sigma_t(s(x)).
 */
class ClassifiedAlbedo : public AlbedoField
{
public:
  ClassifiedAlbedo(std::shared_ptr<const DensityField> scalars, ColorTransferFunction colors);
  Vec3 Evaluate(const Vec3& p) const override
  {
    return this->Colors.Color(this->Scalars->Evaluate(p));
  }
  /// The scalars' native grid is the density's (the scalars it classifies).
  bool SharesNativeCells(const DensityField& density) const override;
  /// The colour of the scalars' own sample at native cell (i, j, k).
  Vec3 NativeValue(int i, int j, int k, const Vec3& centre) const override
  {
    return this->Colors.Color(this->Scalars->NativeValue(i, j, k, centre));
  }
  /// The colours of the scalars' own samples, where the scalars give them
  /// at once (DensityField::NativePoints()).
  bool NativeValues(const std::array<int, 3>& lower, const std::array<int, 3>& count,
    std::vector<float>& scratch, Vec3* out) const override;
  const ColorTransferFunction& GetColors() const { return this->Colors; }
  const DensityField& GetScalars() const { return *this->Scalars; }
  /// The scalars' owner (for one that keeps them alive with the function).
  const std::shared_ptr<const DensityField>& GetScalarsPointer() const { return this->Scalars; }

private:
  std::shared_ptr<const DensityField> Scalars;
  ColorTransferFunction Colors;
};

} // namespace brume

#endif
