// SPDX-License-Identifier: BSD-3-Clause
// VTK arrays and the core's buffers over one memory. Private to Brume::Conversion.
#ifndef vtkBrumeSharedArray_h
#define vtkBrumeSharedArray_h

#include "vtkSmartPointer.h"

#include "brume/FloatBuffer.h" // brume::FloatBuffer, brume::TypedValues

#include <memory>

class vtkDataArray;
class vtkFloatArray;

namespace vtkBrumeSharedArray
{
/**
 * A vtkFloatArray of one component over `buffer`'s floats, without a copy:
 * the array holds a share of the buffer until it is deleted or given other
 * memory (its free function lets go of the share), so either may outlive
 * the other. A 512^3 grid's samples are then in memory once, whether the
 * reconstruction's output is kept by a pipeline, a ParaView proxy or the
 * user.
 */
vtkSmartPointer<vtkFloatArray> Share(const brume::FloatBuffer& buffer, const char* name);

/**
 * A VTK array of one component over `values` in their own type
 * (vtkFloatArray, vtkUnsignedCharArray, vtkUnsignedShortArray,
 * vtkShortArray), without a copy: the array holds `keep` (what keeps the
 * values alive: the field they belong to) until it is deleted or given
 * other memory. Not for writing: the values are read in place by others.
 */
vtkSmartPointer<vtkDataArray> Lend(
  const brume::TypedValues& values, std::shared_ptr<const void> keep, const char* name);

/**
 * The values of `array` (`count` tuples) in place, in their own type,
 * where it is an array of one component of floats, unsigned 8-bit,
 * unsigned or signed 16-bit integers (vtkFloatArray, vtkUnsignedCharArray,
 * vtkUnsignedShortArray, vtkShortArray); otherwise empty values (the
 * caller converts the values itself). They do not hold the array: whoever
 * reads them keeps a reference to the array meanwhile.
 */
brume::TypedValues Borrow(vtkDataArray* array, std::size_t count);
}

#endif
