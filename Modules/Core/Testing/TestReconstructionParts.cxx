// SPDX-License-Identifier: BSD-3-Clause
// The reconstruction's collaborators on their own (brume/Reconstruction.h
// lists them): what each promises, apart from the whole ObjectRadiance that
// TestReconstruction.cxx checks.
#include "TestScenes.h"

#include "brume/Density.h"
#include "brume/DirectTexture.h"
#include "brume/HitBinning.h"
#include "brume/KeptHits.h"
#include "brume/NativeMediumGrid.h"
#include "brume/ObjectDistribution.h"
#include "brume/ObjectLayout.h"
#include "brume/Random.h"
#include "brume/TransferFunction.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <numeric>
#include <thread>

using namespace brume;

namespace
{
using brume::testing::HitStore;

Surface Square(const Material& m)
{
  Surface s;
  s.Name = "square";
  s.Vertices = { { -1, -1, 0 }, { 1, -1, 0 }, { 1, 1, 0 }, { -1, 1, 0 } };
  s.Triangles = { { 0, 1, 2 }, { 0, 2, 3 } };
  s.Mat = m;
  return s;
}

// n hits at pseudo-random places in [0, 1]^3, travelling along +z, flux
// 1 + i / n per channel.
HitStore Scattered(int n)
{
  HitStore store;
  std::uint32_t state = 12345;
  auto next = [&]
  {
    state = state * 1664525u + 1013904223u;
    return static_cast<float>(state >> 8) / 16777216.f;
  };
  for (int i = 0; i < n; ++i)
  {
    const float p[3] = { next(), next(), next() };
    const float f = 1.f + static_cast<float>(i) / static_cast<float>(n);
    store.Position.insert(store.Position.end(), p, p + 3);
    store.Direction.insert(store.Direction.end(), { 0.f, 0.f, 1.f });
    store.Flux.insert(store.Flux.end(), { f, f, f });
    store.Object.push_back(0);
    store.Triangle.push_back(0);
  }
  return store;
}

std::vector<std::uint32_t> Iota(std::size_t n)
{
  std::vector<std::uint32_t> index(n);
  std::iota(index.begin(), index.end(), 0u);
  return index;
}

// A reduction that only says which process this is (nothing is exchanged).
class PlaceOnly : public HistogramReduction
{
public:
  PlaceOnly(int rank, int processes)
    : MyRank(rank)
    , Processes(processes)
  {
  }
  int NumberOfProcesses() const override { return this->Processes; }
  int Rank() const override { return this->MyRank; }
  std::int64_t Max(std::int64_t value) override { return value; }
  void Sum(std::vector<std::int64_t>&) override {}
  void SumOnto(std::vector<std::int64_t>&, int) override {}
  void Broadcast(std::vector<float>&, int) override {}
  void Gather(const std::vector<std::int32_t>&, const std::vector<std::size_t>&,
    std::vector<std::int32_t>&) override
  {
  }

private:
  int MyRank, Processes;
};
}

TEST(ReconstructionParts, KeptHitStoreGroupsByRangesOfCellsInHitOrder)
{
  const HitStore store = Scattered(1000);
  const HitArrays hits = store.View();
  const std::vector<std::uint32_t> index = Iota(1000);
  const std::size_t cells = 4096;
  std::vector<std::uint32_t> cellOf(1000);
  for (std::size_t k = 0; k < cellOf.size(); ++k)
  {
    cellOf[k] = static_cast<std::uint32_t>((k * 2654435761u) % cells);
  }
  KeptHitStore kept(cells, false);
  kept.Keep(hits, index.data(), cellOf.data(), 1000, 1.0, brume::testing::Scrambled);
  const KeptHits& h = kept.GetHits();
  ASSERT_EQ(h.Size(), 1000u);
  EXPECT_TRUE(h.Triangle.empty());
  EXPECT_TRUE(h.Growth.empty()); // no light was aimed
  EXPECT_EQ(kept.RangeStart(0), 0u);
  EXPECT_EQ(kept.RangeStart(KeptHitStore::Ranges), 1000u);
  for (std::size_t r = 0; r < KeptHitStore::Ranges; ++r)
  {
    float lastFlux = 0.f; // the flux grows with the hit's index: hit order
    for (std::size_t k = kept.RangeStart(r); k < kept.RangeStart(r + 1); ++k)
    {
      EXPECT_EQ(h.Hits[k].Cell * KeptHitStore::Ranges / cells, r);
      EXPECT_GT(h.Hits[k].Flux[0], lastFlux);
      lastFlux = h.Hits[k].Flux[0];
    }
  }
}

TEST(ReconstructionParts, KeptHitStoreMergesDeferredBatchesAsIfEachWereMergedInTurn)
{
  const HitStore store = Scattered(900);
  const HitArrays hits = store.View();
  const std::vector<std::uint32_t> index = Iota(900);
  const std::size_t cells = 1000;
  std::vector<std::uint32_t> cellOf(900);
  for (std::size_t k = 0; k < cellOf.size(); ++k)
  {
    cellOf[k] = static_cast<std::uint32_t>((k * 7919u) % cells);
  }
  KeptHitStore inTurn(cells, true), deferred(cells, true);
  deferred.SetDeferred(true);
  for (std::size_t b = 0; b < 3; ++b)
  {
    inTurn.Keep(hits, index.data() + 300 * b, cellOf.data() + 300 * b, 300, 1.0, SerialFor());
    deferred.Keep(hits, index.data() + 300 * b, cellOf.data() + 300 * b, 300, 1.0 / 3.0,
      brume::testing::Scrambled);
  }
  EXPECT_TRUE(deferred.HasPending());
  EXPECT_TRUE(deferred.GetHits().Empty());
  deferred.MergePending(SerialFor());
  EXPECT_FALSE(deferred.HasPending());
  const KeptHits& a = inTurn.GetHits();
  const KeptHits& b = deferred.GetHits();
  ASSERT_EQ(a.Size(), b.Size());
  ASSERT_EQ(a.Triangle.size(), a.Size()); // a surface's hits keep their triangles
  for (std::size_t k = 0; k < a.Size(); ++k)
  {
    EXPECT_EQ(a.Hits[k].Cell, b.Hits[k].Cell);
    EXPECT_EQ(a.Hits[k].Flux[0], b.Hits[k].Flux[0]);
  }
  for (std::size_t r = 0; r <= KeptHitStore::Ranges; ++r)
  {
    EXPECT_EQ(inTurn.RangeStart(r), deferred.RangeStart(r));
  }
  // Scaling the flux scales every hit, exactly by a power of two.
  deferred.ScaleFlux(0.5f, SerialFor());
  for (std::size_t k = 0; k < a.Size(); ++k)
  {
    EXPECT_EQ(b.Hits[k].Flux[1], 0.5f * a.Hits[k].Flux[1]);
  }
}

