// SPDX-License-Identifier: BSD-3-Clause
// Heterogeneous media from OpenVDB grids the test writes itself.
#include "brume/LightTracer.h"
#include "brume/NativeMediumGrid.h"
#include "brume/TransferFunction.h"
#include "brume/VdbDensity.h"

#include "BrumeVdbWriter.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <thread>
#include <vector>

using namespace brume;

namespace
{
std::string WriteSlabGrid(const std::string& name, float value, float voxel)
{
  // 40 x 10 x 40 active voxels of `value`, indices y in [0, 9].
  vdbwriter::Grid grid;
  grid.VoxelSize = voxel;
  grid.Lower = { -20, 0, -20 };
  grid.Upper = { 19, 9, 19 };
  grid.Value = [value](int, int, int) { return value; };
  const std::string path = (std::filesystem::temp_directory_path() / name).string();
  vdbwriter::Write(path, { grid });
  return path;
}

// Varied values on both sides of the origin (0.2 to 0.8) in 0.1 voxels,
// over a background of 0.25.
vdbwriter::Grid VariedGrid()
{
  vdbwriter::Grid grid;
  grid.Background = 0.25f;
  grid.VoxelSize = 0.1;
  grid.Lower = { -13, -5, -9 };
  grid.Upper = { 10, 8, 11 };
  grid.Value = [](int i, int j, int k)
  {
    return 0.5f +
      0.3f *
      std::sin(0.7f * static_cast<float>(i) + 1.3f * static_cast<float>(j) - static_cast<float>(k));
  };
  return grid;
}

// VariedGrid() written to the temporary file `name` and loaded as scalars
// a transfer function classifies.
std::shared_ptr<VdbDensity> VariedScalars(const std::string& name)
{
  const std::string path = (std::filesystem::temp_directory_path() / name).string();
  vdbwriter::Write(path, { VariedGrid() });
  std::string error;
  auto scalars = VdbDensity::LoadScalars(path, "", error);
  EXPECT_TRUE(scalars) << error;
  return scalars;
}
}

TEST(VdbDensity, LoadsTheGridSparselyWithItsTransform)
{
  const std::string path = WriteSlabGrid("brume-test-slab.vdb", 1.5f, 0.1f);
  std::string error;
  auto density = VdbDensity::Load(path, "", error);
  ASSERT_TRUE(density) << error;
  EXPECT_EQ(density->GetNumberOfActiveVoxels(), 40u * 10u * 40u);
  // Voxel centres at j * 0.1, widened by one voxel for the interpolation.
  EXPECT_NEAR(density->GetBounds().lower.y, -0.1f, 1e-6f);
  EXPECT_NEAR(density->GetBounds().upper.y, 1.0f, 1e-6f);
  EXPECT_NEAR(density->Evaluate({ 0.f, 0.45f, 0.f }), 1.5f, 1e-6f);
  EXPECT_NEAR(density->Evaluate({ 0.f, -0.05f, 0.f }), 0.75f, 1e-6f);
  EXPECT_EQ(density->GetMajorants().GlobalMax(), 1.5f);
  // The active voxels among the native cells (the active box and one voxel
  // around it: 42 x 12 x 42), and their mean.
  EXPECT_NEAR(density->OccupiedFraction(), 16000.0 / (42.0 * 12.0 * 42.0), 1e-12);
  EXPECT_DOUBLE_EQ(density->MeanOccupiedDensity(), 1.5);
  EXPECT_EQ(VdbDensity::Load(path, "temperature", error), nullptr);
  EXPECT_NE(
    error.find("no float grid named 'temperature' (its float grids: 'density')"), std::string::npos)
    << error;
}

