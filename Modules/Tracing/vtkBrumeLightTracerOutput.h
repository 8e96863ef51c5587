// SPDX-License-Identifier: BSD-3-Clause
// The hit arrays of vtkBrumeLightTracer's output (private to Brume::Tracing):
// buffers grown with realloc while an execution writes them (glibc moves
// large blocks with mremap, without copying), handed to the output's VTK
// arrays, which free them through the tracer, and taken back by the next
// execution where no one references them any more, so that it writes where
// the last output's hits were (their pages already mapped: a fresh page
// costs a fault on first touch).
#ifndef vtkBrumeLightTracerOutput_h
#define vtkBrumeLightTracerOutput_h

#include "vtkType.h"

#include "brume/LightTracer.h"

#include <cstddef>
#include <vector>

class vtkPolyData;

/**
 * Where the buffers a tracer handed to its output come back. VTK frees a
 * buffer (ReturnOrFree, the arrays' free function) when no array, and no
 * array sharing its vtkBuffer (vtkDataArray::ShallowCopy), references it
 * any more; one freed while its tracer expects them (the output letting go
 * of its data just before the tracer executes) is kept for that execution
 * to write into; any other is freed. A buffer whose tracer is gone is freed.
 */
struct vtkBrumeLightTracerReturnedBuffers
{
  /// The output's hit arrays, in the order the output is given them.
  enum Slot
  {
    PointsSlot,
    DirectionSlot,
    FluxSlot,
    ObjectSlot,
    EmitterSlot,
    DepthSlot,
    TriangleSlot,
    AimSlot,
    Slots
  };

  vtkBrumeLightTracerReturnedBuffers() = default;
  /// Buffers handed out and not yet freed are freed by their arrays.
  ~vtkBrumeLightTracerReturnedBuffers();
  vtkBrumeLightTracerReturnedBuffers(const vtkBrumeLightTracerReturnedBuffers&) = delete;
  vtkBrumeLightTracerReturnedBuffers& operator=(const vtkBrumeLightTracerReturnedBuffers&) = delete;

  /// Brackets the output's letting go of its data.
  void SetExpecting(bool expecting);

  /// The free function of the output's hit arrays.
  static void ReturnOrFree(void* buffer);

  // Set under the hand-out lock (vtkBrumeLightTracerOutput.cxx).
  bool Expecting = false;
  void* Buffer[Slots] = {};
  std::size_t Bytes[Slots] = {};
};

/// The output's hit arrays while an execution writes them (45 bytes a hit).
class vtkBrumeLightTracerOutput
{
public:
  vtkBrumeLightTracerOutput() = default;
  ~vtkBrumeLightTracerOutput();
  vtkBrumeLightTracerOutput(const vtkBrumeLightTracerOutput&) = delete;
  vtkBrumeLightTracerOutput& operator=(const vtkBrumeLightTracerOutput&) = delete;

  /// Whether the hits carry the aim array (where a light is aimed).
  bool WithAim = false;

  /// Takes the buffers of the last output that came back; the bytes taken.
  std::size_t Adopt(vtkBrumeLightTracerReturnedBuffers& returned);
  /// Keeps at most room for n hits of the buffers taken back.
  void Cap(vtkIdType n);
  /// Room for n hits, growing by half at least.
  bool Resize(vtkIdType n);
  /// Room for exactly n hits (to reserve, or to shrink to fit); pages are
  /// mapped only when written.
  bool Reallocate(vtkIdType n);
  /// Writes `hits` from hit `offset` on (there must be room).
  void Write(vtkIdType offset, const std::vector<brume::Hit>& hits);
  /// Hands the first n hits to the output's arrays, which free them
  /// through `owner` (ReturnOrFree).
  void Attach(vtkPolyData* output, vtkIdType n, vtkBrumeLightTracerReturnedBuffers* owner);

private:
  // One array's values, of ValueSize bytes each (Components a hit).
  struct Buffer
  {
    void* Data = nullptr;
    std::size_t Capacity = 0; // in values
    bool Reallocate(std::size_t values, std::size_t valueSize);
  };
  template <typename F>
  void ForEach(F&& f, bool every = false);
  template <typename T>
  T* Values(int slot, vtkIdType offset, int components) const
  {
    return static_cast<T*>(this->Buffers[slot].Data) + components * offset;
  }

  Buffer Buffers[vtkBrumeLightTracerReturnedBuffers::Slots];
};

#endif