TEST(ReconstructionParts, KeptHitStoreReusesReleasedBuffersOfAboutTheSameRun)
{
  const HitStore store = Scattered(5000);
  const HitArrays hits = store.View();
  const std::vector<std::uint32_t> index = Iota(5000);
  const std::vector<std::uint32_t> cellOf(5000, 3);
  KeptHitStore kept(64, false);
  kept.Keep(hits, index.data(), cellOf.data(), 5000, 1.0, SerialFor());
  KeptHits memory = kept.ReleaseMemory();
  EXPECT_TRUE(kept.GetHits().Empty());
  EXPECT_TRUE(memory.Empty());
  const std::size_t capacity = memory.Hits.capacity();
  ASSERT_GE(capacity, 5000u);
  const KeptHit* buffer = memory.Hits.data();
  // Room for more than twice a run's hits is freed, not taken.
  KeptHitStore small(64, false);
  small.ReuseMemory(std::move(memory), 100);
  EXPECT_EQ(small.GetHits().Hits.capacity(), 0u);
  // A run of about as many hits writes where the last one's were.
  memory = kept.ReleaseMemory();
  kept.Keep(hits, index.data(), cellOf.data(), 5000, 1.0, SerialFor());
  memory = kept.ReleaseMemory();
  ASSERT_EQ(memory.Hits.capacity(), capacity);
  buffer = memory.Hits.data();
  kept.ReuseMemory(std::move(memory), 4800);
  kept.Keep(hits, index.data(), cellOf.data(), 4800, 1.0, SerialFor());
  EXPECT_EQ(kept.GetHits().Hits.data(), buffer);
}

TEST(ReconstructionParts, HitBinningSumsEachHitsFluxInItsCell)
{
  // An isotropic medium over [0, 1]^3: value Phi / (4 pi), weight the mean
  // of Phi over the channels, each in the hit's cell of a 4^3 histogram.
  Medium fog;
  fog.Name = "fog";
  fog.Bounds = Box{ Vec3(0.f), Vec3(1.f) };
  const ObjectLayout layout(fog, { 2, 2, 2 }, 2);
  EXPECT_EQ(layout.Cells(), 64u);
  EXPECT_EQ(layout.Texels(), 8u);
  EXPECT_FALSE(layout.ViewDependent);
  HitStore store;
  const float at[2][3] = { { 0.1f, 0.1f, 0.1f }, { 0.9f, 0.6f, 0.3f } };
  for (const auto& p : at)
  {
    store.Position.insert(store.Position.end(), p, p + 3);
    store.Direction.insert(store.Direction.end(), { 1.f, 0.f, 0.f });
    store.Flux.insert(store.Flux.end(), { 1.f, 2.f, 3.f });
    store.Object.push_back(0);
    store.Triangle.push_back(0);
  }
  const std::vector<std::uint32_t> index = Iota(2);
  HitBinning binning(layout);
  EXPECT_FALSE(binning.KeepsHits());
  binning.Clear(false);
  binning.Start(layout, ExactHistogram::QuantumExponent(3.0), false);
  binning.Bin(layout, store.View(), index.data(), 2, nullptr, 1.0, SerialFor());
  EXPECT_EQ(binning.Saturation(), "");
  const Histogram weights = binning.GetWeightHistogram();
  const Histogram values = binning.GetValueHistogram();
  const std::size_t first = 0, second = (1 * 4 + 2) * 4 + 3; // cells (0,0,0), (3,2,1)
  EXPECT_NEAR(weights.Get(first)[0], 2.0, 1e-9);
  EXPECT_NEAR(weights.Get(second)[0], 2.0, 1e-9);
  for (int c = 0; c < 3; ++c)
  {
    // Inv4Pi is a float: 1/(4 pi) to within 1e-7 relative.
    const double expected = (c + 1) / (4.0 * Pi);
    EXPECT_NEAR(values.Get(second)[c], expected, 1e-7 * expected);
  }
  double total = 0.0;
  for (const double w : weights.GetValues())
  {
    total += w;
  }
  EXPECT_NEAR(total, 4.0, 1e-9); // nothing elsewhere
  // A progressive step halves what was binned, exactly.
  binning.Scale(0.5, binning.GetSumsExponent() - 1, SerialFor());
  const Histogram halved = binning.GetWeightHistogram();
  EXPECT_EQ(halved.Get(second)[0], 0.5 * weights.Get(second)[0]);
}

TEST(ReconstructionParts, HitBinningShowsASurfaceItsFrontSideOnly)
{
  const Surface square = Square(Material());
  const ObjectLayout layout(square, MakeChart(square, nullptr), { 2, 2 }, 1);
  HitStore store;
  for (const float dz : { -1.f, 1.f }) // arriving on the front (+z) side, then the back
  {
    store.Position.insert(store.Position.end(), { 0.5f, 0.5f, 0.f });
    store.Direction.insert(store.Direction.end(), { 0.f, 0.f, dz });
    store.Flux.insert(store.Flux.end(), { 1.f, 1.f, 1.f });
    store.Object.push_back(0);
    store.Triangle.push_back(0);
  }
  const std::vector<std::uint32_t> index = Iota(2);
  HitBinning binning(layout);
  binning.Clear(false);
  binning.Start(layout, ExactHistogram::QuantumExponent(1.0), false);
  binning.Bin(layout, store.View(), index.data(), 2, nullptr, 1.0, SerialFor());
  const Histogram weights = binning.GetWeightHistogram();
  double total = 0.0;
  for (const double w : weights.GetValues())
  {
    total += w;
  }
  EXPECT_NEAR(total, 1.0, 1e-9);
}

TEST(ReconstructionParts, MediumScatteringSetsTheForwardPeakApart)
{
  Medium mist;
  mist.Name = "mist";
  mist.Bounds = Box{ Vec3(0.f), Vec3(1.f) };
  mist.SigmaS = Vec3(0.9f);
  mist.SigmaA = Vec3(0.1f);
  mist.G = 0.5f; // resolved: no split
  const MediumScattering resolved(mist);
  EXPECT_EQ(resolved.GetPeak(false).Forward, 0.f);
  EXPECT_EQ(resolved.GetExtinctionFactor(false).x, 1.f);
  mist.G = 0.9f; // past both resolved asymmetries
  const MediumScattering peaked(mist);
  for (const bool directional : { false, true })
  {
    const ForwardPeak& peak = peaked.GetPeak(directional);
    EXPECT_GT(peak.Forward, 0.f);
    // Per view, HG(g) truncated at what HG(ResolvedG) reaches; as
    // spherical harmonics, a Henyey-Greenstein remainder they project.
    if (directional)
    {
      EXPECT_EQ(peak.G, MediumScattering::DirectionalResolvedG);
    }
    else
    {
      EXPECT_EQ(peak.G, 0.9f);
      EXPECT_EQ(peak.Cap, HenyeyGreenstein(MediumScattering::ResolvedG).Evaluate(1.f));
    }
    EXPECT_FLOAT_EQ(peaked.GetExtinctionFactor(directional).y, 1.f - 0.9f * peak.Forward);
  }
  // An albedo folded into the texture: the texel is the source radiance.
  Vec3 factor;
  const Vec3 s = peaked.SourceAt(Vec3(0.3f), Vec3(2.f), false, factor);
  EXPECT_EQ(s.x, 2.f);
  EXPECT_EQ(factor.x, peaked.GetExtinctionFactor(false).x);
}

TEST(ReconstructionParts, ObjectDistributionSharesEveryItemOnce)
{
  ObjectDistribution alone;
  EXPECT_TRUE(alone.EstimatesHere());
  EXPECT_FALSE(alone.SharesTexture());
  EXPECT_EQ(alone.Share(17), (std::array<std::size_t, 2>{ 0, 17 }));
  const int processes = 3;
  std::size_t next = 0;
  for (int r = 0; r < processes; ++r)
  {
    PlaceOnly place(r, processes);
    ObjectDistribution d;
    d.SetReduction(&place);
    EXPECT_TRUE(d.EstimatesHere()); // no owner: every process
    d.SetOwner(1);
    EXPECT_EQ(d.EstimatesHere(), r == 1);
    EXPECT_TRUE(d.SharesTexture());
    const auto share = d.Share(100);
    EXPECT_EQ(share[0], next) << r;
    next = share[1];
  }
  EXPECT_EQ(next, 100u);
  EXPECT_EQ(AssignOwners({ 1.0, 5.0, 2.0, 2.0 }, 2), (std::vector<int>{ 1, 0, 1, 1 }));
}