TEST(VdbDensity, StreamsWithoutOffsetsLoadAndTheirFaultsAreFound)
{
  // A grid written by openvdb::io::Stream (no grid offsets: its
  // descriptor's offsets are zeros, and the grid follows them).
  vdbwriter::Grid grid;
  grid.VoxelSize = 0.1;
  grid.Lower = { -20, 0, -20 };
  grid.Upper = { 19, 9, 19 };
  grid.Value = [](int, int j, int) { return 0.5f + 0.1f * j; };
  const std::string file = "brume-test-file.vdb", stream = "brume-test-stream.vdb";
  vdbwriter::Write(file, { grid });
  vdbwriter::Write(stream, { grid }, true);
  std::string error;
  EXPECT_EQ(CheckVdbFile(stream), "");
  auto fromFile = VdbDensity::Load(file, "", error);
  auto fromStream = VdbDensity::Load(stream, "", error);
  ASSERT_TRUE(fromFile && fromStream) << error;
  EXPECT_EQ(fromStream->GetNumberOfActiveVoxels(), 40u * 10u * 40u);
  for (float y : { 0.05f, 0.33f, 0.71f })
  {
    EXPECT_EQ(fromStream->Evaluate({ 0.12f, y, -0.4f }), fromFile->Evaluate({ 0.12f, y, -0.4f }));
  }
  // A fuzzer's find (128 bytes): a stream whose descriptor's offsets were
  // taken for the grid, so that the transform's name was read from bytes
  // announcing 3.3 GB. OpenVDB built a 12 GB message in 41 s.
  const unsigned char found[] = { 0x20, 0x42, 0x44, 0x56, 0, 0, 0, 0, 0xe0, 0, 0, 0, 0x0a, 0, 0, 0,
    0, 0x0a, 0x3a, 0, 0 };
  std::string bytes(reinterpret_cast<const char*>(found), sizeof(found));
  bytes += "ccf2766d-07ca-490b-8f8e-fd73023ca69d";
  const unsigned char tail[] = { 0, 0, 0, 0, 1, 0, 0, 0, 7, 0, 0, 0, 'd', 'e', 'n', 's', 'i', 't',
    'y', 0x10, 0, 0, 0 };
  bytes.append(reinterpret_cast<const char*>(tail), sizeof(tail));
  bytes += "Tree_float_5_4_3";
  const unsigned char grids[] = { 0, 0, 0, 0, 0x7c, 0, 0x64, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0x11, 0x25,
    1, 0, 0, 0, 0, 0, 5, 0x2b, 1, 0, 0x3f, 0, 0, 0 };
  bytes.append(reinterpret_cast<const char*>(grids), sizeof(grids));
  ASSERT_EQ(bytes.size(), 128u);
  const std::string bad = "brume-test-found.vdb";
  std::ofstream(bad, std::ios::binary) << bytes;
  EXPECT_NE(CheckVdbFile(bad).find("the metadata of grid 0 runs past its data"), std::string::npos)
    << CheckVdbFile(bad);
  EXPECT_EQ(VdbDensity::Load(bad, "", error), nullptr);
  for (const auto& path : { file, stream, bad })
  {
    std::filesystem::remove(path);
  }
}

TEST(VdbDensity, AVoxelSizeBeyondSinglePrecisionIsRefusedNamingTheFile)
{
  vdbwriter::Grid grid;
  grid.VoxelSize = 1e300;
  grid.Lower = { 0, 0, 0 };
  grid.Upper = { 7, 7, 7 };
  grid.Value = [](int, int, int) { return 1.f; };
  const std::string path = "brume-test-1e300.vdb";
  vdbwriter::Write(path, { grid });
  std::string error;
  EXPECT_EQ(VdbDensity::Load(path, "", error), nullptr);
  EXPECT_NE(error.find("OpenVDB grid 'density' of '" + path +
              "': its active voxels span a box that single precision cannot hold (voxel size "
              "1e+300"),
    std::string::npos)
    << error;
  grid.VoxelSize = 1e30; // 8e30 across: a float holds it
  vdbwriter::Write(path, { grid });
  EXPECT_TRUE(VdbDensity::Load(path, "", error)) << error;
  std::filesystem::remove(path);
}

TEST(VdbDensity, SamplesAreOpenVdbsTrilinearSamplesBitwise)
{
  // Varied values in leaves on both sides of the origin, an active tile
  // where a leaf would be (no leaf: read from the tree) and a background
  // above 0 around them.
  vdbwriter::Grid grid = VariedGrid();
  grid.Tiles = { { 1, { 16, 0, 0 }, 2.f } };
  const std::string path =
    (std::filesystem::temp_directory_path() / "brume-test-varied.vdb").string();
  vdbwriter::Write(path, { grid });
  std::string error;
  auto density = VdbDensity::Load(path, "", error);
  ASSERT_TRUE(density) << error;
  std::mt19937 random(7);
  std::uniform_real_distribution<float> x(-1.6f, 3.4f), y(-0.8f, 1.2f), z(-1.2f, 1.5f);
  std::vector<Vec3> points;
  std::vector<std::array<double, 3>> indices;
  for (int n = 0; n < 20000; ++n)
  {
    const Vec3 p(x(random), y(random), z(random));
    points.push_back(p);
    indices.push_back({ p.x / 0.1, p.y / 0.1, p.z / 0.1 });
  }
  // OpenVDB's own samples of the grid as written.
  const std::vector<float> expected = vdbwriter::Sample(path, "density", indices);
  int differing = 0;
  for (std::size_t n = 0; n < points.size(); ++n)
  {
    differing += density->Evaluate(points[n]) == expected[n] ? 0 : 1;
  }
  EXPECT_EQ(differing, 0);
}

