// SPDX-License-Identifier: BSD-3-Clause
#include "brume/VdbDensity.h"
#include "brume/VdbGrid.h"

#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <mutex>
#include <sstream>
#include <vector>

namespace brume
{

struct VdbDensity::Internals
{
  openvdb::FloatGrid::Ptr Grid;
  openvdb::Vec3d Origin;     // world position of index (0, 0, 0)
  openvdb::Vec3d VoxelSize;  // world size of a voxel along each axis
  openvdb::Coord FirstVoxel; // the voxel at the centre of native cell (0, 0, 0)
  std::size_t Active = 0;
  // Scalars (LoadScalars): per majorant block, the smallest and largest value.
  std::vector<float> RangeLow, RangeHigh;
  // The leaves' values by leaf position over the active box widened by a
  // leaf (LeafDims leaves from the one whose first voxel is LeafOrigin),
  // null where the tree has no leaf: a sample reads its eight values
  // without descending the tree (empty where the table would be too large).
  std::vector<const float*> Leaves;
  openvdb::Coord LeafOrigin;
  int LeafDims[3] = { 0, 0, 0 };

  const float* LeafOf(const openvdb::Coord& c) const
  {
    const int i = (c[0] >> 3) - (this->LeafOrigin[0] >> 3);
    const int j = (c[1] >> 3) - (this->LeafOrigin[1] >> 3);
    const int k = (c[2] >> 3) - (this->LeafOrigin[2] >> 3);
    if (i < 0 || j < 0 || k < 0 || i >= this->LeafDims[0] || j >= this->LeafDims[1] ||
      k >= this->LeafDims[2])
    {
      return nullptr;
    }
    return this
      ->Leaves[(static_cast<std::size_t>(k) * this->LeafDims[1] + j) * this->LeafDims[0] + i];
  }

  // LoadGrid's steps, given the grid's active box (index space). The
  // majorants over the density's bounds, the blocks' value ranges for
  // scalars, and the occupied values; false, with `error`, at an active
  // value that is not finite (or a negative density).
  static bool BuildMajorants(VdbDensity& density, const openvdb::FloatGrid& grid,
    const openvdb::CoordBBox& bbox, float background, bool scalars, const ParallelFor& parallelFor,
    std::string& error);
  // Leaves, LeafOrigin and LeafDims.
  void BuildLeafTable(const openvdb::FloatGrid& grid, const openvdb::CoordBBox& bbox);
};

VdbDensity::VdbDensity()
  : Impl(new Internals)
{
}

VdbDensity::~VdbDensity() = default;

std::size_t VdbDensity::GetNumberOfActiveVoxels() const
{
  return this->Impl->Active;
}

openvdb::FloatGrid::Ptr ReadVdbFloatGrid(
  const std::string& fileName, const std::string& gridName, std::string& error)
{
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
  openvdb::FloatGrid::Ptr grid;
  std::string floatGrids; // the names a user could have meant (the first 8)
  int others = 0;
  error = CheckVdbFile(fileName);
  if (!error.empty())
  {
    return nullptr;
  }
  try
  {
    openvdb::io::File file(fileName);
    file.open(false);
    for (auto it = file.beginName(); it != file.endName(); ++it)
    {
      if (!file.readGridMetadata(it.gridName())->isType<openvdb::FloatGrid>())
      {
        continue;
      }
      if (gridName.empty() || it.gridName() == gridName)
      {
        grid = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid(it.gridName()));
        break;
      }
      if (++others <= 8)
      {
        floatGrids +=
          (floatGrids.empty() ? "'" : ", '") + ShortMessage(it.gridName().c_str()) + "'";
      }
      else if (others == 9)
      {
        floatGrids += ", ...";
      }
    }
    file.close();
  }
  catch (const std::exception& e)
  {
    error = "cannot read OpenVDB file '" + fileName + "': " + ShortMessage(e.what());
    return nullptr;
  }
  if (!grid)
  {
    error = "OpenVDB file '" + fileName + "' has no float grid" +
      (gridName.empty() ? std::string() : " named '" + gridName + "'") +
      (floatGrids.empty() ? std::string() : " (its float grids: " + floatGrids + ")");
    return nullptr;
  }
  const auto map = grid->transform().baseMap();
  if (!map->isType<openvdb::math::ScaleTranslateMap>() &&
    !map->isType<openvdb::math::UniformScaleTranslateMap>() &&
    !map->isType<openvdb::math::ScaleMap>() && !map->isType<openvdb::math::UniformScaleMap>() &&
    !map->isType<openvdb::math::TranslationMap>())
  {
    error = "OpenVDB grid '" + grid->getName() +
      "' has a transform that is not an axis-aligned scale and translation";
    return nullptr;
  }
  return grid;
}

