// SPDX-License-Identifier: BSD-3-Clause
#include "brume/BrickedGrid.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#include <algorithm>
#include <atomic>
#include <cmath>

namespace brume
{

namespace
{
// A grid's identity: one more for every grid sampled.
std::uint64_t NewIdentity()
{
  static std::atomic<std::uint64_t> next{ 1 };
  return next.fetch_add(1, std::memory_order_relaxed);
}

// Whether a brick's samples are all one value (it is then held as a constant).
inline bool OneValue(const float* samples)
{
  return std::all_of(
    samples, samples + BrickedGrid::BrickSamples, [&](float v) { return v == samples[0]; });
}

// How many steps ahead of its use a march asks for a point's samples:
// the shells' shadow rays spent 2026, 1774, 1650-1680 and 1660-1720 profile
// samples marching at none, 1, 4 and 8.
constexpr int PrefetchSteps = 4;

// Asks for the cache line holding `p` ahead of its use (a hint).
inline void Prefetch(const float* p)
{
#if defined(__GNUC__)
  __builtin_prefetch(p);
#else
  (void)p;
#endif
}
}

BrickedGrid BrickedGrid::Sample(const std::array<int, 3>& dims, const Box& box,
  const std::function<float(int, int, int)>& value,
  const std::function<bool(const std::array<int, 3>&, const std::array<int, 3>&)>& zeroOver,
  const ParallelFor& parallelFor, float skipped)
{
  return SampleBricks(
    dims, box,
    [&](const std::array<int, 3>& lower, float* out)
    {
      for (int k = 0; k < Size; ++k)
      {
        const int z = std::min(lower[2] + k, dims[2] - 1);
        for (int j = 0; j < Size; ++j)
        {
          const int y = std::min(lower[1] + j, dims[1] - 1);
          for (int i = 0; i < Size; ++i)
          {
            *out++ = value(std::min(lower[0] + i, dims[0] - 1), y, z);
          }
        }
      }
    },
    zeroOver, parallelFor, skipped);
}

std::vector<char> BrickedGrid::Candidates(const std::array<int, 3>& dims,
  const std::function<bool(const std::array<int, 3>&, const std::array<int, 3>&)>& zeroOver,
  const ParallelFor& parallelFor)
{
  std::array<std::size_t, 3> brickDims{};
  for (int a = 0; a < 3; ++a)
  {
    brickDims[a] = static_cast<std::size_t>(BricksAlong(dims[a]));
  }
  const std::size_t bx = brickDims[0], bxy = bx * brickDims[1];
  std::vector<char> candidate(bxy * brickDims[2], 0);
  parallelFor(0, candidate.size(),
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t b = begin; b < end; ++b)
      {
        const std::array<int, 3> lower{ static_cast<int>(b % bx) * Stride,
          static_cast<int>((b % bxy) / bx) * Stride, static_cast<int>(b / bxy) * Stride };
        std::array<int, 3> upper{};
        for (int a = 0; a < 3; ++a)
        {
          upper[a] = std::min(lower[a] + Size - 1, dims[a] - 1);
        }
        candidate[b] = zeroOver(lower, upper) ? 0 : 1;
      }
    });
  return candidate;
}

bool BrickedGrid::SameAs(const BrickedGrid& other) const
{
  for (int a = 0; a < 3; ++a)
  {
    if (this->Dims[a] != other.Dims[a] || this->Bounds.lower[a] != other.Bounds.lower[a] ||
      this->Bounds.upper[a] != other.Bounds.upper[a])
    {
      return false;
    }
  }
  return this->Identity == other.Identity && this->Samples.Data() == other.Samples.Data() &&
    this->Samples.Size() == other.Samples.Size() && this->Slots == other.Slots &&
    this->Constants == other.Constants;
}

void BrickedGrid::CopyBrick(std::size_t brick, float* out) const
{
  const std::int32_t slot = this->Slots[brick];
  if (slot < 0)
  {
    std::fill(out, out + BrickSamples, this->Constants[brick]);
    return;
  }
  const float* in = this->Samples.Data() + static_cast<std::size_t>(slot) * BrickSamples;
  std::copy(in, in + BrickSamples, out);
}

