// SPDX-License-Identifier: BSD-3-Clause
// Beyond the paper: directional (spherical-harmonics) radiance in media and
// progressive refinement. The basis against the addition theorem, the
// directional mode against the per-view reconstruction of the same hits, and
// progressively added particles against one run with all of them (bitwise).
#include "TestScenes.h"
#include "brume/LightTracer.h"
#include "brume/Random.h"
#include "brume/Reconstruction.h"
#include "brume/Sampling.h"
#include "brume/SphericalHarmonics.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstring>
#include <deque>
#include <memory>
#include <mutex>
#include <set>
#include <thread>

using namespace brume;

namespace
{
double Legendre(int l, double x)
{
  switch (l)
  {
    case 0:
      return 1.0;
    case 1:
      return x;
    case 2:
      return 0.5 * (3 * x * x - 1);
    default:
      return 0.5 * (5 * x * x * x - 3 * x);
  }
}

Vec3 RandomDirection(Random& rng)
{
  return SampleUniformSphere(rng.NextFloat(), rng.NextFloat());
}

// The hits of particles [first, last) of a run of `count`, as arrays.
using Hits = brume::testing::HitStore;

Hits Trace(const Scene& scene, std::uint64_t first, std::uint64_t last, std::uint64_t count)
{
  const RayCaster caster(scene);
  const LightTracer tracer(scene, caster, TraceSettings());
  std::vector<Hit> hits;
  TraceCounters counters;
  for (std::uint64_t i = first; i < last; ++i)
  {
    tracer.TraceParticle(i, count, hits, counters);
  }
  return Hits(hits);
}

// One texture per object of the scene at fixed resolutions.
std::vector<std::unique_ptr<ObjectRadiance>> Objects(const Scene& scene)
{
  std::vector<std::unique_ptr<ObjectRadiance>> objects;
  for (const Surface& s : scene.Surfaces)
  {
    objects.emplace_back(new ObjectRadiance(s, MakeChart(s, nullptr), { 12, 12 }, 2));
  }
  for (const Medium& m : scene.Media)
  {
    objects.emplace_back(new ObjectRadiance(m, { 10, 10, 10 }, 2));
  }
  return objects;
}
}

TEST(SphericalHarmonics, AdditionTheoremHolds)
{
  // sum_m Y_lm(a) Y_lm(b) = (2l + 1) / (4 pi) P_l(a . b): orthonormal basis.
  Random rng(3, 0);
  for (int trial = 0; trial < 200; ++trial)
  {
    const Vec3 a = RandomDirection(rng), b = RandomDirection(rng);
    float ya[16], yb[16];
    EvaluateSh(3, a, ya);
    EvaluateSh(3, b, yb);
    for (int l = 0; l <= 3; ++l)
    {
      double sum = 0.0;
      for (int k = l * l; k < (l + 1) * (l + 1); ++k)
      {
        sum += static_cast<double>(ya[k]) * yb[k];
      }
      EXPECT_NEAR(sum, (2 * l + 1) / (4 * M_PI) * Legendre(l, Dot(a, b)), 2e-6) << "l " << l;
    }
  }
}

TEST(SphericalHarmonics, ProjectedHenyeyGreensteinIsItsLegendreSeries)
{
  // One direction of travel w_p projected, then convolved with HG toward
  // w_o: the bands l <= 3 are sum_l g^l (2l + 1) / (4 pi) P_l(w_p . w_o),
  // the truncated series of p(w_p . w_o); with the lobe tail (mean cosine
  // 1: one direction) the whole of p is recovered.
  Random rng(5, 0);
  for (int trial = 0; trial < 50; ++trial)
  {
    const Vec3 wp = RandomDirection(rng), wo = RandomDirection(rng);
    float c[16];
    EvaluateSh(3, wp, c);
    for (const float g : { 0.f, 0.3f, -0.5f, 0.8f })
    {
      double series = 0.0;
      for (int l = 0; l <= 3; ++l)
      {
        series += std::pow(g, l) * (2 * l + 1) / (4 * M_PI) * Legendre(l, Dot(wp, wo));
      }
      EXPECT_NEAR(EvaluateHgFromSh(3, g, c, 1, wo, false), series, 1e-5);
      const double p = HenyeyGreenstein(g).Evaluate(Dot(wp, wo));
      // gL is clamped at 0.999 (a pole at 1): a few 1e-4 of difference.
      EXPECT_NEAR(EvaluateHgFromSh(3, g, c, 1, wo, true), p, 0.02 * p + 5e-4);
    }
  }
}