std::shared_ptr<VdbDensity> VdbDensity::Load(const std::string& fileName,
  const std::string& gridName, std::string& error, const ParallelFor& parallelFor)
{
  return LoadGrid(fileName, gridName, false, error, parallelFor);
}

std::shared_ptr<VdbDensity> VdbDensity::LoadScalars(const std::string& fileName,
  const std::string& gridName, std::string& error, const ParallelFor& parallelFor)
{
  return LoadGrid(fileName, gridName, true, error, parallelFor);
}

bool VdbDensity::ValueRanges(std::vector<float>& lo, std::vector<float>& hi) const
{
  if (this->Impl->RangeHigh.empty())
  {
    return false;
  }
  lo = this->Impl->RangeLow;
  hi = this->Impl->RangeHigh;
  return true;
}

bool VdbDensity::Internals::BuildMajorants(VdbDensity& density, const openvdb::FloatGrid& grid,
  const openvdb::CoordBBox& bbox, float background, bool scalars, const ParallelFor& parallelFor,
  std::string& error)
{
  Internals& impl = *density.Impl;
  const openvdb::Coord lo = bbox.min();
  // Majorants per 8^3 block of the active box: a voxel's value reaches the
  // trilinear samples within one voxel of its centre.
  constexpr int B = 8;
  MajorantGrid& mg = density.Majorants;
  mg.Bounds = density.Bounds;
  const openvdb::Coord dim = bbox.dim();
  for (int a = 0; a < 3; ++a)
  {
    mg.Dims[a] = (dim[a] + 2 + B - 1) / B; // the box spans dim + 2 voxels
  }
  // Blocks are B voxels wide: the majorant grid's box is a whole number of blocks.
  for (int a = 0; a < 3; ++a)
  {
    mg.Bounds.upper[a] = static_cast<float>(
      mg.Bounds.lower[a] + static_cast<double>(mg.Dims[a]) * B * impl.VoxelSize[a]);
  }
  mg.Max.assign(static_cast<std::size_t>(mg.Dims[0]) * mg.Dims[1] * mg.Dims[2], background);
  // Scalars: each block's range of the values its samples interpolate (its
  // voxels and one more layer around), the background where one of those
  // voxels is inactive (counted in `activeAround`).
  std::vector<double> activeAround;
  if (scalars)
  {
    impl.RangeLow.assign(mg.Max.size(), std::numeric_limits<float>::infinity());
    impl.RangeHigh.assign(mg.Max.size(), -std::numeric_limits<float>::infinity());
    activeAround.assign(mg.Max.size(), 0.0);
  }
  auto blockOf = [&](int a, double index)
  {
    const int b = static_cast<int>(std::floor((index - (lo[a] - 1.0)) / B));
    return std::min(mg.Dims[a] - 1, std::max(0, b));
  };
  auto reach = [&](const openvdb::CoordBBox& region, int b0[3], int b1[3])
  {
    for (int a = 0; a < 3; ++a)
    {
      b0[a] = blockOf(a, region.min()[a] - 1.0);
      b1[a] = blockOf(a, region.max()[a] + 1.0);
    }
  };
  // Value v over `region` into the blocks it reaches, block (i, j, k)
  // being entry at(i, j, k) of the arrays: the largest value and, for
  // scalars, the range and the active voxels around (whole numbers, summed
  // exactly in any order: blocks found apart merge into the same grid).
  struct Arrays
  {
    float* Max;
    float* Low;
    float* High;
    double* Around;
  };
  auto add = [&](float v, const openvdb::CoordBBox& region, const Arrays& to, const auto& at)
  {
    int b0[3], b1[3];
    reach(region, b0, b1);
    for (int k = b0[2]; k <= b1[2]; ++k)
      for (int j = b0[1]; j <= b1[1]; ++j)
        for (int i = b0[0]; i <= b1[0]; ++i)
        {
          const std::size_t w = at(i, j, k);
          to.Max[w] = std::max(to.Max[w], v);
          if (scalars)
          {
            to.Low[w] = std::min(to.Low[w], v);
            to.High[w] = std::max(to.High[w], v);
            const int block[3] = { i, j, k };
            double overlap = 1.0;
            for (int a = 0; a < 3; ++a)
            {
              const int first = lo[a] - 1 + block[a] * B - 1, last = first + B + 1;
              overlap *=
                std::max(0, std::min(region.max()[a], last) - std::max(region.min()[a], first) + 1);
            }
            to.Around[w] += overlap;
          }
        }
  };
  const Arrays grids{ mg.Max.data(), impl.RangeLow.data(), impl.RangeHigh.data(),
    activeAround.data() };
  auto gridAt = [&](int i, int j, int k)
  { return (static_cast<std::size_t>(k) * mg.Dims[1] + j) * mg.Dims[0] + i; };
  // Whether a value may be read, and the occupied values and their sum.
  double occupiedValues = 0.0, occupiedSum = 0.0;
  auto valid = [&](float v) { return std::isfinite(v) && (scalars || v >= 0.f); };
  // The leaves' voxels, a batch of leaves at a time on `parallelFor`: each
  // leaf into the window of blocks its voxels reach (at most 3 along an
  // axis), merged into the grid in the leaves' order.
  constexpr int Window = 3;
  struct LeafBlocks
  {
    int First[3] = { 0, 0, 0 }, Count[3] = { 0, 0, 0 };
    float Max[Window * Window * Window], Low[Window * Window * Window],
      High[Window * Window * Window];
    double Around[Window * Window * Window];
    double OccupiedValues = 0.0, OccupiedSum = 0.0;
    bool Valid = true;
  };
  using Leaf = openvdb::FloatTree::LeafNodeType;
  std::vector<const Leaf*> leaves;
  leaves.reserve(grid.constTree().leafCount());
  for (auto leaf = grid.constTree().cbeginLeaf(); leaf; ++leaf)
  {
    leaves.push_back(leaf.getLeaf());
  }
  constexpr std::size_t Batch = 8192;
  std::vector<LeafBlocks> found(std::min(Batch, leaves.size()));
  bool allValid = true;
  for (std::size_t first = 0; first < leaves.size() && allValid; first += Batch)
  {
    const std::size_t n = std::min(Batch, leaves.size() - first);
    parallelFor(0, n,
      [&](std::size_t begin, std::size_t end)
      {
        for (std::size_t l = begin; l < end; ++l)
        {
          const Leaf& leaf = *leaves[first + l];
          LeafBlocks& blocks = found[l];
          int b0[3], b1[3];
          reach(leaf.getNodeBoundingBox(), b0, b1);
          for (int a = 0; a < 3; ++a)
          {
            blocks.First[a] = b0[a];
            blocks.Count[a] = b1[a] - b0[a] + 1;
          }
          std::fill(std::begin(blocks.Max), std::end(blocks.Max), background);
          std::fill(
            std::begin(blocks.Low), std::end(blocks.Low), std::numeric_limits<float>::infinity());
          std::fill(std::begin(blocks.High), std::end(blocks.High),
            -std::numeric_limits<float>::infinity());
          std::fill(std::begin(blocks.Around), std::end(blocks.Around), 0.0);
          blocks.OccupiedValues = blocks.OccupiedSum = 0.0;
          blocks.Valid = true;
          const Arrays to{ blocks.Max, blocks.Low, blocks.High, blocks.Around };
          auto at = [&](int i, int j, int k)
          {
            return static_cast<std::size_t>(
              ((k - blocks.First[2]) * blocks.Count[1] + (j - blocks.First[1])) * blocks.Count[0] +
              (i - blocks.First[0]));
          };
          for (auto it = leaf.cbeginValueOn(); it; ++it)
          {
            const float v = *it;
            if (!valid(v))
            {
              blocks.Valid = false;
              break;
            }
            if (v > 0.f)
            {
              blocks.OccupiedValues += 1.0;
              blocks.OccupiedSum += v;
            }
            if (v > background || scalars)
            {
              const openvdb::Coord xyz = it.getCoord();
              add(v, openvdb::CoordBBox(xyz, xyz), to, at);
            }
          }
        }
      });
    for (std::size_t l = 0; l < n && allValid; ++l)
    {
      const LeafBlocks& blocks = found[l];
      allValid = blocks.Valid;
      occupiedValues += blocks.OccupiedValues;
      occupiedSum += blocks.OccupiedSum;
      for (int k = 0; k < blocks.Count[2]; ++k)
        for (int j = 0; j < blocks.Count[1]; ++j)
          for (int i = 0; i < blocks.Count[0]; ++i)
          {
            const std::size_t w =
              static_cast<std::size_t>((k * blocks.Count[1] + j) * blocks.Count[0] + i);
            const std::size_t b =
              gridAt(blocks.First[0] + i, blocks.First[1] + j, blocks.First[2] + k);
            mg.Max[b] = std::max(mg.Max[b], blocks.Max[w]);
            if (scalars)
            {
              impl.RangeLow[b] = std::min(impl.RangeLow[b], blocks.Low[w]);
              impl.RangeHigh[b] = std::max(impl.RangeHigh[b], blocks.High[w]);
              activeAround[b] += blocks.Around[w];
            }
          }
    }
  }
  // The active tiles above the leaves, in turn, into the grid itself.
  openvdb::FloatGrid::ValueOnCIter tile = grid.cbeginValueOn();
  tile.setMaxDepth(openvdb::FloatGrid::ValueOnCIter::LEAF_DEPTH - 1);
  for (; tile && allValid; ++tile)
  {
    const float v = *tile;
    allValid = valid(v);
    if (!allValid)
    {
      break;
    }
    if (v > 0.f)
    {
      const double voxels = static_cast<double>(tile.getVoxelCount());
      occupiedValues += voxels;
      occupiedSum += voxels * v;
    }
    if (v > background || scalars)
    {
      openvdb::CoordBBox region;
      tile.getBoundingBox(region);
      add(v, region, grids, gridAt);
    }
  }
  if (!allValid)
  {
    error = "OpenVDB grid '" + grid.getName() + "' has negative or non-finite " +
      (scalars ? "scalars" : "densities");
    return false;
  }
  density.OccupiedValues += occupiedValues;
  density.OccupiedSum += occupiedSum;
  for (std::size_t b = 0; b < activeAround.size(); ++b)
  {
    if (activeAround[b] < static_cast<double>((B + 2) * (B + 2) * (B + 2)))
    {
      impl.RangeLow[b] = std::min(impl.RangeLow[b], background);
      impl.RangeHigh[b] = std::max(impl.RangeHigh[b], background);
    }
  }
  mg.MarkEmptyRegions();
  return true;
}

