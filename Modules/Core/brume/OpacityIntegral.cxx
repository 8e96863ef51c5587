// SPDX-License-Identifier: BSD-3-Clause
// The integral of an opacity function's extinction along a linear run of
// scalars (OpacityTransferFunction::MeanExtinction()): what a classified
// grid's cell averages along the axis its scalars change most along
// (brume::ClassifiedDensity::NativeMean()).
#include "brume/TransferFunction.h"

#include <algorithm>
#include <cmath>

namespace brume
{

namespace
{
// G(alpha), an antiderivative of -ln(1 - alpha) in alpha.
double G(double alpha)
{
  return (1.0 - alpha) * std::log1p(-alpha) + alpha;
}

// The integral of -ln(1 - min(alpha, most)) / unit over a run of `length`
// along which alpha goes linearly from a0 to a1.
double PieceIntegral(double a0, double a1, double length, double most, double unit)
{
  if (!(length > 0.0))
  {
    return 0.0;
  }
  auto sigma = [&](double alpha) { return -std::log1p(-std::min(alpha, most)) / unit; };
  if (a0 > a1)
  {
    std::swap(a0, a1); // the integral of a linear run does not depend on its direction
  }
  if (a0 >= most)
  {
    return length * sigma(most);
  }
  double capped = 0.0;
  if (a1 > most)
  {
    // The part of the run past the largest opacity holds it.
    const double above = (a1 - most) / (a1 - a0);
    capped = above * length * sigma(most);
    length *= 1.0 - above;
    a1 = most;
  }
  // Below 1e-7 apart the midpoint is within 3e-5 of the mean (sigma's
  // second derivative in alpha is at most 1e12 below MaxOpacity), where the
  // difference of G would lose digits.
  if (a1 - a0 < 1e-7)
  {
    return capped + length * sigma(0.5 * (a0 + a1));
  }
  return capped + length * (G(a1) - G(a0)) / ((a1 - a0) * unit);
}
}

double OpacityTransferFunction::ExactIntegral(double a, double b) const
{
  const std::vector<Node>& nodes = this->Nodes;
  double sum = 0.0;
  double u = a;
  // The first point above u: u lies in the piece that ends there.
  std::size_t k = static_cast<std::size_t>(
    std::upper_bound(nodes.begin(), nodes.end(), u,
      [](double v, const Node& n) { return v < static_cast<double>(n.Scalar); }) -
    nodes.begin());
  while (u < b)
  {
    const double next = k < nodes.size() ? std::min<double>(b, nodes[k].Scalar) : b;
    if (next > u)
    {
      double a0 = 0.0, a1 = 0.0;
      if (k == 0 || k == nodes.size())
      {
        // Outside the points: the end's opacity.
        a0 = a1 = (k == 0 ? nodes.front() : nodes.back()).Opacity;
      }
      else
      {
        const Node& p = nodes[k - 1];
        const Node& q = nodes[k];
        const double width = static_cast<double>(q.Scalar) - p.Scalar; // > 0: p <= u < q
        const double slope = (static_cast<double>(q.Opacity) - p.Opacity) / width;
        a0 = p.Opacity + slope * (u - p.Scalar);
        a1 = p.Opacity + slope * (next - p.Scalar);
      }
      sum += PieceIntegral(a0, a1, next - u, MaxOpacity, this->UnitDistance);
    }
    u = std::max(u, next);
    ++k;
  }
  return sum;
}

void OpacityTransferFunction::MakeIntegrals()
{
  this->CellIntegrals.clear();
  this->CellPrefix.clear();
  this->StartToPoint.clear();
  this->PointToEnd.clear();
  if (this->Table.empty())
  {
    return;
  }
  const double low = this->TableLow, scale = this->TableScale;
  auto end = [&](int c) { return low + c / scale; }; // where MakeTable() puts the cells' ends
  this->CellIntegrals.resize(TableCells);
  for (int c = 0; c < TableCells; ++c)
  {
    const std::size_t i = static_cast<std::size_t>(c);
    this->CellIntegrals[i] = this->TableExact[i]
      ? this->ExactIntegral(end(c), end(c + 1))
      : 0.5 * (static_cast<double>(this->Table[i]) + this->Table[i + 1]) / scale;
  }
  this->StartToPoint.assign(TableCells, 0.0);
  this->PointToEnd.assign(TableCells, 0.0);
  for (int c = 0; c < TableCells; ++c)
  {
    const std::size_t i = static_cast<std::size_t>(c);
    const double point = this->CellPoint[i];
    if (!std::isnan(point)) // a point of the function in the cell
    {
      this->StartToPoint[i] = this->ExactIntegral(end(c), point) * scale;
      this->PointToEnd[i] = this->ExactIntegral(point, end(c + 1)) * scale;
    }
  }
  // Whole quanta, summed as integers: a sum over a range of cells is then
  // the difference of two prefixes, exactly, whatever the cells outside it
  // hold. A cell's integral is at most h -ln(1 - MaxOpacity) / unit < 16 h /
  // unit, 2^44 quanta (4096 of them below 2^56).
  this->IntegralQuantum = 16.0 / (scale * this->UnitDistance) * std::ldexp(1.0, -44);
  this->CellPrefix.assign(static_cast<std::size_t>(TableCells) + 1, 0);
  for (std::size_t c = 0; c < static_cast<std::size_t>(TableCells); ++c)
  {
    this->CellPrefix[c + 1] =
      this->CellPrefix[c] + std::llround(this->CellIntegrals[c] / this->IntegralQuantum);
  }
}

double OpacityTransferFunction::CellPartial(int c, float x0, float x1, double a, double b) const
{
  const std::size_t i = static_cast<std::size_t>(c);
  const double h = 1.0 / static_cast<double>(this->TableScale);
  if (this->TableExact[i])
  {
    // The function's mean over the run's own scalars in the cell (where
    // the float ends would reach past them), over the cell's part of the
    // table units the run covers.
    const double low = static_cast<double>(this->TableLow) + c * h;
    const double span = (static_cast<double>(x1) - x0) * h;
    const double from = std::max(a, low + x0 * h), until = std::min(b, low + x1 * h);
    if (!(until > from))
    {
      return span * this->ExactExtinction(static_cast<float>(std::clamp(from, a, b)));
    }
    return this->ExactIntegral(from, until) / (until - from) * span;
  }
  // The chord between the cell's two values, over [x0, x1] of its [0, 1].
  const double ta = this->Table[i], tb = this->Table[i + 1];
  return (static_cast<double>(x1) - x0) * (ta + (tb - ta) * 0.5 * (static_cast<double>(x0) + x1)) *
    h;
}

double OpacityTransferFunction::CellsIntegral(int first, int last) const
{
  if (first >= last)
  {
    return 0.0;
  }
  return static_cast<double>(this->CellPrefix[static_cast<std::size_t>(last)] -
           this->CellPrefix[static_cast<std::size_t>(first)]) *
    this->IntegralQuantum;
}

float OpacityTransferFunction::MeanExtinctionElsewhere(float a, float b) const
{
  if (a == b || !std::isfinite(a) || !std::isfinite(b))
  {
    return a == b ? this->Extinction(a) : 0.5f * (this->Extinction(a) + this->Extinction(b));
  }
  if (a > b)
  {
    std::swap(a, b);
  }
  if (this->Table.empty())
  {
    return static_cast<float>(this->ExactIntegral(a, b) / (static_cast<double>(b) - a));
  }
  // The cells as Extinction() finds them (in float, as
  // OpacityFunctionEdit::SameOver() does), so that the result reads the
  // cells an edit compares.
  const float cells = static_cast<float>(TableCells);
  const float xa = (a - this->TableLow) * this->TableScale;
  const float xb = (b - this->TableLow) * this->TableScale;
  // The integral, and the length it covers, in table units inside the
  // table (where the float cells lie), in scalars below and above it (the
  // function's end values there).
  double sum = 0.0, length = 0.0;
  const double low = this->TableLow, scale = this->TableScale;
  if (xa < 0.f)
  {
    const double until = std::min<double>(b, low);
    sum += this->ExactIntegral(a, until);
    length += until - a;
  }
  if (xb >= cells)
  {
    const double from = std::max<double>(a, low + TableCells / scale);
    sum += this->ExactIntegral(from, b);
    length += b - from;
  }
  const float x0 = std::max(xa, 0.f), x1 = std::min(xb, cells);
  if (x0 < x1)
  {
    const int c0 = std::min(static_cast<int>(x0), TableCells - 1);
    const int c1 = std::min(static_cast<int>(x1), TableCells - 1);
    const float f0 = x0 - static_cast<float>(c0), f1 = x1 - static_cast<float>(c1);
    sum += c0 == c1 ? this->CellPartial(c0, f0, f1, a, b)
                    : this->CellPartial(c0, f0, 1.f, a, b) + this->CellsIntegral(c0 + 1, c1) +
        this->CellPartial(c1, 0.f, f1, a, b);
    length += (static_cast<double>(x1) - x0) / scale;
  }
  return length > 0.0 ? static_cast<float>(sum / length) : this->Extinction(a);
}

} // namespace brume
