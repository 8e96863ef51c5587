// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeFieldTuple.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkNew.h"

void vtkBrumeFieldTuple::Set(vtkFieldData* fieldData, const char* name, const double* values, int n)
{
  fieldData->RemoveArray(name);
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->SetNumberOfComponents(n);
  a->InsertNextTuple(values);
  fieldData->AddArray(a);
}
