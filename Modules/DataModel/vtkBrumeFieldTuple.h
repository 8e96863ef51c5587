// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeFieldTuple
 * @brief   one tuple of doubles in a field array of the scene schema
 *
 * How the data model writes a setting into field data (a camera, a
 * medium's coefficients): the field array `name` replaced by one tuple of
 * `n` doubles. Not wrapped.
 */
#ifndef vtkBrumeFieldTuple_h
#define vtkBrumeFieldTuple_h

#include "vtkBrumeDataModelModule.h" // For export macro

class vtkFieldData;

class VTKBRUMEDATAMODEL_EXPORT vtkBrumeFieldTuple
{
public:
  /// Replaces the field array `name` of `fieldData` by one tuple of `n` values.
  static void Set(vtkFieldData* fieldData, const char* name, const double* values, int n);
};

#endif
