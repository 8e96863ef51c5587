// SPDX-License-Identifier: BSD-3-Clause
// The parallel stable counting sort (brume/Grouping.h) and what is built on
// it: hits grouped by object, and binning that gives the same bits whatever
// the threads.
#include "TestScenes.h"

#include "brume/Grouping.h"
#include "brume/Reconstruction.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>

using namespace brume;
using brume::testing::ThreadedFor;
using brume::testing::Trace;

namespace
{
// The items' order after a stable sort by key (the reference).
std::vector<std::size_t> StableOrder(const std::vector<std::size_t>& key)
{
  std::vector<std::size_t> order(key.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::stable_sort(
    order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return key[a] < key[b]; });
  return order;
}
}

TEST(Grouping, IsAStableSortWhateverTheSplit)
{
  std::mt19937_64 random(7);
  for (const std::size_t n : { 0, 1, 1000, 200003 })
  {
    for (const std::size_t groups : { 1, 5, 4097 })
    {
      std::vector<std::size_t> key(n);
      for (std::size_t& k : key)
      {
        // Skewed: most items in a few groups, as hits over objects.
        k = std::min<std::size_t>(groups - 1, random() % (groups + 3) / 2);
      }
      const std::vector<std::size_t> expected = StableOrder(key);
      std::vector<std::size_t> sizes(groups, 0);
      for (const std::size_t k : key)
      {
        ++sizes[k];
      }
      for (const ParallelFor& parallelFor :
        { SerialFor(), ThreadedFor(3, 7), ThreadedFor(2, 1000) })
      {
        std::vector<std::size_t> order(n, n);
        auto keyOf = [&](std::size_t k) { return key[k]; };
        StableGrouping grouping(n, groups);
        grouping.Count(keyOf, parallelFor);
        const std::vector<std::size_t> start = grouping.Starts();
        grouping.Place(
          start, keyOf, [&](std::size_t k, std::size_t position) { order[position] = k; },
          parallelFor);
        EXPECT_EQ(order, expected) << n << " items, " << groups << " groups";
        ASSERT_EQ(start.size(), groups + 1);
        for (std::size_t g = 0; g < groups; ++g)
        {
          EXPECT_EQ(start[g + 1] - start[g], sizes[g]) << "group " << g;
        }
      }
    }
  }
}

TEST(Grouping, PlacesTheGroupsWhereTheCallerLaysThemOut)
{
  // Group 1 first, then a gap of two, then group 0 (as new hits go after
  // the hits a range already holds).
  const std::vector<std::size_t> key = { 0, 1, 0, 1, 1, 0 };
  StableGrouping grouping(key.size(), 2);
  const std::vector<std::size_t>& counts =
    grouping.Count([&](std::size_t k) { return key[k]; }, ThreadedFor(2, 3));
  ASSERT_EQ(counts, (std::vector<std::size_t>{ 3, 3 }));
  std::vector<int> laid(8, -1);
  grouping.Place(
    { 5, 0 }, [&](std::size_t k) { return key[k]; },
    [&](std::size_t k, std::size_t position) { laid[position] = static_cast<int>(k); },
    ThreadedFor(2, 3));
  EXPECT_EQ(laid, (std::vector<int>{ 1, 3, 4, -1, -1, 0, 2, 5 }));
}

TEST(Grouping, HitsGroupByObjectInHitOrderAndBadIdsAreNamed)
{
  std::vector<std::uint16_t> object = { 2, 0, 1, 2, 2, 0 };
  HitArrays hits;
  hits.Object = object.data();
  hits.Count = object.size();
  for (const ParallelFor& parallelFor : { SerialFor(), ThreadedFor(2, 4) })
  {
    ObjectHits groups;
    ASSERT_EQ(GroupHitsByObject(hits, 3, groups, parallelFor), "");
    EXPECT_EQ(groups.Offset, (std::vector<std::size_t>{ 0, 2, 3, 6 }));
    EXPECT_EQ(std::vector<std::uint32_t>(groups.Index.begin(), groups.Index.end()),
      (std::vector<std::uint32_t>{ 1, 5, 2, 0, 3, 4 }));
  }
  object[4] = 7;
  object[5] = 9;
  ObjectHits groups;
  EXPECT_EQ(GroupHitsByObject(hits, 3, groups, ThreadedFor(2, 4)),
    "a particle hit refers to object 7 but the scene has 3 objects");
}

TEST(Grouping, BinningGivesTheSameBitsOnAnyNumberOfThreads)
{
  // The default scene's walls (view-independent) and its
  // forward-scattering fog (view-dependent: its kept hits merged by ranges
  // of cells in parallel), built on one thread and on several that take the
  // work in another order.
  const Scene scene = MakeDefaultScene();
  TraceSettings settings;
  settings.Seed = 3;
  const brume::testing::HitStore store(Trace(scene, 100000, settings));
  const HitArrays hits = store.View();
  ObjectHits groups;
  ASSERT_EQ(GroupHitsByObject(hits, scene.NumberOfObjects(), groups, ThreadedFor(2, 5)), "");
  ObjectHits serialGroups;
  ASSERT_EQ(GroupHitsByObject(hits, scene.NumberOfObjects(), serialGroups, SerialFor()), "");
  ASSERT_TRUE(std::equal(groups.Index.begin(), groups.Index.end(), serialGroups.Index.begin()));
  const Vec3 eye(0.f, 1.f, 3.5f);
  for (std::size_t o = 0; o < scene.NumberOfObjects(); ++o)
  {
    const std::size_t first = groups.Offset[o], count = groups.Offset[o + 1] - first;
    // Coarse histograms, and fine ones beyond the caches (512^2 and 64^3
    // cells).
    for (const int fine : { 0, 1 })
    {
      std::vector<std::unique_ptr<ObjectRadiance>> built;
      for (const ParallelFor& parallelFor : { SerialFor(), ThreadedFor(3, 11) })
      {
        std::unique_ptr<ObjectRadiance> radiance;
        if (o < scene.Surfaces.size())
        {
          const Surface& surface = scene.Surfaces[o];
          const int res = fine ? 256 : 16;
          radiance.reset(new ObjectRadiance(surface, MakeChart(surface, nullptr), { res, res }, 2));
        }
        else
        {
          const int res = fine ? 32 : 8;
          radiance.reset(
            new ObjectRadiance(scene.Media[o - scene.Surfaces.size()], { res, res, res }, 2));
        }
        ASSERT_EQ(
          radiance->Build(hits, groups.Index.data() + first, count, eye, 1e-4, parallelFor), "");
        built.push_back(std::move(radiance));
      }
      EXPECT_EQ(built[0]->GetBinning().GetWeightHistogram().GetValues(),
        built[1]->GetBinning().GetWeightHistogram().GetValues())
        << "object " << o << (fine ? ", fine" : ", coarse");
      EXPECT_EQ(built[0]->GetBinning().GetValueHistogram().GetValues(),
        built[1]->GetBinning().GetValueHistogram().GetValues())
        << "object " << o << (fine ? ", fine" : ", coarse");
      EXPECT_EQ(built[0]->GetTexture().Radiance, built[1]->GetTexture().Radiance)
        << "object " << o << (fine ? ", fine" : ", coarse");
    }
  }
}