TEST(ReconstructionParts, NativeMediumGridIntegratesTheDensityOverRegions)
{
  // Density 2 on x < 1/2 of the box [0, 2] x [0, 1] x [0, 1], 0 beyond.
  Medium smoke;
  smoke.Name = "smoke";
  smoke.SetDensity(std::make_shared<GridDensity>(Box{ Vec3(0.f), Vec3(2.f, 1.f, 1.f) },
    std::array<int, 3>{ 4, 1, 1 }, std::vector<float>{ 2.f, 0.f, 0.f, 0.f }, true));
  NativeMediumGrid grid;
  EXPECT_TRUE(grid.Empty());
  grid.Sample(smoke, NativeMediumGrid::DefaultMemory, SerialFor());
  ASSERT_FALSE(grid.Empty());
  EXPECT_EQ(grid.GetResolution(), (std::array<int, 3>{ 4, 1, 1 }));
  EXPECT_EQ(grid.GetCoarsening(), 1);
  EXPECT_EQ(grid.GetClassification(), nullptr);
  const std::array<int, 3> dims{ 8, 2, 2 };
  grid.BuildTables(smoke.Bounds, dims);
  ASSERT_TRUE(grid.HasTables());
  Region all;
  all.Hi = dims;
  EXPECT_NEAR(grid.RegionIntegral(all), 2.0 * 0.5 * 1.0 * 1.0, 1e-6);
  Region empty = all;
  empty.Lo[0] = 4; // x >= 1
  EXPECT_LE(grid.RegionIntegral(empty), grid.GetEmptyIntegral());
  // A region over both halves belongs where its density is: its centroid
  // lies in the dense part, not at the region's centre.
  std::vector<std::array<Region, 2>> regions(1, { all, all });
  const CentroidMatching matching = grid.Centroids(regions, { 1, 1, 1 }, 8, SerialFor());
  EXPECT_FALSE(matching.Empty());
}

TEST(ReconstructionParts, TheTablesIntegrateTheTrilinearFieldTheHitsSample)
{
  // A grid of point values is interpolated trilinearly between its points,
  // and the tracer's collisions sample that field, so the integral a
  // region's hits are divided by must be that field's, also over
  // histogram cells finer than the grid's: a dense ball's edge, where the
  // field ramps to 0 over a spacing, was held as cells of constant density,
  // whose mass stops half a spacing past the last point inside where the
  // field's ramp reaches a whole spacing (a dense dragon's regions, grown
  // over such cells, read its lit skin 1.7 % too bright).
  const int n = 12;
  std::vector<float> values(static_cast<std::size_t>(n) * n * n);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
      {
        const double r =
          std::sqrt((i - 5.2) * (i - 5.2) + (j - 6.1) * (j - 6.1) + (k - 5.7) * (k - 5.7));
        values[(static_cast<std::size_t>(k) * n + j) * n + i] = r < 4.0 ? 3.f : 0.f;
      }
  Medium ball;
  ball.Name = "ball";
  ball.SetDensity(std::make_shared<GridDensity>(Box{ Vec3(0.f), Vec3(1.f, 1.2f, 0.9f) },
    std::array<int, 3>{ n, n, n }, std::move(values), false));
  NativeMediumGrid grid;
  grid.Sample(ball, NativeMediumGrid::DefaultMemory, SerialFor());
  ASSERT_EQ(grid.GetCoarsening(), 1);
  // Histogram cells about a third of a spacing, not aligned with the points.
  const std::array<int, 3> dims{ 31, 37, 29 };
  grid.BuildTables(ball.Bounds, dims);
  const Vec3 cell = ball.Bounds.Extent() /
    Vec3(static_cast<float>(dims[0]), static_cast<float>(dims[1]), static_cast<float>(dims[2]));
  // Each cell's integral of the field evaluated: exact for a trilinear
  // field by Gauss-Legendre's two points on each piece the points cut it
  // into, here approximated by 12 midpoints an axis (the pieces are at most
  // three a cell), against the table's.
  double worst = 0.0, largest = 0.0, total = 0.0, tableTotal = 0.0;
  for (int k = 0; k < dims[2]; ++k)
    for (int j = 0; j < dims[1]; ++j)
      for (int i = 0; i < dims[0]; ++i)
      {
        const Vec3 lower = ball.Bounds.lower +
          Vec3(static_cast<float>(i), static_cast<float>(j), static_cast<float>(k)) * cell;
        double sum = 0.0;
        constexpr int S = 12;
        for (int z = 0; z < S; ++z)
          for (int y = 0; y < S; ++y)
            for (int x = 0; x < S; ++x)
            {
              const Vec3 f((x + 0.5f) / S, (y + 0.5f) / S, (z + 0.5f) / S);
              sum += ball.Density->Evaluate(lower + cell * f);
            }
        const double evaluated = sum / (S * S * S) * cell.x * cell.y * cell.z;
        Region one;
        one.Lo = { i, j, k };
        one.Hi = { i + 1, j + 1, k + 1 };
        const double table = grid.RegionIntegral(one);
        worst = std::max(worst, std::abs(table - evaluated));
        largest = std::max(largest, evaluated);
        total += evaluated;
        tableTotal += table;
      }
  std::cout << "largest difference from the field's integral over a cell: " << worst / largest
            << " of the largest cell's\n";
  // The midpoints' own error is below 0.5 % of a full cell here; cells of
  // constant density were 63 % of a full cell off.
  EXPECT_LT(worst, 0.01 * largest);
  EXPECT_NEAR(tableTotal, total, 1e-3 * total);
}