TEST(Directional, MatchesThePerViewReconstruction)
{
  // The default scene (a Cornell box with fog) with the fog's g varied: the
  // directional mode evaluated toward two eyes against the per-view texture
  // of the same hits and regions, and both against a per-view texture of
  // 5x more particles (the reference). Exact (up to rounding) for g = 0;
  // the truncation error grows with |g|. Up to DirectionalResolvedG only:
  // beyond, the two set different parts of the phase function's peak apart
  // (MediumScattering::GetPeak), so their voxels hold different quantities and
  // only their images compare (Brume.Evaluation.ForwardPeak, the sweep).
  std::printf("g     order  directional vs per view   vs reference: directional  per view\n");
  double previous = -1.0;
  static_assert(MediumScattering::DirectionalResolvedG >= 0.6f, "g = 0.6 must not be split");
  for (const float g : { 0.f, 0.3f, 0.6f })
  {
    Scene scene = MakeDefaultScene();
    scene.Media[0].G = g;
    ASSERT_EQ(scene.Validate(), "");
    const std::size_t o = scene.Surfaces.size();
    // g = 0 is view independent; its texture is the l = 0 term alone.
    Medium anisotropic = scene.Media[0];
    anisotropic.G = g != 0.f ? g : 1e-7f;
    const Vec3 eyes[2] = { { 0.4f, 0.3f, 3.5f }, { -2.f, 1.f, 2.5f } };
    auto build = [&](std::uint64_t particles, ObjectRadiance& fog)
    {
      const Hits hits = Trace(scene, 0, particles, particles);
      ObjectHits groups;
      ASSERT_EQ(GroupHitsByObject(hits.View(), scene.NumberOfObjects(), groups), "");
      ASSERT_EQ(fog.Build(hits.View(), groups.Index.data() + groups.Offset[o],
                  groups.Offset[o + 1] - groups.Offset[o], eyes[0], 64 * 3.0 / 200000, SerialFor()),
        "");
    };
    ObjectRadiance fog(anisotropic, { 10, 10, 10 }, 2), reference(anisotropic, { 10, 10, 10 }, 2);
    build(200000, fog);
    build(1000000, reference);
    auto relative = [](const std::vector<float>& a, const std::vector<float>& b)
    {
      double difference = 0.0, total = 0.0;
      for (std::size_t k = 0; k < a.size(); ++k)
      {
        difference += std::abs(a[k] - b[k]);
        total += b[k];
      }
      return difference / total;
    };
    for (int order = 1; order <= MaxShOrder; ++order)
    {
      ASSERT_EQ(fog.BuildDirectional(order, SerialFor()), "");
      double worst = 0.0, directionalError = 0.0, perViewError = 0.0;
      for (const Vec3& e : eyes)
      {
        fog.UpdateView(e, SerialFor());
        reference.UpdateView(e, SerialFor());
        std::vector<float> directional;
        fog.GetDirectional().Evaluate(e, directional);
        worst = std::max(worst, relative(directional, fog.GetTexture().Radiance));
        directionalError =
          std::max(directionalError, relative(directional, reference.GetTexture().Radiance));
        perViewError = std::max(
          perViewError, relative(fog.GetTexture().Radiance, reference.GetTexture().Radiance));
      }
      std::printf("%.1f   %d      %.4f                    %.4f       %.4f\n", g, order, worst,
        directionalError, perViewError);
      if (g == 0.f)
      {
        EXPECT_LT(worst, 0.02);
      }
      if (order == MaxShOrder)
      {
        EXPECT_GE(worst, previous * 0.9) << "the error should grow with g";
        previous = worst;
      }
    }
  }
}

