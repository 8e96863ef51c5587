// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeArrayBytes.h"

#include "vtkDataArray.h"

#include <cstddef>
#include <cstring>

bool vtkBrumeArrayBytes::Same(vtkDataArray* a, vtkDataArray* b)
{
  if (!a || !b || a->GetDataType() != b->GetDataType() ||
    a->GetNumberOfComponents() != b->GetNumberOfComponents() ||
    a->GetNumberOfTuples() != b->GetNumberOfTuples())
  {
    return false;
  }
  const vtkIdType n = a->GetNumberOfValues();
  return n == 0 || a->GetVoidPointer(0) == b->GetVoidPointer(0) ||
    std::memcmp(a->GetVoidPointer(0), b->GetVoidPointer(0),
      static_cast<std::size_t>(n) * static_cast<std::size_t>(a->GetDataTypeSize())) == 0;
}