BrickedGrid BrickedGrid::SampleBricks(const std::array<int, 3>& dims, const Box& box,
  const std::function<void(const std::array<int, 3>&, float*)>& brick,
  const std::function<bool(const std::array<int, 3>&, const std::array<int, 3>&)>& zeroOver,
  const ParallelFor& parallelFor, float skipped)
{
  // The bricks that may hold a sample other than 0, in brick order.
  return SampleBricks(
    dims, box, brick, Candidates(dims, zeroOver, parallelFor), parallelFor, skipped);
}

BrickedGrid BrickedGrid::Layout(const std::array<int, 3>& dims, const Box& box, float skipped)
{
  BrickedGrid grid;
  grid.Identity = NewIdentity();
  grid.Dims = dims;
  grid.Bounds = box;
  grid.CellsPerLength =
    Vec3(static_cast<float>(dims[0]), static_cast<float>(dims[1]), static_cast<float>(dims[2])) /
    box.Extent();
  for (int a = 0; a < 3; ++a)
  {
    grid.BrickDims[a] = BricksAlong(dims[a]);
    grid.LastSample[a] = static_cast<float>(std::max(dims[a] - 1, 0));
    grid.LastBrick[a] = static_cast<float>(grid.BrickDims[a] - 1);
  }
  const std::size_t bricks =
    static_cast<std::size_t>(grid.BrickDims[0]) * grid.BrickDims[1] * grid.BrickDims[2];
  grid.Slots.assign(bricks, -1);
  grid.Constants.assign(bricks, skipped);
  return grid;
}

BrickedGrid BrickedGrid::SampleBricks(const std::array<int, 3>& dims, const Box& box,
  const std::function<void(const std::array<int, 3>&, float*)>& brick,
  const std::vector<char>& candidate, const ParallelFor& parallelFor, float skipped)
{
  BrickedGrid grid = Layout(dims, box, skipped);
  const std::size_t bricks = grid.Slots.size();
  const std::size_t bx = grid.BrickDims[0], bxy = bx * grid.BrickDims[1];
  auto brickOrigin = [&](std::size_t b)
  {
    return std::array<int, 3>{ static_cast<int>(b % bx) * Stride,
      static_cast<int>((b % bxy) / bx) * Stride, static_cast<int>(b / bxy) * Stride };
  };
  std::vector<std::size_t> sampled;
  for (std::size_t b = 0; b < bricks; ++b)
  {
    if (candidate[b])
    {
      sampled.push_back(b);
    }
  }
  // Sample them all, each told constant or not while its samples are at
  // hand, then keep those that vary, compacted in brick order.
  FloatBuffer samples = FloatBuffer::Allocate(sampled.size() * BrickSamples);
  std::vector<char> constant(sampled.size(), 0);
  parallelFor(0, sampled.size(),
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t s = begin; s < end; ++s)
      {
        float* out = samples.Data() + s * BrickSamples;
        brick(brickOrigin(sampled[s]), out);
        constant[s] = OneValue(out);
      }
    });
  std::int32_t slots = 0;
  for (std::size_t s = 0; s < sampled.size(); ++s)
  {
    const float* in = samples.Data() + s * BrickSamples;
    const std::size_t b = sampled[s];
    if (constant[s])
    {
      grid.Constants[b] = in[0];
      continue;
    }
    if (static_cast<std::size_t>(slots) != s)
    {
      std::copy(
        in, in + BrickSamples, samples.Data() + static_cast<std::size_t>(slots) * BrickSamples);
    }
    grid.Slots[b] = slots++;
  }
  samples.Truncate(static_cast<std::size_t>(slots) * BrickSamples);
  grid.Samples = std::move(samples);
  grid.Stored = static_cast<std::size_t>(slots);
  return grid;
}