TEST(VdbDensity, BeerLambertThroughAVdbSlab)
{
  // Vertical optical depth: value * (10 voxels) * 0.1 m = 1.5 (the trilinear
  // ramps at both faces integrate to exactly one voxel in all).
  const std::string path = WriteSlabGrid("brume-test-slab2.vdb", 1.5f, 0.1f);
  std::string error;
  Medium smoke;
  smoke.Name = "smoke";
  smoke.SigmaA = Vec3(1.f);
  smoke.SigmaS = Vec3(0.f);
  smoke.SetDensity(VdbDensity::Load(path, "density", error));
  ASSERT_TRUE(smoke.Density) << error;
  Scene scene;
  scene.Media = { smoke };
  Light beam;
  beam.Type = LightType::Directional;
  beam.Direction = Vec3(0.f, -1.f, 0.f);
  beam.BeamCenter = Vec3(0.013f, 3.f, -0.021f);
  beam.BeamRadius = 0.5f;
  scene.Lights = { beam };
  ASSERT_EQ(scene.Validate(), "");
  const RayCaster caster(scene);
  const LightTracer tracer(scene, caster, TraceSettings());
  const std::uint64_t n = 100000;
  std::vector<Hit> hits;
  TraceCounters counters;
  double through = 0;
  for (std::uint64_t i = 0; i < n; ++i)
  {
    ParticleExit exit;
    tracer.TraceParticle(i, n, hits, counters, &exit);
    through += (exit.Escaped && exit.Depth == 0) ? 1.0 : 0.0;
  }
  const double f = through / n, se = std::sqrt(f * (1 - f) / n);
  EXPECT_NEAR(f, std::exp(-1.5), 4 * se);
}

TEST(VdbDensity, SharedSampleVolumesLoadWhenPresent)
{
  const std::filesystem::path dir =
    std::filesystem::path(BRUME_SOURCE_DIR) / ".." / "shared" / "data" / "vdb";
  if (!std::filesystem::exists(dir / "smoke.vdb"))
  {
    GTEST_SKIP() << "no ../shared/data/vdb here";
  }
  for (const char* name : { "smoke.vdb", "box.vdb", "dragon.vdb", "wdas_cloud_sixteenth.vdb" })
  {
    std::string error;
    auto density = VdbDensity::Load((dir / name).string(), "", error);
    ASSERT_TRUE(density) << name << ": " << error;
    EXPECT_GT(density->GetNumberOfActiveVoxels(), 0u) << name;
    EXPECT_GT(density->GetMajorants().GlobalMax(), 0.f) << name;
    // Sparse media have empty blocks the tracker skips.
    EXPECT_LE(density->NumberOfOccupiedBlocks(), density->GetMajorants().Max.size()) << name;
  }
}

TEST(VdbDensity, NativePointsAreTheVoxelsAtTheNativeCellsCentres)
{
  // A classified grid's means interpolate these themselves
  // (ClassifiedDensity::NativeBrick): each must be the field at its cell's
  // centre, and the field between them their trilinear interpolation.
  const std::shared_ptr<VdbDensity> density = VariedScalars("brume-test-native-points.vdb");
  ASSERT_TRUE(density);
  const std::array<int, 3> dims = density->NativeResolution();
  // The active box and one voxel around it.
  EXPECT_EQ(dims, (std::array<int, 3>{ 26, 16, 23 }));
  const Box box = density->NativeBox();
  const std::array<int, 3> lower{ 0, 3, 19 }, count{ 26, 5, 4 }; // the ends included
  std::vector<float> points(static_cast<std::size_t>(count[0]) * count[1] * count[2]);
  ASSERT_TRUE(density->NativePoints(lower, count, points.data()));
  const Vec3 cell = box.Extent() /
    Vec3(static_cast<float>(dims[0]), static_cast<float>(dims[1]), static_cast<float>(dims[2]));
  int differing = 0;
  std::size_t n = 0;
  for (int k = lower[2]; k < lower[2] + count[2]; ++k)
    for (int j = lower[1]; j < lower[1] + count[1]; ++j)
      for (int i = lower[0]; i < lower[0] + count[0]; ++i)
      {
        const Vec3 centre = box.lower +
          (Vec3(static_cast<float>(i), static_cast<float>(j), static_cast<float>(k)) + Vec3(0.5f)) *
            cell;
        // A native cell's value is its voxel itself, not the sampler's
        // rounding of it (what a plain density's native grid holds).
        differing += density->NativeValue(i, j, k, centre) == points[n] ? 0 : 1;
        differing += std::abs(density->Evaluate(centre) - points[n++]) <= 1e-5f ? 0 : 1;
      }
  EXPECT_EQ(differing, 0);
}