namespace
{
// A classified wavelet-like field of n^3 point values over [-1, 1]^3 whose
// opacity function bends at 0.5 (and is 0 below 0.2): many cells' scalars
// span the bend.
Medium ClassifiedWaves(int n)
{
  std::vector<float> values(static_cast<std::size_t>(n) * n * n);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
      {
        const double x = 6.0 * i / (n - 1), y = 5.0 * j / (n - 1), z = 7.0 * k / (n - 1);
        values[(static_cast<std::size_t>(k) * n + j) * n + i] =
          static_cast<float>(0.5 + 0.5 * std::sin(x) * std::cos(y) * std::sin(z + 0.3));
      }
  Medium waves;
  waves.Name = "waves";
  auto scalars = std::make_shared<GridDensity>(
    Box{ Vec3(-1.f), Vec3(1.f) }, std::array<int, 3>{ n, n, n }, std::move(values), false);
  waves.SetDensity(std::make_shared<ClassifiedDensity>(
    scalars, OpacityTransferFunction({ { 0.2f, 0.f }, { 0.5f, 0.1f }, { 1.f, 0.9f } }, 0.1f)));
  return waves;
}

// The scalars of a ClassifiedWaves() medium classified by another function
// (an edit of its opacity).
Medium Reclassified(const Medium& waves, std::vector<OpacityTransferFunction::Node> nodes)
{
  const auto& classified = static_cast<const ClassifiedDensity&>(*waves.Density);
  Medium edited = waves;
  edited.SetDensity(std::make_shared<ClassifiedDensity>(
    classified.GetScalarsPointer(), OpacityTransferFunction(std::move(nodes), 0.1f)));
  return edited;
}

// ClassifiedWaves()'s scalars read as nearest values, or as cell values.
std::shared_ptr<GridDensity> NearestCopy(const ClassifiedDensity& classified, bool cells)
{
  const auto& grid = static_cast<const GridDensity&>(classified.GetScalars());
  std::vector<float> values(grid.GetValues().Size());
  for (std::size_t v = 0; v < values.size(); ++v)
  {
    values[v] = grid.GetValues()[v];
  }
  return std::make_shared<GridDensity>(grid.GetBounds(), grid.GetDimensions(), std::move(values),
    cells, GridDensity::Interpolation::Nearest);
}

// Every cell of two grids' density and scalars, compared bitwise.
bool SameGrids(const NativeMediumGrid& a, const NativeMediumGrid& b)
{
  const auto& dims = a.GetResolution();
  if (dims != b.GetResolution() || a.GetScalars().Empty() != b.GetScalars().Empty())
  {
    return false;
  }
  for (int k = 0; k < dims[2]; ++k)
    for (int j = 0; j < dims[1]; ++j)
      for (int i = 0; i < dims[0]; ++i)
      {
        if (a.GetDensity().At(i, j, k) != b.GetDensity().At(i, j, k) ||
          (!a.GetScalars().Empty() && a.ScalarAt(i, j, k) != b.ScalarAt(i, j, k)))
        {
          return false;
        }
      }
  return true;
}

// A ParallelFor on `threads` threads, each a contiguous share.
ParallelFor ThreadsFor(int threads)
{
  return [threads](std::size_t begin, std::size_t end,
           const std::function<void(std::size_t, std::size_t)>& body)
  {
    std::vector<std::thread> pool;
    const std::size_t n = end - begin;
    for (int t = 0; t < threads; ++t)
    {
      const std::size_t b = begin + n * t / threads, e = begin + n * (t + 1) / threads;
      if (b < e)
      {
        pool.emplace_back([&body, b, e]() { body(b, e); });
      }
    }
    for (auto& thread : pool)
    {
      thread.join();
    }
  };
}
}

TEST(ReconstructionParts, NativeMediumGridKeepsItsOwnResolutionWhereTheMemoryHoldsIt)
{
  // 48^3 points: 48^3 cells of 7^3 bricks' samples (the density; the
  // scalars are the field's own, not copied): 343 bricks x 2 KB is about
  // 0.7 MB.
  const Medium waves = ClassifiedWaves(48);
  NativeMediumGrid native;
  native.Sample(waves, std::size_t(4) << 20, SerialFor());
  EXPECT_EQ(native.GetCoarsening(), 1);
  EXPECT_EQ(native.GetResolution(), (std::array<int, 3>{ 48, 48, 48 }));
  EXPECT_EQ(native.GetFieldResolution(), (std::array<int, 3>{ 48, 48, 48 }));
  EXPECT_FALSE(native.GetScalars().Empty());
  EXPECT_NE(native.GetClassification(), nullptr);
  // The grids' own bytes are within the memory they were given.
  EXPECT_LE(native.GetDensity().GetMemorySize() + native.GetScalars().GetMemorySize(),
    std::size_t(4) << 20);

  // Half a megabyte does not hold even one: coarsened by the smallest factor
  // that fits, the density alone (a mean of scalars is not what the
  // function classifies).
  NativeMediumGrid coarse;
  coarse.Sample(waves, std::size_t(1) << 19, SerialFor());
  EXPECT_EQ(coarse.GetCoarsening(), 2);
  EXPECT_EQ(coarse.GetResolution(), (std::array<int, 3>{ 24, 24, 24 }));
  EXPECT_EQ(coarse.GetFieldResolution(), (std::array<int, 3>{ 48, 48, 48 }));
  EXPECT_TRUE(coarse.GetScalars().Empty());
  EXPECT_LE(coarse.GetDensity().GetMemorySize(), std::size_t(1) << 19);

  // No memory at all: one cell, not an endless search.
  NativeMediumGrid single;
  single.Sample(waves, 1, SerialFor());
  EXPECT_EQ(single.GetResolution(), (std::array<int, 3>{ 1, 1, 1 }));
  EXPECT_EQ(single.GetCoarsening(), 48);

  // Whatever the threads, the same grids bitwise.
  NativeMediumGrid threaded;
  threaded.Sample(waves, std::size_t(4) << 20, ThreadsFor(3));
  EXPECT_TRUE(SameGrids(native, threaded));
}

TEST(ReconstructionParts, NativeMediumGridReadsAGridsScalarsInPlace)
{
  // A classified grid's scalars are its own values: the grid keeps an
  // outline of their bricks (slots and constants, as a copy would have
  // them), not a copy. Each stored brick's cells read the field's values,
  // each constant brick's cells all hold its constant, or the function
  // leaves the brick out (its extinction 0).
  const Medium all = ClassifiedWaves(48);
  const auto& classified = static_cast<const ClassifiedDensity&>(*all.Density);
  const auto& field = static_cast<const GridDensity&>(classified.GetScalars());
  // Nothing up to 0.85: bricks left out.
  Medium waves = all;
  waves.SetDensity(std::make_shared<ClassifiedDensity>(classified.GetScalarsPointer(),
    OpacityTransferFunction({ { 0.85f, 0.f }, { 0.9f, 0.1f }, { 1.f, 0.9f } }, 0.1f)));
  for (const ParallelFor& parallelFor : { SerialFor(), ThreadsFor(3) })
  {
    NativeMediumGrid native;
    native.Sample(waves, std::size_t(4) << 20, parallelFor);
    ASSERT_TRUE(native.ScalarsInPlace());
    EXPECT_EQ(native.GetScalarField(), &field);
    const BrickedGrid& outline = native.GetScalars();
    EXPECT_FALSE(outline.HasSamples());
    EXPECT_GT(outline.NumberOfStoredBricks(), 100u);
    EXPECT_EQ(
      outline.GetMemorySize(), outline.NumberOfBricks() * (sizeof(std::int32_t) + sizeof(float)));
    const auto& dims = native.GetResolution();
    const auto& brickDims = outline.GetBrickDims();
    constexpr int S = BrickedGrid::Size;
    std::int32_t nextSlot = 0;
    int wrong = 0, leftOut = 0;
    for (int bk = 0; bk < brickDims[2]; ++bk)
      for (int bj = 0; bj < brickDims[1]; ++bj)
        for (int bi = 0; bi < brickDims[0]; ++bi)
        {
          const std::array<int, 3> lower{ bi * BrickedGrid::Stride, bj * BrickedGrid::Stride,
            bk * BrickedGrid::Stride };
          const std::size_t b = outline.BrickAt(lower);
          const std::int32_t slot = outline.GetSlots()[b];
          bool allEqual = true, densityZero = true;
          const float first = field.NativeValue(lower[0], lower[1], lower[2], Vec3(0.f));
          for (int k = 0; k < S; ++k)
            for (int j = 0; j < S; ++j)
              for (int i = 0; i < S; ++i)
              {
                const int x = std::min(lower[0] + i, dims[0] - 1),
                          y = std::min(lower[1] + j, dims[1] - 1),
                          z = std::min(lower[2] + k, dims[2] - 1);
                const float v = field.NativeValue(x, y, z, Vec3(0.f));
                allEqual = allEqual && v == first;
                densityZero = densityZero && native.GetDensity().At(x, y, z) == 0.f;
                // The brick's own cells answer ScalarAt() with their values
                // (a constant brick with its constant).
                if (outline.BrickOf(x, y, z) == b &&
                  native.ScalarAt(x, y, z) != (slot >= 0 ? v : outline.GetConstants()[b]))
                {
                  ++wrong;
                }
              }
          if (slot >= 0)
          {
            // Stored bricks vary, in brick order.
            wrong += slot == nextSlot++ && !allEqual ? 0 : 1;
          }
          else if (!(allEqual && outline.GetConstants()[b] == first))
          {
            ++leftOut;
            wrong += densityZero ? 0 : 1;
          }
        }
    EXPECT_EQ(wrong, 0);
    EXPECT_GT(leftOut, 0);
    EXPECT_EQ(static_cast<std::size_t>(nextSlot), outline.NumberOfStoredBricks());
  }
  // Its memory counts the density's samples once: a budget that holds
  // one grid's samples (and both tables) keeps the field's resolution.
  // (343 bricks of 2 KB: 0.7 MB once, 1.4 MB twice.)
  NativeMediumGrid once;
  once.Sample(all, std::size_t(1) << 20, SerialFor());
  EXPECT_EQ(once.GetCoarsening(), 1);
  EXPECT_LE(
    once.GetDensity().GetMemorySize() + once.GetScalars().GetMemorySize(), std::size_t(1) << 20);
}

