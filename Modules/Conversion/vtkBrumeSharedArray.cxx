// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeSharedArray.h"

#include "vtkFloatArray.h"
#include "vtkShortArray.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnsignedShortArray.h"

#include <cstdint>
#include <memory>
#include <mutex>
#include <type_traits>
#include <unordered_map>

namespace vtkBrumeSharedArray
{
namespace
{
// The shares held by arrays, by the memory they were given: a VTK array's
// free function receives the pointer alone.
struct Shares
{
  std::mutex Mutex;
  std::unordered_multimap<const void*, std::shared_ptr<const void>> Held;
};
Shares& TheShares()
{
  // Never destroyed: arrays deleted at exit still let go of theirs.
  static Shares* shares = new Shares;
  return *shares;
}

void LetGo(void* memory)
{
  std::shared_ptr<const void> gone; // released after the lock
  Shares& shares = TheShares();
  std::lock_guard<std::mutex> lock(shares.Mutex);
  auto it = shares.Held.find(memory);
  if (it != shares.Held.end())
  {
    gone = std::move(it->second);
    shares.Held.erase(it);
  }
}
}

vtkSmartPointer<vtkFloatArray> Share(const brume::FloatBuffer& buffer, const char* name)
{
  auto array = vtkSmartPointer<vtkFloatArray>::New();
  array->SetName(name);
  if (buffer.Empty())
  {
    return array;
  }
  float* memory = buffer.Share().get();
  {
    Shares& shares = TheShares();
    std::lock_guard<std::mutex> lock(shares.Mutex);
    shares.Held.emplace(memory, buffer.Share());
  }
  array->SetArray(memory, static_cast<vtkIdType>(buffer.Size()), 0,
    vtkAbstractArray::VTK_DATA_ARRAY_USER_DEFINED);
  array->SetArrayFreeFunction(LetGo);
  return array;
}

namespace
{
template <typename Array, typename T>
vtkSmartPointer<vtkDataArray> LendAs(
  const T* memory, std::size_t count, std::shared_ptr<const void> keep, const char* name)
{
  auto array = vtkSmartPointer<Array>::New();
  array->SetName(name);
  if (count == 0)
  {
    return array;
  }
  {
    Shares& shares = TheShares();
    std::lock_guard<std::mutex> lock(shares.Mutex);
    shares.Held.emplace(memory, std::move(keep));
  }
  // VTK's arrays take writable memory; no one writes through this one.
  array->SetArray(const_cast<T*>(memory), static_cast<vtkIdType>(count), 0,
    vtkAbstractArray::VTK_DATA_ARRAY_USER_DEFINED);
  array->SetArrayFreeFunction(LetGo);
  return array;
}
}

vtkSmartPointer<vtkDataArray> Lend(
  const brume::TypedValues& values, std::shared_ptr<const void> keep, const char* name)
{
  const std::size_t count = values.Size();
  return values.Visit(
    [&](const auto* memory) -> vtkSmartPointer<vtkDataArray>
    {
      using T = std::remove_cv_t<std::remove_pointer_t<decltype(memory)>>;
      if constexpr (std::is_same_v<T, float>)
      {
        return LendAs<vtkFloatArray>(memory, count, std::move(keep), name);
      }
      else if constexpr (std::is_same_v<T, std::uint8_t>)
      {
        return LendAs<vtkUnsignedCharArray>(memory, count, std::move(keep), name);
      }
      else if constexpr (std::is_same_v<T, std::uint16_t>)
      {
        return LendAs<vtkUnsignedShortArray>(memory, count, std::move(keep), name);
      }
      else
      {
        return LendAs<vtkShortArray>(memory, count, std::move(keep), name);
      }
    });
}

brume::TypedValues Borrow(vtkDataArray* array, std::size_t count)
{
  if (!array || array->GetNumberOfComponents() != 1 ||
    static_cast<std::size_t>(array->GetNumberOfTuples()) < count)
  {
    return {};
  }
  if (auto* floats = vtkFloatArray::FastDownCast(array))
  {
    return brume::TypedValues(brume::FloatBuffer::Wrap(floats->GetPointer(0), count, nullptr));
  }
  if (auto* bytes = vtkUnsignedCharArray::FastDownCast(array))
  {
    return brume::TypedValues::Wrap(bytes->GetPointer(0), count, nullptr);
  }
  if (auto* shorts = vtkUnsignedShortArray::FastDownCast(array))
  {
    return brume::TypedValues::Wrap(shorts->GetPointer(0), count, nullptr);
  }
  if (auto* signedShorts = vtkShortArray::FastDownCast(array))
  {
    return brume::TypedValues::Wrap(signedShorts->GetPointer(0), count, nullptr);
  }
  return {};
}
}
