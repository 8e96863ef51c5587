// SPDX-License-Identifier: BSD-3-Clause
// A medium's texture kept only where a renderer reads it: every cell that
// trilinear interpolation mixes in where the density is not 0 is stored,
// bricks far from the density are dropped, and the bricks hold the cells'
// values in their documented order.
#include "brume/BrickedGrid.h"
#include "brume/SparseTexture.h"
#include "brume/Vec3.h"

#include "TestScenes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace brume;

namespace
{
const auto Never = [](const std::array<int, 3>&, const std::array<int, 3>&) { return false; };

// A density over `box` (dims cells), not 0 only inside a ball.
BrickedGrid Ball(const std::array<int, 3>& dims, const Box& box, const Vec3& centre, float radius)
{
  const Vec3 cell = box.Extent() / Vec3(dims[0], dims[1], dims[2]);
  auto value = [&](int i, int j, int k)
  {
    const Vec3 p = box.lower + Vec3(i + 0.5f, j + 0.5f, k + 0.5f) * cell;
    return Length(p - centre) < radius ? 1.f : 0.f;
  };
  return BrickedGrid::Sample(dims, box, value, Never, SerialFor());
}

// Whether cell (i, j, k) of the texture is stored.
bool Stored(const SparseTexture& t, int i, int j, int k)
{
  const auto& d = t.GetDims();
  const auto& b = t.GetBrickDims();
  const int ex = SparseTexture::BrickEdge(d[0]), ey = SparseTexture::BrickEdge(d[1]),
            ez = SparseTexture::BrickEdge(d[2]);
  return t.GetSlots()[(static_cast<std::size_t>(k / ez) * b[1] + j / ey) * b[0] + i / ex] >= 0;
}
}

TEST(SparseTexture, StoresEveryCellInterpolatedWhereTheDensityIsNotZero)
{
  // The density's grid over a larger box than the texture's; textures
  // coarser than, as fine as and finer than the density.
  const Box densityBox{ Vec3(-1.f, -1.f, -1.f), Vec3(3.f, 1.f, 1.f) };
  const Box textureBox{ Vec3(-0.9f, -0.95f, -0.9f), Vec3(2.9f, 0.95f, 0.9f) };
  const BrickedGrid density = Ball({ 40, 20, 20 }, densityBox, Vec3(0.2f, 0.1f, 0.f), 0.45f);
  for (const std::array<int, 3>& dims :
    { std::array<int, 3>{ 19, 9, 9 }, std::array<int, 3>{ 38, 19, 18 },
      std::array<int, 3>{ 77, 37, 36 }, std::array<int, 3>{ 50, 5, 3 } })
  {
    const SparseTexture t = SparseTexture::WhereDensity(dims, textureBox, density);
    ASSERT_EQ(t.GetDims(), dims);
    int checked = 0;
    for (int n = 0; n < 200000; ++n)
    {
      // Points on a scrambled lattice over the texture's box.
      const float u = std::fmod(0.5f + n * 0.7548776662f, 1.f);
      const float v = std::fmod(0.5f + n * 0.5698402910f, 1.f);
      const float w = std::fmod(0.5f + n * 0.3819660113f, 1.f);
      const Vec3 q(u, v, w);
      const Vec3 p = textureBox.lower + q * textureBox.Extent();
      if (!(density.Interpolate(p) > 0.f))
      {
        continue;
      }
      ++checked;
      const CellCentreWeights x(q.x, dims[0]), y(q.y, dims[1]), z(q.z, dims[2]);
      for (int i : { x.I0, x.I1 })
        for (int j : { y.I0, y.I1 })
          for (int k : { z.I0, z.I1 })
          {
            ASSERT_TRUE(Stored(t, i, j, k))
              << "dims " << dims[0] << " " << dims[1] << " " << dims[2] << ": cell " << i << " "
              << j << " " << k << " is read at " << p.x << " " << p.y << " " << p.z;
          }
    }
    EXPECT_GT(checked, 1000);
    // The ball fills a small part of the long box: bricks are dropped.
    EXPECT_LT(t.NumberOfStoredBricks(), t.GetSlots().size()) << dims[0];
  }
}

TEST(SparseTexture, DropsBricksFarFromTheDensity)
{
  const Box box{ Vec3(0.f, 0.f, 0.f), Vec3(64.f, 16.f, 16.f) };
  // A ball near x = 8: a texture of 1 m cells keeps the bricks within a
  // few cells of it, not the far end.
  const BrickedGrid density = Ball({ 64, 16, 16 }, box, Vec3(8.f, 8.f, 8.f), 4.f);
  const SparseTexture t = SparseTexture::WhereDensity({ 64, 16, 16 }, box, density);
  EXPECT_EQ(t.GetBrickDims(), (std::array<int, 3>{ 8, 2, 2 }));
  EXPECT_TRUE(Stored(t, 8, 8, 8));
  EXPECT_FALSE(Stored(t, 40, 8, 8));
  EXPECT_FALSE(Stored(t, 63, 15, 15));
  // x: bricks 0 and 1 (cells up to 15; the ball reaches 12.5, one density
  // cell and one and a half texture cells more is 15), y and z all.
  EXPECT_EQ(t.NumberOfStoredBricks(), 8u);

  // No density anywhere: nothing stored.
  const BrickedGrid empty = Ball({ 64, 16, 16 }, box, Vec3(-100.f, 0.f, 0.f), 1.f);
  EXPECT_EQ(SparseTexture::WhereDensity({ 64, 16, 16 }, box, empty).NumberOfStoredBricks(), 0u);
}

