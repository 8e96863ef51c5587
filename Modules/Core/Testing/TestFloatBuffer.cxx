// SPDX-License-Identifier: BSD-3-Clause
// Grid memory held once: shared float buffers, and a grid's values in the
// type its array holds them.
#include "brume/Density.h"
#include "brume/FloatBuffer.h"
#include "brume/Random.h"
#include "brume/TransferFunction.h"
#include "brume/Vec3.h"

#include "TestScenes.h"

#include <gtest/gtest.h>

#if defined(__linux__)
#include <sys/resource.h>
#endif

#include <algorithm>
#include <cstdint>
#include <limits>
#include <memory>
#include <numeric>
#include <vector>

using namespace brume;

TEST(FloatBuffer, LargeBuffersAreSharedAndCut)
{
  // 4 MB: mapped on its own (but under AddressSanitizer). Cutting keeps the
  // first floats.
  const std::size_t n = std::size_t(1) << 20;
  FloatBuffer buffer = FloatBuffer::Allocate(n);
  ASSERT_EQ(buffer.Size(), n);
  std::iota(buffer.Data(), buffer.Data() + n, 0.f);
  buffer.Truncate(n / 3);
  ASSERT_EQ(buffer.Size(), n / 3);
  EXPECT_EQ(buffer[n / 3 - 1], static_cast<float>(n / 3 - 1));

  // A share outlives the buffer it came from.
  std::shared_ptr<float> share = buffer.Share();
  buffer = FloatBuffer();
  EXPECT_EQ(share.get()[12345], 12345.f);
}

#if defined(__linux__)
namespace
{
long MinorFaults()
{
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_minflt;
}

// Writes every float of the buffer (its index), and checks them; the
// minor page faults that took.
long FillAndCheck(FloatBuffer& buffer)
{
  const long before = MinorFaults();
  std::iota(buffer.Data(), buffer.Data() + buffer.Size(), 0.f);
  const long faults = MinorFaults() - before;
  for (std::size_t i = 0; i < buffer.Size(); i += 4099)
  {
    EXPECT_EQ(buffer[i], static_cast<float>(i));
  }
  return faults;
}

bool UnderAddressSanitizer()
{
#if defined(__SANITIZE_ADDRESS__)
  return true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
  return true;
#endif
#endif
  return false;
}
}

TEST(FloatBuffer, ALargeBufferReleasedServesTheNextOfItsSize)
{
  // A grid sampled again after an edit: its buffer takes the pages of the
  // grid before it, already faulted in, not fresh ones; until the kept
  // pages are given back (FloatBuffer::ReleaseKept()).
  if (UnderAddressSanitizer())
  {
    GTEST_SKIP() << "every buffer comes from operator new under AddressSanitizer";
  }
  const std::size_t n = std::size_t(16) << 20; // 64 MB
  long fresh = 0;
  {
    FloatBuffer first = FloatBuffer::Allocate(n);
    fresh = FillAndCheck(first);
  }
  long reused = 0;
  {
    FloatBuffer second = FloatBuffer::Allocate(n);
    reused = FillAndCheck(second);
  }
  EXPECT_GT(fresh, 0);
  EXPECT_LT(reused, fresh / 4 + 1) << "fresh pages faulted " << fresh << " times";
  // A program that draws its last image gives the kept pages back: they
  // are unmapped (counted), and the next buffer faults in fresh pages.
  EXPECT_GE(FloatBuffer::ReleaseKept(), n * sizeof(float));
  EXPECT_EQ(FloatBuffer::ReleaseKept(), 0u);
  FloatBuffer third = FloatBuffer::Allocate(n);
  EXPECT_GT(FillAndCheck(third), fresh / 2) << "fresh pages faulted " << fresh << " times";
}

