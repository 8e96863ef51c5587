// SPDX-License-Identifier: BSD-3-Clause
// Writes OpenVDB float grids from a function of the voxel index: the one
// place (compiled once) where the project's own volumes and its tests'
// volumes meet OpenVDB's writing templates.
#ifndef BrumeVdbWriter_h
#define BrumeVdbWriter_h

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace brume
{
namespace vdbwriter
{

/// A float grid: voxels of the index box [Lower, Upper] (inclusive) get
/// Value(i, j, k); those whose value is NaN stay inactive (the background).
/// Without Value, the grid holds only its tiles.
struct Grid
{
  std::string Name = "density";
  float Background = 0.f;
  /// Index to world: a uniform scale, then a translation.
  double VoxelSize = 1.0;
  std::array<double, 3> Translation{ 0.0, 0.0, 0.0 };
  /// OpenVDB's GRID_FOG_VOLUME class (otherwise GRID_UNKNOWN).
  bool FogVolume = false;
  std::array<int, 3> Lower{ 0, 0, 0 };
  std::array<int, 3> Upper{ -1, -1, -1 };
  std::function<float(int, int, int)> Value;
  /// Active tiles added after the voxels: (tree level, index origin, value).
  struct Tile
  {
    int Level = 1;
    std::array<int, 3> Origin{ 0, 0, 0 };
    float Value = 0.f;
  };
  std::vector<Tile> Tiles;
  /// Collapse uniform nodes into tiles before writing (OpenVDB's pruneGrid).
  bool Prune = false;
};

/// Writes `grids` into the OpenVDB file `path` (as openvdb::io::File does,
/// or, with `stream`, as openvdb::io::Stream does: without the grids'
/// offsets); returns each grid's active voxel count. Throws
/// std::runtime_error (OpenVDB's message) on failure.
std::vector<std::uint64_t> Write(
  const std::string& path, const std::vector<Grid>& grids, bool stream = false);

/// Balls of `radius` voxels (unit voxels, index space) centred on the x
/// axis at `centres`: density peak (1 - r^2 / radius^2) inside, inactive
/// outside; the grid's index box just holds them. Test volumes whose
/// active voxels fill a known part of a box.
Grid Balls(const std::vector<int>& centres, int radius, float peak);

/// OpenVDB's own trilinear samples (tools::BoxSampler) of the float grid
/// `name` in `path` at index-space points. Throws on failure.
std::vector<float> Sample(const std::string& path, const std::string& name,
  const std::vector<std::array<double, 3>>& points);

} // namespace vdbwriter
} // namespace brume

#endif
