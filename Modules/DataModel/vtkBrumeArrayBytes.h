// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeArrayBytes
 * @brief   whether two data arrays hold the same values, byte for byte
 *
 * How a renderer recognizes data it holds already (textures sent again by
 * a ParaView server, the scalars a slice mapper's atlas was filled from, a
 * transfer function's table left as it was): the same value type, the same
 * tuples of the same components, and the same bytes (the same memory is
 * not compared). Not wrapped.
 */
#ifndef vtkBrumeArrayBytes_h
#define vtkBrumeArrayBytes_h

#include "vtkBrumeDataModelModule.h" // For export macro

class vtkDataArray;

class VTKBRUMEDATAMODEL_EXPORT vtkBrumeArrayBytes
{
public:
  /// False when either is null.
  static bool Same(vtkDataArray* a, vtkDataArray* b);
};

#endif
