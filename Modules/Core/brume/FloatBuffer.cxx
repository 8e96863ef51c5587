// SPDX-License-Identifier: BSD-3-Clause
#include "brume/FloatBuffer.h"

#include <algorithm>
#include <new>

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

// Unmaps a mapping of `bytes` (its length may have been cut since: the
// deleter holds the length that is still mapped).
struct Unmap
{
  std::shared_ptr<std::size_t> Bytes;
  void operator()(float* p) const { munmap(p, *this->Bytes); }
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
  const std::size_t bytes = n * sizeof(float);
  if (bytes >= MappedBytes)
  {
    void* p = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (p == MAP_FAILED)
    {
      throw std::bad_alloc();
    }
#if defined(MADV_HUGEPAGE)
    madvise(p, bytes, MADV_HUGEPAGE); // advice only: without huge pages it stays 4 kB pages
#endif
    buffer.Memory =
      std::shared_ptr<float>(static_cast<float*>(p), Unmap{ std::make_shared<std::size_t>(bytes) });
    return buffer;
  }
#endif
  buffer.Memory = std::shared_ptr<float>(new float[n], std::default_delete<float[]>());
  return buffer;
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
    const std::size_t page = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
    const std::size_t keep = (n * sizeof(float) + page - 1) / page * page;
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