TEST(FloatBuffer, BuffersReleasedTogetherServeTheNextTogether)
{
  // A grid's scalars and extinction released together (a new time step, a
  // volume read again) and made again one after the other: both take kept
  // pages.
  if (UnderAddressSanitizer())
  {
    GTEST_SKIP() << "every buffer comes from operator new under AddressSanitizer";
  }
  const std::size_t n = std::size_t(8) << 20; // 32 MB each
  long fresh = 0;
  {
    FloatBuffer a = FloatBuffer::Allocate(n), b = FloatBuffer::Allocate(n);
    fresh = FillAndCheck(a) + FillAndCheck(b);
  }
  FloatBuffer c = FloatBuffer::Allocate(n);
  FloatBuffer d = FloatBuffer::Allocate(n);
  const long reused = FillAndCheck(c) + FillAndCheck(d);
  EXPECT_GT(fresh, 0);
  EXPECT_LT(reused, fresh / 4 + 1) << "fresh pages faulted " << fresh << " times";
}

TEST(FloatBuffer, ReleasedMappingsGrowShrinkOrGo)
{
  // A kept mapping serves a buffer up to twice its size (grown) or cut to
  // a smaller one; a buffer under half its size maps its own. Every float
  // of each holds what was written.
  const std::size_t n = std::size_t(4) << 20;
  for (const std::size_t next : { n + n / 2, n / 3, n / 5, n })
  {
    {
      FloatBuffer before = FloatBuffer::Allocate(n);
      FillAndCheck(before);
    }
    FloatBuffer buffer = FloatBuffer::Allocate(next);
    ASSERT_EQ(buffer.Size(), next);
    FillAndCheck(buffer);
    buffer.Truncate(next / 2);
    EXPECT_EQ(buffer[next / 2 - 1], static_cast<float>(next / 2 - 1));
  }
}
#endif

TEST(FloatBuffer, SmallBuffersAreCopiedWhenCut)
{
  FloatBuffer small = FloatBuffer::Allocate(100);
  std::iota(small.Data(), small.Data() + 100, 1.f);
  small.Truncate(10);
  ASSERT_EQ(small.Size(), 10u);
  EXPECT_EQ(small[9], 10.f);
  FloatBuffer other = FloatBuffer::Allocate(10);
  std::iota(other.Data(), other.Data() + 10, 1.f);
  EXPECT_EQ(small, other);
  other.Data()[3] = 0.f;
  EXPECT_NE(small, other);
}

TEST(FloatBuffer, WrappedMemoryIsReadInPlace)
{
  auto owner = std::make_shared<std::vector<float>>(std::vector<float>{ 1.f, 2.f, 3.f });
  const FloatBuffer wrapped = FloatBuffer::Wrap(owner->data(), owner->size(), owner);
  std::weak_ptr<std::vector<float>> watch = owner;
  owner.reset();
  EXPECT_FALSE(watch.expired()); // the buffer holds its owner
  EXPECT_EQ(wrapped[2], 3.f);
}

namespace
{
// A 9 x 7 x 5 point grid over the unit cube whose values are integers in
// 0..255, as 8-bit integers (read in place) and as floats.
struct TwoGrids
{
  std::vector<std::uint8_t> Bytes;
  std::shared_ptr<const GridDensity> Typed;
  std::shared_ptr<const GridDensity> Floats;
};
TwoGrids Grids(bool cellValues)
{
  TwoGrids g;
  const std::array<int, 3> dims{ 9, 7, 5 };
  const std::size_t n = 9 * 7 * 5;
  Random rng(7, 0);
  g.Bytes.resize(n);
  std::vector<float> floats(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    g.Bytes[i] = static_cast<std::uint8_t>(rng.NextFloat() * 256.f);
    floats[i] = static_cast<float>(g.Bytes[i]);
  }
  const Box box{ Vec3(0.f), Vec3(1.f) };
  g.Typed = std::make_shared<const GridDensity>(
    box, dims, TypedValues::Wrap(g.Bytes.data(), n, nullptr), cellValues);
  g.Floats = std::make_shared<const GridDensity>(box, dims, floats, cellValues);
  return g;
}
}