TEST(ReconstructionParts, NativeMediumGridKeepsWhatAnEditOfTheFunctionLeft)
{
  // The same scalars classified by a function, then by an edit of its
  // upper part: the edited grid, sampled with the first one offered, is
  // bitwise the grid sampled afresh, and took from the first the bricks
  // whose scalars all lie where the edit changed nothing. An unchanged
  // function (a colour edit) keeps the whole grid and its tables.
  const Medium waves = ClassifiedWaves(48);
  const auto& classified = static_cast<const ClassifiedDensity&>(*waves.Density);
  auto withFunction = [&](std::vector<OpacityTransferFunction::Node> nodes)
  { return Reclassified(waves, std::move(nodes)); };
  const std::size_t memory = std::size_t(4) << 20;
  NativeMediumGrid before;
  before.Sample(waves, memory, SerialFor());
  EXPECT_EQ(before.GetReusedBricks(), 0u);
  const std::size_t all = before.GetSampledBricks();
  EXPECT_GT(all, 100u);
  // Above 0.5 only (the first two points kept, the last one's opacity edited).
  const Medium upper = withFunction({ { 0.2f, 0.f }, { 0.5f, 0.1f }, { 1.f, 0.6f } });
  for (const ParallelFor& parallelFor : { SerialFor(), ThreadsFor(3) })
  {
    NativeMediumGrid fresh, kept;
    fresh.Sample(upper, memory, parallelFor);
    kept.Sample(upper, memory, parallelFor, &before);
    EXPECT_TRUE(SameGrids(fresh, kept));
    // The function is 0 where it was: the scalars' bricks are the same
    // (an outline of the field's own values, which are not copied).
    EXPECT_TRUE(kept.ScalarsInPlace());
    EXPECT_TRUE(kept.GetScalars().SameAs(before.GetScalars()));
    EXPECT_EQ(fresh.GetSampledBricks(), kept.GetSampledBricks() + kept.GetReusedBricks());
    EXPECT_GT(kept.GetReusedBricks(), 0u);
    EXPECT_GT(kept.GetSampledBricks(), 0u);
    std::cout << "an edit above 0.5: " << kept.GetSampledBricks() << " bricks sampled, "
              << kept.GetReusedBricks() << " kept\n";
    // The tables summed from either are the same.
    const Box& box = waves.Bounds;
    fresh.BuildTables(box, { 6, 6, 6 });
    kept.BuildTables(box, { 6, 6, 6 });
    Region everything;
    everything.Lo = { 0, 0, 0 };
    everything.Hi = { 5, 5, 5 };
    EXPECT_EQ(fresh.RegionIntegral(everything), kept.RegionIntegral(everything));
  }
  // A new point inside the kept part, on the function's line: the same
  // values, but cells whose scalars span it now bend, so those bricks are
  // sampled again; still the fresh grid.
  const Medium collinear =
    withFunction({ { 0.2f, 0.f }, { 0.35f, 0.05f }, { 0.5f, 0.1f }, { 1.f, 0.9f } });
  NativeMediumGrid fresh, kept;
  fresh.Sample(collinear, memory, SerialFor());
  kept.Sample(collinear, memory, SerialFor(), &before);
  EXPECT_TRUE(SameGrids(fresh, kept));
  EXPECT_GT(kept.GetSampledBricks(), 0u);

  // Zero up to 0.45 instead of 0.2: other bricks left out, so the
  // scalars are sampled again (those stored before copied); still the
  // fresh grids.
  const Medium later = withFunction({ { 0.45f, 0.f }, { 0.5f, 0.1f }, { 1.f, 0.9f } });
  NativeMediumGrid laterFresh, laterKept;
  laterFresh.Sample(later, memory, SerialFor());
  laterKept.Sample(later, memory, SerialFor(), &before);
  EXPECT_TRUE(SameGrids(laterFresh, laterKept));
  EXPECT_FALSE(laterKept.GetScalars().SameAs(before.GetScalars()));

  // The same function: the whole grid and its tables, nothing sampled.
  before.BuildTables(waves.Bounds, { 6, 6, 6 });
  NativeMediumGrid same;
  same.Sample(withFunction(classified.GetOpacity().GetNodes()), memory, SerialFor(), &before);
  EXPECT_TRUE(SameGrids(before, same));
  EXPECT_EQ(same.GetSampledBricks(), 0u);
  EXPECT_EQ(same.GetReusedBricks(), all);
  EXPECT_TRUE(same.HasTables(waves.Bounds, { 6, 6, 6 }));
  EXPECT_FALSE(same.HasTables(waves.Bounds, { 7, 7, 7 }));

  // Nearest values: the same bricks kept, still the fresh grid.
  {
    auto nearest = NearestCopy(classified, false);
    auto classify = [&](std::vector<OpacityTransferFunction::Node> nodes)
    {
      Medium m = waves;
      m.SetDensity(std::make_shared<ClassifiedDensity>(
        nearest, OpacityTransferFunction(std::move(nodes), 0.1f)));
      return m;
    };
    NativeMediumGrid first, nearestFresh, nearestKept;
    first.Sample(classify(classified.GetOpacity().GetNodes()), memory, SerialFor());
    const Medium edited = classify({ { 0.2f, 0.f }, { 0.5f, 0.1f }, { 1.f, 0.6f } });
    nearestFresh.Sample(edited, memory, SerialFor());
    nearestKept.Sample(edited, memory, ThreadsFor(3), &first);
    EXPECT_TRUE(SameGrids(nearestFresh, nearestKept));
    EXPECT_GT(nearestKept.GetReusedBricks(), 0u);
    EXPECT_GT(nearestKept.GetSampledBricks(), 0u);
  }

  // An unclassified density: the same object shares the whole grid (an
  // edit of the medium's albedo), another is sampled.
  Medium plain = waves;
  plain.SetDensity(classified.GetScalarsPointer());
  NativeMediumGrid plainBefore, plainAgain, plainOther;
  plainBefore.Sample(plain, memory, SerialFor());
  plainAgain.Sample(plain, memory, SerialFor(), &plainBefore);
  EXPECT_TRUE(plainAgain.GetDensity().SameAs(plainBefore.GetDensity()));
  plainOther.Sample(plain, memory, SerialFor(), &before);
  EXPECT_FALSE(plainOther.GetDensity().SameAs(before.GetDensity()));
  EXPECT_TRUE(SameGrids(plainOther, plainBefore));

  // Another field (the same values, another object) is not read.
  const Medium other = ClassifiedWaves(48);
  EXPECT_FALSE(before.SameField(other));
  NativeMediumGrid unrelated;
  unrelated.Sample(other, memory, SerialFor(), &before);
  EXPECT_EQ(unrelated.GetReusedBricks(), 0u);
  EXPECT_TRUE(SameGrids(before, unrelated));
}

