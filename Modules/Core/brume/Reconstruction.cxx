// SPDX-License-Identifier: BSD-3-Clause
#include "brume/Reconstruction.h"

#include "brume/Sampling.h"

#include <algorithm>
#include <cmath>

namespace brume
{

std::array<int, 3> ChooseResolution(
  const Vec3& extent, std::size_t hitCount, double hitsPerTexel, int minimum, int maximum)
{
  // Texels proportional to the hits, shared among the used axes so that the
  // texels are as close to square (cubic) as the extent allows.
  int used = 0;
  double measure = 1.0;
  for (int a = 0; a < 3; ++a)
  {
    if (extent[a] > 0.f)
    {
      ++used;
      measure *= extent[a];
    }
  }
  std::array<int, 3> res{ 1, 1, 1 };
  if (used == 0)
  {
    return res;
  }
  const double texels = std::max(1.0, static_cast<double>(hitCount) / hitsPerTexel);
  const double size = std::pow(measure / texels, 1.0 / used); // texel edge length
  for (int a = 0; a < 3; ++a)
  {
    if (extent[a] > 0.f)
    {
      const double n = std::round(extent[a] / size);
      res[a] =
        static_cast<int>(std::clamp(n, static_cast<double>(minimum), static_cast<double>(maximum)));
    }
  }
  return res;
}

SurfaceRadiance::SurfaceRadiance(
  const Surface& surface, const PlanarFrame& frame, std::array<int, 2> resolution, int refinement)
  : SurfaceRef(surface)
  , Frame(frame)
  , Resolution(resolution)
  , Refinement(refinement)
  // Channels: incident flux R, G, B and the growth weight (their mean).
  , Cells({ resolution[0] * refinement, resolution[1] * refinement, 1 }, 4)
{
}

void SurfaceRadiance::AddHits(const Hit* hits, std::size_t count)
{
  const float uu = Dot(this->Frame.U, this->Frame.U);
  const float vv = Dot(this->Frame.V, this->Frame.V);
  for (std::size_t i = 0; i < count; ++i)
  {
    const Hit& h = hits[i];
    const Vec3 d = Vec3(h.Position[0], h.Position[1], h.Position[2]) - this->Frame.Origin;
    const auto cell =
      this->Cells.CellOf(Dot(d, this->Frame.U) / uu, Dot(d, this->Frame.V) / vv, 0.0);
    const double values[4] = { h.Flux[0], h.Flux[1], h.Flux[2],
      (static_cast<double>(h.Flux[0]) + h.Flux[1] + h.Flux[2]) / 3.0 };
    this->Cells.Add(this->Cells.Index(cell[0], cell[1], 0), values);
  }
}

void SurfaceRadiance::Finalize()
{
  this->Table = SummedAreaTable(this->Cells);
}

void SurfaceRadiance::Estimate(
  std::size_t begin, std::size_t end, double thresholdFlux, float* rgb) const
{
  AdaptiveRegionSettings settings;
  settings.Refinement = { this->Refinement, this->Refinement, 1 };
  settings.Threshold = thresholdFlux;
  settings.WeightChannel = 3;
  const auto& dims = this->Cells.GetDimensions();
  const double cellArea =
    this->Frame.Area() / (static_cast<double>(dims[0]) * static_cast<double>(dims[1]));
  // The diffuse part; view-dependent lobes are not reconstructed here yet.
  const Vec3 rho = this->SurfaceRef.Mat.Reflectance;
  const Vec3 le = this->SurfaceRef.Mat.Emission;
  for (std::size_t t = begin; t < end; ++t)
  {
    const std::array<int, 3> texel{ static_cast<int>(t % this->Resolution[0]),
      static_cast<int>(t / this->Resolution[0]), 0 };
    double perCell[4];
    EstimateTexel(this->Table, dims, texel, settings, perCell);
    for (int c = 0; c < 3; ++c)
    {
      // L_o = rho/pi * E + L_e with the irradiance E = flux / area.
      rgb[3 * (t - begin) + c] = static_cast<float>(rho[c] * InvPi * perCell[c] / cellArea + le[c]);
    }
  }
}

MediumRadiance::MediumRadiance(const Medium& medium, std::array<int, 3> resolution, int refinement)
  : MediumRef(medium)
  , Resolution(resolution)
  , Refinement(refinement)
  // Channels: phase-weighted flux R, G, B and the growth weight (mean flux).
  , Cells({ resolution[0] * refinement, resolution[1] * refinement, resolution[2] * refinement }, 4)
{
}

void MediumRadiance::AddHits(const Hit* hits, std::size_t count, const Vec3& eye)
{
  const Box& box = this->MediumRef.Bounds;
  const Vec3 extent = box.Extent();
  const HenyeyGreenstein phase(this->MediumRef.G);
  for (std::size_t i = 0; i < count; ++i)
  {
    const Hit& h = hits[i];
    const Vec3 p(h.Position[0], h.Position[1], h.Position[2]);
    const Vec3 q = (p - box.lower) / extent;
    const auto cell = this->Cells.CellOf(q.x, q.y, q.z);
    // Phase function from the direction of travel to the direction toward the eye.
    const Vec3 toEye = Normalize(eye - p);
    const double pw =
      phase.Evaluate(Dot(Vec3(h.Direction[0], h.Direction[1], h.Direction[2]), toEye));
    const double values[4] = { pw * h.Flux[0], pw * h.Flux[1], pw * h.Flux[2],
      (static_cast<double>(h.Flux[0]) + h.Flux[1] + h.Flux[2]) / 3.0 };
    this->Cells.Add(this->Cells.Index(cell[0], cell[1], cell[2]), values);
  }
}

void MediumRadiance::Finalize()
{
  this->Table = SummedAreaTable(this->Cells);
}

void MediumRadiance::Estimate(
  std::size_t begin, std::size_t end, double thresholdFlux, float* rgb, float* extinction) const
{
  AdaptiveRegionSettings settings;
  settings.Refinement = { this->Refinement, this->Refinement, this->Refinement };
  settings.Threshold = thresholdFlux;
  settings.WeightChannel = 3;
  const auto& dims = this->Cells.GetDimensions();
  const double cellVolume = static_cast<double>(this->MediumRef.Bounds.Volume()) /
    (static_cast<double>(dims[0]) * dims[1] * dims[2]);
  const Vec3 albedo = this->MediumRef.Albedo();
  const Box& box = this->MediumRef.Bounds;
  const Vec3 voxelSize = box.Extent() /
    Vec3(static_cast<float>(this->Resolution[0]), static_cast<float>(this->Resolution[1]),
      static_cast<float>(this->Resolution[2]));
  const std::size_t nx = this->Resolution[0], nxy = nx * this->Resolution[1];
  for (std::size_t v = begin; v < end; ++v)
  {
    const std::array<int, 3> voxel{ static_cast<int>(v % nx), static_cast<int>((v % nxy) / nx),
      static_cast<int>(v / nxy) };
    double perCell[4];
    EstimateTexel(this->Table, dims, voxel, settings, perCell);
    // The voxel's extinction: sigma_t, times the density's mean over 2^3 points.
    Vec3 sigmaT = this->MediumRef.SigmaT();
    if (this->MediumRef.Density)
    {
      float mean = 0.f;
      for (int k = 0; k < 8; ++k)
      {
        const Vec3 offset(
          0.25f + 0.5f * (k & 1), 0.25f + 0.5f * ((k >> 1) & 1), 0.25f + 0.5f * (k >> 2));
        const Vec3 corner(
          static_cast<float>(voxel[0]), static_cast<float>(voxel[1]), static_cast<float>(voxel[2]));
        mean += this->MediumRef.Density->Evaluate(box.lower + (corner + offset) * voxelSize) / 8.f;
      }
      sigmaT = sigmaT * mean;
    }
    for (int c = 0; c < 3; ++c)
    {
      // J = albedo * sum(p Phi) / V; S = J / sigma_t.
      const double j = albedo[c] * perCell[c] / cellVolume;
      rgb[3 * (v - begin) + c] = sigmaT[c] > 0.f ? static_cast<float>(j / sigmaT[c]) : 0.f;
      extinction[3 * (v - begin) + c] = sigmaT[c];
    }
  }
}

} // namespace brume
