// SPDX-License-Identifier: BSD-3-Clause
// The core's one thread primitive. The core knows no thread library: the
// caller passes a ParallelFor (Brume's VTK modules pass one built on
// vtkSMPTools, see vtkBrumeSMP), and every algorithm that takes one gives
// the same result whatever the ranges it is split into.
#ifndef brume_Parallel_h
#define brume_Parallel_h

#include <cstddef>
#include <functional>

namespace brume
{

/// Runs body(begin, end) over sub-ranges of [begin, end), possibly in parallel.
using ParallelFor = std::function<void(
  std::size_t, std::size_t, const std::function<void(std::size_t, std::size_t)>&)>;

/// A ParallelFor that runs everything on the calling thread.
ParallelFor SerialFor();

} // namespace brume

#endif
