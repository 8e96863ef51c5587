// SPDX-License-Identifier: BSD-3-Clause
// vtkBrumeSceneConversion's ray casters shared while the surfaces are the same.
#include "vtkBrumeSceneConversion.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string_view>
#include <utility>
#include <vector>

namespace
{
// What SharedRayCaster() compares: every surface's vertex and triangle
// counts, and a hash of all their bytes.
struct GeometryKey
{
  std::vector<std::size_t> Counts;
  std::size_t Hash = 0;
  bool operator==(const GeometryKey& o) const
  {
    return this->Hash == o.Hash && this->Counts == o.Counts;
  }
};

static_assert(sizeof(brume::Vec3) == 3 * sizeof(float), "Vec3 is hashed as three floats");
static_assert(sizeof(std::array<std::uint32_t, 3>) == 3 * sizeof(std::uint32_t),
  "a triangle is hashed as three indices");

template <typename T>
std::size_t BytesHash(const std::vector<T>& values)
{
  return std::hash<std::string_view>()(
    std::string_view(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T)));
}

GeometryKey KeyOf(const brume::Scene& scene)
{
  GeometryKey key;
  for (const brume::Surface& surface : scene.Surfaces)
  {
    key.Counts.push_back(surface.Vertices.size());
    key.Counts.push_back(surface.Triangles.size());
    for (const std::size_t h : { BytesHash(surface.Vertices), BytesHash(surface.Triangles) })
    {
      key.Hash ^= h + 0x9e3779b97f4a7c15ULL + (key.Hash << 6) + (key.Hash >> 2);
    }
  }
  return key;
}

struct Casters
{
  std::mutex Mutex;
  std::vector<std::pair<GeometryKey, std::weak_ptr<const brume::RayCaster>>> Built;
  std::size_t Builds = 0;

  static Casters& Instance()
  {
    static Casters casters;
    return casters;
  }
};
}

std::shared_ptr<const brume::RayCaster> vtkBrumeSceneConversion::SharedRayCaster(
  const brume::Scene& scene)
{
  const GeometryKey key = KeyOf(scene);
  Casters& casters = Casters::Instance();
  std::lock_guard<std::mutex> lock(casters.Mutex);
  auto& built = casters.Built;
  built.erase(std::remove_if(built.begin(), built.end(),
                [](const std::pair<GeometryKey, std::weak_ptr<const brume::RayCaster>>& entry)
                { return entry.second.expired(); }),
    built.end());
  for (const auto& entry : built)
  {
    if (entry.first == key)
    {
      if (std::shared_ptr<const brume::RayCaster> kept = entry.second.lock())
      {
        return kept;
      }
    }
  }
  auto caster = std::make_shared<const brume::RayCaster>(scene);
  ++casters.Builds;
  if (caster->GetError().empty())
  {
    built.emplace_back(key, caster);
  }
  return caster;
}

std::size_t vtkBrumeSceneConversion::GetNumberOfRayCasterBuilds()
{
  Casters& casters = Casters::Instance();
  std::lock_guard<std::mutex> lock(casters.Mutex);
  return casters.Builds;
}
