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
  }
}

} // namespace brume