TEST(TypedValues, EachTypeReadsItsNumbers)
{
  const std::uint8_t bytes[] = { 0, 7, 255 };
  const std::uint16_t shorts[] = { 0, 300, 65535 };
  const std::int16_t signedShorts[] = { -32768, -1, 32767 };
  const TypedValues b = TypedValues::Wrap(bytes, 3, nullptr);
  const TypedValues u = TypedValues::Wrap(shorts, 3, nullptr);
  const TypedValues s = TypedValues::Wrap(signedShorts, 3, nullptr);
  EXPECT_EQ(b.GetType(), TypedValues::Type::UInt8);
  EXPECT_EQ(b[2], 255.f);
  EXPECT_EQ(u[1], 300.f);
  EXPECT_EQ(u[2], 65535.f);
  EXPECT_EQ(s[0], -32768.f);
  EXPECT_EQ(s[2], 32767.f);
  // A scan's bytes take one byte a value, 16-bit values two, floats four.
  EXPECT_EQ(b.GetMemorySize(), 3u);
  EXPECT_EQ(u.GetMemorySize(), 6u);
  EXPECT_EQ(TypedValues(FloatBuffer::Allocate(3)).GetMemorySize(), 12u);
  EXPECT_EQ(b.Address(), static_cast<const void*>(bytes));
}

TEST(TypedValues, AnEightBitGridIsTheGridOfItsFloats)
{
  for (const bool cells : { false, true })
  {
    const TwoGrids g = Grids(cells);
    EXPECT_EQ(g.Typed->GetValues().GetMemorySize(), g.Bytes.size());
    Random rng(11, 0);
    for (int t = 0; t < 2000; ++t)
    {
      const Vec3 p(rng.NextFloat(), rng.NextFloat(), rng.NextFloat());
      ASSERT_EQ(g.Typed->Evaluate(p), g.Floats->Evaluate(p)) << cells;
    }
    EXPECT_EQ(g.Typed->GetMajorants().Max, g.Floats->GetMajorants().Max);
    EXPECT_EQ(g.Typed->OccupiedFraction(), g.Floats->OccupiedFraction());
    EXPECT_EQ(g.Typed->MeanOccupiedDensity(), g.Floats->MeanOccupiedDensity());
    if (!cells)
    {
      const Box cell{ Vec3(0.25f), Vec3(0.375f) };
      EXPECT_EQ(g.Typed->NativeMean(3, 2, 1, cell, g.Typed->GetBounds(), 4),
        g.Floats->NativeMean(3, 2, 1, cell, g.Floats->GetBounds(), 4));
    }
    // Classified alike: the same extinction, the same bend checks.
    const OpacityTransferFunction opacity(
      { { 60.f, 0.f }, { 128.f, 0.5f }, { 250.f, 0.9f } }, 0.1f);
    const ClassifiedDensity typed(g.Typed, opacity), floats(g.Floats, opacity);
    for (int t = 0; t < 500; ++t)
    {
      const Vec3 p(rng.NextFloat(), rng.NextFloat(), rng.NextFloat());
      ASSERT_EQ(typed.Evaluate(p), floats.Evaluate(p));
      const Box around{ p - Vec3(0.05f), p + Vec3(0.05f) };
      ASSERT_EQ(typed.BendsWithin(around), floats.BendsWithin(around));
    }
    EXPECT_EQ(typed.GetMajorants().Max, floats.GetMajorants().Max);
    // The occupancy an edit's classification needs, from the counts per
    // integer (a lookup per integer): the bytes' over their type's range,
    // the floats' (whole numbers) over theirs, the same counts.
    const std::vector<std::uint64_t>& counts = g.Typed->GetValueCounts(SerialFor()).Counts;
    ASSERT_EQ(counts.size(), 256u);
    EXPECT_EQ(g.Typed->GetValueCounts(SerialFor()).Lowest, 0);
    EXPECT_EQ(std::accumulate(counts.begin(), counts.end(), std::uint64_t(0)), g.Bytes.size());
    const std::vector<std::uint64_t>& wholeCounts = g.Floats->GetValueCounts(SerialFor()).Counts;
    const int lowest = *std::min_element(g.Bytes.begin(), g.Bytes.end());
    const int highest = *std::max_element(g.Bytes.begin(), g.Bytes.end());
    ASSERT_EQ(g.Floats->GetValueCounts(SerialFor()).Lowest, lowest);
    ASSERT_EQ(wholeCounts.size(), static_cast<std::size_t>(highest - lowest + 1));
    for (std::size_t b = 0; b < wholeCounts.size(); ++b)
    {
      ASSERT_EQ(wholeCounts[b], counts[b + static_cast<std::size_t>(lowest)]) << b;
    }
    EXPECT_EQ(typed.OccupiedFraction(), floats.OccupiedFraction());
    EXPECT_EQ(typed.MeanOccupiedDensity(), floats.MeanOccupiedDensity());
    // Against the function at every value: the same count, and the same
    // sum added in another order.
    double occupied = 0.0, sum = 0.0;
    for (const std::uint8_t value : g.Bytes)
    {
      const float e = opacity.Extinction(static_cast<float>(value));
      occupied += e > 0.f ? 1.0 : 0.0;
      sum += e > 0.f ? e : 0.f;
    }
    EXPECT_EQ(typed.OccupiedFraction(), occupied / static_cast<double>(g.Bytes.size()));
    EXPECT_NEAR(typed.MeanOccupiedDensity(), sum / occupied, 1e-12 * sum / occupied);
    EXPECT_GT(typed.OccupiedFraction(), 0.3);
    EXPECT_LT(typed.OccupiedFraction(), 0.9);
  }
}

