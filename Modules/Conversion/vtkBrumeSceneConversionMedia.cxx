// SPDX-License-Identifier: BSD-3-Clause
// vtkBrumeSceneConversion's media: coefficients, and the density an
// OpenVDB grid or an array gives, classified by a transfer function when
// the medium has one.
#include "vtkBrumeSceneConversionInternals.h"

#include "vtkBrumeSceneConversion.h"

#include "vtkBrumeFieldCache.h"
#include "vtkBrumeSharedArray.h"

#include "vtkArrayDispatch.h"
#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeSMP.h"
#include "vtkCellData.h"
#include "vtkDataArrayRange.h"
#include "vtkImageData.h"
#include "vtkMatrix3x3.h"
#include "vtkPointData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"

#include "brume/TransferFunction.h"
#include "brume/VdbDensity.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <utility>
#include <vector>

namespace vtkBrumeSceneConversionInternals
{
namespace
{
// The scalar-opacity transfer function of a medium's field data, if any:
// BrumeScalarOpacity (tuples of scalar and opacity) and
// BrumeScalarOpacityUnitDistance (default 1). Empty when valid or absent.
std::string ReadOpacityFunction(
  vtkFieldData* fd, std::optional<brume::OpacityTransferFunction>& function)
{
  vtkDataArray* points = fd ? fd->GetArray(vtkBrumeNames::ScalarOpacity) : nullptr;
  std::string error;
  double unit = 1.0;
  const bool hasUnit = ReadField(fd, vtkBrumeNames::ScalarOpacityUnitDistance, 1, &unit, error);
  if (!error.empty())
  {
    return error;
  }
  if (!points)
  {
    return hasUnit ? "has a BrumeScalarOpacityUnitDistance without a BrumeScalarOpacity "
                     "transfer function"
                   : std::string();
  }
  if (points->GetNumberOfComponents() != 2)
  {
    return "has a BrumeScalarOpacity that is not (scalar, opacity) pairs (2 components)";
  }
  std::vector<brume::OpacityTransferFunction::Node> nodes;
  for (vtkIdType i = 0; i < points->GetNumberOfTuples(); ++i)
  {
    nodes.push_back({ static_cast<float>(points->GetComponent(i, 0)),
      static_cast<float>(points->GetComponent(i, 1)) });
  }
  error = brume::OpacityTransferFunction::Validate(nodes, unit);
  if (!error.empty())
  {
    return "has a BrumeScalarOpacity transfer function that " + error;
  }
  function.emplace(std::move(nodes), static_cast<float>(unit));
  return {};
}

// The colour transfer function of a medium's field data, if any:
// BrumeScalarColor (tuples of scalar, red, green, blue), a factor on the
// albedo. Empty when valid or absent.
std::string ReadColorFunction(
  vtkFieldData* fd, std::optional<brume::ColorTransferFunction>& function)
{
  vtkDataArray* points = fd ? fd->GetArray(vtkBrumeNames::ScalarColor) : nullptr;
  if (!points)
  {
    return {};
  }
  if (!fd->GetArray(vtkBrumeNames::ScalarOpacity))
  {
    return "has a BrumeScalarColor without a BrumeScalarOpacity transfer function";
  }
  if (points->GetNumberOfComponents() != 4)
  {
    return "has a BrumeScalarColor that is not (scalar, red, green, blue) tuples (4 components)";
  }
  std::vector<brume::ColorTransferFunction::Node> nodes;
  for (vtkIdType i = 0; i < points->GetNumberOfTuples(); ++i)
  {
    nodes.push_back({ static_cast<float>(points->GetComponent(i, 0)),
      brume::Vec3(static_cast<float>(points->GetComponent(i, 1)),
        static_cast<float>(points->GetComponent(i, 2)),
        static_cast<float>(points->GetComponent(i, 3))) });
  }
  const std::string error = brume::ColorTransferFunction::Validate(nodes);
  if (!error.empty())
  {
    return "has a BrumeScalarColor transfer function that " + error;
  }
  function.emplace(std::move(nodes));
  return {};
}

// Both functions of a medium's field data, if any. Empty when valid or absent.
std::string ReadTransferFunctions(vtkFieldData* fd,
  std::optional<brume::OpacityTransferFunction>& opacity,
  std::optional<brume::ColorTransferFunction>& colors)
{
  const std::string error = ReadOpacityFunction(fd, opacity);
  return error.empty() ? ReadColorFunction(fd, colors) : error;
}

// `field` as the medium holds it: with a reference to the array its grid
// was read from (if any), whose memory a grid of a float array reads. The
// cache holds the grid alone, and lets it go when the array is deleted.
template <typename Field>
std::shared_ptr<Field> Holding(std::shared_ptr<Field> field, vtkDataArray* array)
{
  if (!array)
  {
    return field;
  }
  auto both = std::make_shared<std::pair<std::shared_ptr<Field>, vtkSmartPointer<vtkDataArray>>>(
    std::move(field), array);
  return std::shared_ptr<Field>(both, both->first.get());
}

// The medium's density: `scalars` (read from `array`, if any) classified
// when it has an opacity function, and its albedo coloured when it has a
// colour function too.
void SetClassified(brume::Medium& m, const std::shared_ptr<const brume::DensityField>& scalars,
  vtkDataArray* array, std::optional<brume::OpacityTransferFunction>& opacity,
  std::optional<brume::ColorTransferFunction>& colors)
{
  if (!opacity)
  {
    m.SetDensity(Holding(scalars, array));
    return;
  }
  if (colors)
  {
    m.AlbedoFactor =
      Holding(std::shared_ptr<const brume::AlbedoField>(
                std::make_shared<brume::ClassifiedAlbedo>(scalars, std::move(*colors))),
        array);
  }
  m.SetDensity(
    Holding(vtkBrumeSceneConversionInternals::FieldCache::Instance().Classified(scalars, *opacity,
              [&](const brume::ClassifiedDensity* previous)
              {
                return std::make_shared<const brume::ClassifiedDensity>(
                  scalars, *opacity, vtkBrumeSMP::ParallelFor(), previous);
              }),
      array));
}

// The medium's coefficients (BrumeSigmaA, BrumeSigmaS, BrumeG), scaled by
// BrumeDensityScale. Empty when valid.
std::string ReadCoefficients(vtkFieldData* fd, brume::Medium& m)
{
  std::string error;
  if (!ReadVec3(fd, vtkBrumeNames::SigmaA, m.SigmaA, error) ||
    !ReadVec3(fd, vtkBrumeNames::SigmaS, m.SigmaS, error))
  {
    return error.empty() ? "lacks the BrumeSigmaA or BrumeSigmaS field array" : error;
  }
  double g = 0.0;
  if (ReadField(fd, vtkBrumeNames::G, 1, &g, error))
  {
    m.G = static_cast<float>(g);
  }
  double scale = 1.0;
  ReadField(fd, vtkBrumeNames::DensityScale, 1, &scale, error);
  if (!error.empty())
  {
    return error;
  }
  if (!(scale >= 0.0) || !std::isfinite(scale))
  {
    return "has a BrumeDensityScale that is negative or not finite";
  }
  // Density scales the coefficients.
  m.SigmaA = m.SigmaA * static_cast<float>(scale);
  m.SigmaS = m.SigmaS * static_cast<float>(scale);
  return {};
}

std::atomic<std::size_t> OpenVDBLoads{ 0 };

// An OpenVDB grid loaded for a conversion, found again by the next one
// while someone holds it (the textures hold their scene's): the tracer and
// the reconstruction of a re-trace (an edit of the medium's transfer
// function or albedo) read the same grid object, so the reconstruction
// keeps what the edit left (brume::NativeMediumGrid::SameField), and the
// file is not read again. Keyed by the file's path, size and modification
// time, the grid's name and how its values are read.
std::shared_ptr<const brume::VdbDensity> SharedVdb(
  const std::string& file, const std::string& grid, bool scalars, std::string& error)
{
  struct Key
  {
    std::string File, Grid;
    bool Scalars;
    std::uintmax_t Size;
    std::filesystem::file_time_type Time;
    bool operator==(const Key& o) const
    {
      return File == o.File && Grid == o.Grid && Scalars == o.Scalars && Size == o.Size &&
        Time == o.Time;
    }
  };
  std::error_code failed;
  const std::filesystem::path path = std::filesystem::absolute(file, failed);
  Key key{ failed ? file : path.lexically_normal().string(), grid, scalars,
    std::filesystem::file_size(file, failed), {} };
  if (!failed)
  {
    key.Time = std::filesystem::last_write_time(file, failed);
  }
  auto load = [&]() -> std::shared_ptr<const brume::VdbDensity>
  {
    OpenVDBLoads.fetch_add(1, std::memory_order_relaxed);
    return scalars ? brume::VdbDensity::LoadScalars(file, grid, error, vtkBrumeSMP::ParallelFor())
                   : brume::VdbDensity::Load(file, grid, error, vtkBrumeSMP::ParallelFor());
  };
  if (failed)
  {
    return load(); // says what is wrong with the file
  }
  static std::mutex mutex;
  static std::vector<std::pair<Key, std::weak_ptr<const brume::VdbDensity>>> kept;
  {
    std::lock_guard<std::mutex> lock(mutex);
    kept.erase(std::remove_if(kept.begin(), kept.end(),
                 [](const auto& entry) { return entry.second.expired(); }),
      kept.end());
    for (const auto& entry : kept)
    {
      if (entry.first == key)
      {
        if (auto found = entry.second.lock())
        {
          return found;
        }
      }
    }
  }
  std::shared_ptr<const brume::VdbDensity> loaded = load();
  if (loaded)
  {
    std::lock_guard<std::mutex> lock(mutex);
    kept.emplace_back(key, loaded);
  }
  return loaded;
}

// The density of a sparse OpenVDB grid, used in place. With a transfer
// function, the grid's values are scalars it classifies.
std::string LoadVdbDensity(vtkFieldData* fd, const std::string& vdbFile, brume::Medium& m)
{
  std::optional<brume::OpacityTransferFunction> opacity;
  std::optional<brume::ColorTransferFunction> colors;
  std::string error = ReadTransferFunctions(fd, opacity, colors);
  if (!error.empty())
  {
    return error;
  }
  std::shared_ptr<const brume::DensityField> density =
    SharedVdb(vdbFile, ReadString(fd, vtkBrumeNames::VDBGrid), opacity.has_value(), error);
  if (!density)
  {
    return error;
  }
  SetClassified(m, density, nullptr, opacity, colors);
  return {};
}

// The image's density array: named by BrumeDensityArray, else the active
// scalars (point data first); `cells` when it is cell data. Null when the
// image has none; empty unless the named array is missing.
std::string FindDensityArray(
  vtkImageData* image, vtkFieldData* fd, vtkDataArray*& density, bool& cells)
{
  const std::string name = ReadString(fd, vtkBrumeNames::DensityArray);
  density = nullptr;
  cells = false;
  if (!name.empty())
  {
    density = image->GetPointData()->GetArray(name.c_str());
    if (!density)
    {
      density = image->GetCellData()->GetArray(name.c_str());
      cells = density != nullptr;
    }
    if (!density)
    {
      return "has no density array '" + name + "' (named by BrumeDensityArray)";
    }
  }
  else if ((density = image->GetPointData()->GetScalars()) == nullptr)
  {
    density = image->GetCellData()->GetScalars();
    cells = density != nullptr;
  }
  return {};
}

// BrumeInterpolation: linear (the default) or nearest. Empty when valid.
std::string ReadInterpolation(vtkFieldData* fd, brume::GridDensity::Interpolation& interpolation)
{
  interpolation = brume::GridDensity::Interpolation::Linear;
  const std::string interpolationName = ReadString(fd, vtkBrumeNames::Interpolation);
  if (interpolationName == "nearest")
  {
    interpolation = brume::GridDensity::Interpolation::Nearest;
  }
  else if (!interpolationName.empty() && interpolationName != "linear")
  {
    return "has a BrumeInterpolation '" + interpolationName + "' (expected linear or nearest)";
  }
  return {};
}

// Component `c` of the density array's tuples: scalars a transfer function
// classifies (`classified`: any finite value), else densities (finite and
// not negative), read in the array's own type on every thread into
// `values`, or only checked where `values` is null. Empty when valid.
struct ReadComponent
{
  template <typename Array>
  void operator()(Array* array, int c, bool classified, float* values, std::atomic<bool>& bad,
    bool threads = true) const
  {
    const auto tuples = vtk::DataArrayTupleRange(array);
    auto read = [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType i = begin; i < end; ++i)
      {
        const double v = static_cast<double>(tuples[i][c]);
        if (!std::isfinite(v) || (!classified && !(v >= 0.0)))
        {
          bad = true;
          return;
        }
        if (values)
        {
          values[static_cast<std::size_t>(i)] = static_cast<float>(v);
        }
      }
    };
    if (threads)
    {
      vtkSMPTools::For(0, tuples.size(), read);
    }
    else
    {
      read(0, tuples.size());
    }
  }
};

// The values of component `c`: an array of one component of floats, 8- or
// 16-bit integers is read in place, in its own type (the media made from
// it hold the array); other arrays are converted to floats.
std::string ReadDensityValues(
  vtkDataArray* density, int c, bool classified, brume::TypedValues& values)
{
  const auto count = static_cast<std::size_t>(density->GetNumberOfTuples());
  values = vtkBrumeSharedArray::Borrow(density, count);
  const bool shared = !values.Empty() || count == 0;
  brume::FloatBuffer converted;
  if (!shared)
  {
    converted = brume::FloatBuffer::Allocate(count);
  }
  float* out = shared ? nullptr : converted.Data();
  std::atomic<bool> bad{ false };
  ReadComponent read;
  if (!vtkArrayDispatch::Dispatch::Execute(density, read, c, classified, out, bad))
  {
    // Through vtkDataArray's API, whose tuple buffer is not for threads.
    read(density, c, classified, out, bad, false);
  }
  if (bad)
  {
    values = brume::TypedValues();
    return classified ? "has non-finite scalars" : "has negative or non-finite densities";
  }
  if (!shared)
  {
    values = brume::TypedValues(std::move(converted));
  }
  return {};
}

}