TEST(Progressive, AddedParticlesEqualOneRunBitwise)
{
  // 2 x 6000 particles added in two steps against 12,000 at once: the
  // histograms, the textures and the directional coefficients are equal
  // bit for bit (the first step's fluxes scale by exactly 1/2).
  const Scene scene = MakeDefaultScene();
  const std::uint64_t n = 6000;
  const Hits first = Trace(scene, 0, n, n), second = Trace(scene, n, 2 * n, 2 * n);
  const Hits all = Trace(scene, 0, 2 * n, 2 * n);
  ASSERT_EQ(first.Object.size() + second.Object.size(), all.Object.size());
  const Vec3 eye(0.f, 0.f, 3.f);
  const double threshold = 16 * 3.0 / (2 * n);
  auto progressive = Objects(scene), single = Objects(scene);
  ObjectHits g1, g2, ga;
  ASSERT_EQ(GroupHitsByObject(first.View(), scene.NumberOfObjects(), g1), "");
  ASSERT_EQ(GroupHitsByObject(second.View(), scene.NumberOfObjects(), g2), "");
  ASSERT_EQ(GroupHitsByObject(all.View(), scene.NumberOfObjects(), ga), "");
  bool sawViewDependent = false;
  for (std::size_t o = 0; o < scene.NumberOfObjects(); ++o)
  {
    auto range = [&](const ObjectHits& g) { return g.Offset[o + 1] - g.Offset[o]; };
    ObjectRadiance& p = *progressive[o];
    ObjectRadiance& s = *single[o];
    ASSERT_EQ(p.Build(first.View(), g1.Index.data() + g1.Offset[o], range(g1), eye, 2 * threshold,
                SerialFor()),
      "");
    if (p.GetLayout().ViewDependent)
    {
      sawViewDependent = true;
      ASSERT_EQ(p.BuildDirectional(2, SerialFor()), "");
      ASSERT_EQ(
        s.Build(all.View(), ga.Index.data() + ga.Offset[o], range(ga), eye, threshold, SerialFor()),
        "");
      ASSERT_EQ(s.BuildDirectional(2, SerialFor()), "");
    }
    else
    {
      ASSERT_EQ(
        s.Build(all.View(), ga.Index.data() + ga.Offset[o], range(ga), eye, threshold, SerialFor()),
        "");
    }
    const std::vector<float> before = p.GetTexture().Radiance;
    ASSERT_EQ(p.Add(second.View(), g2.Index.data() + g2.Offset[o], range(g2), 0.5, eye, threshold,
                SerialFor()),
      "");
    EXPECT_EQ(p.GetBinning().GetWeightHistogram().GetValues(),
      s.GetBinning().GetWeightHistogram().GetValues())
      << o;
    EXPECT_EQ(p.GetBinning().GetValueHistogram().GetValues(),
      s.GetBinning().GetValueHistogram().GetValues())
      << o;
    EXPECT_EQ(p.GetTexture().Radiance, s.GetTexture().Radiance) << o;
    EXPECT_EQ(p.GetDirectional().GetCoefficients(), s.GetDirectional().GetCoefficients()) << o;
    const Histogram valueHistogram = s.GetBinning().GetValueHistogram();
    const auto& values = valueHistogram.GetValues();
    if (std::any_of(values.begin(), values.end(), [](double v) { return v != 0.0; }))
    {
      EXPECT_NE(p.GetTexture().Radiance, before) << o;
    }
  }
  EXPECT_TRUE(sawViewDependent);
}

