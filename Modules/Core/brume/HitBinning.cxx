// SPDX-License-Identifier: BSD-3-Clause
// Binning the hits of an object into its histograms (brume/HitBinning.h):
// the cell of every hit, one pass in hit order for view-independent objects,
// the kept hits grouped by cell for view-dependent ones, and their weights
// toward an eye.
#include "brume/HitBinning.h"

#include "brume/DirectLight.h"
#include "brume/Material.h"
#include "brume/Reflection.h"
#include "brume/Sampling.h"

#include <algorithm>
#include <cmath>

namespace brume
{

namespace
{
// Whether a heterogeneous medium's albedo varies: each hit's scattered
// light then carries the albedo of its cell (CellAlbedo), and the
// reconstruction normalizes by the albedo-weighted extinction
// (ObjectRadiance::ToRadiance()).
bool VaryingAlbedo(const ObjectLayout& layout)
{
  const Medium* medium = layout.MediumRef;
  return medium && medium->Density && medium->AlbedoFactor && layout.Scattering.HasVaryingAlbedo();
}

// Barycentric coordinates of p (projected) in the triangle abc.
void Barycentric(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& p, float& u, float& v)
{
  const Vec3 e0 = b - a, e1 = c - a, e2 = p - a;
  const float d00 = Dot(e0, e0), d01 = Dot(e0, e1), d11 = Dot(e1, e1);
  const float d20 = Dot(e2, e0), d21 = Dot(e2, e1);
  const float det = d00 * d11 - d01 * d01;
  u = det != 0.f ? (d11 * d20 - d01 * d21) / det : 0.f;
  v = det != 0.f ? (d00 * d21 - d01 * d20) / det : 0.f;
}

// The histogram cell of a hit: its (u, v) on the surface's chart, or its
// position in the medium's box.
class CellLocator
{
public:
  explicit CellLocator(const ObjectLayout& layout)
    : Dims(layout.Dims)
    , MediumRef(layout.MediumRef)
    , SurfaceRef(layout.SurfaceRef)
    , Chart(layout.Chart)
    , Planar(!layout.MediumRef && layout.Chart.Type == SurfaceChart::Kind::Planar)
    , Bounds(layout.MediumRef ? layout.MediumRef->Bounds : Box())
    , UU(Dot(layout.Chart.Frame.U, layout.Chart.Frame.U))
    , VV(Dot(layout.Chart.Frame.V, layout.Chart.Frame.V))
  {
    for (int a = 0; a < 3; ++a)
    {
      this->Size[a] = this->Dims[a];
      this->Top[a] = this->Dims[a] - 1;
    }
  }

  std::uint32_t operator()(const HitArrays& hits, std::uint32_t i) const
  {
    const Vec3 p(hits.Position[3 * i], hits.Position[3 * i + 1], hits.Position[3 * i + 2]);
    if (this->MediumRef)
    {
      const Vec3 q = (p - this->Bounds.lower) / this->Bounds.Extent();
      return this->Index(q.x, q.y, q.z);
    }
    if (this->Planar)
    {
      const Vec3 d = p - this->Chart.Frame.Origin;
      return this->Index(
        Dot(d, this->Chart.Frame.U) / this->UU, Dot(d, this->Chart.Frame.V) / this->VV, 0.0);
    }
    const std::uint32_t t = hits.Triangle[i];
    const auto& tri = this->SurfaceRef->Triangles[t];
    float b1, b2;
    Barycentric(this->SurfaceRef->Vertices[tri[0]], this->SurfaceRef->Vertices[tri[1]],
      this->SurfaceRef->Vertices[tri[2]], p, b1, b2);
    const auto& uv = this->Chart.TriangleUV[t];
    const float b0 = 1.f - b1 - b2;
    return this->Index(
      b0 * uv[0] + b1 * uv[2] + b2 * uv[4], b0 * uv[1] + b1 * uv[3] + b2 * uv[5], 0.0);
  }

private:
  // The cell of (s, t, r) in [0, 1)^3, clamped to the grid (NaN: cell 0).
  std::uint32_t Index(double s, double t, double r) const
  {
    const std::size_t c0 = this->Cell(s, 0), c1 = this->Cell(t, 1);
    const std::size_t c2 = this->Top[2] > 0.0 ? this->Cell(r, 2) : 0;
    return static_cast<std::uint32_t>((c2 * this->Dims[1] + c1) * this->Dims[0] + c0);
  }
  // floor(q n) clamped to [0, n - 1] along axis a, without floor(): x >= 0
  // exactly when floor(x) >= 0, x >= n - 1 exactly when floor(x) >= n - 1
  // (an integer), and truncation is floor in between. A third of the
  // binning's instructions went to floor()'s expansion (SSE2 has no roundsd).
  std::size_t Cell(double q, int a) const
  {
    const double x = q * this->Size[a];
    if (!(x >= 0.0))
    {
      return 0;
    }
    return static_cast<std::size_t>(static_cast<int>(std::min(x, this->Top[a])));
  }