std::string ReadMediumFunctions(vtkFieldData* fd, brume::Medium& m,
  std::optional<brume::OpacityTransferFunction>& opacity,
  std::optional<brume::ColorTransferFunction>& colors)
{
  const std::string error = ReadCoefficients(fd, m);
  return error.empty() ? ReadTransferFunctions(fd, opacity, colors) : error;
}

std::string ConvertMedium(vtkImageData* image, brume::Medium& m)
{
  vtkFieldData* fd = image->GetFieldData();
  std::string error = ReadCoefficients(fd, m);
  if (!error.empty())
  {
    return error;
  }

  // A sparse OpenVDB grid, used in place.
  const std::string vdbFile = ReadString(fd, vtkBrumeNames::VDBFile);
  if (!vdbFile.empty())
  {
    return LoadVdbDensity(fd, vdbFile, m);
  }

  double b[6];
  image->GetBounds(b);
  m.Bounds = { { static_cast<float>(b[0]), static_cast<float>(b[2]), static_cast<float>(b[4]) },
    { static_cast<float>(b[1]), static_cast<float>(b[3]), static_cast<float>(b[5]) } };
  vtkDataArray* density = nullptr;
  bool cells = false;
  error = FindDensityArray(image, fd, density, cells);
  if (!error.empty())
  {
    return error;
  }
  if (!density)
  {
    if (fd->GetAbstractArray(vtkBrumeNames::ScalarOpacity) ||
      fd->GetAbstractArray(vtkBrumeNames::ScalarColor))
    {
      return "has a transfer function (BrumeScalarOpacity or BrumeScalarColor) but no scalars "
             "to classify";
    }
    return {}; // homogeneous
  }
  // A transfer function classifies the array's scalars; without one the
  // array is the density itself.
  std::optional<brume::OpacityTransferFunction> opacity;
  std::optional<brume::ColorTransferFunction> colors;
  error = ReadTransferFunctions(fd, opacity, colors);
  if (!error.empty())
  {
    return error;
  }
  double component = 0.0;
  if (ReadField(fd, vtkBrumeNames::ScalarComponent, 1, &component, error) && !opacity)
  {
    return "has a BrumeScalarComponent without a BrumeScalarOpacity transfer function";
  }
  if (!error.empty())
  {
    return error;
  }
  const int components = density->GetNumberOfComponents();
  if (!opacity && components != 1)
  {
    return "has a density array with more than one component";
  }
  if (!(component >= 0.0 && component < components) || component != std::floor(component))
  {
    std::ostringstream os;
    os << "has a BrumeScalarComponent " << component << ", but its array '"
       << (density->GetName() ? density->GetName() : "") << "' has " << components
       << (components == 1 ? " component" : " components");
    return os.str();
  }
  brume::GridDensity::Interpolation interpolation;
  error = ReadInterpolation(fd, interpolation);
  if (!error.empty())
  {
    return error;
  }
  const double* direction = image->GetDirectionMatrix()->GetData();
  const double identity[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  if (!std::equal(direction, direction + 9, identity))
  {
    return "is an oriented image (non-identity direction matrix), which is not supported";
  }
  int dims[3];
  image->GetDimensions(dims);
  if (dims[0] < 1 || dims[1] < 1 || dims[2] < 1)
  {
    std::ostringstream os;
    os << "has an empty or inverted extent (" << dims[0] << " x " << dims[1] << " x " << dims[2]
       << " points)";
    return os.str();
  }
  std::array<int, 3> n{ dims[0], dims[1], dims[2] };
  if (cells)
  {
    for (int& d : n)
    {
      d = std::max(1, d - 1);
    }
  }
  // The grid reads one value per point (or cell): an array of another
  // length (a vtkImageData put together by hand) is refused, not read past.
  const double expected = static_cast<double>(n[0]) * n[1] * n[2];
  if (static_cast<double>(density->GetNumberOfTuples()) != expected)
  {
    std::ostringstream os;
    os << "has " << density->GetNumberOfTuples() << " tuples in its density array '"
       << (density->GetName() ? density->GetName() : "") << "', not the " << expected << " of its "
       << n[0] << " x " << n[1] << " x " << n[2] << (cells ? " cells" : " points");
    return os.str();
  }
  const FieldCache::GridKey key{ density, density->GetMTime(), static_cast<int>(component),
    opacity.has_value(), n, m.Bounds, cells, interpolation };
  std::shared_ptr<const brume::GridDensity> grid = FieldCache::Instance().Grid(key,
    [&]() -> std::shared_ptr<const brume::GridDensity>
    {
      brume::TypedValues values;
      error = ReadDensityValues(density, key.Component, key.Classified, values);
      if (!error.empty())
      {
        return nullptr;
      }
      return std::make_shared<const brume::GridDensity>(
        m.Bounds, n, std::move(values), cells, interpolation, vtkBrumeSMP::ParallelFor());
    });
  if (!grid)
  {
    return error;
  }
  SetClassified(m, grid, density, opacity, colors);
  return {};
}
}

std::size_t vtkBrumeSceneConversion::GetNumberOfOpenVDBLoads()
{
  return vtkBrumeSceneConversionInternals::OpenVDBLoads.load();
}
