// SPDX-License-Identifier: BSD-3-Clause
// vtkBrumeSceneConversion's readers of field data, shared by its two units
// (vtkBrumeSceneConversion.cxx: the collection, surfaces, lights;
// vtkBrumeSceneConversionMedia.cxx: media). Private to Brume::DataModel.
#ifndef vtkBrumeSceneConversionInternals_h
#define vtkBrumeSceneConversionInternals_h

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkStringArray.h"

#include "brume/Medium.h"
#include "brume/TransferFunction.h"
#include "brume/Vec3.h"

#include <optional>
#include <sstream>
#include <string>

class vtkImageData;

namespace vtkBrumeSceneConversionInternals
{
// Reads a field-data tuple of `n` components; false when absent.
inline bool ReadField(vtkFieldData* fd, const char* name, int n, double* values, std::string& error)
{
  vtkDataArray* a = fd ? vtkDataArray::SafeDownCast(fd->GetAbstractArray(name)) : nullptr;
  if (!a)
  {
    return false;
  }
  if (a->GetNumberOfTuples() < 1 || a->GetNumberOfComponents() != n)
  {
    std::ostringstream os;
    os << "field array '" << name << "' must have one tuple of " << n << " components";
    error = os.str();
    return false;
  }
  a->GetTuple(0, values);
  return true;
}

inline bool ReadVec3(vtkFieldData* fd, const char* name, brume::Vec3& v, std::string& error)
{
  double d[3];
  if (!ReadField(fd, name, 3, d, error))
  {
    return false;
  }
  v = { static_cast<float>(d[0]), static_cast<float>(d[1]), static_cast<float>(d[2]) };
  return true;
}

inline std::string ReadString(vtkFieldData* fd, const char* name)
{
  auto* a = fd ? vtkStringArray::SafeDownCast(fd->GetAbstractArray(name)) : nullptr;
  return a && a->GetNumberOfValues() > 0 ? a->GetValue(0) : std::string();
}

/// A medium from its image (the schema in vtkBrumeSceneConversion.h); empty
/// when valid, otherwise what is wrong.
std::string ConvertMedium(vtkImageData* image, brume::Medium& m);

/// A medium's coefficients and transfer functions as ConvertMedium reads
/// them from its field data, without its density; empty when valid.
std::string ReadMediumFunctions(vtkFieldData* fd, brume::Medium& m,
  std::optional<brume::OpacityTransferFunction>& opacity,
  std::optional<brume::ColorTransferFunction>& colors);
}

#endif