TEST(SparseTexture, CellsReadAreTheSameWhateverTheThreads)
{
  // Bricks along z that reach the same texture planes (coarser texture),
  // one each (as fine) and planes of their own (finer); the layers taken
  // in reverse on four threads, one to seven layers a piece.
  const Box densityBox{ Vec3(-1.f, -1.f, -1.f), Vec3(3.f, 1.f, 1.f) };
  const Box textureBox{ Vec3(-0.9f, -0.95f, -0.9f), Vec3(2.9f, 0.95f, 0.9f) };
  const BrickedGrid density = Ball({ 40, 20, 45 }, densityBox, Vec3(0.2f, 0.1f, 0.f), 0.7f);
  for (const std::array<int, 3>& dims :
    { std::array<int, 3>{ 19, 9, 9 }, std::array<int, 3>{ 38, 19, 43 },
      std::array<int, 3>{ 77, 37, 90 }, std::array<int, 3>{ 50, 5, 3 } })
  {
    const std::vector<std::uint8_t> serial =
      SparseTexture::CellsRead(dims, textureBox, density, SerialFor());
    ASSERT_EQ(serial.size(), static_cast<std::size_t>(dims[0]) * dims[1] * dims[2]);
    EXPECT_GT(std::count(serial.begin(), serial.end(), 1), 0);
    EXPECT_LT(std::count(serial.begin(), serial.end(), 1), static_cast<long>(serial.size()));
    for (std::size_t pieces : { 7, 3, 1 })
    {
      EXPECT_EQ(
        SparseTexture::CellsRead(dims, textureBox, density, brume::testing::ThreadedFor(4, pieces)),
        serial)
        << dims[0] << " " << dims[1] << " " << dims[2] << ", " << pieces << " pieces";
    }
    // The bricks of those cells, found before, are WhereDensity()'s.
    const SparseTexture kept = SparseTexture::FromCellsRead(dims, serial);
    const SparseTexture found = SparseTexture::WhereDensity(dims, textureBox, density);
    EXPECT_EQ(kept.GetSlots(), found.GetSlots());
    EXPECT_EQ(kept.NumberOfStoredBricks(), found.NumberOfStoredBricks());
    // Cells of another texture: none read, none stored.
    EXPECT_EQ(SparseTexture::FromCellsRead({ dims[0] + 1, dims[1], dims[2] }, serial)
                .NumberOfStoredBricks(),
      0u);
  }
}

TEST(SparseTexture, GathersCellsBrickByBrick)
{
  // An axis of fewer cells than a brick's side: bricks are that thin there.
  const std::array<int, 3> dims{ 13, 3, 9 };
  const Box box{ Vec3(0.f, 0.f, 0.f), Vec3(13.f, 3.f, 9.f) };
  const BrickedGrid density = Ball({ 13, 3, 9 }, box, Vec3(2.f, 1.5f, 2.f), 1.f);
  const SparseTexture t = SparseTexture::WhereDensity(dims, box, density);
  ASSERT_EQ(t.GetBrickCells(), 8u * 3u * 8u);
  std::vector<float> values(2 * static_cast<std::size_t>(13 * 3 * 9));
  for (std::size_t v = 0; v < values.size(); ++v)
  {
    values[v] = static_cast<float>(v + 1);
  }
  const std::vector<float> bricks = t.Gather(values, 2);
  ASSERT_EQ(bricks.size(), t.NumberOfStoredBricks() * t.GetBrickCells() * 2);
  std::size_t nonZero = 0;
  for (int k = 0; k < dims[2]; ++k)
    for (int j = 0; j < dims[1]; ++j)
      for (int i = 0; i < dims[0]; ++i)
      {
        const std::size_t b = (static_cast<std::size_t>(k / 8) * 1 + j / 3) * 2 + i / 8;
        const int slot = t.GetSlots()[b];
        if (slot < 0)
        {
          continue;
        }
        const std::size_t at =
          slot * t.GetBrickCells() + (static_cast<std::size_t>(k % 8) * 3 + j % 3) * 8 + i % 8;
        const std::size_t cell = (static_cast<std::size_t>(k) * 3 + j) * 13 + i;
        EXPECT_EQ(bricks[2 * at], values[2 * cell]);
        EXPECT_EQ(bricks[2 * at + 1], values[2 * cell + 1]);
        nonZero += 2;
      }
  // Everything else is padding, 0.
  std::size_t zeros = 0;
  for (float b : bricks)
  {
    zeros += b == 0.f ? 1 : 0;
  }
  EXPECT_EQ(zeros + nonZero, bricks.size());
  EXPECT_GT(t.NumberOfStoredBricks(), 0u);
  EXPECT_LT(t.NumberOfStoredBricks(), t.GetSlots().size());
}
