// SPDX-License-Identifier: BSD-3-Clause
// The evaluation tables as CSV files (private to Brume::Evaluation).
#ifndef vtkBrumeEvaluationTable_h
#define vtkBrumeEvaluationTable_h

#include "vtkNew.h"
#include "vtkTable.h"

#include <string>

struct vtkBrumeEvaluationTable
{
  /// Appends an empty column of type `Array` named `name` to `table`.
  template <typename Array>
  static Array* AddColumn(vtkTable* table, const char* name)
  {
    vtkNew<Array> column;
    column->SetName(name);
    table->AddColumn(column);
    return column;
  }

  /**
   * Writes `table` as CSV: the column names, then one line per row. Strings
   * are written as they are (in double quotes when they hold a comma, a
   * quote or a line break), integer columns as integers, the others as a
   * C++ stream writes a double (6 significant digits). False, with the
   * reason in `error`, when the file cannot be written.
   */
  static bool WriteCsv(vtkTable* table, const char* fileName, std::string& error);
};

#endif