TEST(VdbDensity, AClassifiedGridsCellsAreTheirVoxelsOrTheirMeans)
{
  // The native grid of an OpenVDB field classified by a function whose
  // points lie inside its values (0.2 to 0.8): a cell whose 27 voxels span
  // one of the points holds the mean of 4^3 samples of the classified
  // field (OpenVDB's trilinear sampler, classified after), any other the
  // function at its voxel.
  const std::shared_ptr<const DensityField> scalars = VariedScalars("brume-test-classified.vdb");
  ASSERT_TRUE(scalars);
  const auto classified = std::make_shared<ClassifiedDensity>(
    scalars, OpacityTransferFunction({ { 0.3f, 0.f }, { 0.45f, 0.6f }, { 0.7f, 0.2f } }, 0.05f));
  Medium medium;
  medium.Name = "classified";
  medium.Bounds = classified->GetBounds();
  medium.SigmaS = Vec3(1.f);
  medium.Density = classified;
  NativeMediumGrid native;
  native.Sample(medium, std::size_t(1) << 30, SerialFor());
  ASSERT_EQ(native.GetCoarsening(), 1);
  const std::array<int, 3> dims = scalars->NativeResolution();
  ASSERT_EQ(native.GetResolution(), dims);
  const Box box = scalars->NativeBox();
  const Vec3 cell = box.Extent() /
    Vec3(static_cast<float>(dims[0]), static_cast<float>(dims[1]), static_cast<float>(dims[2]));
  int bending = 0, differing = 0;
  for (int k = 0; k < dims[2]; ++k)
    for (int j = 0; j < dims[1]; ++j)
      for (int i = 0; i < dims[0]; ++i)
      {
        const Vec3 lower = box.lower +
          Vec3(static_cast<float>(i), static_cast<float>(j), static_cast<float>(k)) * cell;
        const Box own{ lower, lower + cell };
        std::array<int, 3> first{}, count{};
        const int at[3] = { i, j, k };
        for (int a = 0; a < 3; ++a)
        {
          first[a] = std::max(at[a] - 1, 0);
          count[a] = std::min(at[a] + 1, dims[a] - 1) - first[a] + 1;
        }
        float points[27];
        ASSERT_TRUE(scalars->NativePoints(first, count, points));
        const int n = count[0] * count[1] * count[2];
        const float lo = *std::min_element(points, points + n);
        const float hi = *std::max_element(points, points + n);
        bool bends = false;
        for (const float point : { 0.3f, 0.45f, 0.7f })
        {
          bends = bends || (lo < point && point < hi);
        }
        bending += bends ? 1 : 0;
        const double expected = bends
          ? classified->NativeMean(i, j, k, own, medium.Bounds, NativeMediumGrid::BendSamples)
          : classified->GetOpacity().Extinction(
              points[((at[2] - first[2]) * count[1] + at[1] - first[1]) * count[0] + at[0] -
                first[0]]);
        const double got = native.GetDensity().At(i, j, k);
        differing += std::abs(got - expected) <= 1e-4 * std::max(1.0, expected) ? 0 : 1;
      }
  EXPECT_GT(bending, 1000);
  EXPECT_EQ(differing, 0);

  // An edit of the function where no voxel lies (its voxels span 0.2 to
  // 0.8, its background is 0.25): every brick is kept from its voxels'
  // range, and the grid is bitwise the one sampled afresh.
  auto withFunction = [&](float last)
  {
    Medium m = medium;
    m.Density = std::make_shared<ClassifiedDensity>(scalars,
      OpacityTransferFunction({ { 0.1f, 0.f }, { 0.3f, 0.f }, { 0.45f, 0.6f }, { 0.7f, 0.2f },
                                { 0.85f, 0.2f }, { 0.95f, last } },
        0.05f));
    return m;
  };
  NativeMediumGrid before, fresh, kept;
  before.Sample(withFunction(0.9f), std::size_t(1) << 30, SerialFor());
  const Medium edited = withFunction(0.4f);
  fresh.Sample(edited, std::size_t(1) << 30, SerialFor());
  kept.Sample(edited, std::size_t(1) << 30, SerialFor(), &before);
  EXPECT_GT(kept.GetReusedBricks(), 0u);
  EXPECT_EQ(kept.GetSampledBricks(), 0u);
  int unequal = 0;
  for (int k = 0; k < dims[2]; ++k)
    for (int j = 0; j < dims[1]; ++j)
      for (int i = 0; i < dims[0]; ++i)
      {
        unequal += fresh.GetDensity().At(i, j, k) == kept.GetDensity().At(i, j, k) &&
            fresh.GetScalars().At(i, j, k) == kept.GetScalars().At(i, j, k)
          ? 0
          : 1;
      }
  EXPECT_EQ(unequal, 0);
}

