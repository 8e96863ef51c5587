// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeLightTracerOutput.h"

#include "vtkBrumeHitConversion.h"
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnsignedIntArray.h"
#include "vtkUnsignedShortArray.h"

#include <algorithm>
#include <cstdlib>
#include <mutex>
#include <type_traits>
#include <unordered_map>

namespace
{
using Returned = vtkBrumeLightTracerReturnedBuffers;

// Every buffer handed to an output array and not yet freed: its tracer's
// returned buffers (null once that tracer is gone), slot and size. Never
// destroyed: arrays may be freed during the process's exit.
struct HandOut
{
  Returned* Owner;
  int Slot;
  std::size_t Bytes;
};
std::mutex& HandOutMutex()
{
  static auto* mutex = new std::mutex;
  return *mutex;
}
std::unordered_map<void*, HandOut>& HandedOut()
{
  static auto* handed = new std::unordered_map<void*, HandOut>;
  return *handed;
}

// Each slot's values: bytes each, and how many a hit.
constexpr std::size_t ValueSize[Returned::Slots] = { sizeof(float), sizeof(float), sizeof(float),
  sizeof(unsigned short), sizeof(unsigned short), sizeof(unsigned char), sizeof(unsigned int),
  sizeof(unsigned char) };
constexpr int Components[Returned::Slots] = { 3, 3, 3, 1, 1, 1, 1, 1 };
}

vtkBrumeLightTracerReturnedBuffers::~vtkBrumeLightTracerReturnedBuffers()
{
  const std::lock_guard<std::mutex> lock(HandOutMutex());
  for (auto& handed : HandedOut())
  {
    if (handed.second.Owner == this)
    {
      handed.second.Owner = nullptr;
    }
  }
  for (void*& buffer : this->Buffer)
  {
    std::free(buffer);
    buffer = nullptr;
  }
}

void vtkBrumeLightTracerReturnedBuffers::SetExpecting(bool expecting)
{
  const std::lock_guard<std::mutex> lock(HandOutMutex());
  this->Expecting = expecting;
}

void vtkBrumeLightTracerReturnedBuffers::ReturnOrFree(void* buffer)
{
  {
    const std::lock_guard<std::mutex> lock(HandOutMutex());
    const auto it = HandedOut().find(buffer);
    if (it != HandedOut().end())
    {
      const HandOut h = it->second;
      HandedOut().erase(it);
      if (h.Owner && h.Owner->Expecting && !h.Owner->Buffer[h.Slot])
      {
        h.Owner->Buffer[h.Slot] = buffer;
        h.Owner->Bytes[h.Slot] = h.Bytes;
        return;
      }
    }
  }
  std::free(buffer);
}

bool vtkBrumeLightTracerOutput::Buffer::Reallocate(std::size_t values, std::size_t valueSize)
{
  void* p = std::realloc(this->Data, std::max<std::size_t>(1, values) * valueSize);
  if (!p)
  {
    return false;
  }
  this->Data = p;
  this->Capacity = values;
  return true;
}

vtkBrumeLightTracerOutput::~vtkBrumeLightTracerOutput()
{
  for (Buffer& buffer : this->Buffers)
  {
    std::free(buffer.Data);
  }
}

// f(slot, buffer) for each buffer this output has (the aim's where lights
// are aimed), or for every one.
template <typename F>
void vtkBrumeLightTracerOutput::ForEach(F&& f, bool every)
{
  for (int slot = 0; slot < Returned::Slots; ++slot)
  {
    if (slot != Returned::AimSlot || this->WithAim || every)
    {
      f(slot, this->Buffers[slot]);
    }
  }
}

std::size_t vtkBrumeLightTracerOutput::Adopt(vtkBrumeLightTracerReturnedBuffers& returned)
{
  const std::lock_guard<std::mutex> lock(HandOutMutex());
  std::size_t bytes = 0;
  this->ForEach(
    [&](int slot, Buffer& buffer)
    {
      if (returned.Buffer[slot])
      {
        // Its pages, already mapped, are written again.
        std::free(buffer.Data);
        buffer.Data = returned.Buffer[slot];
        buffer.Capacity = returned.Bytes[slot] / ValueSize[slot];
        bytes += returned.Bytes[slot];
        returned.Buffer[slot] = nullptr;
      }
    },
    true);
  return bytes;
}

void vtkBrumeLightTracerOutput::Cap(vtkIdType n)
{
  this->ForEach(
    [&](int slot, Buffer& buffer)
    {
      const std::size_t values = Components[slot] * static_cast<std::size_t>(n);
      if (buffer.Data && buffer.Capacity > values)
      {
        buffer.Reallocate(values, ValueSize[slot]); // a shrink: on failure it stays as it was
      }
    },
    true);
}

