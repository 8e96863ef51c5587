// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeEvaluationTable.h"

#include "vtkDataArray.h"
#include "vtkStringArray.h"
#include "vtkType.h"

#include <fstream>

namespace
{
std::string Field(const std::string& text)
{
  if (text.find_first_of(",\"\n\r") == std::string::npos)
  {
    return text;
  }
  std::string quoted = "\"";
  for (char c : text)
  {
    quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  }
  return quoted + "\"";
}

void WriteValue(std::ostream& os, vtkAbstractArray* column, vtkIdType row)
{
  if (auto* strings = vtkStringArray::SafeDownCast(column))
  {
    os << Field(strings->GetValue(row));
  }
  else if (auto* numbers = vtkDataArray::SafeDownCast(column))
  {
    const int type = numbers->GetDataType();
    if (type != VTK_FLOAT && type != VTK_DOUBLE)
    {
      os << static_cast<long long>(numbers->GetComponent(row, 0));
    }
    else
    {
      os << numbers->GetComponent(row, 0);
    }
  }
}
}

bool vtkBrumeEvaluationTable::WriteCsv(vtkTable* table, const char* fileName, std::string& error)
{
  std::ofstream csv(fileName ? fileName : "");
  if (!csv)
  {
    error = std::string("cannot write ") + (fileName ? fileName : "(no file name)");
    return false;
  }
  for (vtkIdType c = 0; c < table->GetNumberOfColumns(); ++c)
  {
    csv << (c ? "," : "") << Field(table->GetColumnName(c) ? table->GetColumnName(c) : "");
  }
  csv << "\n";
  for (vtkIdType r = 0; r < table->GetNumberOfRows(); ++r)
  {
    for (vtkIdType c = 0; c < table->GetNumberOfColumns(); ++c)
    {
      if (c)
      {
        csv << ",";
      }
      WriteValue(csv, table->GetColumn(c), r);
    }
    csv << "\n";
  }
  csv.close();
  if (!csv)
  {
    error = std::string("could not finish writing ") + fileName;
    return false;
  }
  return true;
}