TEST(Progressive, RejectsAddBeforeBuildAndBadScales)
{
  const Scene scene = MakeDefaultScene();
  auto objects = Objects(scene);
  const Hits hits = Trace(scene, 0, 2000, 2000);
  std::vector<std::uint32_t> none;
  EXPECT_NE(objects[0]->Add(hits.View(), none.data(), 0, 0.5, Vec3(0.f), 1.0, SerialFor()), "");
  ASSERT_EQ(objects[0]->Build(hits.View(), none.data(), 0, Vec3(0.f), 1.0, SerialFor()), "");
  EXPECT_NE(objects[0]->Add(hits.View(), none.data(), 0, -1.0, Vec3(0.f), 1.0, SerialFor()), "");
  EXPECT_NE(objects[0]->Add(hits.View(), none.data(), 0, NAN, Vec3(0.f), 1.0, SerialFor()), "");
  EXPECT_NE(objects[0]->BuildDirectional(2, SerialFor()), "")
    << "surfaces have no directional mode";
  EXPECT_NE(objects.back()->BuildDirectional(2, SerialFor()), "") << "the fog is not built yet";
  // A hit refers to a triangle the surface lacks: refused before anything changes.
  Hits bad = hits;
  std::vector<std::uint32_t> all(bad.Object.size());
  for (std::size_t i = 0; i < all.size(); ++i)
  {
    all[i] = static_cast<std::uint32_t>(i);
    bad.Triangle[i] = 1000000;
  }
  Surface sphere = scene.Surfaces[0];
  sphere.Vertices.push_back(Vec3(0.f, 0.f, 5.f)); // no longer planar: an atlas, TriangleId needed
  sphere.Triangles.push_back({ 0, 1, static_cast<std::uint32_t>(sphere.Vertices.size() - 1) });
  ObjectRadiance curved(sphere, MakeChart(sphere, nullptr), { 8, 8 }, 2);
  std::vector<std::uint32_t> wall;
  for (std::uint32_t i = 0; i < hits.Object.size(); ++i)
  {
    if (hits.Object[i] == 0)
    {
      wall.push_back(i);
    }
  }
  ASSERT_FALSE(wall.empty());
  ASSERT_EQ(curved.Build(hits.View(), wall.data(), wall.size(), Vec3(0.f), 1.0, SerialFor()), "");
  const std::vector<double> before = curved.GetBinning().GetValueHistogram().GetValues();
  ASSERT_TRUE(std::any_of(before.begin(), before.end(), [](double v) { return v != 0.0; }));
  EXPECT_NE(curved.Add(bad.View(), all.data(), all.size(), 0.5, Vec3(0.f), 1.0, SerialFor()), "");
  EXPECT_EQ(curved.GetBinning().GetValueHistogram().GetValues(), before);
}

namespace
{
// R "processes" as threads meeting at every reduction: each brings its
// values, the last to arrive finds the totals, every one takes them.
struct Meeting
{
  explicit Meeting(int processes)
    : Processes(processes)
  {
  }
  std::mutex Mutex;
  std::condition_variable Changed;
  int Processes;
  int Arrived = 0;
  int Left = 0;
  std::vector<std::int64_t> Totals;
};

class ThreadReduction : public HistogramReduction
{
public:
  ThreadReduction(Meeting& meeting, int rank)
    : Place(meeting)
    , Index(rank)
  {
  }
  int NumberOfProcesses() const override { return this->Place.Processes; }
  int Rank() const override { return this->Index; }
  // Each process's values at its offset in zeros, summed: the concatenation.
  void Gather(const std::vector<std::int32_t>& mine, const std::vector<std::size_t>& counts,
    std::vector<std::int32_t>& all) override
  {
    std::size_t offset = 0, total = 0;
    for (std::size_t r = 0; r < counts.size(); ++r)
    {
      offset += r < static_cast<std::size_t>(this->Index) ? counts[r] : 0;
      total += counts[r];
    }
    std::vector<std::int64_t> v(total, 0);
    std::copy(mine.begin(), mine.end(), v.begin() + static_cast<std::ptrdiff_t>(offset));
    this->Meet(v, false);
    all.assign(v.begin(), v.end());
  }
  std::int64_t Max(std::int64_t value) override
  {
    std::vector<std::int64_t> v{ value };
    this->Meet(v, true);
    return v[0];
  }
  void Sum(std::vector<std::int64_t>& values) override
  {
    this->Meet(values, false);
    this->Bytes += 2 * values.size() * sizeof(std::int64_t);
  }
  // The totals on `root`; every other process keeps its own values.
  void SumOnto(std::vector<std::int64_t>& values, int root) override
  {
    std::vector<std::int64_t> totals = values;
    this->Meet(totals, false);
    if (this->Index == root)
    {
      values.swap(totals);
    }
    this->Bytes += values.size() * sizeof(std::int64_t);
  }
  // The root's bits summed with zeros from the others.
  void Broadcast(std::vector<float>& data, int root) override
  {
    std::vector<std::int64_t> bits(data.size(), 0);
    if (this->Index == root)
    {
      for (std::size_t i = 0; i < data.size(); ++i)
      {
        std::uint32_t b;
        std::memcpy(&b, &data[i], sizeof b);
        bits[i] = b;
      }
    }
    this->Meet(bits, false);
    for (std::size_t i = 0; i < data.size(); ++i)
    {
      const auto b = static_cast<std::uint32_t>(bits[i]);
      std::memcpy(&data[i], &b, sizeof b);
    }
    this->Bytes += data.size() * sizeof(float);
  }

private:
  void Meet(std::vector<std::int64_t>& values, bool max)
  {
    Meeting& m = this->Place;
    std::unique_lock<std::mutex> lock(m.Mutex);
    m.Changed.wait(lock, [&] { return m.Left == 0; }); // the last round is read
    if (m.Arrived == 0)
    {
      m.Totals = values;
    }
    else
    {
      for (std::size_t i = 0; i < values.size(); ++i)
      {
        m.Totals[i] = max ? std::max(m.Totals[i], values[i]) : m.Totals[i] + values[i];
      }
    }
    if (++m.Arrived == m.Processes)
    {
      m.Left = m.Processes;
      m.Changed.notify_all();
    }
    else
    {
      m.Changed.wait(lock, [&] { return m.Left > 0; });
    }
    values = m.Totals;
    if (--m.Left == 0)
    {
      m.Arrived = 0;
      m.Changed.notify_all();
    }
  }
  Meeting& Place;
  int Index;
};
}