TEST(ReconstructionParts, NativeMediumGridEditedInItsOwnMemoryIsTheFreshGrid)
{
  // Edits one after another, each grid sampled again in the memory of the
  // one before (the render pass's edits): every cell bitwise the grid
  // sampled afresh, on one thread or three. The edits make bricks constant
  // (a flat stretch of the function), vary again, leave some out (zero up
  // to 0.45) and take more in (zero up to 0.05); a grid whose samples a
  // copy shares is not written, the copy keeps its values.
  const Medium waves = ClassifiedWaves(64);
  auto withFunction = [&](std::vector<OpacityTransferFunction::Node> nodes)
  { return Reclassified(waves, std::move(nodes)); };
  const std::vector<Medium> edits = {
    withFunction({ { 0.2f, 0.f }, { 0.5f, 0.1f }, { 1.f, 0.6f } }),
    withFunction({ { 0.2f, 0.f }, { 0.3f, 0.4f }, { 0.9f, 0.4f }, { 1.f, 0.6f } }),
    withFunction({ { 0.2f, 0.f }, { 0.5f, 0.1f }, { 1.f, 0.6f } }),
    withFunction({ { 0.45f, 0.f }, { 0.5f, 0.1f }, { 1.f, 0.9f } }),
    withFunction({ { 0.05f, 0.f }, { 0.5f, 0.1f }, { 1.f, 0.9f } }),
    waves,
  };
  const std::size_t memory = std::size_t(16) << 20;
  for (const ParallelFor& parallelFor : { SerialFor(), ThreadsFor(3) })
  {
    NativeMediumGrid grid;
    grid.Sample(waves, memory, parallelFor);
    std::size_t inPlace = 0;
    for (std::size_t e = 0; e < edits.size(); ++e)
    {
      const float* before = grid.GetDensity().GetSamples().Data();
      const std::size_t stored = grid.GetDensity().NumberOfStoredBricks();
      const std::uint64_t identity = grid.GetDensity().GetIdentity();
      NativeMediumGrid fresh, edited;
      fresh.Sample(edits[e], memory, parallelFor);
      edited.Sample(edits[e], memory, parallelFor, std::move(grid));
      EXPECT_TRUE(grid.Empty());
      EXPECT_TRUE(SameGrids(fresh, edited)) << "edit " << e;
      EXPECT_EQ(fresh.GetSampledBricks(), edited.GetSampledBricks() + edited.GetReusedBricks());
      EXPECT_NE(edited.GetDensity().GetIdentity(), identity);
      EXPECT_EQ(
        edited.GetDensity().NumberOfStoredBricks(), fresh.GetDensity().NumberOfStoredBricks());
      EXPECT_TRUE(edited.GetDensity().HasSamples());
      const bool same = edited.GetDensity().GetSamples().Data() == before;
      if (edited.GetDensity().NumberOfStoredBricks() == stored)
      {
        // As many bricks stored: the same memory (fewer: cut where it was
        // mapped on its own, copied where small).
        EXPECT_TRUE(same) << "edit " << e;
        ++inPlace;
      }
      std::cout << "edit " << e << ": " << stored << " -> "
                << edited.GetDensity().NumberOfStoredBricks() << " stored bricks, "
                << edited.GetReusedBricks() << " left, " << edited.GetSampledBricks()
                << " sampled, " << (same ? "in place" : "moved") << "\n";
      grid = std::move(edited);
    }
    EXPECT_GE(inPlace, 1u);

    // A copy shares the samples: the edit goes elsewhere, the copy is kept.
    const BrickedGrid copy = grid.GetDensity();
    NativeMediumGrid shared;
    shared.Sample(edits[0], memory, parallelFor, std::move(grid));
    NativeMediumGrid fresh, again;
    fresh.Sample(edits[0], memory, parallelFor);
    EXPECT_TRUE(SameGrids(fresh, shared));
    EXPECT_NE(shared.GetDensity().GetSamples().Data(), copy.GetSamples().Data());
    again.Sample(waves, memory, parallelFor);
    EXPECT_TRUE(again.GetDensity().HasSamples());
    bool copyKept = true;
    const auto& dims = copy.GetDims();
    for (int k = 0; k < dims[2]; ++k)
      for (int j = 0; j < dims[1]; ++j)
        for (int i = 0; i < dims[0]; ++i)
        {
          copyKept = copyKept && copy.At(i, j, k) == again.GetDensity().At(i, j, k);
        }
    EXPECT_TRUE(copyKept);
  }
}

TEST(ReconstructionParts, NativeMediumGridOfNearestOrCellValuesIsTheirValuesClassified)
{
  // Nearest values (and cell values): every sample of a cell reads its own
  // value, so the grid, sampled a brick at a time, is each cell's value
  // classified, and where the function bends inside a cell's neighbourhood
  // the cell's mean of 4^3 samples gives the same float.
  for (const bool cells : { false, true })
  {
    const Medium linear = ClassifiedWaves(40);
    const auto& classified = static_cast<const ClassifiedDensity&>(*linear.Density);
    auto scalars = NearestCopy(classified, cells);
    Medium medium = linear;
    auto density = std::make_shared<ClassifiedDensity>(scalars, classified.GetOpacity());
    medium.SetDensity(density);
    NativeMediumGrid native;
    native.Sample(medium, std::size_t(64) << 20, ThreadsFor(3));
    ASSERT_EQ(native.GetCoarsening(), 1);
    const std::array<int, 3>& dims = native.GetResolution();
    const Box& box = native.GetBox();
    const Vec3 cell = box.Extent() /
      Vec3(static_cast<float>(dims[0]), static_cast<float>(dims[1]), static_cast<float>(dims[2]));
    int bending = 0, differing = 0;
    for (int k = 0; k < dims[2]; ++k)
      for (int j = 0; j < dims[1]; ++j)
        for (int i = 0; i < dims[0]; ++i)
        {
          const float own = classified.GetOpacity().Extinction(
            scalars->GetValues()[(static_cast<std::size_t>(k) * dims[1] + j) * dims[0] + i]);
          const Vec3 lower = box.lower +
            Vec3(static_cast<float>(i), static_cast<float>(j), static_cast<float>(k)) * cell;
          const Box region{ lower, lower + cell };
          if (density->BendsWithinNativeCell(i, j, k, region))
          {
            ++bending;
            differing += static_cast<float>(density->DensityField::NativeMean(
                           i, j, k, region, medium.Bounds, NativeMediumGrid::BendSamples)) != own;
          }
          differing += native.GetDensity().At(i, j, k) != own;
        }
    EXPECT_GT(bending, 1000) << (cells ? "cells" : "points");
    EXPECT_EQ(differing, 0) << (cells ? "cells" : "points");
  }
}