BrickedGrid BrickedGrid::ResampleInPlace(BrickedGrid&& previous, const std::vector<char>& keep,
  const std::function<void(const std::array<int, 3>&, float*)>& brick,
  const std::vector<char>& candidate, const ParallelFor& parallelFor, float skipped)
{
  if (!previous.HasSamples() || (!previous.SoleOwner() && previous.Stored > 0))
  {
    // Another holds the samples (or an outline has none): a grid of its
    // own, previous's bricks copied where kept and held.
    const BrickedGrid before = std::move(previous);
    previous = BrickedGrid();
    return SampleBricks(
      before.Dims, before.Bounds,
      [&](const std::array<int, 3>& lower, float* out)
      {
        const std::size_t b = before.BrickAt(lower);
        if (keep[b] && (before.Slots[b] < 0 || before.HasSamples()))
        {
          before.CopyBrick(b, out);
          return;
        }
        brick(lower, out);
      },
      candidate, parallelFor, skipped);
  }
  BrickedGrid grid = std::move(previous);
  previous = BrickedGrid();
  grid.Identity = NewIdentity();
  const std::size_t bricks = grid.Slots.size();
  const std::size_t bx = grid.BrickDims[0], bxy = bx * grid.BrickDims[1];
  auto origin = [&](std::size_t b)
  {
    return std::array<int, 3>{ static_cast<int>(b % bx) * Stride,
      static_cast<int>((b % bxy) / bx) * Stride, static_cast<int>(b / bxy) * Stride };
  };
  // Bricks written again: those stored before, into their own slots, and
  // the candidates constant before, into a buffer of their own; in brick
  // order. Stored bricks that are no longer candidates free their slots.
  std::vector<std::size_t> own, loose;
  std::vector<std::int32_t> freed;
  for (std::size_t b = 0; b < bricks; ++b)
  {
    if (!candidate[b])
    {
      if (grid.Slots[b] >= 0)
      {
        freed.push_back(grid.Slots[b]);
      }
      grid.Slots[b] = -1;
      grid.Constants[b] = skipped;
    }
    else if (!keep[b])
    {
      (grid.Slots[b] >= 0 ? own : loose).push_back(b);
    }
  }
  std::vector<char> ownConstant(own.size(), 0);
  parallelFor(0, own.size(),
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t s = begin; s < end; ++s)
      {
        float* out = grid.Samples.Data() +
          static_cast<std::size_t>(grid.Slots[own[s]]) * static_cast<std::size_t>(BrickSamples);
        brick(origin(own[s]), out);
        ownConstant[s] = OneValue(out) ? 1 : 0;
      }
    });
  FloatBuffer looseSamples = FloatBuffer::Allocate(loose.size() * BrickSamples);
  std::vector<char> looseConstant(loose.size(), 0);
  parallelFor(0, loose.size(),
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t s = begin; s < end; ++s)
      {
        float* out = looseSamples.Data() + s * BrickSamples;
        brick(origin(loose[s]), out);
        looseConstant[s] = OneValue(out) ? 1 : 0;
      }
    });
  for (std::size_t s = 0; s < own.size(); ++s)
  {
    const std::size_t b = own[s];
    if (ownConstant[s])
    {
      grid.Constants[b] = grid.Samples[static_cast<std::size_t>(grid.Slots[b]) * BrickSamples];
      freed.push_back(grid.Slots[b]);
      grid.Slots[b] = -1;
    }
  }
  std::sort(freed.begin(), freed.end());
  // The bricks that now vary: into the freed slots, then past the last.
  std::size_t slots = grid.Stored, reused = 0, added = 0;
  for (std::size_t s = 0; s < loose.size(); ++s)
  {
    added += looseConstant[s] ? 0 : 1;
  }
  const std::size_t grown = added > freed.size() ? added - freed.size() : 0;
  if (grown > 0)
  {
    FloatBuffer larger = FloatBuffer::Allocate((slots + grown) * BrickSamples);
    std::copy(grid.Samples.begin(), grid.Samples.begin() + slots * BrickSamples, larger.Data());
    grid.Samples = std::move(larger);
  }
  for (std::size_t s = 0; s < loose.size(); ++s)
  {
    const std::size_t b = loose[s];
    const float* in = looseSamples.Data() + s * BrickSamples;
    if (looseConstant[s])
    {
      grid.Constants[b] = in[0];
      continue;
    }
    const std::int32_t slot =
      reused < freed.size() ? freed[reused++] : static_cast<std::int32_t>(slots++);
    std::copy(
      in, in + BrickSamples, grid.Samples.Data() + static_cast<std::size_t>(slot) * BrickSamples);
    grid.Slots[b] = slot;
    grid.Constants[b] = skipped;
  }
  // Slots still free: the last stored bricks move into them.
  std::vector<std::int64_t> owner(slots, -1);
  for (std::size_t b = 0; b < bricks; ++b)
  {
    if (grid.Slots[b] >= 0)
    {
      owner[static_cast<std::size_t>(grid.Slots[b])] = static_cast<std::int64_t>(b);
    }
  }
  std::size_t top = slots;
  for (std::size_t h = reused; h < freed.size(); ++h)
  {
    const std::size_t hole = static_cast<std::size_t>(freed[h]);
    while (top > 0 && owner[top - 1] < 0)
    {
      --top;
    }
    if (top == 0 || top - 1 <= hole)
    {
      break;
    }
    const std::size_t from = top - 1;
    const float* in = grid.Samples.Data() + from * BrickSamples;
    std::copy(in, in + BrickSamples, grid.Samples.Data() + hole * BrickSamples);
    grid.Slots[static_cast<std::size_t>(owner[from])] = static_cast<std::int32_t>(hole);
    owner[hole] = owner[from];
    owner[from] = -1;
  }
  while (top > 0 && owner[top - 1] < 0)
  {
    --top;
  }
  grid.Samples.Truncate(top * BrickSamples);
  grid.Stored = top;
  return grid;
}