void VdbDensity::Internals::BuildLeafTable(
  const openvdb::FloatGrid& grid, const openvdb::CoordBBox& bbox)
{
  const openvdb::Coord lo = bbox.min(), hi = bbox.max();
  // The leaf table, where it takes at most 2^24 pointers (128 MiB).
  for (int a = 0; a < 3; ++a)
  {
    this->LeafOrigin[a] = ((lo[a] - 8) >> 3) * 8; // arithmetic shift: floor division by 8
    this->LeafDims[a] = ((hi[a] + 8) >> 3) - (this->LeafOrigin[a] >> 3) + 1;
  }
  const double leafCells =
    static_cast<double>(this->LeafDims[0]) * this->LeafDims[1] * this->LeafDims[2];
  if (leafCells <= static_cast<double>(1 << 24))
  {
    this->Leaves.assign(static_cast<std::size_t>(leafCells), nullptr);
    for (auto leaf = grid.constTree().cbeginLeaf(); leaf; ++leaf)
    {
      const openvdb::Coord origin = leaf->origin();
      const int i = (origin[0] >> 3) - (this->LeafOrigin[0] >> 3);
      const int j = (origin[1] >> 3) - (this->LeafOrigin[1] >> 3);
      const int k = (origin[2] >> 3) - (this->LeafOrigin[2] >> 3);
      if (i >= 0 && j >= 0 && k >= 0 && i < this->LeafDims[0] && j < this->LeafDims[1] &&
        k < this->LeafDims[2])
      {
        this
          ->Leaves[(static_cast<std::size_t>(k) * this->LeafDims[1] + j) * this->LeafDims[0] + i] =
          leaf->buffer().data();
      }
    }
  }
  else
  {
    this->LeafDims[0] = this->LeafDims[1] = this->LeafDims[2] = 0;
  }
}