TEST(ReconstructionParts, NativeMediumGridAveragesTheCellsWhereTheFunctionBends)
{
  // Where a cell's scalars span one of the function's points, its
  // extinction is its mean over the cell (interpolated from the 27 points
  // around the cell as evaluating them gives, integrated along one axis:
  // ClassifiedDensity::NativeMean()), not the function at the cell's own
  // scalar (the grid's point, where the field peaks); elsewhere the
  // function at its scalar.
  const Medium waves = ClassifiedWaves(40);
  const auto& classified = static_cast<const ClassifiedDensity&>(*waves.Density);
  NativeMediumGrid native;
  native.Sample(waves, std::size_t(64) << 20, SerialFor());
  const Box& box = native.GetBox();
  const Vec3 cell = box.Extent() / Vec3(40.f);
  int bending = 0, averaged = 0;
  double worst = 0.0, worstSampled = 0.0;
  for (int k = 0; k < 40; ++k)
    for (int j = 0; j < 40; ++j)
      for (int i = 0; i < 40; ++i)
      {
        const float atScalar = classified.GetOpacity().Extinction(native.ScalarAt(i, j, k));
        const Vec3 lower = box.lower +
          Vec3(static_cast<float>(i), static_cast<float>(j), static_cast<float>(k)) * cell;
        // The grid asks it from the 27 points directly: the same answer.
        ASSERT_EQ(classified.BendsWithinNativeCell(i, j, k, Box{ lower, lower + cell }),
          classified.BendsWithin(Box{ lower, lower + cell }))
          << i << " " << j << " " << k;
        if (classified.BendsWithin(Box{ lower, lower + cell }))
        {
          ++bending;
          const float mean = native.GetDensity().At(i, j, k);
          averaged += mean != atScalar ? 1 : 0;
          // Brick by brick, the same float as the cell's own NativeMean().
          ASSERT_EQ(mean,
            static_cast<float>(classified.NativeMean(
              i, j, k, Box{ lower, lower + cell }, waves.Bounds, NativeMediumGrid::BendSamples)))
            << i << " " << j << " " << k;
          // The cell's mean of the field as evaluating it gives: against
          // 16^3 samples, and closer than 4^3 samples.
          const double dense = classified.DensityField::NativeMean(
            i, j, k, Box{ lower, lower + cell }, waves.Bounds, 16);
          const double sampled = classified.DensityField::NativeMean(
            i, j, k, Box{ lower, lower + cell }, waves.Bounds, 4);
          // Relative to the largest extinction over the cell's 27 points.
          float lo = native.ScalarAt(i, j, k), hi = lo;
          for (int z = std::max(k - 1, 0); z <= std::min(k + 1, 39); ++z)
            for (int y = std::max(j - 1, 0); y <= std::min(j + 1, 39); ++y)
              for (int x = std::max(i - 1, 0); x <= std::min(i + 1, 39); ++x)
              {
                lo = std::min(lo, native.ScalarAt(x, y, z));
                hi = std::max(hi, native.ScalarAt(x, y, z));
              }
          const double largest = classified.GetOpacity().MaxExtinction(lo, hi);
          worst = std::max(worst, std::abs(mean - dense) / largest);
          worstSampled = std::max(worstSampled, std::abs(sampled - dense) / largest);
        }
        else
        {
          ASSERT_EQ(native.GetDensity().At(i, j, k), atScalar) << i << " " << j << " " << k;
        }
      }
  EXPECT_GT(bending, 1000);
  EXPECT_GT(averaged, bending / 2);
  std::cout << "largest difference from 16^3 samples, over the cell's largest extinction: " << worst
            << " (4^3 samples: " << worstSampled << ")\n";
  EXPECT_LT(worst, 4e-3);
}

TEST(ReconstructionParts, DirectTextureSupportsMediaAndPlanarSurfacesWithoutMirrors)
{
  Medium fog;
  fog.Name = "fog";
  fog.Bounds = Box{ Vec3(0.f), Vec3(1.f) };
  EXPECT_TRUE(DirectTexture::Supports(ObjectLayout(fog, { 2, 2, 2 }, 1)));
  const Surface wall = Square(Material());
  EXPECT_TRUE(DirectTexture::Supports(ObjectLayout(wall, MakeChart(wall, nullptr), { 2, 2 }, 1)));
  Material mirror;
  mirror.Type = MaterialType::Mirror;
  const Surface glass = Square(mirror);
  EXPECT_FALSE(
    DirectTexture::Supports(ObjectLayout(glass, MakeChart(glass, nullptr), { 2, 2 }, 1)));
  DirectTexture direct;
  direct.Enable(ObjectLayout(fog, { 2, 2, 2 }, 1), nullptr, { 4, 4, 4 });
  EXPECT_FALSE(direct.IsEnabled()); // no light
  EXPECT_FALSE(direct.HasArrivals());
}

TEST(ReconstructionParts, AWallOfUniformHitsShowsItsIrradianceUnbiased)
{
  // Hits spread uniformly over a Lambertian square, each texel holding
  // about the threshold's number of them: the texture's mean is rho E / pi
  // within the standard error of independent trials (each its own hits, a
  // Poisson count). Regions grown on the hits they average would read it
  // 5-7 % too bright here (DensityEstimation.RegionsGrownOnTheOtherHalfAreUnbiased).
  Surface wall;
  wall.Name = "wall";
  wall.Vertices = { { -1, -1, 0 }, { 1, -1, 0 }, { 1, 1, 0 }, { -1, 1, 0 } };
  wall.Triangles = { { 0, 1, 2 }, { 0, 2, 3 } };
  wall.Mat.Reflectance = Vec3(0.5f);
  const int res = 16;
  const double hitsPerTexel = 16.0, flux = 1e-3;
  const double expected = 0.5 / Pi * (hitsPerTexel * res * res * flux) / 4.0;
  const int trials = 1000;
  double sum = 0.0, sum2 = 0.0;
  for (int trial = 0; trial < trials; ++trial)
  {
    Random rng(91, static_cast<std::uint64_t>(trial));
    HitStore store;
    for (double time = -std::log(1.0 - rng.NextDouble()); time < hitsPerTexel * res * res;
         time -= std::log(1.0 - rng.NextDouble()))
    {
      const float p[3] = { static_cast<float>(2.0 * rng.NextDouble() - 1.0),
        static_cast<float>(2.0 * rng.NextDouble() - 1.0), 0.f };
      store.Position.insert(store.Position.end(), p, p + 3);
      store.Direction.insert(store.Direction.end(), { 0.f, 0.f, -1.f });
      store.Flux.insert(store.Flux.end(), 3, static_cast<float>(flux));
      store.Object.push_back(0);
      store.Triangle.push_back(p[1] > p[0] ? 1 : 0);
      store.Emitter.push_back(0);
      store.Depth.push_back(1);
    }
    std::vector<std::uint32_t> index(store.Object.size());
    std::iota(index.begin(), index.end(), 0u);
    ObjectRadiance radiance(wall, MakeChart(wall, nullptr), { res, res }, 2);
    radiance.Options().ParticleFlux = flux;
    ASSERT_EQ(radiance.Build(store.View(), index.data(), index.size(), { 0, 0, 5 },
                hitsPerTexel * flux, SerialFor()),
      "");
    const TextureView texture = radiance.GetTexture();
    ASSERT_EQ(texture.Radiance.size(), static_cast<std::size_t>(3 * res * res));
    double mean = 0.0;
    for (int t = 0; t < res * res; ++t)
    {
      mean += texture.Radiance[3 * t] / (res * res * expected);
    }
    sum += mean;
    sum2 += mean * mean;
  }
  const double mean = sum / trials;
  const double error = std::sqrt((sum2 / trials - mean * mean) / (trials - 1));
  std::printf("texture mean over rho E / pi: %.4f +- %.4f\n", mean, error);
  EXPECT_NEAR(mean, 1.0, 4.0 * error);
}

