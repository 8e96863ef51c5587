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
  this->RunIntegrals.clear();
  this->RunBefore.clear();
  this->RunFrom.clear();
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
  constexpr int Runs = TableCells / IntegralRun;
  static_assert(Runs * IntegralRun == TableCells, "runs tile the table");
  this->RunIntegrals.assign(Runs, 0.0);
  this->RunBefore.assign(TableCells, 0.0);
  this->RunFrom.assign(TableCells, 0.0);
  for (int r = 0; r < Runs; ++r)
  {
    const std::size_t first = static_cast<std::size_t>(r) * IntegralRun;
    double before = 0.0;
    for (std::size_t c = first; c < first + IntegralRun; ++c)
    {
      this->RunBefore[c] = before;
      before += this->CellIntegrals[c];
    }
    this->RunIntegrals[static_cast<std::size_t>(r)] = before;
    double from = 0.0;
    for (std::size_t c = first + IntegralRun; c-- > first;)
    {
      from += this->CellIntegrals[c];
      this->RunFrom[c] = from;
    }
  }
}

double OpacityTransferFunction::CellPartial(int c, double a, double b) const
{
  const std::size_t i = static_cast<std::size_t>(c);
  if (this->TableExact[i])
  {
    return this->ExactIntegral(a, b);
  }
  // The chord between the cell's two values, over [x0, x1] of the cell's [0, 1].
  const double scale = this->TableScale, low = this->TableLow;
  const double x0 = std::clamp((a - low) * scale - c, 0.0, 1.0);
  const double x1 = std::clamp((b - low) * scale - c, 0.0, 1.0);
  const double ta = this->Table[i], tb = this->Table[i + 1];
  return (x1 - x0) * (ta + (tb - ta) * 0.5 * (x0 + x1)) / scale;
}

double OpacityTransferFunction::CellsIntegral(int first, int last) const
{
  if (first >= last)
  {
    return 0.0;
  }
  const int r0 = first / IntegralRun, r1 = (last - 1) / IntegralRun;
  double sum = 0.0;
  if (r0 == r1)
  {
    for (int c = first; c < last; ++c)
    {
      sum += this->CellIntegrals[static_cast<std::size_t>(c)];
    }
    return sum;
  }
  // Each term holds cells of [first, last) only.
  sum = this->RunFrom[static_cast<std::size_t>(first)];
  for (int r = r0 + 1; r < r1; ++r)
  {
    sum += this->RunIntegrals[static_cast<std::size_t>(r)];
  }
  return sum +
    (last % IntegralRun == 0 ? this->RunIntegrals[static_cast<std::size_t>(r1)]
                             : this->RunBefore[static_cast<std::size_t>(last)]);
}

float OpacityTransferFunction::MeanExtinction(float a, float b) const
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
  const double low = this->TableLow, scale = this->TableScale;
  const double top = low + TableCells / scale;
  double sum = 0.0;
  // Below and above the table: the function's end values.
  if (a < low)
  {
    sum += this->ExactIntegral(a, std::min<double>(b, low));
  }
  if (b > top)
  {
    sum += this->ExactIntegral(std::max<double>(a, top), b);
  }
  const double u0 = std::max<double>(a, low), u1 = std::min<double>(b, top);
  if (u0 < u1)
  {
    // The cells as Extinction() finds them (in float, as
    // OpacityFunctionEdit::SameOver() does), so that the result reads the
    // cells an edit compares.
    auto cellOf = [&](double u)
    {
      const float x = (static_cast<float>(u) - this->TableLow) * this->TableScale;
      return std::clamp(static_cast<int>(std::max(x, 0.f)), 0, TableCells - 1);
    };
    const int c0 = cellOf(u0), c1 = cellOf(u1);
    if (c0 == c1)
    {
      sum += this->CellPartial(c0, u0, u1);
    }
    else
    {
      sum += this->CellPartial(c0, u0, low + (c0 + 1) / scale) + this->CellsIntegral(c0 + 1, c1) +
        this->CellPartial(c1, low + c1 / scale, u1);
    }
  }
  return static_cast<float>(sum / (static_cast<double>(b) - a));
}

} // namespace brume