std::shared_ptr<VdbDensity> VdbDensity::LoadGrid(const std::string& fileName,
  const std::string& gridName, bool scalars, std::string& error, const ParallelFor& parallelFor)
{
  const openvdb::FloatGrid::Ptr grid = ReadVdbFloatGrid(fileName, gridName, error);
  if (!grid)
  {
    return nullptr;
  }
  const openvdb::math::Transform& transform = grid->transform();
  const std::string what =
    "OpenVDB grid '" + ShortMessage(grid->getName().c_str()) + "' of '" + fileName + "'";
  auto density = std::shared_ptr<VdbDensity>(new VdbDensity);
  Internals& impl = *density->Impl;
  impl.Origin = transform.indexToWorld(openvdb::Vec3d(0.0));
  impl.VoxelSize = transform.indexToWorld(openvdb::Vec3d(1.0)) - impl.Origin;
  for (int a = 0; a < 3; ++a)
  {
    if (!(impl.VoxelSize[a] > 0.0))
    {
      error = what + " has a non-positive voxel size";
      return nullptr;
    }
  }
  const openvdb::CoordBBox bbox = grid->evalActiveVoxelBoundingBox();
  if (bbox.empty() || grid->activeVoxelCount() == 0)
  {
    error = what + " has no active voxels";
    return nullptr;
  }
  const float background = grid->background();
  if (!std::isfinite(background) || (!scalars && !(background >= 0.f)))
  {
    error = what + " has a negative or non-finite background";
    return nullptr;
  }
  impl.Active = static_cast<std::size_t>(grid->activeVoxelCount());

  // World box of the active voxels (voxel centres sit at integer indices),
  // widened by one voxel: trilinear interpolation reaches that far.
  const openvdb::Coord lo = bbox.min(), hi = bbox.max();
  impl.FirstVoxel = lo - openvdb::Coord(1);
  for (int a = 0; a < 3; ++a)
  {
    density->Bounds.lower[a] =
      static_cast<float>(impl.Origin[a] + (lo[a] - 1.0) * impl.VoxelSize[a]);
    density->Bounds.upper[a] =
      static_cast<float>(impl.Origin[a] + (hi[a] + 1.0) * impl.VoxelSize[a]);
    if (!std::isfinite(density->Bounds.lower[a]) || !std::isfinite(density->Bounds.upper[a]) ||
      !(density->Bounds.upper[a] > density->Bounds.lower[a]))
    {
      std::ostringstream size;
      size << impl.VoxelSize[a];
      error = what +
        ": its active voxels span a box that single precision cannot hold (voxel size " +
        size.str() + ", index box " + std::to_string(lo[a]) + " to " + std::to_string(hi[a]) +
        " along axis " + std::to_string(a) + ")";
      return nullptr;
    }
  }
  if (!Internals::BuildMajorants(*density, *grid, bbox, background, scalars, parallelFor, error))
  {
    return nullptr;
  }
  impl.Grid = grid;
  impl.BuildLeafTable(*grid, bbox);
  // The native cells in all; a background above 0 fills the rest.
  const std::array<int, 3> cells = density->NativeResolution();
  density->GridValues = static_cast<double>(cells[0]) * cells[1] * cells[2];
  if (background > 0.f)
  {
    density->OccupiedSum += static_cast<double>(background) *
      std::max(0.0, density->GridValues - density->OccupiedValues);
    density->OccupiedValues = std::max(density->OccupiedValues, density->GridValues);
  }
  return density;
}