bool vtkBrumeLightTracerOutput::Resize(vtkIdType n)
{
  // Growing by half at least: a realloc that glibc cannot remap (its mmap
  // threshold rises once large blocks are freed) copies the buffer, so it
  // must not happen at every batch.
  bool ok = true;
  this->ForEach(
    [&](int slot, Buffer& buffer)
    {
      const std::size_t values = Components[slot] * static_cast<std::size_t>(n);
      ok = ok &&
        (values <= buffer.Capacity ||
          buffer.Reallocate(
            std::max(values, buffer.Capacity + buffer.Capacity / 2), ValueSize[slot]));
    });
  return ok;
}

bool vtkBrumeLightTracerOutput::Reallocate(vtkIdType n)
{
  bool ok = true;
  this->ForEach(
    [&](int slot, Buffer& buffer) {
      ok = ok && buffer.Reallocate(Components[slot] * static_cast<std::size_t>(n), ValueSize[slot]);
    });
  return ok;
}

void vtkBrumeLightTracerOutput::Write(vtkIdType offset, const std::vector<brume::Hit>& hits)
{
  float* p = this->Values<float>(Returned::PointsSlot, offset, 3);
  float* d = this->Values<float>(Returned::DirectionSlot, offset, 3);
  float* f = this->Values<float>(Returned::FluxSlot, offset, 3);
  auto* o = this->Values<unsigned short>(Returned::ObjectSlot, offset, 1);
  auto* e = this->Values<unsigned short>(Returned::EmitterSlot, offset, 1);
  auto* depth = this->Values<unsigned char>(Returned::DepthSlot, offset, 1);
  auto* triangle = this->Values<unsigned int>(Returned::TriangleSlot, offset, 1);
  for (std::size_t i = 0; i < hits.size(); ++i)
  {
    const brume::Hit& h = hits[i];
    // Element by element: std::copy of three floats is a memmove call.
    for (int a = 0; a < 3; ++a)
    {
      p[3 * i + a] = h.Position[a];
      d[3 * i + a] = h.Direction[a];
      f[3 * i + a] = h.Flux[a];
    }
    o[i] = h.Object;
    e[i] = h.Emitter;
    depth[i] = h.Depth;
    triangle[i] = h.Triangle;
  }
  if (this->WithAim)
  {
    auto* aim = this->Values<unsigned char>(Returned::AimSlot, offset, 1);
    for (std::size_t i = 0; i < hits.size(); ++i)
    {
      aim[i] = hits[i].Aim;
    }
  }
}

void vtkBrumeLightTracerOutput::Attach(
  vtkPolyData* output, vtkIdType n, vtkBrumeLightTracerReturnedBuffers* owner)
{
  this->Reallocate(n); // shrink to fit
  auto make = [&](auto array, int slot, const char* name)
  {
    Buffer& buffer = this->Buffers[slot];
    {
      const std::lock_guard<std::mutex> lock(HandOutMutex());
      HandedOut()[buffer.Data] = { owner, slot, buffer.Capacity * ValueSize[slot] };
    }
    array->SetName(name);
    array->SetNumberOfComponents(Components[slot]);
    using Value = typename std::remove_reference_t<decltype(*array)>::ValueType;
    array->SetArray(static_cast<Value*>(buffer.Data), Components[slot] * n, 0,
      vtkAbstractArray::VTK_DATA_ARRAY_USER_DEFINED);
    array->SetArrayFreeFunction(&vtkBrumeLightTracerReturnedBuffers::ReturnOrFree);
    buffer.Data = nullptr;
    buffer.Capacity = 0;
    return array;
  };
  vtkNew<vtkPoints> points;
  points->SetData(make(vtkSmartPointer<vtkFloatArray>::New(), Returned::PointsSlot, "Points"));
  output->SetPoints(points);
  vtkPointData* pd = output->GetPointData();
  pd->AddArray(make(vtkSmartPointer<vtkFloatArray>::New(), Returned::DirectionSlot,
    vtkBrumeHitConversion::DirectionName));
  pd->AddArray(make(
    vtkSmartPointer<vtkFloatArray>::New(), Returned::FluxSlot, vtkBrumeHitConversion::FluxName));
  pd->AddArray(make(vtkSmartPointer<vtkUnsignedShortArray>::New(), Returned::ObjectSlot,
    vtkBrumeHitConversion::ObjectIdName));
  pd->AddArray(make(vtkSmartPointer<vtkUnsignedShortArray>::New(), Returned::EmitterSlot,
    vtkBrumeHitConversion::EmitterIdName));
  pd->AddArray(make(vtkSmartPointer<vtkUnsignedCharArray>::New(), Returned::DepthSlot,
    vtkBrumeHitConversion::DepthName));
  pd->AddArray(make(vtkSmartPointer<vtkUnsignedIntArray>::New(), Returned::TriangleSlot,
    vtkBrumeHitConversion::TriangleIdName));
  if (this->WithAim)
  {
    pd->AddArray(make(vtkSmartPointer<vtkUnsignedCharArray>::New(), Returned::AimSlot,
      vtkBrumeHitConversion::AimName));
  }
}