BrickedGrid BrickedGrid::Outline(const std::array<int, 3>& dims, const Box& box,
  const std::function<void(const std::array<int, 3>&, float*)>& brick,
  const std::vector<char>& candidate, const ParallelFor& parallelFor, float skipped)
{
  BrickedGrid grid = Layout(dims, box, skipped);
  const std::size_t bricks = grid.Slots.size();
  const std::size_t bx = grid.BrickDims[0], bxy = bx * grid.BrickDims[1];
  // Each candidate evaluated into one brick's buffer: constant (its value
  // kept) or stored (marked, its slot given after, in brick order).
  std::vector<char> stored(bricks, 0);
  parallelFor(0, bricks,
    [&](std::size_t begin, std::size_t end)
    {
      float in[BrickSamples];
      for (std::size_t b = begin; b < end; ++b)
      {
        if (!candidate[b])
        {
          continue;
        }
        brick({ static_cast<int>(b % bx) * Stride, static_cast<int>((b % bxy) / bx) * Stride,
                static_cast<int>(b / bxy) * Stride },
          in);
        if (OneValue(in))
        {
          grid.Constants[b] = in[0];
        }
        else
        {
          stored[b] = 1;
        }
      }
    });
  std::int32_t slots = 0;
  for (std::size_t b = 0; b < bricks; ++b)
  {
    if (stored[b])
    {
      grid.Slots[b] = slots++;
    }
  }
  grid.Stored = static_cast<std::size_t>(slots);
  return grid;
}

std::size_t BrickedGrid::GetMemorySize() const
{
  return this->Slots.size() * sizeof(std::int32_t) + this->Constants.size() * sizeof(float) +
    this->Samples.Size() * sizeof(float);
}

float BrickedGrid::At(int i, int j, int k) const
{
  const int b[3] = { std::min(i / Stride, this->BrickDims[0] - 1),
    std::min(j / Stride, this->BrickDims[1] - 1), std::min(k / Stride, this->BrickDims[2] - 1) };
  const std::size_t brick = this->BrickIndex(b[0], b[1], b[2]);
  const std::int32_t slot = this->Slots[brick];
  if (slot < 0)
  {
    return this->Constants[brick];
  }
  const int l[3] = { i - Stride * b[0], j - Stride * b[1], k - Stride * b[2] };
  return this->Samples[static_cast<std::size_t>(slot) * BrickSamples +
    static_cast<std::size_t>((l[2] * Size + l[1]) * Size + l[0])];
}

