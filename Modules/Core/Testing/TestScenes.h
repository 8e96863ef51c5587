// SPDX-License-Identifier: BSD-3-Clause
// Scenes shared by the core's tests.
#ifndef brume_TestScenes_h
#define brume_TestScenes_h

#include "brume/LightTracer.h"
#include "brume/RayCaster.h"
#include "brume/Reconstruction.h"
#include "brume/Scene.h"

#include <algorithm>
#include <atomic>
#include <functional>
#include <string>
#include <thread>
#include <vector>

namespace brume
{
namespace testing
{
/// A ParallelFor that hands out ranges of three, last first: what is made
/// with it must not depend on how the work is split.
inline void Scrambled(
  std::size_t begin, std::size_t end, const std::function<void(std::size_t, std::size_t)>& body)
{
  for (std::size_t b = end; b > begin;)
  {
    const std::size_t a = b - std::min<std::size_t>(3, b - begin);
    body(a, b);
    b = a;
  }
}

/// The six faces of the closed box [-1, 1]^3 (inward normals), all of material m.
inline std::vector<Surface> ClosedBox(const Material& m)
{
  const Vec3 c[8] = { { -1, -1, -1 }, { 1, -1, -1 }, { -1, 1, -1 }, { 1, 1, -1 }, { -1, -1, 1 },
    { 1, -1, 1 }, { -1, 1, 1 }, { 1, 1, 1 } };
  // Quads counter-clockwise seen from inside.
  const int faces[6][4] = { { 0, 4, 5, 1 }, { 2, 3, 7, 6 }, { 0, 1, 3, 2 }, { 4, 6, 7, 5 },
    { 0, 2, 6, 4 }, { 1, 5, 7, 3 } };
  std::vector<Surface> walls;
  for (int f = 0; f < 6; ++f)
  {
    Surface s;
    s.Name = "wall" + std::to_string(f);
    for (int k = 0; k < 4; ++k)
    {
      s.Vertices.push_back(c[faces[f][k]]);
    }
    s.Triangles = { { 0, 1, 2 }, { 0, 2, 3 } };
    s.Mat = m;
    walls.push_back(s);
  }
  return walls;
}
/// The hits of a run in structure-of-arrays form.
struct HitStore
{
  std::vector<float> Position, Direction, Flux;
  std::vector<std::uint16_t> Object;
  std::vector<std::uint32_t> Triangle;
  std::vector<std::uint16_t> Emitter;
  std::vector<std::uint8_t> Depth;
  HitStore() = default;
  explicit HitStore(const std::vector<Hit>& hits)
  {
    for (const Hit& h : hits)
    {
      Position.insert(Position.end(), h.Position, h.Position + 3);
      Direction.insert(Direction.end(), h.Direction, h.Direction + 3);
      Flux.insert(Flux.end(), h.Flux, h.Flux + 3);
      Object.push_back(h.Object);
      Triangle.push_back(h.Triangle);
      Emitter.push_back(h.Emitter);
      Depth.push_back(h.Depth);
    }
  }
  HitArrays View() const
  {
    HitArrays a;
    a.Position = Position.data();
    a.Direction = Direction.data();
    a.Flux = Flux.data();
    a.Object = Object.data();
    a.Triangle = Triangle.data();
    a.Emitter = Emitter.data();
    a.Depth = Depth.data();
    a.Count = Object.size();
    return a;
  }
};

/// Traces particles 0 .. n - 1 of a run of n on one thread; the total power of the lights in
/// `power`.
inline std::vector<Hit> Trace(
  const Scene& scene, std::uint64_t n, const TraceSettings& settings, Vec3* power = nullptr)
{
  const RayCaster caster(scene);
  const LightTracer tracer(scene, caster, settings);
  if (power)
  {
    *power = tracer.GetTotalPower();
  }
  std::vector<Hit> hits;
  TraceCounters counters;
  for (std::uint64_t i = 0; i < n; ++i)
  {
    tracer.TraceParticle(i, n, hits, counters);
  }
  return hits;
}

/**
 * A ParallelFor over `threads` threads that splits a range into `pieces`
 * sub-ranges, which the threads take in whatever order they get to them:
 * algorithms must give the same result as with SerialFor().
 */
inline ParallelFor ThreadedFor(int threads, std::size_t pieces)
{
  return [threads, pieces](std::size_t begin, std::size_t end,
           const std::function<void(std::size_t, std::size_t)>& body)
  {
    const std::size_t n = end - begin;
    const std::size_t parts = std::max<std::size_t>(1, std::min(pieces, n));
    std::atomic<std::size_t> next{ 0 };
    auto work = [&]
    {
      for (std::size_t p = next++; p < parts; p = next++)
      {
        // The last pieces first, so that the order differs from hit order.
        const std::size_t q = parts - 1 - p;
        if (begin + n * q / parts < begin + n * (q + 1) / parts)
        {
          body(begin + n * q / parts, begin + n * (q + 1) / parts);
        }
      }
    };
    std::vector<std::thread> pool;
    for (int t = 1; t < threads; ++t)
    {
      pool.emplace_back(work);
    }
    work();
    for (std::thread& t : pool)
    {
      t.join();
    }
  };
}
} // namespace testing
} // namespace brume

#endif