TEST(TypedValues, OnlyWholeFloatsAreCountedPerInteger)
{
  // Floats that are not all whole numbers within 16 bits' range (a
  // fraction, a NaN, a value past either end) are not counted per integer:
  // they are classified value by value, and both ways give the occupancy
  // of the function at every value.
  const std::array<int, 3> dims{ 5, 4, 3 };
  const Box box{ Vec3(0.f), Vec3(1.f) };
  std::vector<float> whole(60);
  for (std::size_t i = 0; i < whole.size(); ++i)
  {
    whole[i] = static_cast<float>(static_cast<int>(i * 37 % 61) - 20);
  }
  EXPECT_FALSE(GridDensity(box, dims, whole, false).GetValueCounts(SerialFor()).Counts.empty());
  EXPECT_EQ(GridDensity(box, dims, whole, false).GetValueCounts(SerialFor()).Lowest, -20);
  for (const float odd : { 0.5f, std::numeric_limits<float>::quiet_NaN(), 65536.f, -32769.f })
  {
    std::vector<float> values = whole;
    values[33] = odd;
    EXPECT_TRUE(GridDensity(box, dims, values, false).GetValueCounts(SerialFor()).Counts.empty())
      << odd;
  }
  // 0.5 in one value, the others whole: the per-value path's occupancy.
  std::vector<float> values = whole;
  values[7] = 10.5f;
  const OpacityTransferFunction opacity({ { -5.f, 0.f }, { 12.f, 0.6f }, { 40.f, 0.1f } }, 0.1f);
  const ClassifiedDensity counted(
    std::make_shared<const GridDensity>(box, dims, whole, false), opacity);
  const ClassifiedDensity each(
    std::make_shared<const GridDensity>(box, dims, values, false), opacity);
  auto occupiedShare = [&](const std::vector<float>& v)
  {
    double n = 0.0;
    for (const float x : v)
    {
      n += opacity.Extinction(x) > 0.f ? 1.0 : 0.0;
    }
    return n / static_cast<double>(v.size());
  };
  EXPECT_EQ(counted.OccupiedFraction(), occupiedShare(whole));
  EXPECT_EQ(each.OccupiedFraction(), occupiedShare(values));
  // values[7] was -5, where the function is 0: one more value occupied.
  EXPECT_EQ(whole[7], -5.f);
  EXPECT_EQ(each.OccupiedFraction(), counted.OccupiedFraction() + 1.0 / 60.0);
}

