// SPDX-License-Identifier: BSD-3-Clause
// How many texels an object's texture gets: from its hits, spread over its
// extent (ChooseResolution), finer for a dense medium (MediumHitsPerTexel)
// and where a medium's hits gather (HitConcentration).
#include "brume/Resolution.h"

#include "brume/DirectLight.h"

#include <algorithm>
#include <cmath>

namespace brume
{

double MediumHitsPerTexel(const Medium& medium, std::size_t hitCount, double threshold)
{
  if (!medium.Density || hitCount == 0)
  {
    return threshold;
  }
  const double volume = medium.Bounds.Volume();
  const double boxEdge = std::cbrt(volume * threshold / static_cast<double>(hitCount));
  const Vec3 sigmaT = medium.SigmaT(), albedo = medium.Albedo();
  double transport = 0.0;
  for (int c = 0; c < 3; ++c)
  {
    transport += sigmaT[c] * (1.0 - albedo[c] * medium.G) / 3.0;
  }
  transport *= medium.Density->MeanOccupiedDensity();
  if (!(transport > 0.0) || !std::isfinite(transport))
  {
    return threshold;
  }
  // (edge / box edge)^3 of the texels' count, between the occupied
  // fraction and 1.
  const double ratio = 1.0 / transport / boxEdge;
  return threshold * std::clamp(ratio * ratio * ratio, medium.Density->OccupiedFraction(), 1.0);
}

int MediumVoxelRefinement(const Medium& medium, const std::array<int, 3>& particleTexels)
{
  if (!medium.Density)
  {
    return 1;
  }
  const std::array<int, 3> native = medium.Density->NativeResolution();
  // The particles' texels per voxel, rounded up.
  int resolved = 1;
  for (int a = 0; a < 3; ++a)
  {
    resolved = std::max(resolved, (particleTexels[a] + native[a] - 1) / std::max(native[a], 1));
  }
  if (resolved == 1)
  {
    return 1;
  }
  const Vec3 extent = medium.Density->NativeBox().Extent();
  double voxel = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    if (native[a] > 0 && extent[a] > 0.f)
    {
      voxel = std::max(voxel, static_cast<double>(extent[a]) / native[a]);
    }
  }
  // Its largest density: the mean free path where the light enters the
  // dense part (a dragon's, whose occupied voxels' mean is half its
  // body's, with the fringe).
  const std::vector<float>& blocks = medium.Density->GetMajorants().Max;
  const double densest =
    blocks.empty() ? 0.0 : static_cast<double>(*std::max_element(blocks.begin(), blocks.end()));
  const double voxels = voxel * static_cast<double>(MaxComponent(medium.SigmaT())) * densest;
  if (!std::isfinite(voxels))
  {
    return 1;
  }
  // Voxels per mean free path, rounded.
  return std::min(resolved,
    static_cast<int>(std::clamp(std::round(voxels), 1.0, static_cast<double>(MaxVoxelRefinement))));
}

std::array<int, 3> PilotGridResolution(const Box& box)
{
  return ChooseResolution(box.Extent(), 4096, 1.0, 1, 64);
}

namespace
{
// Counts the cells cellOf(k) of items [0, count) into `counts` (already
// sized) in fixed chunks of items, each into counts of its own, on the
// threads of parallelFor: whole numbers, so the sums do not depend on how
// the chunks are split or added.
template <typename CellOf>
void CountInChunks(std::size_t count, CellOf cellOf, std::vector<std::int64_t>& counts,
  const ParallelFor& parallelFor)
{
  const std::size_t chunks = std::clamp<std::size_t>(count / 65536, 1, 16);
  std::vector<std::vector<std::int64_t>> partial(chunks);
  parallelFor(0, chunks,
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t chunk = begin; chunk < end; ++chunk)
      {
        std::vector<std::int64_t>& mine = partial[chunk];
        mine.assign(counts.size(), 0);
        const std::size_t first = count * chunk / chunks, last = count * (chunk + 1) / chunks;
        for (std::size_t k = first; k < last; ++k)
        {
          const std::size_t cell = cellOf(k);
          if (cell < mine.size())
          {
            ++mine[cell];
          }
        }
      }
    });
  for (const std::vector<std::int64_t>& mine : partial)
  {
    for (std::size_t c = 0; c < counts.size(); ++c)
    {
      counts[c] += mine[c];
    }
  }
}