inline std::size_t BrickedGrid::Locate(const Vec3& q, int i0[3], float w[3]) const
{
  // u: the position in samples (cell centres at integers), clamped. No
  // division: 10^8 calls march a 512^3 grid's shadow rays, so the three
  // axes go through SSE2's lanes together: the same float operations, the
  // clamps of the brick and of i0 taken before truncating (equal for the
  // non-negative values they see).
  constexpr float PerStride = 1.f / static_cast<float>(Stride);
#if defined(__SSE2__)
  const __m128 zero = _mm_setzero_ps();
  __m128 u = _mm_sub_ps(_mm_set_ps(0.f, q.z, q.y, q.x), _mm_set1_ps(0.5f));
  u = _mm_min_ps(_mm_max_ps(u, zero), _mm_load_ps(this->LastSample.data()));
  const __m128i b = _mm_cvttps_epi32(
    _mm_min_ps(_mm_mul_ps(u, _mm_set1_ps(PerStride)), _mm_load_ps(this->LastBrick.data())));
  const __m128 local =
    _mm_sub_ps(u, _mm_mul_ps(_mm_cvtepi32_ps(b), _mm_set1_ps(static_cast<float>(Stride))));
  const __m128i first = _mm_cvttps_epi32(
    _mm_min_ps(_mm_max_ps(local, zero), _mm_set1_ps(static_cast<float>(Size - 2))));
  alignas(16) int bricks[4], firsts[4];
  alignas(16) float weights[4];
  _mm_store_si128(reinterpret_cast<__m128i*>(bricks), b);
  _mm_store_si128(reinterpret_cast<__m128i*>(firsts), first);
  _mm_store_ps(weights, _mm_sub_ps(local, _mm_cvtepi32_ps(first)));
  for (int a = 0; a < 3; ++a)
  {
    i0[a] = firsts[a];
    w[a] = weights[a];
  }
  return this->BrickIndex(bricks[0], bricks[1], bricks[2]);
#else
  int b[3];
  for (int a = 0; a < 3; ++a)
  {
    float u = q[a] - 0.5f;
    u = u > 0.f ? (u < this->LastSample[a] ? u : this->LastSample[a]) : 0.f;
    b[a] = static_cast<int>(std::min(u * PerStride, this->LastBrick[a]));
    const float local = u - static_cast<float>(Stride * b[a]);
    i0[a] = static_cast<int>(std::min(std::max(local, 0.f), static_cast<float>(Size - 2)));
    w[a] = local - static_cast<float>(i0[a]);
  }
  return this->BrickIndex(b[0], b[1], b[2]);
#endif
}

float BrickedGrid::Trilinear(std::int32_t slot, const int i0[3], const float w[3]) const
{
  const float* s = this->Samples.Data() + static_cast<std::size_t>(slot) * BrickSamples +
    (i0[2] * Size + i0[1]) * Size + i0[0];
  auto row = [&](int dj, int dk)
  {
    const float* r = s + (dk * Size + dj) * Size;
    return r[0] * (1.f - w[0]) + r[1] * w[0];
  };
  const float c0 = row(0, 0) * (1.f - w[1]) + row(1, 0) * w[1];
  const float c1 = row(0, 1) * (1.f - w[1]) + row(1, 1) * w[1];
  return c0 * (1.f - w[2]) + c1 * w[2];
}

float BrickedGrid::Interpolate(const Vec3& p) const
{
  int i0[3];
  float w[3];
  const std::size_t brick = this->Locate((p - this->Bounds.lower) * this->CellsPerLength, i0, w);
  const std::int32_t slot = this->Slots[brick];
  return slot < 0 ? this->Constants[brick] : this->Trilinear(slot, i0, w);
}