  const std::array<int, 3>& Dims;
  double Size[3], Top[3]; // Dims and Dims - 1
  const Medium* MediumRef;
  const Surface* SurfaceRef;
  const SurfaceChart& Chart;
  bool Planar;
  Box Bounds;
  float UU, VV;
};
}

HitBinning::HitBinning(const ObjectLayout& layout)
  : ViewDependent(layout.ViewDependent)
  , Store(layout.Cells(), layout.SurfaceRef != nullptr)
{
}

void HitBinning::FixView(const ObjectLayout& layout, const Vec3& eye)
{
  this->ViewFixed = this->ViewDependent;
  this->FixedEye = eye;
  this->FixedNormals =
    this->ViewFixed && layout.SurfaceRef ? layout.UnitNormals() : std::vector<Vec3>();
}

void HitBinning::Clear(bool deferred)
{
  this->Store.Clear();
  this->Store.SetDeferred(deferred);
}

void HitBinning::Start(const ObjectLayout& layout, int sumsExponent, bool lobeCast)
{
  this->SumsExponent = sumsExponent;
  this->LobeCast = lobeCast;
  // View-independent objects (and fixed views) keep exact sums (for
  // Add()); the others keep hits.
  this->Weights = this->KeepsHits() ? ExactHistogram() : this->NewSums(layout.Dims, 2);
  this->Values = this->KeepsHits() ? ExactHistogram() : this->NewSums(layout.Dims, 6);
  this->Clamped = false;
}

std::string HitBinning::Saturation() const
{
  if (this->Clamped)
  {
    return "a hit's weighted flux exceeds 2^" +
      std::to_string(ExactHistogram::MaxTermBits - ExactHistogram::FractionBits) +
      " times a particle's: the histograms' exact sums cannot hold it";
  }
  return {};
}

ExactHistogram HitBinning::NewSums(const std::array<int, 3>& dims, int channels) const
{
  return ExactHistogram(dims, channels, this->SumsExponent);
}

void HitBinning::ClearSums()
{
  this->Weights = ExactHistogram();
  this->Values = ExactHistogram();
}

Histogram HitBinning::GetWeightHistogram() const
{
  Histogram h;
  this->Weights.ToHistogram(h, 2);
  return h;
}

Histogram HitBinning::GetValueHistogram() const
{
  Histogram h;
  this->Values.ToHistogram(h, 2);
  return h;
}

void HitBinning::Scale(double scale, int sumsExponent, const ParallelFor& parallelFor)
{
  // The particles already binned were normalized by a smaller count: scale
  // them (exactly, when the count grows by a power of two).
  if (this->KeepsHits())
  {
    this->Store.ScaleFlux(static_cast<float>(scale), parallelFor);
  }
  else
  {
    // Exactly, as a change of quantum, when the scale is a power of two.
    this->Weights.Scale(scale);
    this->Values.Scale(scale);
  }
  this->SumsExponent = sumsExponent;
}

void HitBinning::MergePending(const ParallelFor& parallelFor)
{
  if (this->Store.HasPending())
  {
    this->Store.MergePending(parallelFor);
  }
  this->Store.SetDeferred(false);
}

// Here, where the binning calls it for every hit: inlined.
inline bool HitBinning::FromFront(
  const ObjectLayout& layout, const HitArrays& hits, std::uint32_t i) const
{
  // The particle travels against the front (winding) normal of its triangle.
  const std::uint32_t t = hits.Triangle ? hits.Triangle[i] : 0;
  const std::vector<Vec3>& normals = layout.TriangleNormals;
  const Vec3& n = normals[t < normals.size() ? t : 0];
  const Vec3 d(hits.Direction[3 * i], hits.Direction[3 * i + 1], hits.Direction[3 * i + 2]);
  return Dot(n, d) < 0.f;
}

void HitBinning::Bin(const ObjectLayout& layout, const HitArrays& hits, const std::uint32_t* index,
  std::size_t count, const DirectLight* direct, double runShare, const ParallelFor& parallelFor,
  bool everyThread)
{
  const CellLocator cellOfHit(layout);
  if (VaryingAlbedo(layout))
  {
    this->Albedo.emplace(*layout.MediumRef);
  }
  else
  {
    this->Albedo.reset();
  }
  std::vector<std::uint32_t> scattered;
  if (direct)
  {
    // The first interactions after a delta light are computed, not estimated.
    scattered.reserve(count);
    for (std::size_t k = 0; k < count; ++k)
    {
      if (!direct->IsFirstInteraction(hits.Emitter[index[k]], hits.Depth[index[k]]))
      {
        scattered.push_back(index[k]);
      }
    }
    index = scattered.data();
    count = scattered.size();
  }
  if (!this->KeepsHits())
  {
    this->BinInPlace(layout, hits, index, count, cellOfHit, parallelFor, everyThread);
  }
  else
  {
    this->KeepHits(layout, hits, index, count, cellOfHit, runShare, parallelFor);
  }
}

inline void HitBinning::WeighHit(const ObjectLayout& layout, const Vec3& eye, const float* position,
  const float* direction, const float* flux, std::uint32_t triangle,
  const std::vector<Vec3>& normals, double* value) const
{
  if (layout.MediumRef)
  {
    // The remainder of the phase function once its peak is set apart, from
    // the direction of travel to the eye: WeighKept() evaluates the same
    // expression in vectorized blocks.
    const ForwardPeak& peak = layout.Scattering.GetPeak(false);
    const float dx = eye.x - position[0], dy = eye.y - position[1], dz = eye.z - position[2];
    const float cosine = (direction[0] * dx + direction[1] * dy + direction[2] * dz) /
      std::sqrt(dx * dx + dy * dy + dz * dz);
    const float p = peak.Remainder(cosine);
    for (int c = 0; c < 3; ++c)
    {
      value[c] = static_cast<double>(p) * flux[c];
    }
    return;
  }
  const Surface& surface = *layout.SurfaceRef;
  const Vec3 pos(position[0], position[1], position[2]);
  const Vec3 dir(direction[0], direction[1], direction[2]);
  // The BRDF from the incoming direction to the eye.
  Material coloured; // where the surface's reflectance varies over it
  const Material& m = surface.VertexReflectance.empty()
    ? surface.MaterialOf(triangle)
    : (coloured = surface.MaterialAt(triangle, pos));
  // A cast lobe is left out: the diffuse part alone.
  const bool diffuseOnly =
    this->LobeCast && m.Type == MaterialType::Phong && MirrorReflection::Casts(m);
  Vec3 n = normals[triangle];
  if (Dot(n, dir) > 0.f)
  {
    n = -n;
  }
  const Vec3 toEye = Normalize(eye - pos);
  const Vec3 f =
    diffuseOnly ? EvaluateDiffuseBrdf(m, n, -dir, toEye) : EvaluateBrdf(m, n, -dir, toEye);
  for (int c = 0; c < 3; ++c)
  {
    value[c] = static_cast<double>(f[c]) * flux[c];
  }
}

template <bool Shared>
inline void HitBinning::AddTerms(
  const ObjectLayout& layout, const HitArrays& hits, std::uint32_t i, std::uint32_t cell)
{
  const float* f = hits.Flux + 3 * i;
  const std::uint32_t triangle = hits.Triangle ? hits.Triangle[i] : 0;
  // Each term in its half's channels.
  const int half = HitHalf(hits.Position + 3 * i);
  double v[3];
  if (this->ViewFixed)
  {
    // The terms the kept hits would give toward the fixed eye
    // (WeighKept()), their growth scale in float as kept.
    const double w[1] = { (static_cast<double>(f[0]) + f[1] + f[2]) / 3.0 *
      static_cast<float>(hits.GrowthScale(i)) };
    this->Weights.AddNonNegative<Shared>(cell, half, w);
    this->WeighHit(layout, this->FixedEye, hits.Position + 3 * i, hits.Direction + 3 * i, f,
      triangle, this->FixedNormals, v);
    if (this->Albedo)
    {
      const Vec3 a = this->Albedo->At(
        Vec3(hits.Position[3 * i], hits.Position[3 * i + 1], hits.Position[3 * i + 2]));
      for (int c = 0; c < 3; ++c)
      {
        v[c] *= a[c];
      }
    }
    this->Values.AddNonNegative<Shared>(cell, 3 * half, v);
    return;
  }
  const double w[1] = { (static_cast<double>(f[0]) + f[1] + f[2]) / 3.0 * hits.GrowthScale(i) };
  this->Weights.AddNonNegative<Shared>(cell, half, w);
  if (layout.MediumRef)
  {
    const Vec3 a = this->Albedo ? this->Albedo->At(Vec3(hits.Position[3 * i],
                                    hits.Position[3 * i + 1], hits.Position[3 * i + 2]))
                                : Vec3(1.f);
    for (int c = 0; c < 3; ++c)
    {
      v[c] = Inv4Pi * static_cast<double>(f[c]) * a[c];
    }
  }
  else
  {
    const Surface& surface = *layout.SurfaceRef;
    Material coloured; // where the surface's reflectance varies over it
    const Material& m = surface.VertexReflectance.empty()
      ? surface.MaterialOf(triangle)
      : (coloured = surface.MaterialAt(triangle,
           Vec3(hits.Position[3 * i], hits.Position[3 * i + 1], hits.Position[3 * i + 2])));
    for (int c = 0; c < 3; ++c)
    {
      v[c] = m.Reflectance[c] * InvPi * static_cast<double>(f[c]);
    }
  }
  this->Values.AddNonNegative<Shared>(cell, 3 * half, v);
}

template <typename Locator>
void HitBinning::BinInPlace(const ObjectLayout& layout, const HitArrays& hits,
  const std::uint32_t* index, std::size_t count, const Locator& cellOfHit,
  const ParallelFor& parallelFor, bool everyThread)
{
  // View-independent objects: every hit is added to its cell; nothing is
  // kept. The sums are exact (any order of the terms gives the same bits),
  // so on every thread the hits are split between threads that add into
  // the same sums word by word atomically: the same bits whatever the
  // split, and no memory beyond the object's sums. An atomic add costs
  // more than a plain one: one thread adds plainly.
  if (everyThread)
  {
    parallelFor(0, count,
      [&](std::size_t begin, std::size_t end)
      { this->BinInto<true>(layout, hits, index + begin, end - begin, cellOfHit); });
  }
  else
  {
    this->BinInto<false>(layout, hits, index, count, cellOfHit);
  }
  this->Clamped = this->Clamped || this->Weights.Saturated() || this->Values.Saturated();
}

template <bool Shared, typename Locator>
void HitBinning::BinInto(const ObjectLayout& layout, const HitArrays& hits,
  const std::uint32_t* index, std::size_t count, const Locator& cellOfHit)
{
  // The loop is bound by memory latency, not arithmetic: an object's hits
  // are spread over the whole run's arrays, and a fine histogram (64 bytes
  // a cell: a weight and three values a half; megabytes at 10^7 particles)
  // misses the caches at nearly every hit. So a hit Ahead of the one whose
  // cell is found is asked for, and its cell's sums are asked for Lag hits
  // before they are added to (a software pipeline): 10^7 particles of the
  // default scene bin in 0.07-0.09 s a wall instead of 0.17 s with the hits
  // grouped by ranges of cells first, and nothing is allocated.
  // A surface shows light arriving on its front side only (the back side's
  // is reflected, not shown): other hits have no cell.
  constexpr std::uint32_t NoCell = ~std::uint32_t(0);
  constexpr std::size_t Ahead = 32, Lag = 16;
  std::uint32_t waitingHit[Lag], waitingCell[Lag];
  for (std::size_t k = 0; k < count + Lag; ++k)
  {
    // Hit k - Lag's terms added, then its slot taken by hit k.
    const std::size_t slot = k % Lag;
    if (k >= Lag && waitingCell[slot] != NoCell)
    {
      this->AddTerms<Shared>(layout, hits, waitingHit[slot], waitingCell[slot]);
    }
    if (k < count)
    {
      if (k + Ahead < count)
      {
        const std::uint32_t j = index[k + Ahead];
        __builtin_prefetch(hits.Position + 3 * j);
        __builtin_prefetch(hits.Direction + 3 * j);
        __builtin_prefetch(hits.Flux + 3 * j);
      }
      const std::uint32_t i = index[k];
      const std::uint32_t cell =
        layout.MediumRef || this->FromFront(layout, hits, i) ? cellOfHit(hits, i) : NoCell;
      if (cell != NoCell)
      {
        this->Weights.Prefetch(cell);
        this->Values.Prefetch(cell);
      }
      waitingHit[slot] = i;
      waitingCell[slot] = cell;
    }
  }
}

template <typename Locator>
void HitBinning::KeepHits(const ObjectLayout& layout, const HitArrays& hits,
  const std::uint32_t* index, std::size_t count, const Locator& cellOfHit, double runShare,
  const ParallelFor& parallelFor)
{
  // View-dependent objects keep their hits with their histogram cells,
  // grouped by ranges of cells: a new eye re-weights them (WeighKept).
  // Surfaces keep the hits arriving on their front side only.
  std::vector<std::uint32_t> front;
  if (!layout.MediumRef)
  {
    for (std::size_t k = 0; k < count; ++k)
    {
      if (this->FromFront(layout, hits, index[k]))
      {
        front.push_back(index[k]);
      }
    }
    index = front.data();
    count = front.size();
  }
  // Every element written below, in parallel: not zeroed first.
  std::vector<std::uint32_t, UninitializedAllocator<std::uint32_t>> cellOf(count);
  parallelFor(0, count,
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t k = begin; k < end; ++k)
      {
        cellOf[k] = cellOfHit(hits, index[k]);
      }
    });
  this->Store.Keep(hits, index, cellOf.data(), count, runShare, parallelFor,
    this->Albedo ? &*this->Albedo : nullptr);
}