std::array<int, 3> VdbDensity::NativeResolution() const
{
  // The voxels of the bounds (the active box and one voxel around it, whose
  // faces sit on voxel centres) and the half voxels beyond: one cell per
  // voxel centre.
  std::array<int, 3> voxels{};
  for (int a = 0; a < 3; ++a)
  {
    voxels[a] = std::max(1,
      static_cast<int>(
        std::lround(static_cast<double>(this->Bounds.Extent()[a]) / this->Impl->VoxelSize[a])) +
        1);
  }
  return voxels;
}

Box VdbDensity::NativeBox() const
{
  Box box = this->Bounds;
  for (int a = 0; a < 3; ++a)
  {
    box.lower[a] -= static_cast<float>(0.5 * this->Impl->VoxelSize[a]);
    box.upper[a] += static_cast<float>(0.5 * this->Impl->VoxelSize[a]);
  }
  return box;
}

bool VdbDensity::NativePoints(
  const std::array<int, 3>& lower, const std::array<int, 3>& count, float* out) const
{
  // Native cell i's centre is voxel FirstVoxel + i (the bounds' faces sit
  // on the centres of the voxels around the active box).
  const Internals& impl = *this->Impl;
  const openvdb::tree::ValueAccessor<const openvdb::FloatTree, false> accessor(
    impl.Grid->constTree());
  for (int z = 0; z < count[2]; ++z)
    for (int y = 0; y < count[1]; ++y)
      for (int x = 0; x < count[0]; ++x)
      {
        const openvdb::Coord xyz =
          impl.FirstVoxel + openvdb::Coord(lower[0] + x, lower[1] + y, lower[2] + z);
        const float* leaf = impl.LeafOf(xyz);
        *out++ = leaf ? leaf[openvdb::FloatTree::LeafNodeType::coordToOffset(xyz)]
                      : accessor.getValue(xyz);
      }
  return true;
}

