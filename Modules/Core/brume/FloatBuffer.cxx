// SPDX-License-Identifier: BSD-3-Clause
#include "brume/FloatBuffer.h"

#include <algorithm>
#include <mutex>
#include <new>
#include <utility>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

// Under AddressSanitizer every buffer comes from operator new, at its exact
// size, so that the sanitizer sees each read past a grid's end.
#if defined(__SANITIZE_ADDRESS__)
#define BRUME_MAPPED_BUFFERS 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define BRUME_MAPPED_BUFFERS 0
#endif
#endif
#if !defined(BRUME_MAPPED_BUFFERS)
#if defined(__linux__)
#define BRUME_MAPPED_BUFFERS 1
#else
#define BRUME_MAPPED_BUFFERS 0
#endif
#endif

namespace brume
{

namespace
{
#if BRUME_MAPPED_BUFFERS
// Buffers from this size on are mapped on their own, in huge pages where offered.
constexpr std::size_t MappedBytes = std::size_t(2) << 20;

std::size_t PageBytes()
{
  static const std::size_t page = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
  return page;
}

std::size_t WholePages(std::size_t bytes)
{
  const std::size_t page = PageBytes();
  return (bytes + page - 1) / page * page;
}

/**
 * The mappings of buffers no one holds any more, kept for the next
 * Allocate() of a large buffer: a grid sampled again after an edit of its
 * transfer function is written into the pages the grid before it had
 * faulted in, where fresh pages would each be zeroed by the system first
 * (on a virtual machine, 3 of a 512^3 grid's 7 s after an edit). Kept
 * pages are given to the system to take back when it needs them
 * (MADV_FREE), and every kept mapping is unmapped as soon as a large
 * buffer is allocated that none of them serves, before it is mapped: a
 * new large buffer is never mapped beside kept ones.
 */
class MappingCache
{
public:
  static MappingCache& Get()
  {
    static MappingCache* cache = new MappingCache(); // never destroyed: buffers outlive statics
    return *cache;
  }

  // A mapping of `bytes` (whole pages): a kept one of at least half that
  // size, cut or grown to it, else a new one; null where none could be made.
  void* Take(std::size_t bytes)
  {
    std::vector<std::pair<void*, std::size_t>> released;
    void* taken = nullptr;
    std::size_t had = 0;
    {
      std::lock_guard<std::mutex> lock(this->Mutex);
      // The kept mapping closest in size among those of at least half of it;
      // the others stay for the allocations after it (a grid's scalars and
      // extinction, released and made again together), unless none serves.
      const auto distance = [&](std::size_t n) { return n > bytes ? n - bytes : bytes - n; };
      auto best = this->Kept.end();
      for (auto it = this->Kept.begin(); it != this->Kept.end(); ++it)
      {
        if (2 * it->second >= bytes &&
          (best == this->Kept.end() || distance(it->second) < distance(best->second)))
        {
          best = it;
        }
      }
      if (best != this->Kept.end())
      {
        taken = best->first;
        had = best->second;
        this->Kept.erase(best);
      }
      else
      {
        released.swap(this->Kept);
      }
    }
    for (const auto& [p, n] : released)
    {
      munmap(p, n);
    }
    if (taken && had > bytes)
    {
      munmap(static_cast<char*>(taken) + bytes, had - bytes);
    }
    else if (taken && had < bytes)
    {
      // Grown where it lies or moved: its pages keep their memory either way.
      void* grown = mremap(taken, had, bytes, MREMAP_MAYMOVE);
      if (grown == MAP_FAILED)
      {
        munmap(taken, had);
        taken = nullptr;
      }
      else
      {
        taken = grown;
      }
    }
    if (!taken)
    {
      taken = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
      if (taken == MAP_FAILED)
      {
        return nullptr;
      }
    }
#if defined(MADV_HUGEPAGE)
    madvise(taken, bytes, MADV_HUGEPAGE); // advice only: without huge pages it stays 4 kB pages
#endif
    return taken;
  }