void HitBinning::WeighKept(
  const ObjectLayout& layout, const Vec3& eye, bool weights, const ParallelFor& parallelFor)
{
  this->Values = this->NewSums(layout.Dims, 6);
  ExactHistogram& value = this->Values;
  if (weights)
  {
    this->Weights = this->NewSums(layout.Dims, 2);
  }
  ExactHistogram& weight = this->Weights;
  const KeptHits& kept = this->Store.GetHits();
  constexpr std::size_t Ranges = KeptHitStore::Ranges;
  // The kept hits' incident flux, with their weighted flux in the same pass
  // over them (exact sums: the order of the terms does not matter).
  // Each term in its half's channels (HitHalf()).
  auto addWeight = [&](const KeptHit& h, std::size_t k, int half)
  {
    const double w[1] = { (static_cast<double>(h.Flux[0]) + h.Flux[1] + h.Flux[2]) / 3.0 *
      kept.GrowthOf(k) };
    weight.AddNonNegative(h.Cell, half, w);
  };
  const Medium* medium = layout.MediumRef;
  // Media: the remainder of the phase function once its peak is set apart.
  const ForwardPeak& peak = layout.Scattering.GetPeak(false);
  if (medium)
  {
    // Phase function from the direction of travel to the eye, in blocks
    // whose arithmetic the compiler vectorizes (square roots and divisions
    // are most of the cost).
    parallelFor(0, Ranges,
      [&](std::size_t begin, std::size_t end)
      {
        constexpr std::size_t Block = 16;
        float dx[Block], dy[Block], dz[Block], ux[Block], uy[Block], uz[Block], p[Block];
        const std::size_t last = this->Store.RangeStart(end);
        for (std::size_t first = this->Store.RangeStart(begin); first < last; first += Block)
        {
          const std::size_t n = std::min(Block, last - first);
          for (std::size_t i = 0; i < Block; ++i)
          {
            const KeptHit& h = kept.Hits[first + std::min(i, n - 1)];
            dx[i] = eye.x - h.Position[0];
            dy[i] = eye.y - h.Position[1];
            dz[i] = eye.z - h.Position[2];
            ux[i] = h.Direction[0];
            uy[i] = h.Direction[1];
            uz[i] = h.Direction[2];
          }
          for (std::size_t i = 0; i < Block; ++i)
          {
            const float cosine = (ux[i] * dx[i] + uy[i] * dy[i] + uz[i] * dz[i]) /
              std::sqrt(dx[i] * dx[i] + dy[i] * dy[i] + dz[i] * dz[i]);
            p[i] = peak.Remainder(cosine);
          }
          for (std::size_t i = 0; i < n; ++i)
          {
            const KeptHit& h = kept.Hits[first + i];
            const int half = HitHalf(h.Position);
            const double v[3] = { static_cast<double>(p[i]) * h.Flux[0],
              static_cast<double>(p[i]) * h.Flux[1], static_cast<double>(p[i]) * h.Flux[2] };
            value.AddNonNegative(h.Cell, 3 * half, v);
            if (weights)
            {
              addWeight(h, first + i, half);
            }
          }
        }
      });
  }
  else
  {
    // The triangles' normals, once per update rather than per hit.
    const std::vector<Vec3> normals = layout.UnitNormals();
    parallelFor(0, Ranges,
      [&](std::size_t begin, std::size_t end)
      {
        for (std::size_t k = this->Store.RangeStart(begin); k < this->Store.RangeStart(end); ++k)
        {
          const KeptHit& h = kept.Hits[k];
          const int half = HitHalf(h.Position);
          double v[3];
          this->WeighHit(
            layout, eye, h.Position, h.Direction, h.Flux, kept.TriangleOf(k), normals, v);
          value.AddNonNegative(h.Cell, 3 * half, v);
          if (weights)
          {
            addWeight(h, k, half);
          }
        }
      });
  }
}

} // namespace brume