float VdbDensity::NativeValue(int i, int j, int k, const Vec3& centre) const
{
  (void)centre;
  float value = 0.f;
  this->NativePoints({ i, j, k }, { 1, 1, 1 }, &value);
  return value;
}

float VdbDensity::Evaluate(const Vec3& p) const
{
  const Internals& impl = *this->Impl;
  const openvdb::Vec3R index((p.x - impl.Origin[0]) / impl.VoxelSize[0],
    (p.y - impl.Origin[1]) / impl.VoxelSize[1], (p.z - impl.Origin[2]) / impl.VoxelSize[2]);
  // OpenVDB's trilinear sample (BoxSampler) of the eight voxels about the
  // point, read from the leaf table where their leaves are in it, else from
  // the tree through an accessor of this call alone (threads share the
  // tree, not an accessor; unregistered: the tree outlives the call). The
  // values are the tree's and the interpolation is BoxSampler's own, so
  // the sample is bitwise BoxSampler::sample's.
  const openvdb::Vec3i ijk = openvdb::tools::local_util::floorVec3(index);
  const openvdb::Vec3R uvw = index - ijk;
  const openvdb::tree::ValueAccessor<const openvdb::FloatTree, false> accessor(
    impl.Grid->constTree());
  float data[2][2][2];
  for (int a = 0; a < 2; ++a)
  {
    for (int b = 0; b < 2; ++b)
    {
      for (int c = 0; c < 2; ++c)
      {
        const openvdb::Coord xyz(ijk[0] + a, ijk[1] + b, ijk[2] + c);
        const float* leaf = impl.LeafOf(xyz);
        data[a][b][c] = leaf ? leaf[openvdb::FloatTree::LeafNodeType::coordToOffset(xyz)]
                             : accessor.getValue(xyz);
      }
    }
  }
  return openvdb::tools::BoxSampler::trilinearInterpolation(data, uvw);
}

namespace
{
// Reads little-endian values and length-prefixed strings, never past `End`.
class VdbScanner
{
public:
  VdbScanner(std::istream& in, std::int64_t end)
    : In(in)
    , End(end)
  {
  }
  std::int64_t Left() { return this->End - static_cast<std::int64_t>(this->In.tellg()); }
  template <typename T>
  bool Read(T& value)
  {
    if (this->Left() < static_cast<std::int64_t>(sizeof(T)))
    {
      return false;
    }
    this->In.read(reinterpret_cast<char*>(&value), sizeof(T));
    return static_cast<bool>(this->In);
  }
  bool Skip(std::int64_t bytes)
  {
    if (bytes < 0 || bytes > this->Left())
    {
      return false;
    }
    this->In.seekg(bytes, std::ios::cur);
    return static_cast<bool>(this->In);
  }
  bool String(std::string* out = nullptr)
  {
    std::uint32_t size = 0;
    if (!this->Read(size) || static_cast<std::int64_t>(size) > this->Left())
    {
      return false;
    }
    if (!out)
    {
      return this->Skip(size);
    }
    out->resize(size);
    this->In.read(out->data(), size);
    return static_cast<bool>(this->In);
  }
  // A MetaMap: count, then (name, type name, byte count, bytes) entries.
  bool Metadata()
  {
    std::uint32_t count = 0;
    if (!this->Read(count) || static_cast<std::int64_t>(count) * 12 > this->Left())
    {
      return false;
    }
    for (std::uint32_t i = 0; i < count; ++i)
    {
      std::uint32_t bytes = 0;
      if (!this->String() || !this->String() || !this->Read(bytes) || !this->Skip(bytes))
      {
        return false;
      }
    }
    return true;
  }
  std::istream& In;
  std::int64_t End;
};
}

