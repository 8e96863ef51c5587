// SPDX-License-Identifier: BSD-3-Clause
#include "BrumeVdbWriter.h"

#include <openvdb/io/Stream.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <stdexcept>

namespace brume
{
namespace vdbwriter
{

std::vector<std::uint64_t> Write(
  const std::string& path, const std::vector<Grid>& grids, bool stream)
{
  try
  {
    openvdb::initialize();
    openvdb::GridPtrVec out;
    std::vector<std::uint64_t> active;
    for (const Grid& g : grids)
    {
      auto grid = openvdb::FloatGrid::create(g.Background);
      grid->setName(g.Name);
      if (g.FogVolume)
      {
        grid->setGridClass(openvdb::GRID_FOG_VOLUME);
      }
      auto transform = openvdb::math::Transform::createLinearTransform(g.VoxelSize);
      transform->postTranslate(
        openvdb::Vec3d(g.Translation[0], g.Translation[1], g.Translation[2]));
      grid->setTransform(transform);
      if (g.Value)
      {
        auto accessor = grid->getAccessor();
        for (int k = g.Lower[2]; k <= g.Upper[2]; ++k)
          for (int j = g.Lower[1]; j <= g.Upper[1]; ++j)
            for (int i = g.Lower[0]; i <= g.Upper[0]; ++i)
            {
              const float v = g.Value(i, j, k);
              if (!std::isnan(v))
              {
                accessor.setValue(openvdb::Coord(i, j, k), v);
              }
            }
      }
      for (const Grid::Tile& t : g.Tiles)
      {
        grid->tree().addTile(
          t.Level, openvdb::Coord(t.Origin[0], t.Origin[1], t.Origin[2]), t.Value, true);
      }
      if (g.Prune)
      {
        grid->pruneGrid();
      }
      active.push_back(grid->activeVoxelCount());
      out.push_back(grid);
    }
    if (stream)
    {
      std::ofstream os(path, std::ios::binary);
      openvdb::io::Stream(os).write(out);
      if (!os)
      {
        throw std::runtime_error(path + ": cannot write the stream");
      }
      return active;
    }
    openvdb::io::File file(path);
    file.write(out);
    file.close();
    return active;
  }
  catch (const openvdb::Exception& e)
  {
    throw std::runtime_error(path + ": " + e.what());
  }
}

Grid Balls(const std::vector<int>& centres, int radius, float peak)
{
  Grid grid;
  const auto [first, last] = std::minmax_element(centres.begin(), centres.end());
  grid.Lower = { *first - radius, -radius, -radius };
  grid.Upper = { *last + radius, radius, radius };
  const float r2max = static_cast<float>(radius * radius);
  grid.Value = [centres, r2max, peak](int i, int j, int k)
  {
    for (int centre : centres)
    {
      const float r2 = static_cast<float>((i - centre) * (i - centre) + j * j + k * k);
      if (r2 < r2max)
      {
        return peak * (1.f - r2 / r2max);
      }
    }
    return std::nanf("");
  };
  return grid;
}

std::vector<float> Sample(const std::string& path, const std::string& name,
  const std::vector<std::array<double, 3>>& points)
{
  try
  {
    openvdb::initialize();
    openvdb::io::File file(path);
    file.open();
    auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid(name));
    file.close();
    if (!grid)
    {
      throw std::runtime_error(path + ": no float grid named '" + name + "'");
    }
    std::vector<float> samples;
    samples.reserve(points.size());
    for (const auto& p : points)
    {
      samples.push_back(
        openvdb::tools::BoxSampler::sample(grid->tree(), openvdb::Vec3R(p[0], p[1], p[2])));
    }
    return samples;
  }
  catch (const openvdb::Exception& e)
  {
    throw std::runtime_error(path + ": " + e.what());
  }
}

} // namespace vdbwriter
} // namespace brume