constexpr std::size_t Skipped = ~std::size_t(0);
}

void CountHitsOverPilotGrid(const HitArrays& hits, const std::uint32_t* index, std::size_t count,
  const Box& box, std::vector<std::int64_t>& counts, const ParallelFor& parallelFor)
{
  const std::array<int, 3> res = PilotGridResolution(box);
  counts.resize(static_cast<std::size_t>(res[0]) * res[1] * res[2], 0);
  const Vec3 extent = box.Extent();
  auto cellOf = [&](std::size_t k)
  {
    const float* p = hits.Position + 3 * static_cast<std::size_t>(index[k]);
    int c[3];
    for (int a = 0; a < 3; ++a)
    {
      const float u = extent[a] > 0.f ? (p[a] - box.lower[a]) / extent[a] : 0.f;
      // Hits on the box's faces (or a hair beyond) count in its edge cells.
      c[a] = std::clamp(static_cast<int>(u * static_cast<float>(res[a])), 0, res[a] - 1);
    }
    return (static_cast<std::size_t>(c[2]) * res[1] + c[1]) * res[0] + c[0];
  };
  CountInChunks(count, cellOf, counts, parallelFor);
}

std::array<int, 3> PilotGridResolution(const PlanarFrame& frame)
{
  return ChooseResolution(Vec3(Length(frame.U), Length(frame.V), 0.f), 4096, 1.0, 1, 4096);
}

void CountHitsOverPilotGrid(const HitArrays& hits, const std::uint32_t* index, std::size_t count,
  const PlanarFrame& frame, std::size_t firstDeltaEmitter, std::size_t deltaLights,
  std::vector<std::int64_t>& counts, const ParallelFor& parallelFor)
{
  const std::array<int, 3> res = PilotGridResolution(frame);
  counts.resize(static_cast<std::size_t>(res[0]) * res[1], 0);
  const float uu = Dot(frame.U, frame.U), vv = Dot(frame.V, frame.V);
  const bool direct = deltaLights > 0 && hits.Emitter && hits.Depth;
  auto cellOf = [&](std::size_t k)
  {
    const std::size_t i = index[k];
    if (direct &&
      DirectLight::IsFirstInteraction(
        hits.Emitter[i], hits.Depth[i], firstDeltaEmitter, deltaLights))
    {
      return Skipped;
    }
    const Vec3 d =
      Vec3(hits.Position[3 * i], hits.Position[3 * i + 1], hits.Position[3 * i + 2]) - frame.Origin;
    const float q[2] = { uu > 0.f ? Dot(d, frame.U) / uu : 0.f,
      vv > 0.f ? Dot(d, frame.V) / vv : 0.f };
    int c[2];
    for (int a = 0; a < 2; ++a)
    {
      c[a] = std::clamp(static_cast<int>(q[a] * static_cast<float>(res[a])), 0, res[a] - 1);
    }
    return static_cast<std::size_t>(c[1]) * res[0] + c[0];
  };
  CountInChunks(count, cellOf, counts, parallelFor);
}

double HitConcentration(const std::vector<std::int64_t>& counts)
{
  double sum = 0.0, pairs = 0.0;
  for (const std::int64_t n : counts)
  {
    const double v = static_cast<double>(n);
    sum += v;
    pairs += v * (v - 1.0);
  }
  if (!(sum > 1.0))
  {
    return 1.0;
  }
  const double concentration = static_cast<double>(counts.size()) * pairs / (sum * sum);
  return std::clamp(concentration, 1.0, MaxHitConcentration);
}

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

} // namespace brume