TEST(TypedValues, SixteenBitGridsClassifyFromTheirCounts)
{
  // Unsigned and signed 16-bit values over their whole range, classified
  // by a function with points on both sides of 0: the occupancy from the
  // counts per integer is that of the same values as floats.
  const std::array<int, 3> dims{ 17, 13, 11 };
  const std::size_t n = 17 * 13 * 11;
  Random rng(13, 0);
  std::vector<std::uint16_t> unsignedValues(n);
  std::vector<std::int16_t> signedValues(n);
  std::vector<float> unsignedFloats(n), signedFloats(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    unsignedValues[i] = static_cast<std::uint16_t>(rng.NextFloat() * 65535.f);
    signedValues[i] = static_cast<std::int16_t>(rng.NextFloat() * 65535.f - 32768.f);
    unsignedFloats[i] = unsignedValues[i];
    signedFloats[i] = signedValues[i];
  }
  const Box box{ Vec3(0.f), Vec3(1.f) };
  const OpacityTransferFunction opacity(
    { { -20000.f, 0.f }, { -3000.f, 0.4f }, { 9000.f, 0.f }, { 40000.f, 0.7f } }, 0.1f);
  auto compare = [&](const TypedValues& values, std::vector<float> floats, int lowest)
  {
    auto typedGrid = std::make_shared<const GridDensity>(box, dims, values, false);
    auto floatGrid = std::make_shared<const GridDensity>(box, dims, std::move(floats), false);
    EXPECT_EQ(typedGrid->GetValueCounts(SerialFor()).Lowest, lowest);
    EXPECT_EQ(typedGrid->GetValueCounts(SerialFor()).Counts.size(), 65536u);
    const ClassifiedDensity typed(typedGrid, opacity), asFloats(floatGrid, opacity);
    EXPECT_EQ(typed.OccupiedFraction(), asFloats.OccupiedFraction());
    EXPECT_NEAR(typed.MeanOccupiedDensity(), asFloats.MeanOccupiedDensity(),
      1e-12 * asFloats.MeanOccupiedDensity());
    EXPECT_GT(typed.OccupiedFraction(), 0.2);
  };
  compare(TypedValues::Wrap(unsignedValues.data(), n, nullptr), unsignedFloats, 0);
  compare(TypedValues::Wrap(signedValues.data(), n, nullptr), signedFloats, -32768);
}

TEST(TypedValues, CountsAreTheSameWhateverTheThreads)
{
  // Two chunks of counted values (bytes, and the same as whole floats),
  // counted once serially and once on three threads in seven pieces.
  const std::array<int, 3> dims{ 256, 128, 160 };
  const std::size_t n = 256 * 128 * 160;
  std::vector<std::uint8_t> bytes(n);
  std::vector<float> floats(n);
  Random rng(17, 0);
  for (std::size_t i = 0; i < n; ++i)
  {
    bytes[i] = static_cast<std::uint8_t>(rng.NextFloat() * 200.f + 20.f);
    floats[i] = bytes[i];
  }
  const Box box{ Vec3(0.f), Vec3(1.f) };
  for (const bool whole : { false, true })
  {
    auto make = [&]()
    {
      return whole ? GridDensity(box, dims, floats, false)
                   : GridDensity(box, dims, TypedValues::Wrap(bytes.data(), n, nullptr), false);
    };
    const GridDensity serial = make(), threaded = make();
    const GridDensity::ValueCounts& a = serial.GetValueCounts(SerialFor());
    const GridDensity::ValueCounts& b = threaded.GetValueCounts(brume::testing::ThreadedFor(3, 7));
    EXPECT_EQ(a.Lowest, whole ? 20 : 0);
    EXPECT_EQ(b.Lowest, a.Lowest);
    EXPECT_EQ(b.Counts, a.Counts);
    EXPECT_EQ(std::accumulate(a.Counts.begin(), a.Counts.end(), std::uint64_t(0)), n);
  }
}
