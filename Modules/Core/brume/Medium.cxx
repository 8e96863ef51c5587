// SPDX-License-Identifier: BSD-3-Clause
#include "brume/Medium.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace brume
{

Vec3 Medium::Albedo() const
{
  const Vec3 st = this->SigmaT();
  Vec3 a;
  for (int c = 0; c < 3; ++c)
  {
    a[c] = st[c] > 0.f ? this->SigmaS[c] / st[c] : 0.f;
  }
  return a;
}

CellAlbedo::CellAlbedo(const Medium& medium)
  : Field(medium.AlbedoFactor.get())
  , Native(medium.AlbedoFactor->SharesNativeCells(*medium.Density))
{
  const Box box = medium.Density->NativeBox();
  const std::array<int, 3> dims = medium.Density->NativeResolution();
  this->Lower = box.lower;
  for (int a = 0; a < 3; ++a)
  {
    this->Dims[a] = std::max(dims[a], 1);
    this->Cell[a] = (box.upper[a] - box.lower[a]) / static_cast<float>(this->Dims[a]);
  }
}

Vec3 CellAlbedo::Centre(int i, int j, int k) const
{
  return Vec3(this->Lower.x + (static_cast<float>(i) + 0.5f) * this->Cell.x,
    this->Lower.y + (static_cast<float>(j) + 0.5f) * this->Cell.y,
    this->Lower.z + (static_cast<float>(k) + 0.5f) * this->Cell.z);
}

void CellAlbedo::AtCells(const std::array<int, 3>& lower, const std::array<int, 3>& count,
  std::vector<float>& scratch, Vec3* out) const
{
  if (this->Native && this->Field->NativeValues(lower, count, scratch, out))
  {
    return;
  }
  for (int k = lower[2]; k < lower[2] + count[2]; ++k)
    for (int j = lower[1]; j < lower[1] + count[1]; ++j)
      for (int i = lower[0]; i < lower[0] + count[0]; ++i)
      {
        *out++ = this->AtCell(i, j, k);
      }
}

Vec3 CellAlbedo::At(const Vec3& p) const
{
  int c[3];
  for (int a = 0; a < 3; ++a)
  {
    const float x = (p[a] - this->Lower[a]) / this->Cell[a];
    // NaN and below the grid: cell 0.
    c[a] = x >= 0.f ? static_cast<int>(std::min(x, static_cast<float>(this->Dims[a] - 1))) : 0;
  }
  return this->AtCell(c[0], c[1], c[2]);
}

std::string Medium::Validate() const
{
  if (!IsFinite(this->SigmaA) || !IsFinite(this->SigmaS) || MinComponent(this->SigmaA) < 0.f ||
    MinComponent(this->SigmaS) < 0.f)
  {
    return "has a negative or non-finite sigma_a or sigma_s";
  }
  if (!(std::abs(this->G) < 1.f))
  {
    return "has |g| >= 1 (g = " + std::to_string(this->G) + ")";
  }
  if (!IsFinite(this->Bounds.lower) || !IsFinite(this->Bounds.upper) ||
    !(MinComponent(this->Bounds.Extent()) > 0.f))
  {
    return "has an empty or non-finite box";
  }
  if (this->Density && !std::isfinite(this->Density->GetMajorants().GlobalMax()))
  {
    return "has a non-finite density";
  }
  return {};
}

float MediumTracker::BlockMajorant() const
{
  if (!this->Grid)
  {
    return this->ScaleMax;
  }
  return this->ScaleMax * this->Grid->At(this->Cell[0], this->Cell[1], this->Cell[2]);
}

bool MediumTracker::Begin(const Medium& medium, const Vec3& o, const Vec3& d, float tMax)
{
  this->Tracked = &medium;
  float t0 = 0.f, t1 = tMax;
  this->ScaleMax = MaxComponent(medium.SigmaT());
  if (!(this->ScaleMax > 0.f) || !medium.Bounds.Intersect(o, d, t0, t1) || !(t1 > t0))
  {
    return false;
  }
  this->T = t0;
  this->TEnd = t1;
  this->Grid = medium.Density ? &medium.Density->GetMajorants() : nullptr;
  if (!this->Grid)
  {
    this->TBlockEnd = t1;
    return true;
  }
  // 3D DDA set-up (Amanatides & Woo 1987) from the entry point.
  const MajorantGrid& g = *this->Grid;
  const Vec3 extent = g.Bounds.Extent();
  const Vec3 p = o + d * t0;
  this->TBlockEnd = t1;
  for (int a = 0; a < 3; ++a)
  {
    const float size = extent[a] / static_cast<float>(g.Dims[a]);
    const int cell = static_cast<int>(std::floor((p[a] - g.Bounds.lower[a]) / size));
    this->Cell[a] = std::min(g.Dims[a] - 1, std::max(0, cell));
    if (d[a] > 0.f)
    {
      this->Step[a] = 1;
      this->TNext[a] = t0 + (g.Bounds.lower[a] + (this->Cell[a] + 1) * size - p[a]) / d[a];
      this->TDelta[a] = size / d[a];
    }
    else if (d[a] < 0.f)
    {
      this->Step[a] = -1;
      this->TNext[a] = t0 + (g.Bounds.lower[a] + this->Cell[a] * size - p[a]) / d[a];
      this->TDelta[a] = -size / d[a];
    }
    else
    {
      this->Step[a] = 0;
      this->TNext[a] = std::numeric_limits<float>::infinity();
      this->TDelta[a] = std::numeric_limits<float>::infinity();
    }
    this->TBlockEnd = std::min(this->TBlockEnd, this->TNext[a]);
  }
  return true;
}

bool MediumTracker::Advance()
{
  if (!this->Grid || this->TBlockEnd >= this->TEnd)
  {
    return false;
  }
  this->T = this->TBlockEnd;
  int axis = 0;
  if (this->TNext[1] < this->TNext[axis])
  {
    axis = 1;
  }
  if (this->TNext[2] < this->TNext[axis])
  {
    axis = 2;
  }
  this->Cell[axis] += this->Step[axis];
  if (this->Cell[axis] < 0 || this->Cell[axis] >= this->Grid->Dims[axis])
  {
    return false;
  }
  this->TNext[axis] += this->TDelta[axis];
  this->TBlockEnd =
    std::min(this->TEnd, std::min(this->TNext[0], std::min(this->TNext[1], this->TNext[2])));
  return true;
}

bool MediumTracker::Next(Random& rng)
{
  for (;;)
  {
    const float majorant = this->BlockMajorant();
    if (majorant > 0.f)
    {
      // Exponential step; memorylessness lets each block restart it.
      const float t = this->T - std::log1p(-rng.NextFloat()) / majorant;
      if (t < this->TBlockEnd)
      {
        this->T = t;
        this->Majorant = majorant;
        return true;
      }
    }
    if (!this->Advance())
    {
      return false;
    }
    // Through an empty region, the same steps without reading its blocks.
    while (this->Grid->InEmptyRegion(this->Cell))
    {
      if (!this->Advance())
      {
        return false;
      }
    }
  }
}

const Medium* SampleCollision(const std::vector<Medium>& media, const Vec3& o, const Vec3& d,
  float tMax, Random& rng, Vec3& weight, float& t, MediumTracker* trackers)
{
  int active = 0;
  for (const Medium& medium : media)
  {
    MediumTracker& tracker = trackers[active];
    if (tracker.Begin(medium, o, d, tMax) && tracker.Next(rng))
    {
      ++active;
    }
  }
  while (active > 0)
  {
    int next = 0;
    for (int i = 1; i < active; ++i)
    {
      if (trackers[i].T < trackers[next].T)
      {
        next = i;
      }
    }
    MediumTracker& tracker = trackers[next];
    const Medium& medium = *tracker.Tracked;
    const Vec3 sigmaT = medium.SigmaTAt(o + d * tracker.T);
    const float majorant = tracker.Majorant;
    // Probability of a real collision, weighted by the weight per channel.
    float realWeight = 0.f, nullWeight = 0.f;
    for (int c = 0; c < 3; ++c)
    {
      realWeight += sigmaT[c] * weight[c];
      nullWeight += std::max(0.f, majorant - sigmaT[c]) * weight[c];
    }
    const float pReal =
      realWeight + nullWeight > 0.f ? realWeight / (realWeight + nullWeight) : 0.f;
    const bool real = pReal >= 1.f || (pReal > 0.f && rng.NextFloat() < pReal);
    if (real)
    {
      if (pReal < 1.f)
      {
        weight = weight * sigmaT / (majorant * pReal);
      }
      t = tracker.T;
      return &medium;
    }
    for (int c = 0; c < 3; ++c)
    {
      weight[c] *= std::max(0.f, majorant - sigmaT[c]) / (majorant * (1.f - pReal));
    }
    if (!tracker.Next(rng))
    {
      trackers[next] = trackers[--active];
    }
  }
  return nullptr;
}

Vec3 Transmittance(const std::vector<Medium>& media, const Vec3& o, const Vec3& d, float distance,
  Random& rng, MediumTracker& tracker)
{
  Vec3 tr(1.f);
  for (const Medium& medium : media)
  {
    if (medium.IsHomogeneous())
    {
      float t0 = 0.f, t1 = distance;
      if (medium.Bounds.Intersect(o, d, t0, t1) && t1 > t0)
      {
        const Vec3 sigmaT = medium.SigmaT();
        for (int c = 0; c < 3; ++c)
        {
          tr[c] *= std::exp(-sigmaT[c] * (t1 - t0));
        }
      }
      continue;
    }
    // Ratio tracking: at each tentative collision, keep the null fraction.
    if (tracker.Begin(medium, o, d, distance))
    {
      while (tracker.Next(rng))
      {
        const Vec3 sigmaT = medium.SigmaTAt(o + d * tracker.T);
        for (int c = 0; c < 3; ++c)
        {
          tr[c] *= std::max(0.f, 1.f - sigmaT[c] / tracker.Majorant);
        }
        if (!(MaxComponent(tr) > 0.f))
        {
          return Vec3(0.f);
        }
      }
    }
  }
  return tr;
}

} // namespace brume
