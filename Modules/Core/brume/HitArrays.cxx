// SPDX-License-Identifier: BSD-3-Clause
#include "brume/HitArrays.h"

#include <algorithm>

namespace brume
{

std::string GroupHitsByObject(
  const HitArrays& hits, std::size_t objects, ObjectHits& groups, const ParallelFor& parallelFor)
{
  // Ids out of range fall in one more group, reported below.
  auto objectOf = [&](std::size_t i) { return std::min<std::size_t>(hits.Object[i], objects); };
  StableGrouping grouping(hits.Count, objects + 1);
  const std::vector<std::size_t>& counts = grouping.Count(objectOf, parallelFor);
  if (counts[objects] > 0)
  {
    const std::size_t i =
      static_cast<std::size_t>(std::find_if(hits.Object, hits.Object + hits.Count,
                                 [&](std::uint16_t object) { return object >= objects; }) -
        hits.Object);
    return "a particle hit refers to object " + std::to_string(hits.Object[i]) +
      " but the scene has " + std::to_string(objects) + " objects";
  }
  groups.Offset = grouping.Starts();
  groups.Offset.pop_back(); // the out-of-range group, empty
  groups.Index.resize(hits.Count);
  grouping.Place(
    groups.Offset, objectOf,
    [&](std::size_t i, std::size_t position)
    { groups.Index[position] = static_cast<std::uint32_t>(i); },
    parallelFor);
  return {};
}

} // namespace brume
