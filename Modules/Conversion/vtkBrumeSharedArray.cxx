// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeSharedArray.h"

#include "vtkFloatArray.h"
#include "vtkShortArray.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnsignedShortArray.h"

#include <memory>
#include <mutex>
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
  std::unordered_multimap<const void*, std::shared_ptr<float>> Held;
};
Shares& TheShares()
{
  // Never destroyed: arrays deleted at exit still let go of theirs.
  static Shares* shares = new Shares;
  return *shares;
}

void LetGo(void* memory)
{
  std::shared_ptr<float> gone; // released after the lock
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