namespace
{
// An albedo factor of `low` on x < Step, `high` beyond.
class SteppedAlbedo : public AlbedoField
{
public:
  SteppedAlbedo(const Vec3& low, const Vec3& high)
    : Low(low)
    , High(high)
  {
  }
  Vec3 Evaluate(const Vec3& p) const override { return p.x < Step ? this->Low : this->High; }
  static constexpr float Step = 0.5f;

private:
  Vec3 Low, High;
};

// A medium of density 1 over [0, 1]^3 (8 cells along x), sigma_t 1 and
// albedo 1 times `albedo`'s factor (none: 1), asymmetry g.
Medium UnitFog(std::shared_ptr<const AlbedoField> albedo, float g)
{
  Medium fog;
  fog.Name = "fog";
  fog.SigmaA = Vec3(0.f);
  fog.SigmaS = Vec3(1.f);
  fog.G = g;
  fog.SetDensity(std::make_shared<GridDensity>(
    Box{ Vec3(0.f), Vec3(1.f) }, std::array<int, 3>{ 8, 1, 1 }, std::vector<float>(8, 1.f), true));
  fog.AlbedoFactor = std::move(albedo);
  return fog;
}

// Hits at uniform places in [0, 1]^3 (a Poisson count of mean `mean`),
// travelling along +z, flux `low` on x < SteppedAlbedo::Step, `high` beyond.
HitStore UniformHits(double mean, float low, float high, std::uint64_t stream)
{
  HitStore store;
  Random rng(57, stream);
  for (double time = -std::log(1.0 - rng.NextDouble()); time < mean;
       time -= std::log(1.0 - rng.NextDouble()))
  {
    const float p[3] = { rng.NextFloat(), rng.NextFloat(), rng.NextFloat() };
    const float f = p[0] < SteppedAlbedo::Step ? low : high;
    store.Position.insert(store.Position.end(), p, p + 3);
    store.Direction.insert(store.Direction.end(), { 0.f, 0.f, 1.f });
    store.Flux.insert(store.Flux.end(), 3, f);
    store.Object.push_back(0);
    store.Triangle.push_back(0);
    store.Emitter.push_back(0);
    store.Depth.push_back(1);
  }
  return store;
}
}

TEST(ReconstructionParts, AnAlbedoStepInsideARegionKeepsTheLightItsHitsScattered)
{
  // The albedo steps inside the one texel, and so does the light the hits
  // bring (high where the albedo is, as multiple scattering makes it): 1
  // on the left half, 1/4 on the right. A renderer draws sigma_t a(x) S;
  // over the texel that must be what its hits scattered, sum(a p Phi), so
  // S = sum(a p Phi) / integral of sigma_t a: in expectation
  // lambda p (a_L Phi_L + a_R Phi_R) / (a_L + a_R) for lambda hits per unit
  // volume. The mean of the light times the albedo, lambda p (Phi_L + Phi_R) / 2,
  // would lose the covariance of the two: red (a = 1 | 0.2) 0.625 against
  // 0.875 of lambda p, blue (0.2 | 1) 0.625 against 0.375. Isotropic (the
  // hits binned as they come) and g = 0.3 toward an eye far along +z (the
  // hits kept, each weighted by HG(0.3) at 0 degrees), within four of the
  // estimate's standard errors (a Poisson sum's: the root of its squared
  // terms). Also with the density's grid coarsened to one cell (its memory
  // too small for more), whose factor is then its field cells' mean
  // weighted by the density: its hits carry their field cell's (its
  // centre's factor, 0.2 in red, would read the texel 3 times too bright).
  const Vec3 low(1.f, 0.6f, 0.2f), high(0.2f, 0.6f, 1.f);
  const float lowFlux = 1.f, highFlux = 0.25f;
  const double lambda = 40000.0;
  for (const bool coarsened : { false, true })
    for (const float g : { 0.f, 0.3f })
    {
      const Medium fog = UnitFog(std::make_shared<SteppedAlbedo>(low, high), g);
      const HitStore store = UniformHits(lambda, lowFlux, highFlux, 1);
      std::vector<std::uint32_t> index(store.Object.size());
      std::iota(index.begin(), index.end(), 0u);
      ObjectRadiance radiance(fog, { 1, 1, 1 }, 2);
      radiance.Options().ParticleFlux = 1.0;
      if (coarsened)
      {
        radiance.Options().NativeMemory = 1;
      }
      const Vec3 eye(0.5f, 0.5f, 1e6f);
      ASSERT_EQ(
        radiance.Build(store.View(), index.data(), index.size(), eye, 1e9, SerialFor()), "");
      ASSERT_EQ(radiance.GetNative().GetCoarsening(), coarsened ? 8 : 1);
      const TextureView texture = radiance.GetTexture();
      ASSERT_EQ(texture.Radiance.size(), 3u);
      const double p = g == 0.f ? Inv4Pi : HenyeyGreenstein(g).Evaluate(1.f);
      for (int c = 0; c < 3; ++c)
      {
        const double aL = low[c], aR = high[c];
        const double expected = lambda * p * (aL * lowFlux + aR * highFlux) / (aL + aR);
        double squares = 0.0;
        for (std::size_t i = 0; i < index.size(); ++i)
        {
          const double term =
            p * store.Flux[3 * i] * (store.Position[3 * i] < SteppedAlbedo::Step ? aL : aR);
          squares += term * term;
        }
        const double error = std::sqrt(squares) / (0.5 * (aL + aR));
        EXPECT_NEAR(texture.Radiance[static_cast<std::size_t>(c)], expected, 4.0 * error)
          << (coarsened ? "coarsened, " : "") << "g " << g << ", channel " << c
          << ": the mean of the light alone gives " << lambda * p * 0.5 * (lowFlux + highFlux);
      }
    }
}

TEST(ReconstructionParts, AnAlbedoAlikeEverywhereLeavesTheRegionsAndTheTexture)
{
  // An albedo factor of 1/2 everywhere scales each hit's scattered light
  // and the extinction it is divided by alike: the texture is the one of no
  // factor, texel by texel (regions grow by the incident flux, which a kept
  // hit's growth scale restores), binned as the hits come and kept.
  for (const float g : { 0.f, 0.3f })
  {
    const HitStore store = UniformHits(20000.0, 1.f, 0.25f, 2);
    std::vector<std::uint32_t> index(store.Object.size());
    std::iota(index.begin(), index.end(), 0u);
    std::vector<float> textures[2];
    for (int withFactor = 0; withFactor < 2; ++withFactor)
    {
      const Medium fog =
        UnitFog(withFactor ? std::make_shared<SteppedAlbedo>(Vec3(0.5f), Vec3(0.5f)) : nullptr, g);
      ObjectRadiance radiance(fog, { 6, 6, 6 }, 2);
      radiance.Options().ParticleFlux = 1.0;
      ASSERT_EQ(radiance.Build(store.View(), index.data(), index.size(), Vec3(0.5f, 0.5f, 4.f),
                  40.0, SerialFor()),
        "");
      textures[withFactor] = radiance.GetTexture().Radiance;
    }
    ASSERT_EQ(textures[0].size(), textures[1].size());
    int differing = 0;
    for (std::size_t t = 0; t < textures[0].size(); ++t)
    {
      differing += std::abs(textures[1][t] - textures[0][t]) > 1e-5f * textures[0][t] ? 1 : 0;
    }
    EXPECT_EQ(differing, 0) << "g " << g;
  }
}
