// SPDX-License-Identifier: BSD-3-Clause
#include "brume/TransferFunction.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace brume
{

std::string OpacityTransferFunction::Validate(const std::vector<Node>& nodes, double unitDistance)
{
  if (nodes.empty())
  {
    return "has no opacity points";
  }
  for (std::size_t i = 0; i < nodes.size(); ++i)
  {
    std::ostringstream at;
    at << "opacity point " << i << " (scalar " << nodes[i].Scalar << ", opacity "
       << nodes[i].Opacity << ")";
    if (!std::isfinite(nodes[i].Scalar))
    {
      return at.str() + " has a non-finite scalar";
    }
    if (!(nodes[i].Opacity >= 0.f && nodes[i].Opacity <= 1.f))
    {
      return at.str() + " has an opacity outside [0, 1]";
    }
    if (i > 0 && nodes[i].Scalar < nodes[i - 1].Scalar)
    {
      return at.str() + " comes before the previous point's scalar: scalars must not decrease";
    }
  }
  if (!(unitDistance > 0.0) || !std::isfinite(unitDistance))
  {
    return "has a unit distance that is not a finite positive number";
  }
  return {};
}

OpacityTransferFunction::OpacityTransferFunction(std::vector<Node> nodes, float unitDistance)
  : Nodes(std::move(nodes))
  , UnitDistance(unitDistance)
{
  this->MakeTable();
  this->MakeIntegrals();
}

void OpacityTransferFunction::MakeTable()
{
  this->CellPoint.assign(TableCells, std::numeric_limits<float>::quiet_NaN());
  this->CellPointExtinction.assign(TableCells, 0.f);
  const double lo = this->Nodes.front().Scalar, hi = this->Nodes.back().Scalar;
  const double step = (hi - lo) / TableCells;
  if (!(step > 0.0) || !std::isfinite(step))
  {
    return; // one scalar: every value exact
  }
  this->TableLow = static_cast<float>(lo);
  this->TableScale = static_cast<float>(TableCells / (hi - lo));
  // The cells' ends where Extinction() puts them (x = (s - low) * scale).
  std::vector<double> ends(TableCells + 1);
  for (int c = 0; c <= TableCells; ++c)
  {
    ends[static_cast<std::size_t>(c)] =
      static_cast<double>(this->TableLow) + c / static_cast<double>(this->TableScale);
  }
  this->Table.resize(TableCells + 1);
  for (int c = 0; c <= TableCells; ++c)
  {
    this->Table[static_cast<std::size_t>(c)] =
      this->ExactExtinction(static_cast<float>(ends[static_cast<std::size_t>(c)]));
  }
  const double unit = this->UnitDistance;
  auto sigma = [unit](double alpha) { return -std::log1p(-alpha) / unit; };
  std::size_t node = 0;
  for (int c = 0; c < TableCells; ++c)
  {
    const double a = ends[static_cast<std::size_t>(c)], b = ends[static_cast<std::size_t>(c) + 1];
    // A point in [a, b] (the function may bend or step there), or an
    // opacity past MaxOpacity: exact.
    while (node < this->Nodes.size() && this->Nodes[node].Scalar < a)
    {
      ++node;
    }
    const float alphaA = this->Opacity(static_cast<float>(a));
    const float alphaB = this->Opacity(static_cast<float>(b));
    if ((node < this->Nodes.size() && this->Nodes[node].Scalar <= b) ||
      std::max(alphaA, alphaB) >= MaxOpacity)
    {
      continue;
    }
    // alpha is linear over the cell and sigma convex in alpha: the chord
    // between the table's values is farthest above sigma where sigma's
    // slope in alpha equals the chord's, 1 / (unit (1 - alpha*)) = dS / dA.
    const double fa = this->Table[static_cast<std::size_t>(c)];
    const double fb = this->Table[static_cast<std::size_t>(c) + 1];
    const double dA = static_cast<double>(alphaB) - alphaA, dS = fb - fa;
    double error = 0.0, at = std::max(fa, fb);
    if (dA != 0.0 && dS != 0.0)
    {
      const double star = std::clamp(
        1.0 - dA / (unit * dS), std::min<double>(alphaA, alphaB), std::max<double>(alphaA, alphaB));
      at = sigma(star);
      error = fa + (star - alphaA) * dS / dA - at;
    }
    // The table's values themselves are sigma rounded to float.
    const double rounding = 4.0 * std::numeric_limits<float>::epsilon() * std::max(fa, fb);
    if (error <= TableTolerance * at + rounding)
    {
      this->TableExact[static_cast<std::size_t>(c)] = 0;
      this->TableError = std::max(this->TableError, at > 0.0 ? error / at : 0.0);
    }
  }
  // The points' own values, where Extinction() finds their scalars.
  for (const Node& n : this->Nodes)
  {
    const float x = (n.Scalar - this->TableLow) * this->TableScale;
    if (x >= 0.f && x < static_cast<float>(TableCells))
    {
      const std::size_t c = static_cast<std::size_t>(x);
      this->CellPoint[c] = n.Scalar;
      this->CellPointExtinction[c] = this->ExactExtinction(n.Scalar);
    }
  }
  // Maxima of the table's values over runs of 2^l ends, for MaxExtinction().
  this->TableMax.assign(1, this->Table);
  for (int width = 2; width <= TableCells + 1; width *= 2)
  {
    const std::vector<float>& below = this->TableMax.back();
    std::vector<float> row(static_cast<std::size_t>(TableCells + 2 - width));
    for (std::size_t i = 0; i < row.size(); ++i)
    {
      row[i] = std::max(below[i], below[i + static_cast<std::size_t>(width / 2)]);
    }
    this->TableMax.push_back(std::move(row));
  }
}

void OpacityTransferFunction::Extinctions(float* values, int n) const
{
  int m = 0;
#if defined(__SSE2__)
  const float* table = this->Table.data();
  const char* exact = this->TableExact.data();
  // Four at a time: the table's operations lane by lane (std::min(r, t)
  // is (t < r) ? t : r, that is _mm_min_ps(t, r); std::max(a, b) is
  // _mm_max_ps(b, a)), from cells clamped into the table so that every
  // read is in it; a lane outside the table or in a cell evaluated
  // exactly (a function's point: a scan's whole numbers often lie there)
  // is then given Extinction() alone.
  const __m128 lowV = _mm_set1_ps(this->TableLow), scaleV = _mm_set1_ps(this->TableScale);
  const __m128 zero = _mm_setzero_ps(), cells = _mm_set1_ps(static_cast<float>(TableCells));
  const __m128 last = _mm_set1_ps(std::nextafter(static_cast<float>(TableCells), 0.f));
  for (; !this->Table.empty() && m + 4 <= n; m += 4)
  {
    alignas(16) float scalars[4];
    const __m128 v = _mm_loadu_ps(values + m);
    _mm_store_ps(scalars, v);
    const __m128 x = _mm_mul_ps(_mm_sub_ps(v, lowV), scaleV);
    const int inside = _mm_movemask_ps(_mm_and_ps(_mm_cmpge_ps(x, zero), _mm_cmplt_ps(x, cells)));
    const __m128 within = _mm_min_ps(_mm_max_ps(x, zero), last); // x itself where inside
    const __m128i cell = _mm_cvttps_epi32(within);
    alignas(16) int c[4];
    _mm_store_si128(reinterpret_cast<__m128i*>(c), cell);
    const __m128 a = _mm_setr_ps(table[c[0]], table[c[1]], table[c[2]], table[c[3]]);
    const __m128 b =
      _mm_setr_ps(table[c[0] + 1], table[c[1] + 1], table[c[2] + 1], table[c[3] + 1]);
    const __m128 r =
      _mm_add_ps(a, _mm_mul_ps(_mm_sub_ps(b, a), _mm_sub_ps(within, _mm_cvtepi32_ps(cell))));
    _mm_storeu_ps(values + m, _mm_min_ps(_mm_max_ps(b, a), r));
    for (int l = 0; l < 4; ++l)
    {
      if (!((inside >> l) & 1) || exact[c[l]])
      {
        values[m + l] = this->Extinction(scalars[l]);
      }
    }
  }
#endif
  for (; m < n; ++m)
  {
    values[m] = this->Extinction(values[m]);
  }
}

float OpacityTransferFunction::Opacity(float s) const
{
  // The first node past s; s at a node's scalar takes the last node there.
  const auto next = std::upper_bound(
    this->Nodes.begin(), this->Nodes.end(), s, [](float v, const Node& n) { return v < n.Scalar; });
  if (next == this->Nodes.begin())
  {
    return this->Nodes.front().Opacity;
  }
  if (next == this->Nodes.end())
  {
    return this->Nodes.back().Opacity;
  }
  const Node& a = *(next - 1);
  const Node& b = *next;
  const float t = (s - a.Scalar) / (b.Scalar - a.Scalar);
  return a.Opacity + (b.Opacity - a.Opacity) * t;
}

float OpacityTransferFunction::ExtinctionOfOpacity(float alpha) const
{
  return -std::log1p(-std::min(alpha, MaxOpacity)) / this->UnitDistance;
}

float OpacityTransferFunction::ExactExtinction(float s) const
{
  return this->ExtinctionOfOpacity(this->Opacity(s));
}

float OpacityTransferFunction::MaxExtinction(float lo, float hi) const
{
  // A piecewise-linear function's largest value on [lo, hi] is at an end or
  // at a node inside; extinction grows with opacity.
  float alpha = std::max(this->Opacity(lo), this->Opacity(hi));
  for (const Node& n : this->Nodes)
  {
    if (n.Scalar >= lo && n.Scalar <= hi)
    {
      alpha = std::max(alpha, n.Opacity);
    }
  }
  float largest = this->ExtinctionOfOpacity(alpha);
  // The table's values over [lo, hi]: linear within a cell, so at most
  // those at lo, at hi and at the cells' ends between.
  if (!this->Table.empty() && hi >= lo)
  {
    largest = std::max({ largest, this->Extinction(lo), this->Extinction(hi) });
    const float x0 = (lo - this->TableLow) * this->TableScale;
    const float x1 = (hi - this->TableLow) * this->TableScale;
    const float cells = static_cast<float>(TableCells);
    if (x1 >= 1.f && x0 < cells)
    {
      // Ends c0 + 1 ... c1 of the cells lo and hi fall in.
      const int first = x0 < 0.f ? 0 : static_cast<int>(x0) + 1;
      const int last = x1 >= cells ? TableCells : static_cast<int>(x1);
      if (first <= last)
      {
        largest = std::max(largest, this->TableRangeMax(first, last));
      }
    }
  }
  return largest;
}

bool OpacityTransferFunction::SameAs(const OpacityTransferFunction& other) const
{
  if (this->UnitDistance != other.UnitDistance || this->Nodes.size() != other.Nodes.size())
  {
    return false;
  }
  return std::equal(this->Nodes.begin(), this->Nodes.end(), other.Nodes.begin(),
    [](const Node& a, const Node& b) { return a.Scalar == b.Scalar && a.Opacity == b.Opacity; });
}

OpacityFunctionEdit::OpacityFunctionEdit(
  const OpacityTransferFunction& before, const OpacityTransferFunction& after)
  : Before(before)
  , After(after)
{
  this->Comparable = before.UnitDistance == after.UnitDistance &&
    before.TableLow == after.TableLow && before.TableScale == after.TableScale &&
    before.Table.size() == after.Table.size();
  if (!this->Comparable || before.Table.empty())
  {
    return;
  }
  // A cell exact in both reads the points (compared per range); one that
  // is linear in both reads its two table values.
  const int cells = OpacityTransferFunction::TableCells;
  this->ChangedCells.assign(static_cast<std::size_t>(cells) + 1, 0);
  for (std::size_t c = 0; c < static_cast<std::size_t>(cells); ++c)
  {
    const bool exact = before.TableExact[c] != 0;
    const bool same = exact == (after.TableExact[c] != 0) &&
      (exact || (before.Table[c] == after.Table[c] && before.Table[c + 1] == after.Table[c + 1]));
    this->ChangedCells[c + 1] = this->ChangedCells[c] + (same ? 0 : 1);
  }
}

bool OpacityFunctionEdit::SameOver(float lo, float hi) const
{
  if (!this->Comparable || !std::isfinite(lo) || !std::isfinite(hi) || lo > hi)
  {
    return false;
  }
  const OpacityTransferFunction& before = this->Before;
  if (!before.Table.empty())
  {
    // The cells Extinction() finds for scalars in [lo, hi]: between those
    // of lo and hi, its float arithmetic being monotonic.
    const float x0 = (lo - before.TableLow) * before.TableScale;
    const float x1 = (hi - before.TableLow) * before.TableScale;
    const float cells = static_cast<float>(OpacityTransferFunction::TableCells);
    if (x1 >= 0.f && x0 < cells)
    {
      const int c0 = x0 < 0.f ? 0 : static_cast<int>(x0);
      const int c1 = x1 >= cells ? OpacityTransferFunction::TableCells - 1 : static_cast<int>(x1);
      if (this->ChangedCells[static_cast<std::size_t>(c1) + 1] !=
        this->ChangedCells[static_cast<std::size_t>(c0)])
      {
        return false;
      }
    }
  }
  // The points Opacity() reads for scalars in [lo, hi]: from the last at
  // or below lo (or the first) to the first above hi (or the last; not
  // read where the last at or below hi is at hi itself: a scalar at a
  // point takes that point's opacity exactly), and whether the range
  // reaches past either end. Interpolated scalars stay within the values
  // they lie between (GridDensity's weights are below 1), so [lo, hi]
  // holds every scalar a brick classifies.
  struct Span
  {
    std::size_t First, Last;
    bool Before, After;
  };
  using Node = OpacityTransferFunction::Node;
  auto span = [lo, hi](const std::vector<Node>& nodes)
  {
    auto above = [](float v, const Node& n) { return v < n.Scalar; };
    const auto ua = std::upper_bound(nodes.begin(), nodes.end(), lo, above);
    const auto ub = std::upper_bound(nodes.begin(), nodes.end(), hi, above);
    Span s{};
    s.Before = ua == nodes.begin();
    s.After = ub == nodes.end();
    s.First = s.Before ? 0 : static_cast<std::size_t>(ua - nodes.begin()) - 1;
    const std::size_t at = static_cast<std::size_t>(ub - nodes.begin());
    s.Last = s.After ? nodes.size() - 1 : (at > 0 && nodes[at - 1].Scalar == hi ? at - 1 : at);
    return s;
  };
  const Span mine = span(before.Nodes), theirs = span(this->After.Nodes);
  if (mine.Before != theirs.Before || mine.After != theirs.After ||
    mine.Last - mine.First != theirs.Last - theirs.First)
  {
    return false;
  }
  for (std::size_t n = 0; n <= mine.Last - mine.First; ++n)
  {
    const Node& x = before.Nodes[mine.First + n];
    const Node& y = this->After.Nodes[theirs.First + n];
    if (x.Scalar != y.Scalar || x.Opacity != y.Opacity)
    {
      return false;
    }
  }
  return true;
}

float OpacityTransferFunction::TableRangeMax(int first, int last) const
{
  // The sparse table: level l holds the maxima of 2^l ends from each end.
  int level = 0;
  while ((2 << level) <= last - first + 1)
  {
    ++level;
  }
  const std::vector<float>& row = this->TableMax[static_cast<std::size_t>(level)];
  return std::max(
    row[static_cast<std::size_t>(first)], row[static_cast<std::size_t>(last - (1 << level) + 1)]);
}

ClassifiedDensity::ClassifiedDensity(std::shared_ptr<const DensityField> scalars,
  OpacityTransferFunction opacity, const ParallelFor& parallelFor)
  : ClassifiedDensity(std::move(scalars), std::move(opacity), parallelFor, nullptr)
{
}

ClassifiedDensity::ClassifiedDensity(std::shared_ptr<const DensityField> scalars,
  OpacityTransferFunction opacity, const ParallelFor& parallelFor,
  const ClassifiedDensity* previous)
  : Scalars(std::move(scalars))
  , Opacity(std::move(opacity))
{
  this->Bounds = this->Scalars->GetBounds();
  this->Grid = dynamic_cast<const GridDensity*>(this->Scalars.get());
  for (const auto& node : this->Opacity.GetNodes())
  {
    if (this->Points.empty() || node.Scalar != this->Points.back())
    {
      this->Points.push_back(node.Scalar); // validated: not decreasing
    }
  }
  // A grid's values: the fraction and mean of those the function makes
  // positive (other fields: the non-empty majorant blocks').
  const GridDensity* grid = this->Grid;
  const GridDensity::ValueCounts* integers = grid ? &grid->GetValueCounts(parallelFor) : nullptr;
  if (integers && !integers->Counts.empty())
  {
    // Integers: each integer's extinction once, weighted by how many values
    // hold it (the sums of the loop below, added in another order).
    const std::vector<std::uint64_t>& counts = integers->Counts;
    double occupied = 0.0, sum = 0.0;
    for (std::size_t b = 0; b < counts.size(); ++b)
    {
      const float v = counts[b]
        ? this->Opacity.Extinction(static_cast<float>(integers->Lowest + static_cast<int>(b)))
        : 0.f;
      if (v > 0.f)
      {
        occupied += static_cast<double>(counts[b]);
        sum += static_cast<double>(counts[b]) * v;
      }
    }
    this->SetOccupied(static_cast<double>(grid->GetValues().Size()), { occupied }, { sum });
  }
  else if (grid)
  {
    // Counted chunk by chunk, each chunk's occupancy kept from the previous
    // function where the edit left the function as it was over the chunk's
    // values (the same floats: the totals are those counted afresh).
    const TypedValues& typed = grid->GetValues();
    const std::size_t chunks = (typed.Size() + OccupiedChunk - 1) / OccupiedChunk;
    std::vector<char> kept;
    if (previous && previous->Scalars == this->Scalars && previous->ChunkOccupied.size() == chunks)
    {
      const std::vector<float>& ranges = grid->GetChunkRanges(parallelFor);
      const OpacityFunctionEdit edit(previous->Opacity, this->Opacity);
      kept.assign(chunks, 0);
      this->ChunkOccupied.assign(chunks, 0.0);
      this->ChunkSums.assign(chunks, 0.0);
      for (std::size_t c = 0; c < chunks; ++c)
      {
        if (edit.SameOver(ranges[2 * c], ranges[2 * c + 1]))
        {
          kept[c] = 1;
          this->ChunkOccupied[c] = previous->ChunkOccupied[c];
          this->ChunkSums[c] = previous->ChunkSums[c];
          ++this->KeptChunks;
        }
      }
    }
    typed.Visit(
      [&](const auto* values)
      {
        CountOccupiedChunkRuns(
          typed.Size(),
          [&](std::size_t first, std::size_t n, float* out)
          {
            for (std::size_t i = 0; i < n; ++i)
            {
              out[i] = static_cast<float>(values[first + i]);
            }
            this->Opacity.Extinctions(out, static_cast<int>(n));
          },
          parallelFor, kept, this->ChunkOccupied, this->ChunkSums);
      });
    this->SetOccupied(static_cast<double>(typed.Size()), this->ChunkOccupied, this->ChunkSums);
  }
  this->Majorants = this->Scalars->GetMajorants();
  std::vector<float>& lo = this->RangeLow;
  std::vector<float>& hi = this->RangeHigh;
  if (!this->Scalars->ValueRanges(lo, hi) || hi.size() != this->Majorants.Max.size())
  {
    lo.clear();
    hi.clear();
    // Without ranges, the function's largest extinction everywhere.
    const auto& nodes = this->Opacity.GetNodes();
    const float all = this->Opacity.MaxExtinction(nodes.front().Scalar, nodes.back().Scalar);
    std::fill(this->Majorants.Max.begin(), this->Majorants.Max.end(), all);
    this->Majorants.MarkEmptyRegions();
    return;
  }
  for (std::size_t b = 0; b < hi.size(); ++b)
  {
    // A block of non-finite values only (none to range over) has none to classify.
    this->Majorants.Max[b] = lo[b] <= hi[b] ? this->Opacity.MaxExtinction(lo[b], hi[b]) : 0.f;
  }
  this->Majorants.MarkEmptyRegions();
}

namespace
{
/**
 * The mean extinction over native cell `index` (the box half a spacing
 * around point `index`, clamped at the grid's ends) of a grid of `dims`
 * points whose values `at(x, y, z)` gives (asked for points within one of
 * `index`), interpolated trilinearly and classified after.
 *
 * Along any line parallel to an axis the interpolated scalar is linear
 * between two points, so along the axis the scalars change most along
 * through the point the cell's two halves are integrated exactly
 * (OpacityTransferFunction::MeanExtinction()), at s x s lines evenly over
 * the other two axes (where InterpolateNativeSamples() puts its samples).
 * A sheet one voxel thin, across which the function steps within a
 * fraction of a cell, is then integrated, not sampled: its mean of s^3
 * samples made the shells' (Data/scenes/shells.json) shadows 10 to 15 %
 * too light.
 */
double ClassifiedCellMean(const OpacityTransferFunction& function, const int index[3],
  const std::array<int, 3>& dims, int s, const float* points, const std::array<int, 3>& first,
  const std::array<int, 3>& count)
{
  // The points as (x, y, z) from `first`, x fastest.
  const std::ptrdiff_t stride[3] = { 1, count[0],
    static_cast<std::ptrdiff_t>(count[0]) * count[1] };
  const float* own = points + (index[0] - first[0]) * stride[0] +
    (index[1] - first[1]) * stride[1] + (index[2] - first[2]) * stride[2];
  int axis = 0;
  float most = -1.f;
  for (int a = 0; a < 3; ++a)
  {
    const std::ptrdiff_t down = index[a] > 0 ? stride[a] : 0;
    const std::ptrdiff_t up = index[a] < dims[a] - 1 ? stride[a] : 0;
    const float change = std::abs(own[up] - *own) + std::abs(*own - own[-down]);
    if (change > most)
    {
      most = change;
      axis = a;
    }
  }
  const int lateral[2] = { (axis + 1) % 3, (axis + 2) % 3 };
  constexpr int M = GridDensity::MaxNativeSamples;
  std::ptrdiff_t from[2][M], to[2][M]; // offsets of the two points a line lies between
  float weight[2][M];
  for (int l = 0; l < 2; ++l)
  {
    const int a = lateral[l], n = dims[a];
    for (int m = 0; m < s; ++m)
    {
      const float u = (static_cast<float>(m) + 0.5f) / static_cast<float>(s) - 0.5f;
      const float x = std::clamp(static_cast<float>(index[a]) + u, 0.f, static_cast<float>(n - 1));
      const int i0 = n == 1 ? 0 : std::min(n - 2, static_cast<int>(x));
      from[l][m] = (i0 - first[a]) * stride[a];
      to[l][m] = (std::min(i0 + 1, n - 1) - first[a]) * stride[a];
      weight[l][m] = n == 1 ? 0.f : x - static_cast<float>(i0);
    }
  }
  auto lerp = [](float a, float b, float t) { return a + (b - a) * t; };
  // The scalars on the s x s lines at the points before, at and after the
  // cell's own along the axis (clamped at the grid's ends).
  const int n = dims[axis], i = index[axis];
  const std::ptrdiff_t along[3] = { (std::max(i - 1, 0) - first[axis]) * stride[axis],
    (i - first[axis]) * stride[axis], (std::min(i + 1, n - 1) - first[axis]) * stride[axis] };
  float onLines[3][M][M];
  for (int k = 0; k < 3; ++k)
    for (int mq = 0; mq < s; ++mq)
    {
      const float* p0 = points + along[k] + from[1][mq];
      const float* p1 = points + along[k] + to[1][mq];
      for (int m = 0; m < s; ++m)
      {
        const float a0 = lerp(p0[from[0][m]], p0[to[0][m]], weight[0][m]);
        const float a1 = lerp(p1[from[0][m]], p1[to[0][m]], weight[0][m]);
        onLines[k][mq][m] = lerp(a0, a1, weight[1][mq]);
      }
    }
  double sum = 0.0;
  for (int mq = 0; mq < s; ++mq)
    for (int m = 0; m < s; ++m)
    {
      const float centre = onLines[1][mq][m];
      // Half a spacing before and after the point, where the cell ends
      // (at the grid's ends the cell is clamped: its outer half holds the
      // point's own scalar).
      const float before = i > 0 ? 0.5f * (onLines[0][mq][m] + centre) : centre;
      const float after = i < n - 1 ? 0.5f * (centre + onLines[2][mq][m]) : centre;
      sum += static_cast<double>(function.MeanExtinction(before, centre)) +
        function.MeanExtinction(centre, after);
    }
  return sum / (2.0 * s * s);
}
}

double ClassifiedDensity::NativeMean(
  int i, int j, int k, const Box& cell, const Box& bounds, int s) const
{
  if (s < 1 || s > GridDensity::MaxNativeSamples ||
    (this->Grid &&
      (this->Grid->HasCellValues() ||
        this->Grid->GetInterpolation() == GridDensity::Interpolation::Nearest)))
  {
    // Nearest values and cell values: every sample reads the cell's own value.
    return DensityField::NativeMean(i, j, k, cell, bounds, s);
  }
  // Point values interpolated linearly: the 27 points around point (i, j, k).
  const std::array<int, 3> dims = this->Scalars->NativeResolution();
  const int index[3] = { i, j, k };
  std::array<int, 3> first{}, count{};
  for (int a = 0; a < 3; ++a)
  {
    first[a] = std::clamp(index[a] - 1, 0, std::max(dims[a] - 1, 0));
    count[a] = std::min(dims[a] - 1, index[a] + 1) - first[a] + 1;
  }
  float points[27];
  if (count[0] < 1 || count[1] < 1 || count[2] < 1 ||
    !this->Scalars->NativePoints(first, count, points))
  {
    return DensityField::NativeMean(i, j, k, cell, bounds, s);
  }
  return ClassifiedCellMean(this->Opacity, index, dims, s, points, first, count);
}

bool ClassifiedDensity::BendsWithinNativeCell(int i, int j, int k, const Box& cell) const
{
  if (!this->Grid || this->Grid->HasCellValues())
  {
    return this->BendsWithin(cell);
  }
  // Point values: the cell around point (i, j, k) reaches half a spacing
  // towards each neighbour, so its values are those the 27 points around
  // it interpolate (clamped at the grid's ends), as BendsWithin() finds.
  const std::array<int, 3>& dims = this->Grid->GetDimensions();
  const int at[3] = { i, j, k };
  int first[3], last[3];
  for (int a = 0; a < 3; ++a)
  {
    first[a] = std::clamp(at[a] - 1, 0, dims[a] - 1);
    last[a] = std::clamp(at[a] + 1, first[a], dims[a] - 1);
  }
  return this->Grid->GetValues().Visit(
    [&](const auto* values)
    {
      float lo = static_cast<float>(
        values[(static_cast<std::size_t>(first[2]) * dims[1] + first[1]) * dims[0] + first[0]]);
      float hi = lo;
      for (int z = first[2]; z <= last[2]; ++z)
        for (int y = first[1]; y <= last[1]; ++y)
        {
          const auto* row = values + (static_cast<std::size_t>(z) * dims[1] + y) * dims[0];
          for (int x = first[0]; x <= last[0]; ++x)
          {
            const float v = static_cast<float>(row[x]);
            lo = std::min(lo, v);
            hi = std::max(hi, v);
          }
        }
      return this->PointBetween(lo, hi);
    });
}

namespace
{
constexpr int MostBrickCells = 8, MostBrickPoints = MostBrickCells + 2;

// The values that the size^3 cells from `lower` read: their own and one
// beyond on either side, clamped at the grid's ends (`dims` values along
// each axis).
void BrickWindow(const std::array<int, 3>& lower, int size, const std::array<int, 3>& dims,
  std::array<int, 3>& first, std::array<int, 3>& count)
{
  for (int a = 0; a < 3; ++a)
  {
    const int last = std::min(lower[a] + size - 1, dims[a] - 1);
    first[a] = std::max(0, std::min(lower[a], dims[a] - 1) - 1);
    count[a] = std::min(dims[a] - 1, last + 1) - first[a] + 1;
  }
}
}

bool ClassifiedDensity::NativeBrickPoints(const std::array<int, 3>& lower, int size, float* points,
  std::array<int, 3>& first, std::array<int, 3>& count) const
{
  if (size < 1 || size > MostBrickCells)
  {
    return false;
  }
  BrickWindow(lower, size, this->Scalars->NativeResolution(), first, count);
  return this->Scalars->NativePoints(first, count, points);
}

namespace
{
// The smallest and largest of n floats (NaN when one is not finite).
void PointRange(const float* points, std::size_t n, float* range)
{
  float lo = points[0], hi = points[0];
  bool finite = true;
  for (std::size_t p = 0; p < n; ++p)
  {
    finite = finite && std::isfinite(points[p]);
    lo = std::min(lo, points[p]);
    hi = std::max(hi, points[p]);
  }
  range[0] = finite ? lo : std::numeric_limits<float>::quiet_NaN();
  range[1] = finite ? hi : std::numeric_limits<float>::quiet_NaN();
}
}

bool ClassifiedDensity::NativeBrickRange(
  const std::array<int, 3>& lower, int size, float* range) const
{
  float points[MostBrickPoints * MostBrickPoints * MostBrickPoints];
  std::array<int, 3> first{}, count{};
  if (this->NativeBrickPoints(lower, size, points, first, count))
  {
    PointRange(points, static_cast<std::size_t>(count[0]) * count[1] * count[2], range);
    return true;
  }
  if (!this->Grid || size < 1 || size > MostBrickCells)
  {
    return false;
  }
  // A grid read otherwise (nearest values, cell values): its cells read
  // the values of their own cell or point and of the neighbours' (BendsWithin(),
  // the samples of NativeMean()), the same window of values.
  this->GridWindowRange(lower, size, range);
  return true;
}

void ClassifiedDensity::GridWindowRange(
  const std::array<int, 3>& lower, int size, float* range) const
{
  float points[MostBrickPoints * MostBrickPoints * MostBrickPoints];
  std::array<int, 3> first{}, count{};
  const std::array<int, 3>& dims = this->Grid->GetDimensions();
  BrickWindow(lower, size, dims, first, count);
  std::size_t n = 0;
  this->Grid->GetValues().Visit(
    [&](const auto* values)
    {
      for (int z = first[2]; z < first[2] + count[2]; ++z)
        for (int y = first[1]; y < first[1] + count[1]; ++y)
        {
          const auto* row = values + (static_cast<std::size_t>(z) * dims[1] + y) * dims[0];
          for (int x = first[0]; x < first[0] + count[0]; ++x)
          {
            points[n++] = static_cast<float>(row[x]);
          }
        }
      return true;
    });
  PointRange(points, n, range);
}

bool ClassifiedDensity::NativeBrick(
  const std::array<int, 3>& lower, int size, int s, float* out, float* range) const
{
  constexpr int MostCells = MostBrickCells, MostPoints = MostBrickPoints;
  if (size < 1 || size > MostCells || s < 1 || s > GridDensity::MaxNativeSamples)
  {
    return false;
  }
  if (this->Grid &&
    (this->Grid->HasCellValues() ||
      this->Grid->GetInterpolation() == GridDensity::Interpolation::Nearest))
  {
    // Nearest values and cell values: each of a cell's s^3 samples lies
    // less than half a cell from its centre, so it reads the cell's own
    // value, and their mean is the function at that value, exactly (a
    // float summed s^3 <= 512 times in double, then divided by that power
    // of two; NativeMean() gives the same): every cell is its own value
    // classified, bending or not.
    const std::array<int, 3>& dims = this->Grid->GetDimensions();
    if (s != 1 && s != 2 && s != 4 && s != 8)
    {
      return false;
    }
    if (range)
    {
      this->GridWindowRange(lower, size, range);
    }
    this->Grid->GetValues().Visit(
      [&](const auto* values)
      {
        for (int k = 0; k < size; ++k)
        {
          const int z = std::min(lower[2] + k, dims[2] - 1);
          for (int j = 0; j < size; ++j)
          {
            const int y = std::min(lower[1] + j, dims[1] - 1);
            const auto* row = values + (static_cast<std::size_t>(z) * dims[1] + y) * dims[0];
            for (int i = 0; i < size; ++i)
            {
              *out++ = this->Opacity.Extinction(
                static_cast<float>(row[std::min(lower[0] + i, dims[0] - 1)]));
            }
          }
        }
        return true;
      });
    return true;
  }
  const std::array<int, 3> dims = this->Scalars->NativeResolution();
  // The cells along each axis, and the points they read: one beyond on
  // either side, clamped at the grid's ends.
  int cell[3][MostCells], lo[3];
  std::array<int, 3> first{}, count{};
  float points[MostPoints * MostPoints * MostPoints];
  if (!this->NativeBrickPoints(lower, size, points, first, count))
  {
    return false;
  }
  for (int a = 0; a < 3; ++a)
  {
    for (int c = 0; c < size; ++c)
    {
      cell[a][c] = std::min(lower[a] + c, dims[a] - 1);
    }
    lo[a] = first[a];
  }
  float pointRange[2];
  PointRange(points, static_cast<std::size_t>(count[0]) * count[1] * count[2], pointRange);
  if (range)
  {
    range[0] = pointRange[0];
    range[1] = pointRange[1];
  }
  auto at = [&](int x, int y, int z)
  { return points[((z - lo[2]) * count[1] + (y - lo[1])) * count[0] + (x - lo[0])]; };
  if (pointRange[0] <= pointRange[1] && !this->PointBetween(pointRange[0], pointRange[1]))
  {
    // Finite points, and none of the function's between the brick's
    // smallest and largest: no cell's range holds one either (each is
    // within the brick's), so every cell is the function at its point.
    for (int k = 0; k < size; ++k)
      for (int j = 0; j < size; ++j)
      {
        float* row = out;
        for (int i = 0; i < size; ++i)
        {
          *out++ = at(cell[0][i], cell[1][j], cell[2][k]);
        }
        this->Opacity.Extinctions(row, size);
      }
    return true;
  }
  // Each cell's range over its 27 points (BendsWithinNativeCell()), one axis at a time.
  auto window = [&](int a, int c, int& from, int& to)
  {
    from = std::max(cell[a][c] - 1, 0);
    to = std::min(cell[a][c] + 1, dims[a] - 1);
  };
  float lowX[MostPoints * MostPoints * MostCells], highX[MostPoints * MostPoints * MostCells];
  for (int z = 0; z < count[2]; ++z)
    for (int y = 0; y < count[1]; ++y)
      for (int i = 0; i < size; ++i)
      {
        int from, to;
        window(0, i, from, to);
        float l = at(from, lo[1] + y, lo[2] + z), h = l;
        for (int x = from + 1; x <= to; ++x)
        {
          const float v = at(x, lo[1] + y, lo[2] + z);
          l = std::min(l, v);
          h = std::max(h, v);
        }
        const int n = (z * count[1] + y) * size + i;
        lowX[n] = l;
        highX[n] = h;
      }
  float lowXY[MostPoints * MostCells * MostCells], highXY[MostPoints * MostCells * MostCells];
  for (int z = 0; z < count[2]; ++z)
    for (int j = 0; j < size; ++j)
      for (int i = 0; i < size; ++i)
      {
        int from, to;
        window(1, j, from, to);
        float l = lowX[(z * count[1] + from - lo[1]) * size + i];
        float h = highX[(z * count[1] + from - lo[1]) * size + i];
        for (int y = from + 1; y <= to; ++y)
        {
          l = std::min(l, lowX[(z * count[1] + y - lo[1]) * size + i]);
          h = std::max(h, highX[(z * count[1] + y - lo[1]) * size + i]);
        }
        lowXY[(z * size + j) * size + i] = l;
        highXY[(z * size + j) * size + i] = h;
      }
  for (int k = 0; k < size; ++k)
    for (int j = 0; j < size; ++j)
      for (int i = 0; i < size; ++i)
      {
        int from, to;
        window(2, k, from, to);
        float l = lowXY[((from - lo[2]) * size + j) * size + i];
        float h = highXY[((from - lo[2]) * size + j) * size + i];
        for (int z = from + 1; z <= to; ++z)
        {
          l = std::min(l, lowXY[((z - lo[2]) * size + j) * size + i]);
          h = std::max(h, highXY[((z - lo[2]) * size + j) * size + i]);
        }
        if (!this->PointBetween(l, h))
        {
          *out++ = this->Opacity.Extinction(at(cell[0][i], cell[1][j], cell[2][k]));
          continue;
        }
        // NativeMean(), from the brick's points.
        const int index[3] = { cell[0][i], cell[1][j], cell[2][k] };
        *out++ = static_cast<float>(
          ClassifiedCellMean(this->Opacity, index, dims, s, points, first, count));
      }
  return true;
}

bool ClassifiedDensity::BendsWithin(const Box& region) const
{
  const GridDensity* grid = this->Grid;
  if (!grid)
  {
    return this->BendsWithinBlocks(region);
  }
  const GridDensity& g = *grid;
  const std::array<int, 3>& dims = g.GetDimensions();
  const Box& bounds = g.GetBounds();
  // The values that define the region: the cells it touches, or the points
  // around the cells it touches.
  int first[3], last[3];
  for (int a = 0; a < 3; ++a)
  {
    const float extent = bounds.Extent()[a];
    const int n = dims[a];
    const float lo = (region.lower[a] - bounds.lower[a]) / extent;
    const float hi = (region.upper[a] - bounds.lower[a]) / extent;
    if (g.HasCellValues())
    {
      first[a] = static_cast<int>(std::floor(lo * n));
      last[a] = static_cast<int>(std::floor(hi * n));
    }
    else
    {
      first[a] = static_cast<int>(std::floor(lo * (n - 1)));
      last[a] = static_cast<int>(std::ceil(hi * (n - 1)));
    }
    first[a] = std::clamp(first[a], 0, n - 1);
    last[a] = std::clamp(last[a], first[a], n - 1);
  }
  const TypedValues& values = g.GetValues();
  float lo = values[(static_cast<std::size_t>(first[2]) * dims[1] + first[1]) * dims[0] + first[0]];
  float hi = lo;
  for (int k = first[2]; k <= last[2]; ++k)
    for (int j = first[1]; j <= last[1]; ++j)
      for (int i = first[0]; i <= last[0]; ++i)
      {
        const float v = values[(static_cast<std::size_t>(k) * dims[1] + j) * dims[0] + i];
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
  return this->PointBetween(lo, hi);
}

bool ClassifiedDensity::BendsWithinBlocks(const Box& region) const
{
  // The value ranges of the majorant blocks the region overlaps (kept by the constructor).
  const std::vector<float>& lo = this->RangeLow;
  const std::vector<float>& hi = this->RangeHigh;
  const MajorantGrid& mg = this->Majorants;
  if (hi.empty())
  {
    return true;
  }
  int first[3], last[3];
  for (int a = 0; a < 3; ++a)
  {
    const float size = mg.Bounds.Extent()[a] / static_cast<float>(mg.Dims[a]);
    first[a] =
      std::clamp(static_cast<int>(std::floor((region.lower[a] - mg.Bounds.lower[a]) / size)), 0,
        mg.Dims[a] - 1);
    last[a] =
      std::clamp(static_cast<int>(std::floor((region.upper[a] - mg.Bounds.lower[a]) / size)),
        first[a], mg.Dims[a] - 1);
  }
  float l = std::numeric_limits<float>::infinity(), h = -l;
  for (int k = first[2]; k <= last[2]; ++k)
    for (int j = first[1]; j <= last[1]; ++j)
      for (int i = first[0]; i <= last[0]; ++i)
      {
        const std::size_t b = (static_cast<std::size_t>(k) * mg.Dims[1] + j) * mg.Dims[0] + i;
        l = std::min(l, lo[b]);
        h = std::max(h, hi[b]);
      }
  return this->PointBetween(l, h);
}

std::string ColorTransferFunction::Validate(const std::vector<Node>& nodes)
{
  if (nodes.empty())
  {
    return "has no colour points";
  }
  for (std::size_t i = 0; i < nodes.size(); ++i)
  {
    std::ostringstream at;
    at << "colour point " << i << " (scalar " << nodes[i].Scalar << ", colour " << nodes[i].Color.x
       << " " << nodes[i].Color.y << " " << nodes[i].Color.z << ")";
    if (!std::isfinite(nodes[i].Scalar))
    {
      return at.str() + " has a non-finite scalar";
    }
    for (int c = 0; c < 3; ++c)
    {
      if (!(nodes[i].Color[c] >= 0.f && nodes[i].Color[c] <= 1.f))
      {
        return at.str() + " has a colour component outside [0, 1]";
      }
    }
    if (i > 0 && nodes[i].Scalar < nodes[i - 1].Scalar)
    {
      return at.str() + " comes before the previous point's scalar: scalars must not decrease";
    }
  }
  return {};
}

ColorTransferFunction::ColorTransferFunction(std::vector<Node> nodes)
  : Nodes(std::move(nodes))
{
}

Vec3 ColorTransferFunction::Color(float s) const
{
  Vec3 colour;
  this->Colors(&s, 1, &colour);
  return colour;
}

void ColorTransferFunction::Colors(const float* s, std::size_t n, Vec3* out) const
{
  const std::vector<Node>& nodes = this->Nodes;
  std::size_t pair = nodes.size(); // the first point past the last scalar's; none yet
  for (std::size_t m = 0; m < n; ++m)
  {
    const float v = s[m];
    if (!(pair < nodes.size() && nodes[pair - 1].Scalar <= v && v < nodes[pair].Scalar))
    {
      const auto next = std::upper_bound(
        nodes.begin(), nodes.end(), v, [](float x, const Node& node) { return x < node.Scalar; });
      if (next == nodes.begin() || next == nodes.end())
      {
        out[m] = next == nodes.begin() ? nodes.front().Color : nodes.back().Color;
        pair = nodes.size();
        continue;
      }
      pair = static_cast<std::size_t>(next - nodes.begin());
    }
    const Node& a = nodes[pair - 1];
    const Node& b = nodes[pair];
    const float t = (v - a.Scalar) / (b.Scalar - a.Scalar);
    out[m] = a.Color + (b.Color - a.Color) * t;
  }
}

ClassifiedAlbedo::ClassifiedAlbedo(
  std::shared_ptr<const DensityField> scalars, ColorTransferFunction colors)
  : Scalars(std::move(scalars))
  , Colors(std::move(colors))
{
}

bool ClassifiedAlbedo::SharesNativeCells(const DensityField& density) const
{
  if (this->Scalars->NativeResolution() != density.NativeResolution())
  {
    return false;
  }
  const Box a = this->Scalars->NativeBox(), b = density.NativeBox();
  for (int i = 0; i < 3; ++i)
  {
    if (a.lower[i] != b.lower[i] || a.upper[i] != b.upper[i])
    {
      return false;
    }
  }
  return true;
}

bool ClassifiedAlbedo::NativeValues(const std::array<int, 3>& lower,
  const std::array<int, 3>& count, std::vector<float>& scratch, Vec3* out) const
{
  scratch.resize(static_cast<std::size_t>(count[0]) * count[1] * count[2]);
  if (!this->Scalars->NativePoints(lower, count, scratch.data()))
  {
    return false;
  }
  this->Colors.Colors(scratch.data(), scratch.size(), out);
  return true;
}

} // namespace brume