TEST(VdbDensity, MajorantsAndRangesAreFoundAlikeOnThreadsAndBoundTheSamples)
{
  // Leaves of varied values, an active tile and a background: the
  // majorants, the scalars' block ranges and the occupancy found leaf by
  // leaf on three threads are those found on one, and bound OpenVDB's
  // trilinear samples of every block.
  vdbwriter::Grid grid = VariedGrid();
  grid.Tiles = { { 1, { 16, 0, 0 }, 2.f } };
  const std::string path =
    (std::filesystem::temp_directory_path() / "brume-test-majorants.vdb").string();
  vdbwriter::Write(path, { grid });
  const ParallelFor threads = [](std::size_t begin, std::size_t end,
                                const std::function<void(std::size_t, std::size_t)>& body)
  {
    std::vector<std::thread> pool;
    for (int t = 0; t < 3; ++t)
    {
      const std::size_t b = begin + (end - begin) * t / 3, e = begin + (end - begin) * (t + 1) / 3;
      pool.emplace_back([&body, b, e]() { body(b, e); });
    }
    for (auto& thread : pool)
    {
      thread.join();
    }
  };
  std::mt19937 random(11);
  std::uniform_real_distribution<float> x(-1.6f, 3.4f), y(-0.8f, 1.2f), z(-1.2f, 1.5f);
  for (const bool scalars : { false, true })
  {
    std::string error;
    const auto serial =
      scalars ? VdbDensity::LoadScalars(path, "", error) : VdbDensity::Load(path, "", error);
    ASSERT_TRUE(serial) << error;
    const auto threaded = scalars ? VdbDensity::LoadScalars(path, "", error, threads)
                                  : VdbDensity::Load(path, "", error, threads);
    ASSERT_TRUE(threaded) << error;
    const MajorantGrid& majorants = serial->GetMajorants();
    EXPECT_EQ(majorants.Max, threaded->GetMajorants().Max);
    EXPECT_EQ(serial->OccupiedFraction(), threaded->OccupiedFraction());
    EXPECT_EQ(serial->MeanOccupiedDensity(), threaded->MeanOccupiedDensity());
    std::vector<float> lo, hi, threadedLo, threadedHi;
    EXPECT_EQ(serial->ValueRanges(lo, hi), scalars);
    EXPECT_EQ(threaded->ValueRanges(threadedLo, threadedHi), scalars);
    EXPECT_EQ(lo, threadedLo);
    EXPECT_EQ(hi, threadedHi);
    EXPECT_EQ(*std::max_element(majorants.Max.begin(), majorants.Max.end()), 2.f); // the tile
    const Vec3 block = majorants.Bounds.Extent() /
      Vec3(static_cast<float>(majorants.Dims[0]), static_cast<float>(majorants.Dims[1]),
        static_cast<float>(majorants.Dims[2]));
    int outside = 0;
    for (int n = 0; n < 20000; ++n)
    {
      const Vec3 p(x(random), y(random), z(random));
      const Vec3 q = (p - majorants.Bounds.lower) / block;
      int b[3];
      for (int a = 0; a < 3; ++a)
      {
        b[a] = std::clamp(static_cast<int>(std::floor(q[a])), 0, majorants.Dims[a] - 1);
      }
      if (!serial->GetBounds().Contains(p))
      {
        continue;
      }
      const float v = serial->Evaluate(p);
      const std::size_t at =
        (static_cast<std::size_t>(b[2]) * majorants.Dims[1] + b[1]) * majorants.Dims[0] + b[0];
      outside += v <= majorants.Max[at] ? 0 : 1;
      if (scalars)
      {
        outside += lo[at] <= v && v <= hi[at] ? 0 : 1;
      }
    }
    EXPECT_EQ(outside, 0) << (scalars ? "scalars" : "densities");
  }
  std::filesystem::remove(path);
}