int BrickedGrid::ConstantRun(const Vec3& q, const Vec3& dq, std::size_t brick, int most) const
{
  // Along each axis, the brick takes the positions (before clamping) from
  // Stride b to Stride (b + 1), beyond them at the first and last bricks.
  constexpr double Margin = 1e-3; // cells
  const std::size_t bricks[3] = { brick % static_cast<std::size_t>(this->BrickDims[0]),
    brick / static_cast<std::size_t>(this->BrickDims[0]) %
      static_cast<std::size_t>(this->BrickDims[1]),
    brick / (static_cast<std::size_t>(this->BrickDims[0]) * this->BrickDims[1]) };
  double run = most;
  for (int a = 0; a < 3; ++a)
  {
    const int b = static_cast<int>(bricks[a]);
    const double u = static_cast<double>(q[a]) - 0.5, du = dq[a];
    const bool first = b == 0, last = b == this->BrickDims[a] - 1;
    const double lo = Stride * b + Margin, hi = Stride * (b + 1) - Margin;
    if ((!first && u < lo) || (!last && u > hi))
    {
      return 0;
    }
    if (du > 0.0 && !last)
    {
      run = std::min(run, std::floor((hi - u) / du) + 1.0);
    }
    else if (du < 0.0 && !first)
    {
      run = std::min(run, std::floor((u - lo) / -du) + 1.0);
    }
  }
  return static_cast<int>(std::max(run, 0.0));
}

int BrickedGrid::ConstantSamples(const Vec3& p, const Vec3& step, int most, float& value) const
{
  // p's brick, as Interpolate() finds it.
  int i0[3];
  float w[3];
  const Vec3 q = (p - this->Bounds.lower) * this->CellsPerLength;
  const std::size_t brick = this->Locate(q, i0, w);
  if (this->Slots[brick] >= 0)
  {
    return 0;
  }
  value = this->Constants[brick];
  return this->ConstantRun(q, step * this->CellsPerLength, brick, most);
}

double BrickedGrid::SumAlong(
  const Vec3& x, const Vec3& d, float t0, float h, int n, double stop) const
{
  // A point of the march: where it lies in cells, its brick, and the
  // first of its eight samples with their weights.
  struct Point
  {
    Vec3 Q;
    std::size_t Brick;
    int I0[3];
    float W[3];
  };
  auto locate = [&](int i, Point& point)
  {
    const Vec3 p = x + d * (t0 + (static_cast<float>(i) + 0.5f) * h);
    point.Q = (p - this->Bounds.lower) * this->CellsPerLength;
    point.Brick = this->Locate(point.Q, point.I0, point.W);
  };
  const Vec3 dq = d * h * this->CellsPerLength;
  double sum = 0.0;
  Point at{}, next{};
  if (n > 0)
  {
    locate(0, at);
  }
  for (int i = 0; i < n;)
  {
    const std::int32_t slot = this->Slots[at.Brick];
    // A constant brick's value at the point and at those of its run after
    // it (none where it lies within a margin of a face: then it alone).
    const int samples = slot < 0 ? std::max(this->ConstantRun(at.Q, dq, at.Brick, n - i), 1) : 1;
    // The next point found first, and the samples of the point a few
    // steps past it asked of memory while this one's are interpolated: a
    // shadow ray's samples are mostly cache misses (the rays of a sweep
    // cross each brick once per plane). Where it lies need not be exact.
    if (i + samples < n)
    {
      locate(i + samples, next);
      int aheadI0[3];
      float aheadW[3];
      const std::size_t ahead =
        this->Locate(next.Q + dq * static_cast<float>(PrefetchSteps), aheadI0, aheadW);
      const std::int32_t aheadSlot = this->Slots[ahead];
      if (aheadSlot >= 0)
      {
        const float* s = this->Samples.Data() + static_cast<std::size_t>(aheadSlot) * BrickSamples +
          (aheadI0[2] * Size + aheadI0[1]) * Size + aheadI0[0];
        for (const int row : { 0, Size, Size * Size, Size * Size + Size })
        {
          Prefetch(s + row);
        }
      }
    }
    const float value = slot < 0 ? this->Constants[at.Brick] : this->Trilinear(slot, at.I0, at.W);
    for (int k = 0; k < samples; ++k, ++i)
    {
      sum += value;
      if (stop > 0.0 && sum > stop)
      {
        return sum;
      }
    }
    if (i < n)
    {
      at = next;
    }
  }
  return sum;
}

void BrickedGrid::ForEachNonZeroCell(const std::function<void(int, int, int, float)>& f) const
{
  this->ForEachNonZeroCellOfLayers(0, this->BrickDims[2], f);
}

} // namespace brume
