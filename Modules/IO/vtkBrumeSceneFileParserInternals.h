// SPDX-License-Identifier: BSD-3-Clause
// The scene-file parser's reader of values (errors naming the file and the
// field) and its field-data writers, shared by its two units
// (vtkBrumeSceneFileParser.cxx: the scene, surfaces, lights, camera;
// vtkBrumeSceneFileParserMedia.cxx: media and their densities). Private to
// Brume::IO.
#ifndef vtkBrumeSceneFileParserInternals_h
#define vtkBrumeSceneFileParserInternals_h

#include "vtkBrumeQuotes.h"
#include "vtkBrumeSceneConversion.h"
#include "vtkBrumeSceneFileParser.h"
#include "vtkFieldData.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"

#include <cmath>
#include <set>
#include <sstream>
#include <string>
#include <utility>

namespace vtkBrumeSceneFileParserInternals
{
constexpr double Huge = 1e12;

inline void AddTuple(vtkFieldData* fd, const char* name, const double* v, int n)
{
  vtkBrumeSceneConversion::AppendTuple(fd, name, v, n);
}

inline void AddString(vtkFieldData* fd, const char* name, const std::string& value)
{
  auto* existing = vtkStringArray::SafeDownCast(fd->GetAbstractArray(name));
  vtkSmartPointer<vtkStringArray> a = existing;
  if (!a)
  {
    a = vtkSmartPointer<vtkStringArray>::New();
    a->SetName(name);
    fd->AddArray(a);
  }
  a->InsertNextValue(value);
}
}

// Reads values with errors that name the file and the field.
class vtkBrumeSceneFileParser::Parser
{
public:
  explicit Parser(std::string file)
    : File(std::move(file))
  {
  }
  std::string Error;

  bool Fail(const std::string& path, const std::string& message)
  {
    if (this->Error.empty())
    {
      this->Error = vtkBrumeBoundQuotes(this->File + ": " + path + ": " + message);
    }
    return false;
  }

  // Only the listed keys may appear in an object.
  bool Keys(const json& j, const std::string& path, const std::set<std::string>& allowed)
  {
    if (!j.is_object())
    {
      return this->Fail(path, "expected an object");
    }
    for (auto it = j.begin(); it != j.end(); ++it)
    {
      if (!allowed.count(it.key()))
      {
        return this->Fail(path, "unknown key '" + it.key() + "'");
      }
    }
    return true;
  }

  bool Number(const json& j, const std::string& path, double& out, double lo, double hi)
  {
    if (!j.is_number())
    {
      return this->Fail(path, "expected a number");
    }
    out = j.get<double>();
    if (!std::isfinite(out) || out < lo || out > hi)
    {
      std::ostringstream os;
      os << "expected a finite number in [" << lo << ", " << hi << "], not " << out;
      return this->Fail(path, os.str());
    }
    return true;
  }

  /// A whole number in [lo, hi] (2.0 is accepted, 2.5 is not).
  bool Integer(const json& j, const std::string& path, double& out, double lo, double hi)
  {
    if (!this->Number(j, path, out, lo, hi))
    {
      return false;
    }
    if (out != std::floor(out))
    {
      std::ostringstream os;
      os << "expected a whole number in [" << lo << ", " << hi << "], not " << out;
      return this->Fail(path, os.str());
    }
    return true;
  }

  bool IntegerVector(
    const json& j, const std::string& path, double* out, int n, double lo, double hi)
  {
    if (!j.is_array() || static_cast<int>(j.size()) != n)
    {
      return this->Fail(path, "expected " + std::to_string(n) + " whole numbers");
    }
    for (int i = 0; i < n; ++i)
    {
      if (!this->Integer(j[i], path + "[" + std::to_string(i) + "]", out[i], lo, hi))
      {
        return false;
      }
    }
    return true;
  }

  bool Vector(const json& j, const std::string& path, double* out, int n, double lo, double hi)
  {
    if (!j.is_array() || static_cast<int>(j.size()) != n)
    {
      return this->Fail(path, "expected " + std::to_string(n) + " numbers");
    }
    for (int i = 0; i < n; ++i)
    {
      if (!this->Number(j[i], path + "[" + std::to_string(i) + "]", out[i], lo, hi))
      {
        return false;
      }
    }
    return true;
  }

  bool String(const json& j, const std::string& path, std::string& out)
  {
    if (!j.is_string() || j.get<std::string>().empty())
    {
      return this->Fail(path, "expected a non-empty string");
    }
    out = j.get<std::string>();
    return true;
  }

  std::string File;
};

#endif