namespace
{
// Particles [0, 5000), [5000, 12000) and [12000, 20000) of a run of
// 20,000 of the default scene, for three processes, and all of them for one.
struct ThreeProcessRun
{
  const Scene scene = MakeDefaultScene();
  const std::uint64_t n = 20000;
  const std::uint64_t cut[4] = { 0, 5000, 12000, 20000 };
  const Hits all = Trace(scene, 0, n, n);
  const double threshold = 16 * 3.0 / n;
  const Vec3 eye{ 0.f, 0.f, 3.f }, other{ 1.f, 0.5f, 3.f };
};
}

TEST(Distributed, ReducedHistogramsEqualOneProcessBitwise)
{
  // Particles [0, 5000), [5000, 12000) and [12000, 20000) of a run of
  // 20,000 on three processes, against one process with all of them: every
  // histogram, texture and projection, after a build, a view change and a
  // projection. The exact sums do not depend on which process adds what.
  const ThreeProcessRun run3;
  auto run = [&](const Hits& hits, HistogramReduction* reduction)
  {
    auto objects = Objects(run3.scene);
    ObjectHits groups;
    EXPECT_EQ(GroupHitsByObject(hits.View(), run3.scene.NumberOfObjects(), groups), "");
    for (std::size_t o = 0; o < objects.size(); ++o)
    {
      objects[o]->Distribution().SetReduction(reduction);
      EXPECT_EQ(objects[o]->Build(hits.View(), groups.Index.data() + groups.Offset[o],
                  groups.Offset[o + 1] - groups.Offset[o], run3.eye, run3.threshold, SerialFor()),
        "");
      if (objects[o]->GetLayout().ViewDependent)
      {
        objects[o]->UpdateView(run3.other, SerialFor());
        EXPECT_EQ(objects[o]->BuildDirectional(3, SerialFor()), "");
      }
    }
    return objects;
  };
  Meeting meeting(3);
  std::vector<std::unique_ptr<ThreadReduction>> reductions;
  std::vector<Hits> parts;
  for (int r = 0; r < 3; ++r)
  {
    reductions.push_back(std::make_unique<ThreadReduction>(meeting, r));
    parts.push_back(Trace(run3.scene, run3.cut[r], run3.cut[r + 1], run3.n));
  }
  std::vector<std::unique_ptr<ObjectRadiance>> distributed[3];
  std::vector<std::thread> threads;
  for (int r = 1; r < 3; ++r)
  {
    threads.emplace_back([&, r] { distributed[r] = run(parts[r], reductions[r].get()); });
  }
  distributed[0] = run(parts[0], reductions[0].get());
  for (auto& t : threads)
  {
    t.join();
  }
  const auto single = run(run3.all, nullptr);
  for (std::size_t o = 0; o < single.size(); ++o)
  {
    for (const auto& process : distributed)
    {
      EXPECT_EQ(process[o]->GetBinning().GetWeightHistogram().GetValues(),
        single[o]->GetBinning().GetWeightHistogram().GetValues())
        << o;
      EXPECT_EQ(process[o]->GetBinning().GetValueHistogram().GetValues(),
        single[o]->GetBinning().GetValueHistogram().GetValues())
        << o;
      EXPECT_EQ(process[o]->GetTexture().Radiance, single[o]->GetTexture().Radiance) << o;
      EXPECT_EQ(process[o]->GetDirectional().GetCoefficients(),
        single[o]->GetDirectional().GetCoefficients())
        << o;
    }
  }
  EXPECT_GT(reductions[0]->Bytes, 0u) << "nothing was reduced";
}

