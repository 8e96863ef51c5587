// SPDX-License-Identifier: BSD-3-Clause
// VTK arrays and the core's buffers over one memory. Private to Brume::Conversion.
#ifndef vtkBrumeSharedArray_h
#define vtkBrumeSharedArray_h

#include "vtkSmartPointer.h"

#include "brume/FloatBuffer.h"

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
 * The values of `array` (`count` tuples) as a buffer over the array's own
 * memory, where it is a vtkFloatArray of one component; otherwise an empty
 * buffer (the caller converts the values itself). The buffer does not hold
 * the array: whoever reads it keeps a reference to the array meanwhile.
 */
brume::FloatBuffer Borrow(vtkDataArray* array, std::size_t count);
}

#endif