std::string CheckVdbFile(const std::string& fileName)
{
  std::ifstream in(fileName, std::ios::binary);
  if (!in)
  {
    return "cannot open OpenVDB file '" + fileName + "'";
  }
  in.seekg(0, std::ios::end);
  const std::int64_t size = static_cast<std::int64_t>(in.tellg());
  in.seekg(0);
  VdbScanner scan(in, size);
  const std::string corrupt = "'" + fileName + "' is not a valid OpenVDB file: ";
  std::int64_t magic = 0;
  std::uint32_t version = 0, major = 0, minor = 0;
  char hasOffsets = 0;
  if (!scan.Read(magic) || magic != 0x56444220)
  {
    return corrupt + "no VDB magic number";
  }
  // The header's layout follows the file version (openvdb/io/Archive.cc).
  if (!scan.Read(version))
  {
    return corrupt + "truncated header";
  }
  if (version < 211 || version > 224)
  {
    return corrupt + "file format version " + std::to_string(version) +
      " is not one OpenVDB 10 reads";
  }
  if (version < 216)
  {
    // Before grid instancing a grid's transform follows its topology, whose
    // size only reading it tells: what the transform announces cannot be
    // checked first (a fuzzer's find: a version-211 grid announcing a 3 GB
    // transform name, which OpenVDB allocated).
    return "'" + fileName + "' has the OpenVDB file format version " + std::to_string(version) +
      ", older than 216, the oldest Brume reads: save the grid again with a recent OpenVDB";
  }
  char isCompressed = 0;
  if (!scan.Read(major) || !scan.Read(minor) || (version >= 212 && !scan.Read(hasOffsets)) ||
    (version >= 220 && version < 222 && !scan.Read(isCompressed)) ||
    !scan.Skip(version >= 218 ? 36 : 16))
  {
    return corrupt + "truncated header";
  }
  if (!scan.Metadata())
  {
    return corrupt + "the file metadata runs past the end of the file";
  }
  std::int32_t grids = 0;
  if (!scan.Read(grids) || grids < 0 || static_cast<std::int64_t>(grids) * 32 > scan.Left())
  {
    return corrupt + "bad grid count";
  }
  for (std::int32_t g = 0; g < grids; ++g)
  {
    std::int64_t gridPos = 0, blockPos = 0, endPos = 0;
    if (!scan.String() || !scan.String() || (version >= 216 && !scan.String()))
    {
      return corrupt + "grid descriptor " + std::to_string(g) + " runs past the end of the file";
    }
    // Every descriptor holds three offsets (OpenVDB's GridDescriptor::read
    // reads them whether or not the file says it has offsets).
    if (!scan.Read(gridPos) || !scan.Read(blockPos) || !scan.Read(endPos))
    {
      return corrupt + "grid descriptor " + std::to_string(g) + " runs past the end of the file";
    }
    if (!hasOffsets)
    {
      // A stream without offsets: the first grid follows its descriptor, and
      // where the next one starts is known only after reading the first.
      gridPos = static_cast<std::int64_t>(in.tellg());
      blockPos = endPos = size;
    }
    if (!(0 <= gridPos && gridPos <= blockPos && blockPos <= endPos && endPos <= size))
    {
      return corrupt + "grid " + std::to_string(g) + " has offsets outside the file";
    }
    in.seekg(gridPos);
    VdbScanner grid(in, blockPos);
    std::uint32_t compression = 0;
    std::string map;
    if ((version >= 222 && !grid.Read(compression)) || !grid.Metadata())
    {
      return corrupt + "the metadata of grid " + std::to_string(g) + " runs past its data";
    }
    // OpenVDB's Transform::read reads the map's type name whatever the version.
    if (!grid.String(&map) || map.size() > 64)
    {
      return corrupt + "grid " + std::to_string(g) + " has no valid transform";
    }
    if (!hasOffsets)
    {
      break;
    }
    in.seekg(endPos);
  }
  return "";
}

std::string ShortMessage(const char* what)
{
  std::string out;
  for (const char* c = what; c && *c && out.size() < 200; ++c)
  {
    const bool printable = *c >= 0x20 && *c < 0x7f;
    const char ch = printable ? *c : ' ';
    if (ch == ' ' && (out.empty() || out.back() == ' '))
    {
      continue;
    }
    out += ch;
  }
  if (what && std::strlen(what) > out.size() && out.size() >= 200)
  {
    out += "...";
  }
  return out;
}

} // namespace brume