TEST(Distributed, OwnersEstimateAndEveryProcessGetsTheSameTexturesBitwise)
{
  // The same three processes, each object estimated by one owner
  // (AssignOwners by EstimateCost) in the four steps of a distributed
  // build: every process ends with the textures and projections of one
  // process holding every hit; the owner alone with the histograms; and
  // the reductions move less than summing every histogram on every process.
  const ThreeProcessRun run3;
  auto run = [&](const Hits& hits, HistogramReduction* reduction, bool owners)
  {
    auto objects = Objects(run3.scene);
    ObjectHits groups;
    EXPECT_EQ(GroupHitsByObject(hits.View(), run3.scene.NumberOfObjects(), groups), "");
    std::vector<double> costs;
    for (const auto& object : objects)
    {
      costs.push_back(object->GetLayout().EstimateCost());
    }
    const std::vector<int> owner =
      AssignOwners(costs, reduction ? reduction->NumberOfProcesses() : 1);
    for (std::size_t o = 0; o < objects.size(); ++o)
    {
      objects[o]->Distribution().SetReduction(reduction);
      objects[o]->Distribution().SetOwner(owners ? owner[o] : -1);
      EXPECT_EQ(objects[o]->BuildHistograms(hits.View(), groups.Index.data() + groups.Offset[o],
                  groups.Offset[o + 1] - groups.Offset[o], run3.threshold, SerialFor()),
        "");
    }
    for (auto& object : objects)
    {
      object->SumHistograms(run3.eye, SerialFor());
    }
    for (auto& object : objects)
    {
      object->EstimateTexture(SerialFor());
    }
    for (auto& object : objects)
    {
      object->ShareTexture(SerialFor());
      if (object->GetLayout().ViewDependent)
      {
        object->UpdateView(run3.other, SerialFor());
        EXPECT_EQ(object->BuildDirectional(3, SerialFor()), "");
      }
    }
    return objects;
  };
  // The reductions outlive the objects that hold them.
  Meeting meetings[2] = { Meeting(3), Meeting(3) };
  std::vector<std::unique_ptr<ThreadReduction>> reductions[2];
  auto distribute = [&](bool owners, std::vector<std::unique_ptr<ObjectRadiance>>* out)
  {
    std::vector<std::unique_ptr<ThreadReduction>>& reduction = reductions[owners ? 0 : 1];
    std::vector<Hits> parts;
    for (int r = 0; r < 3; ++r)
    {
      reduction.push_back(std::make_unique<ThreadReduction>(meetings[owners ? 0 : 1], r));
      parts.push_back(Trace(run3.scene, run3.cut[r], run3.cut[r + 1], run3.n));
    }
    std::vector<std::thread> threads;
    for (int r = 1; r < 3; ++r)
    {
      threads.emplace_back([&, r] { out[r] = run(parts[r], reduction[r].get(), owners); });
    }
    out[0] = run(parts[0], reduction[0].get(), owners);
    for (auto& t : threads)
    {
      t.join();
    }
    std::size_t bytes = 0;
    for (const auto& process : reduction)
    {
      bytes += process->Bytes;
    }
    return bytes;
  };
  std::vector<std::unique_ptr<ObjectRadiance>> owned[3], everywhere[3];
  const std::size_t ownedBytes = distribute(true, owned);
  const std::size_t everywhereBytes = distribute(false, everywhere);
  const auto single = run(run3.all, nullptr, false);
  std::set<int> used;
  for (std::size_t o = 0; o < single.size(); ++o)
  {
    for (int r = 0; r < 3; ++r)
    {
      const ObjectRadiance& mine = *owned[r][o];
      used.insert(mine.Distribution().GetOwner());
      EXPECT_EQ(mine.Distribution().EstimatesHere(), mine.Distribution().GetOwner() == r) << o;
      EXPECT_EQ(mine.GetTexture().Radiance, single[o]->GetTexture().Radiance)
        << o << " on process " << r;
      EXPECT_EQ(
        mine.GetDirectional().GetCoefficients(), single[o]->GetDirectional().GetCoefficients())
        << o << " on process " << r;
      EXPECT_EQ(mine.GetTexture().Radiance, everywhere[r][o]->GetTexture().Radiance) << o;
      if (mine.Distribution().EstimatesHere())
      {
        EXPECT_EQ(mine.GetBinning().GetWeightHistogram().GetValues(),
          single[o]->GetBinning().GetWeightHistogram().GetValues())
          << o;
        EXPECT_EQ(mine.GetBinning().GetValueHistogram().GetValues(),
          single[o]->GetBinning().GetValueHistogram().GetValues())
          << o;
      }
      else
      {
        EXPECT_TRUE(mine.GetBinning().GetWeightHistogram().GetValues().empty()) << o;
      }
    }
  }
  EXPECT_EQ(used.size(), 3u) << "every process owns an object";
  std::printf(
    "bytes reduced: %zu with owners, %zu summing everywhere\n", ownedBytes, everywhereBytes);
  EXPECT_LT(ownedBytes, everywhereBytes);
}