  std::size_t Release()
  {
    std::vector<std::pair<void*, std::size_t>> released;
    {
      std::lock_guard<std::mutex> lock(this->Mutex);
      released.swap(this->Kept);
    }
    std::size_t bytes = 0;
    for (const auto& [p, n] : released)
    {
      munmap(p, n);
      bytes += n;
    }
    return bytes;
  }

  void Give(void* p, std::size_t bytes)
  {
#if defined(MADV_FREE)
    madvise(p, bytes, MADV_FREE);
#endif
    std::lock_guard<std::mutex> lock(this->Mutex);
    this->Kept.emplace_back(p, bytes);
  }

private:
  std::mutex Mutex;
  std::vector<std::pair<void*, std::size_t>> Kept;
};

// Gives a mapping back to the cache (its length may have been cut since:
// the deleter holds the length that is still mapped).
struct Unmap
{
  std::shared_ptr<std::size_t> Bytes;
  void operator()(float* p) const
  {
    if (*this->Bytes != 0)
    {
      MappingCache::Get().Give(p, *this->Bytes);
    }
  }
};
#endif
}

FloatBuffer FloatBuffer::Allocate(std::size_t n)
{
  FloatBuffer buffer;
  buffer.Count = n;
  if (n == 0)
  {
    return buffer;
  }
  if (n > static_cast<std::size_t>(-1) / sizeof(float))
  {
    throw std::bad_alloc();
  }
#if BRUME_MAPPED_BUFFERS
  if (n * sizeof(float) >= MappedBytes)
  {
    const std::size_t bytes = WholePages(n * sizeof(float));
    void* p = MappingCache::Get().Take(bytes);
    if (!p)
    {
      throw std::bad_alloc();
    }
    buffer.Memory =
      std::shared_ptr<float>(static_cast<float*>(p), Unmap{ std::make_shared<std::size_t>(bytes) });
    return buffer;
  }
#endif
  buffer.Memory = std::shared_ptr<float>(new float[n], std::default_delete<float[]>());
  return buffer;
}

std::size_t FloatBuffer::ReleaseKept()
{
#if BRUME_MAPPED_BUFFERS
  return MappingCache::Get().Release();
#else
  return 0;
#endif
}

FloatBuffer FloatBuffer::Wrap(const float* data, std::size_t n, std::shared_ptr<const void> owner)
{
  FloatBuffer buffer;
  buffer.Count = n;
  // Shares `owner`'s count; the floats are only read through it.
  buffer.Memory = std::shared_ptr<float>(std::move(owner), const_cast<float*>(data));
  return buffer;
}

void FloatBuffer::Truncate(std::size_t n)
{
  if (n >= this->Count)
  {
    return;
  }
#if BRUME_MAPPED_BUFFERS
  if (Unmap* unmap = std::get_deleter<Unmap>(this->Memory))
  {
    const std::size_t keep = WholePages(n * sizeof(float));
    if (keep < *unmap->Bytes)
    {
      munmap(reinterpret_cast<char*>(this->Memory.get()) + keep, *unmap->Bytes - keep);
      *unmap->Bytes = keep;
    }
    if (keep == 0)
    {
      this->Memory.reset();
    }
    this->Count = n;
    return;
  }
#endif
  FloatBuffer kept = Allocate(n);
  std::copy(this->begin(), this->begin() + n, kept.Data());
  *this = std::move(kept);
}

bool operator==(const FloatBuffer& a, const FloatBuffer& b)
{
  return a.Count == b.Count && std::equal(a.begin(), a.end(), b.begin());
}

TypedValues::TypedValues(FloatBuffer floats)
  : Count(floats.Size())
  , FloatValues(std::move(floats))
{
  this->Floats = this->FloatValues.Data();
}

std::size_t TypedValues::GetMemorySize() const
{
  return this->Count * (this->Kind == Type::UInt8 ? 1 : (this->Kind == Type::Float32 ? 4 : 2));
}

const void* TypedValues::Address() const
{
  switch (this->Kind)
  {
    case Type::UInt8:
      return this->Bytes8;
    case Type::UInt16:
      return this->Unsigned16;
    case Type::Int16:
      return this->Signed16;
    case Type::Float32:
      break;
  }
  return this->Floats;
}

} // namespace brume
