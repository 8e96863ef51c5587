// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeFieldCache.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkNew.h"

#include <algorithm>
#include <iterator>

namespace vtkBrumeSceneConversionInternals
{
namespace
{
bool Same(const brume::Vec3& a, const brume::Vec3& b)
{
  return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
}

bool SameFunction(const brume::OpacityTransferFunction& a, const brume::OpacityTransferFunction& b)
{
  const auto& x = a.GetNodes();
  const auto& y = b.GetNodes();
  if (x.size() != y.size() || a.GetUnitDistance() != b.GetUnitDistance())
  {
    return false;
  }
  for (std::size_t i = 0; i < x.size(); ++i)
  {
    if (x[i].Scalar != y[i].Scalar || x[i].Opacity != y[i].Opacity)
    {
      return false;
    }
  }
  return true;
}

void ArrayDeleted(vtkObject* caller, unsigned long, void*, void*)
{
  FieldCache::Instance().Forget(static_cast<vtkDataArray*>(caller));
}
}

bool FieldCache::GridKey::operator==(const GridKey& o) const
{
  return this->Array == o.Array && this->Time == o.Time && this->Component == o.Component &&
    this->Classified == o.Classified && this->Dims == o.Dims &&
    Same(this->Bounds.lower, o.Bounds.lower) && Same(this->Bounds.upper, o.Bounds.upper) &&
    this->Cells == o.Cells && this->Interpolation == o.Interpolation;
}

FieldCache& FieldCache::Instance()
{
  // Never destroyed: arrays deleted at exit still tell it.
  static FieldCache* cache = new FieldCache;
  return *cache;
}

std::shared_ptr<const brume::GridDensity> FieldCache::Grid(const GridKey& key, const MakeGrid& make)
{
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    for (const Entry& e : this->Entries)
    {
      if (e.Key == key)
      {
        return e.Grid;
      }
    }
  }
  // Made without the lock: another medium converts meanwhile.
  std::shared_ptr<const brume::GridDensity> grid = make();
  if (!grid)
  {
    return grid;
  }
  std::lock_guard<std::mutex> lock(this->Mutex);
  auto known = std::find_if(this->Entries.begin(), this->Entries.end(),
    [&](const Entry& e) { return e.Key.Array == key.Array; });
  if (known != this->Entries.end())
  {
    // The array changed, or is read otherwise: one grid per array.
    *known = Entry{ key, grid, nullptr };
    return grid;
  }
  vtkNew<vtkCallbackCommand> forget;
  forget->SetCallback(ArrayDeleted);
  key.Array->AddObserver(vtkCommand::DeleteEvent, forget);
  this->Entries.push_back(Entry{ key, grid, nullptr });
  return grid;
}

std::shared_ptr<const brume::ClassifiedDensity> FieldCache::Classified(
  const std::shared_ptr<const brume::DensityField>& scalars,
  const brume::OpacityTransferFunction& opacity, const MakeClassified& make)
{
  std::shared_ptr<const brume::ClassifiedDensity> previous;
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    for (const Entry& e : this->Entries)
    {
      if (e.Grid == scalars && e.Classified)
      {
        if (SameFunction(e.Classified->GetOpacity(), opacity))
        {
          return e.Classified;
        }
        previous = e.Classified;
      }
    }
  }
  std::shared_ptr<const brume::ClassifiedDensity> classified = make(previous.get());
  std::lock_guard<std::mutex> lock(this->Mutex);
  for (Entry& e : this->Entries)
  {
    if (e.Grid == scalars)
    {
      e.Classified = classified;
    }
  }
  return classified;
}

std::size_t FieldCache::NumberOfKeptArrays()
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  return this->Entries.size();
}

void FieldCache::Forget(vtkDataArray* array)
{
  std::vector<Entry> gone; // released after the lock
  std::lock_guard<std::mutex> lock(this->Mutex);
  auto first = std::stable_partition(this->Entries.begin(), this->Entries.end(),
    [&](const Entry& e) { return e.Key.Array != array; });
  std::move(first, this->Entries.end(), std::back_inserter(gone));
  this->Entries.erase(first, this->Entries.end());
}
}