TEST(Distributed, OwnersShareTheCostOutEvenly)
{
  // Largest first, each to the least loaded process, the lowest rank
  // among equals: the same owners for the same costs.
  EXPECT_EQ(AssignOwners({ 5.0, 3.0, 2.0 }, 1), (std::vector<int>{ 0, 0, 0 }));
  EXPECT_EQ(AssignOwners({ 5.0, 3.0, 2.0 }, 2), (std::vector<int>{ 0, 1, 1 }));
  EXPECT_EQ(AssignOwners({ 1.0, 1.0, 1.0, 1.0 }, 2), (std::vector<int>{ 0, 1, 0, 1 }));
  EXPECT_EQ(AssignOwners({ 1.0, 9.0 }, 4), (std::vector<int>{ 1, 0 }));
  // The default scene's objects on 2 processes: the fog's share, though
  // the largest single object, stays within the largest object of the
  // other's.
  const Scene scene = MakeDefaultScene();
  const auto objects = Objects(scene);
  std::vector<double> costs;
  for (const auto& object : objects)
  {
    costs.push_back(object->GetLayout().EstimateCost());
  }
  const std::vector<int> owners = AssignOwners(costs, 2);
  double load[2] = { 0.0, 0.0 };
  for (std::size_t o = 0; o < costs.size(); ++o)
  {
    load[owners[o]] += costs[o];
  }
  const double largest = *std::max_element(costs.begin(), costs.end());
  EXPECT_LE(std::abs(load[0] - load[1]), largest);
}

TEST(Distributed, ExactSumsAreTheDoubleSumsToRounding)
{
  // The fog's incident-flux histogram of the default scene, summed over
  // its cells, against its hits' terms summed in long double: each term is
  // rounded once by at most half a quantum (2^-41 of a particle's flux).
  const Scene scene = MakeDefaultScene();
  const std::uint64_t n = 20000;
  const Hits all = Trace(scene, 0, n, n);
  ObjectHits groups;
  ASSERT_EQ(GroupHitsByObject(all.View(), scene.NumberOfObjects(), groups), "");
  auto objects = Objects(scene);
  const std::size_t fog = scene.Surfaces.size();
  ASSERT_TRUE(scene.IsMedium(fog));
  const std::uint32_t* index = groups.Index.data() + groups.Offset[fog];
  const std::size_t count = groups.Offset[fog + 1] - groups.Offset[fog];
  const double particle = 15.0 * 0.25 * Pi / static_cast<double>(n); // the emitter's power / n
  objects[fog]->Options().ParticleFlux = particle;
  ASSERT_EQ(
    objects[fog]->Build(all.View(), index, count, Vec3(0.f, 0.f, 3.f), 16 * particle, SerialFor()),
    "");
  long double expected = 0.0L;
  for (std::size_t k = 0; k < count; ++k)
  {
    const float* f = all.View().Flux + 3 * index[k];
    expected += (static_cast<long double>(f[0]) + f[1] + f[2]) / 3.0L;
  }
  long double total = 0.0L;
  const Histogram weights = objects[fog]->GetBinning().GetWeightHistogram();
  for (double v : weights.GetValues())
  {
    total += v;
  }
  const double difference = static_cast<double>(std::abs(total - expected) / expected);
  std::printf("%zu terms: exact sums %.17Lg, long double %.17Lg, relative difference %g\n", count,
    total, expected, difference);
  EXPECT_GT(count, 1000u);
  EXPECT_LE(std::abs(total - expected),
    static_cast<long double>(count) * std::ldexp(particle, -40) + 1e-15L * expected);
}
