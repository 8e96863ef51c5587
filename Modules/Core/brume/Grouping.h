// SPDX-License-Identifier: BSD-3-Clause
// A stable counting sort in parallel: items grouped by a small key, each
// group in the items' own order. Hits are grouped this way by object, and
// an object's kept hits by ranges of histogram cells.
#ifndef brume_Grouping_h
#define brume_Grouping_h

#include "brume/Parallel.h"

#include <algorithm>
#include <cstddef>
#include <memory>
#include <new>
#include <utility>
#include <vector>

namespace brume
{

/**
 * Groups n items: item k belongs to group groupOf(k) (< groups). Count()
 * counts each group's items; Place() then calls place(k, position) once per
 * item, group g's items at first[g], first[g] + 1, ... in their order, so
 * that the caller may lay the groups out as it likes (after other items, in
 * gaps). Both passes run over fixed blocks of items (as many as the items
 * and groups allow, at most MaxBlocks) in parallel: every item is read in
 * order within its block (the reads stream, the writes go to one place per
 * group and block), and the result does not depend on how parallelFor
 * splits the blocks.
 */
class StableGrouping
{
public:
  static constexpr std::size_t MaxBlocks = 64;

  StableGrouping(std::size_t n, std::size_t groups)
    : Items(n)
    , Groups(groups)
  {
    // Blocks of at least 16,384 items, and at most about 2^20 block counts.
    const std::size_t byItems = std::max<std::size_t>(1, n / 16384);
    const std::size_t byGroups = std::max<std::size_t>(1, (std::size_t(1) << 20) / (groups + 1));
    this->Blocks = std::min({ MaxBlocks, byItems, byGroups });
    this->BlockCounts.assign(this->Blocks * groups, 0);
  }

  /// Counts each group's items; returns the counts (groups of them).
  template <typename GroupOf>
  const std::vector<std::size_t>& Count(GroupOf groupOf, const ParallelFor& parallelFor)
  {
    parallelFor(0, this->Blocks,
      [&](std::size_t begin, std::size_t end)
      {
        for (std::size_t b = begin; b < end; ++b)
        {
          // Locals: the counts are size_t, as the members are.
          std::size_t* counts = this->BlockCounts.data() + b * this->Groups;
          const std::size_t blockBegin = this->BlockBegin(b), blockEnd = this->BlockBegin(b + 1);
          for (std::size_t k = blockBegin; k < blockEnd; ++k)
          {
            ++counts[groupOf(k)];
          }
        }
      });
    this->Counts.assign(this->Groups, 0);
    for (std::size_t b = 0; b < this->Blocks; ++b)
    {
      for (std::size_t g = 0; g < this->Groups; ++g)
      {
        this->Counts[g] += this->BlockCounts[b * this->Groups + g];
      }
    }
    return this->Counts;
  }

  /// The counts' prefix sums: where each group starts when the groups are
  /// laid out one after the other (groups + 1 entries).
  std::vector<std::size_t> Starts() const
  {
    std::vector<std::size_t> start(this->Groups + 1, 0);
    for (std::size_t g = 0; g < this->Groups; ++g)
    {
      start[g + 1] = start[g] + this->Counts[g];
    }
    return start;
  }

  /// After Count(): place(k, position) for every item, group g's items
  /// from first[g] on, in their order (groupOf as given to Count()).
  template <typename GroupOf, typename PlaceItem>
  void Place(const std::vector<std::size_t>& first, GroupOf groupOf, PlaceItem place,
    const ParallelFor& parallelFor)
  {
    // Each block's cursor per group: after the earlier blocks' items.
    std::vector<std::size_t> cursor(this->BlockCounts.size());
    for (std::size_t g = 0; g < this->Groups; ++g)
    {
      std::size_t position = first[g];
      for (std::size_t b = 0; b < this->Blocks; ++b)
      {
        cursor[b * this->Groups + g] = position;
        position += this->BlockCounts[b * this->Groups + g];
      }
    }
    parallelFor(0, this->Blocks,
      [&](std::size_t begin, std::size_t end)
      {
        for (std::size_t b = begin; b < end; ++b)
        {
          std::size_t* next = cursor.data() + b * this->Groups;
          const std::size_t blockBegin = this->BlockBegin(b), blockEnd = this->BlockBegin(b + 1);
          for (std::size_t k = blockBegin; k < blockEnd; ++k)
          {
            place(k, next[groupOf(k)]++);
          }
        }
      });
  }

private:
  std::size_t BlockBegin(std::size_t b) const { return this->Items * b / this->Blocks; }

  std::size_t Items;
  std::size_t Groups;
  std::size_t Blocks = 1;
  std::vector<std::size_t> BlockCounts; // Blocks x Groups
  std::vector<std::size_t> Counts;
};

/**
 * An allocator whose default construction leaves a trivial element as it
 * is: a vector of plain records sized before its elements are written
 * (std::vector<T, UninitializedAllocator<T>>(n)) is not zeroed first, and
 * its pages are first touched by the threads that write them.
 */
template <typename T>
class UninitializedAllocator : public std::allocator<T>
{
public:
  template <typename U>
  struct rebind
  {
    using other = UninitializedAllocator<U>;
  };
  UninitializedAllocator() = default;
  template <typename U>
  UninitializedAllocator(const UninitializedAllocator<U>&) noexcept
  {
  }
  template <typename U>
  void construct(U* p) noexcept
  {
    ::new (static_cast<void*>(p)) U;
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args)
  {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

} // namespace brume

#endif
