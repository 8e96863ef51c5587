// SPDX-License-Identifier: BSD-3-Clause
// The slice mapper's 3D textures: the source radiance, the extinction (at
// the source's resolution, its own, or a constant), directional radiance and its
// evaluation toward the eye.
#include "vtkBrumeOpenGLSliceVolumeMapperInternals.h"

#include "vtkBrumeArrayBytes.h"
#include "vtkBrumeDataModelNames.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkSMPTools.h"
#include "vtkShortArray.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnsignedShortArray.h"
#include "vtk_glew.h"

#include "brume/SphericalHarmonics.h"

#include <algorithm>
#include <atomic>
#include <bitset>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>

namespace
{
// The points of a transfer function's extinction table (evenly over
// `range`, linear between its values, its end values beyond): the scalars
// where its slope changes, and by how much (extinction per unit of the
// scalar). Between its points a ray's classified extinction is the table's
// line along the interpolated scalar, which one sample a fine cell
// integrates; across a point it is not (a one-voxel sheet's tent through a
// step took -21 % to +51 % of its optical depth, by where the samples
// fell). A slope that changes by more than a hundredth of itself from one
// table value to the next is a point; -ln(1 - alpha) curves by less
// between its points (by 0.3 % at alpha = 0.9 over 4,096 values), until
// alpha nears 1. Changes within the floats' rounding are none.
struct Kink
{
  double Scalar, SlopeChange;
};
std::vector<Kink> TransferKinks(vtkDataArray* table, const double range[2])
{
  std::vector<Kink> kinks;
  const vtkIdType n = table ? table->GetNumberOfTuples() : 0;
  if (n < 2 || !(range[1] > range[0]))
  {
    return kinks;
  }
  std::vector<double> v(static_cast<std::size_t>(n));
  double largest = 0.0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    v[static_cast<std::size_t>(i)] = table->GetTuple1(i);
    largest = std::max(largest, std::abs(v[static_cast<std::size_t>(i)]));
  }
  const double rounding = 1e-6 * largest;
  const double step = (range[1] - range[0]) / static_cast<double>(n - 1);
  // Slope i: from value i - 1 to i; flat beyond the ends.
  auto slope = [&](std::size_t i) { return i == 0 || i == v.size() ? 0.0 : v[i] - v[i - 1]; };
  for (std::size_t i = 0; i < v.size(); ++i)
  {
    const double before = slope(i), after = slope(i + 1);
    const double change = std::abs(after - before);
    if (change > rounding && change > 0.01 * std::max(std::abs(before), std::abs(after)))
    {
      kinks.push_back({ range[0] + step * static_cast<double>(i), change / step });
    }
  }
  return kinks;
}

// The steepest slope of a table (each component of it, evenly over `range`
// and linear between its values): the most its value changes per unit of
// the scalar, 0 for a table of one value or no range. The GPU's row,
// resampled from it linearly, is no steeper.
double TransferSteepest(vtkDataArray* table, const double range[2])
{
  const vtkIdType n = table ? table->GetNumberOfTuples() : 0;
  if (n < 2 || !(range[1] > range[0]))
  {
    return 0.0;
  }
  double steepest = 0.0;
  for (int c = 0; c < table->GetNumberOfComponents(); ++c)
  {
    double last = table->GetComponent(0, c);
    for (vtkIdType i = 1; i < n; ++i)
    {
      const double v = table->GetComponent(i, c);
      steepest = std::max(steepest, std::abs(v - last));
      last = v;
    }
  }
  return steepest * static_cast<double>(n - 1) / (range[1] - range[0]);
}

// Uploads `values` (`components` floats per voxel) as a 3D texture clamped
// at the edges and filtered with `filter` (nearest or linear). RGB data go
// up as RGBA (4 floats a voxel): a software rasterizer samples 16-byte
// texels faster than 12-byte ones (god-rays.json, 512 x 512 under llvmpipe:
// 84 against 73 ms a frame).
//
// A texture of that size and kind already there is filled in place
// (glTexSubImage3D): a view update re-uploads the source radiance every
// frame, and new storage costs a software rasterizer fresh pages each time.
// Null `values` make the storage (or keep it) and leave the texels to the
// caller.
bool Upload3D(vtkTextureObject* texture, vtkOpenGLRenderWindow* window, const int dims[3],
  int components, int filter, const float* values)
{
  if (texture->GetHandle() && texture->GetContext() == window &&
    texture->GetTarget() == GL_TEXTURE_3D && static_cast<int>(texture->GetWidth()) == dims[0] &&
    static_cast<int>(texture->GetHeight()) == dims[1] &&
    static_cast<int>(texture->GetDepth()) == dims[2] && texture->GetComponents() == components &&
    texture->GetVTKDataType() == VTK_FLOAT && (components == 1 || components == 4))
  {
    texture->SetMinificationFilter(filter);
    texture->SetMagnificationFilter(filter);
    texture->Activate(); // binds it and sends the filters
    if (values)          // else the caller sends the texels
    {
      glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
      glTexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, 0, dims[0], dims[1], dims[2],
        components == 1 ? GL_RED : GL_RGBA, GL_FLOAT, values);
    }
    texture->Deactivate();
    return true;
  }
  texture->SetContext(window);
  texture->SetInternalFormat(0); // the default for floats of `components`, not the last kind's
  texture->SetWrapS(vtkTextureObject::ClampToEdge);
  texture->SetWrapT(vtkTextureObject::ClampToEdge);
  texture->SetWrapR(vtkTextureObject::ClampToEdge);
  texture->SetMinificationFilter(filter);
  texture->SetMagnificationFilter(filter);
  return texture->Create3DFromRaw(static_cast<unsigned int>(dims[0]),
    static_cast<unsigned int>(dims[1]), static_cast<unsigned int>(dims[2]), components, VTK_FLOAT,
    const_cast<float*>(values));
}

// Fills rgba (4 floats per cell, alpha 0) from a cell array of 1 or 3
// components, in parallel; returns the first cell whose value is not finite
// (or negative, with `nonNegative`), or `cells` if none.
vtkIdType ToRgba(vtkDataArray* array, vtkIdType cells, bool nonNegative, std::vector<float>& rgba)
{
  rgba.resize(4 * static_cast<std::size_t>(cells));
  const int n = array->GetNumberOfComponents();
  auto* typed = vtkFloatArray::FastDownCast(array);
  std::atomic<vtkIdType> firstBad(cells);
  vtkSMPTools::For(0, cells,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType i = begin; i < end; ++i)
      {
        bool bad = false;
        for (int c = 0; c < 3; ++c)
        {
          const int from = n == 3 ? c : 0;
          const float v = typed ? typed->GetValue(i * n + from)
                                : static_cast<float>(array->GetComponent(i, from));
          rgba[4 * i + c] = v;
          bad = bad || !std::isfinite(v) || (nonNegative && !(v >= 0.f));
        }
        rgba[4 * i + 3] = 0.f;
        if (bad)
        {
          vtkIdType seen = firstBad.load();
          while (i < seen && !firstBad.compare_exchange_weak(seen, i))
          {
          }
          return;
        }
      }
    });
  return firstBad.load();
}

// Whether every cell's three values are alike.
bool Grey(const std::vector<float>& rgba)
{
  for (std::size_t i = 0; i + 3 < rgba.size(); i += 4)
  {
    if (rgba[i] != rgba[i + 1] || rgba[i] != rgba[i + 2])
    {
      return false;
    }
  }
  return true;
}

// Whether the RGB values of `rgba` are alike in every cell; if so, they are
// copied to `constant`.
bool Uniform(const std::vector<float>& rgba, float constant[3])
{
  if (rgba.size() < 4)
  {
    return false;
  }
  for (std::size_t i = 4; i < rgba.size(); ++i)
  {
    if (i % 4 != 3 && rgba[i] != rgba[i % 4])
    {
      return false;
    }
  }
  std::copy(rgba.begin(), rgba.begin() + 3, constant);
  return true;
}
}

bool vtkBrumeOpenGLSliceVolumeMapper::UploadTextures(
  vtkImageData* input, vtkOpenGLRenderWindow* renWin, const int dims[3], int interpolation)
{
  // Two RGBA float 3D textures: source radiance and extinction.
  Internals& impl = *this->Impl;
  const vtkIdType cells = static_cast<vtkIdType>(dims[0]) * dims[1] * dims[2];
  std::vector<float>& s = impl.SourceValues;
  // The source radiance per cell (expanded from the sparse form's bricks).
  const vtkIdType badSource =
    ToRgba(DenseSourceArray(input, vtkBrumeNames::SourceRadiance), cells, false, s);
  // The extinction array of the last upload, unmodified (a view update
  // keeps it: vtkBrumeRadianceConversion::FromMedium): its values are known.
  // The sparse form has none (ExtinctionData replaces it).
  vtkDataArray* extinction = input->GetCellData()->GetArray(vtkBrumeNames::Extinction);
  const bool known = !this->ExtinctionData && extinction == impl.ExtinctionArray &&
    extinction->GetMTime() == impl.ExtinctionArrayTime &&
    impl.ExtinctionValues.size() == 4 * static_cast<std::size_t>(cells);
  std::vector<float>& e = known ? impl.ExtinctionValues : impl.Scratch;
  if (!extinction)
  {
    e.assign(4 * static_cast<std::size_t>(cells), 1.f);
  }
  const vtkIdType badExtinction = known || !extinction ? cells : ToRgba(extinction, cells, true, e);
  if (badSource < cells || badExtinction < cells)
  {
    vtkErrorMacro("Cannot draw this medium: its extinction must be finite and "
                  "non-negative and its source radiance finite (cell "
      << std::min(badSource, badExtinction) << ").");
    return false;
  }
  // With extinction at its own resolution the source texture holds S, which
  // the shader multiplies by the fine sigma_t; otherwise it holds J.
  impl.SourceIsRadiance = this->ExtinctionData != nullptr;
  if (!impl.SourceIsRadiance)
  {
    // The texture holds J = S sigma_t: filtered between voxels, J and
    // sigma_t stay bounded where the medium thins out (S would not).
    std::atomic<bool> overflow(false);
    vtkSMPTools::For(0, 4 * cells,
      [&](vtkIdType begin, vtkIdType end)
      {
        bool finite = true;
        for (vtkIdType i = begin; i < end; ++i)
        {
          s[i] *= e[i];
          finite = finite && std::isfinite(s[i]);
        }
        if (!finite)
        {
          overflow = true;
        }
      });
    if (overflow)
    {
      vtkErrorMacro("Cannot draw this medium: its source radiance times its extinction "
                    "overflows.");
      return false;
    }
  }
  const int filter = interpolation == VTK_NEAREST_INTERPOLATION ? vtkTextureObject::Nearest
                                                                : vtkTextureObject::Linear;
  impl.ExtinctionArray = nullptr;
  if (!Upload3D(impl.Source, renWin, dims, 4, filter, s.data()) ||
    !(impl.SourceIsRadiance ? this->UploadExtinction(renWin, filter)
                            : this->UploadInputExtinction(renWin, dims, filter, e)))
  {
    vtkErrorMacro("Could not create the 3D textures (" << dims[0] << " x " << dims[1] << " x "
                                                       << dims[2] << "): nothing drawn.");
    return false;
  }
  if (!impl.SourceIsRadiance)
  {
    impl.ExtinctionArray = extinction;
    impl.ExtinctionArrayTime = extinction->GetMTime();
  }
  else
  {
    e.assign(e.size(), 1.f); // directional coefficients: S, like the source
  }
  if (!this->UploadDirectional(input, renWin, dims, filter, e))
  {
    return false;
  }
  impl.Interpolation = interpolation;
  impl.TextureTime.Modified();
  return true;
}

bool vtkBrumeOpenGLSliceVolumeMapper::UploadInputExtinction(
  vtkOpenGLRenderWindow* renWin, const int dims[3], int filter, const std::vector<float>& e)
{
  // The extinction at the source's resolution (the input's own). A view
  // update changes the source alone: the extinction is uploaded only when
  // its values or filter changed, and a homogeneous medium's is a uniform.
  Internals& impl = *this->Impl;
  const bool same = impl.ExtinctionGrid == nullptr && impl.Extinction->GetHandle() &&
    impl.ExtinctionInterpolation == filter &&
    (&e == &impl.ExtinctionValues || impl.ExtinctionValues == e);
  impl.ExtinctionGrid = nullptr;
  impl.Bricked = false;
  impl.Albedo = false;
  if (same)
  {
    return true;
  }
  impl.ConstantExtinction = Uniform(e, impl.Constant);
  impl.ExtinctionGrey = Grey(e);
  if (&e != &impl.ExtinctionValues)
  {
    impl.ExtinctionValues.assign(e.begin(), e.end());
  }
  impl.ExtinctionInterpolation = filter;
  if (impl.ConstantExtinction)
  {
    // The sampler still needs a texture; one voxel.
    const int one[3] = { 1, 1, 1 };
    return Upload3D(impl.Extinction, renWin, one, 4, filter, e.data());
  }
  return Upload3D(impl.Extinction, renWin, dims, 4, filter, e.data());
}

bool vtkBrumeOpenGLSliceVolumeMapper::UploadExtinction(vtkOpenGLRenderWindow* renWin, int filter)
{
  // The grid of its own changes seldom (it is the density's): uploaded only
  // when it is another grid, was modified, or is filtered otherwise.
  Internals& impl = *this->Impl;
  vtkImageData* grid = this->ExtinctionData;
  if (impl.ExtinctionGrid == grid && impl.ExtinctionTime > grid->GetMTime() &&
    impl.ExtinctionInterpolation == filter && impl.Extinction->GetHandle() &&
    !(impl.Bricked && impl.AtlasDepthError > this->ExtinctionDepthTolerance))
  {
    return true;
  }
  int pointDims[3];
  grid->GetDimensions(pointDims);
  const int dims[3] = { pointDims[0] - 1, pointDims[1] - 1, pointDims[2] - 1 };
  impl.Bricked = grid->GetFieldData()->GetArray(vtkBrumeNames::ExtinctionBrickSamples) ||
    grid->GetFieldData()->GetArray(vtkBrumeNames::ExtinctionCellValues);
  if (impl.Bricked ? !this->UploadBricks(grid, dims, renWin, filter)
                   : !this->UploadDenseExtinction(grid, dims, renWin, filter))
  {
    return false;
  }
  impl.ExtinctionGrid = grid;
  impl.ExtinctionInterpolation = filter;
  impl.ExtinctionTime.Modified();
  return true;
}

bool vtkBrumeOpenGLSliceVolumeMapper::UploadDenseExtinction(
  vtkImageData* grid, const int dims[3], vtkOpenGLRenderWindow* renWin, int filter)
{
  Internals& impl = *this->Impl;
  const vtkIdType cells = static_cast<vtkIdType>(dims[0]) * dims[1] * dims[2];
  std::vector<float> e;
  const vtkIdType bad =
    ToRgba(grid->GetCellData()->GetArray(vtkBrumeNames::Extinction), cells, true, e);
  if (bad < cells)
  {
    vtkErrorMacro("Cannot draw this medium: its extinction must be finite and non-negative "
                  "(cell "
      << bad << " of the extinction grid).");
    return false;
  }
  impl.ExtinctionValues.clear();
  impl.MaxExtinction = e.empty() ? 0.0 : *std::max_element(e.begin(), e.end());
  impl.ConstantExtinction = Uniform(e, impl.Constant);
  impl.ExtinctionGrey = Grey(e);
  return Upload3D(impl.Extinction, renWin, dims, 4, filter, e.data());
}

bool vtkBrumeOpenGLSliceVolumeMapper::UploadBricks(
  vtkImageData* grid, const int dims[3], vtkOpenGLRenderWindow* renWin, int filter)
{
  // The slots side by side in a 3D atlas (at least one, so that the
  // sampler has a texture), about cubic in slots; the brick table beside it.
  Internals& impl = *this->Impl;
  impl.ExtinctionValues.clear();
  impl.ConstantExtinction = false;
  vtkFieldData* fd = grid->GetFieldData();
  vtkDataArray* slots = fd->GetArray(vtkBrumeNames::ExtinctionBrickSlots);
  vtkDataArray* values = fd->GetArray(vtkBrumeNames::ExtinctionBrickValues);
  vtkDataArray* scale = fd->GetArray(vtkBrumeNames::ExtinctionScale);
  constexpr int B = ExtinctionBrickSize;
  constexpr vtkIdType BrickCells = B * B * B;
  const int brickDims[3] = { ExtinctionBricksAlong(dims[0]), ExtinctionBricksAlong(dims[1]),
    ExtinctionBricksAlong(dims[2]) };
  const vtkIdType bricks = slots->GetNumberOfTuples();
  // The slots' samples, or the cells' own values (a field's array read in
  // place), each slot then the brick whose cells it holds, from its first.
  vtkDataArray* samples = fd->GetArray(vtkBrumeNames::ExtinctionBrickSamples);
  vtkDataArray* cellValues = samples ? nullptr : fd->GetArray(vtkBrumeNames::ExtinctionCellValues);
  // Each brick's slot: the reconstruction's integers where they are that
  // (a sparse 2048^3 grid has 2.5 10^7 bricks), else read once.
  std::vector<int> converted;
  const int* slotOf = nullptr;
  if (vtkIntArray* ints = vtkIntArray::FastDownCast(slots))
  {
    slotOf = ints->GetPointer(0);
  }
  else
  {
    converted.resize(static_cast<std::size_t>(bricks));
    for (vtkIdType b = 0; b < bricks; ++b)
    {
      converted[static_cast<std::size_t>(b)] = static_cast<int>(slots->GetTuple1(b));
    }
    slotOf = converted.data();
  }
  std::vector<int> slotFirst; // 3 per slot
  vtkIdType slotCount = samples ? samples->GetNumberOfTuples() / BrickCells : 0;
  if (cellValues)
  {
    for (vtkIdType b = 0; b < bricks; ++b)
    {
      slotCount = std::max(slotCount, static_cast<vtkIdType>(slotOf[b]) + 1);
    }
    slotFirst.assign(3 * static_cast<std::size_t>(slotCount), 0);
    for (vtkIdType b = 0; b < bricks; ++b)
    {
      const vtkIdType slot = slotOf[b];
      if (slot >= 0)
      {
        int* first = &slotFirst[3 * static_cast<std::size_t>(slot)];
        first[0] = (B - 1) * static_cast<int>(b % brickDims[0]);
        first[1] = (B - 1) * static_cast<int>((b / brickDims[0]) % brickDims[1]);
        first[2] =
          (B - 1) * static_cast<int>(b / (static_cast<vtkIdType>(brickDims[0]) * brickDims[1]));
      }
    }
  }
  vtkDataArray* source = samples ? samples : cellValues;
  int atlas[3];
  atlas[0] = std::max(1, static_cast<int>(std::ceil(std::cbrt(static_cast<double>(slotCount)))));
  atlas[1] =
    std::max(1, static_cast<int>(std::ceil(std::sqrt(static_cast<double>(slotCount) / atlas[0]))));
  atlas[2] = std::max(1,
    static_cast<int>(
      (slotCount + atlas[0] * atlas[1] - 1) / (static_cast<vtkIdType>(atlas[0]) * atlas[1])));
  const int texels[3] = { B * atlas[0], B * atlas[1], B * atlas[2] };
  int maxSize = 0;
  glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &maxSize);
  // The brick table names a slot as x + 2048 y in a float, exactly.
  if (texels[0] > maxSize || texels[1] > maxSize || texels[2] > maxSize || atlas[0] > 2048 ||
    atlas[1] > 2048)
  {
    vtkErrorMacro("Cannot draw this medium: its "
      << slotCount << " bricks of extinction need a 3D texture of " << texels[0] << " x "
      << texels[1] << " x " << texels[2] << ", beyond this GPU's " << maxSize << ".");
    return false;
  }
  double largest = 0.0; // the largest value, stored or constant, before the scale
  auto invalid = [](double v) { return !(v >= 0.0) || !std::isfinite(v); };
  // Scalars a transfer function classifies may be negative; its table bounds sigma_t.
  vtkDataArray* transfer = fd->GetArray(vtkBrumeNames::ExtinctionTransferFunction);
  impl.Classified = transfer != nullptr;
  impl.Albedo = false;
  auto invalidSample = [&](double v) { return impl.Classified ? !std::isfinite(v) : invalid(v); };
  // Slot by slot on every thread (512^3 fields store 10^8 samples): each
  // slot's largest value, and the first slot holding an invalid sample.
  std::vector<double> slotLargest(static_cast<std::size_t>(slotCount), 0.0);
  std::vector<double> slotLeast(static_cast<std::size_t>(slotCount), 0.0);
  std::vector<char> slotIntegers(static_cast<std::size_t>(slotCount), 1);
  std::vector<float> slotHigh(static_cast<std::size_t>(slotCount), 0.f); // scalars: can be < 0
  std::vector<double> slotTop(static_cast<std::size_t>(slotCount), 0.0);
  std::vector<float> slotSteep(static_cast<std::size_t>(slotCount), 0.f);
  std::atomic<vtkIdType> firstBad{ slotCount };
  vtkFloatArray* floats = vtkFloatArray::FastDownCast(source);
  vtkUnsignedCharArray* bytes = vtkUnsignedCharArray::FastDownCast(source);
  vtkUnsignedShortArray* shorts = vtkUnsignedShortArray::FastDownCast(source);
  vtkShortArray* signedShorts = vtkShortArray::FastDownCast(source);
  // Arrays read in their own memory are read on every thread.
  const bool threads = floats || bytes || shorts || signedShorts;
  // What 16-bit values of half quantum h may change: along any ray across
  // the grid (at most its diagonal) the extinction moves by at most h times
  // its largest change per unit of value (the scale, times a transfer
  // function's steepest slope), and a classified albedo by h times its own.
  double perValue = 0.0, albedoPerValue = 0.0;
  for (int c = 0; c < 3; ++c)
  {
    perValue = std::max(perValue, std::abs(scale->GetComponent(0, c)));
  }
  if (transfer)
  {
    double transferRange[2] = { 0.0, 0.0 };
    if (vtkDataArray* r = fd->GetArray(vtkBrumeNames::ExtinctionTransferRange))
    {
      r->GetTuple(0, transferRange);
    }
    perValue *= TransferSteepest(transfer, transferRange);
    albedoPerValue =
      TransferSteepest(fd->GetArray(vtkBrumeNames::AlbedoTransferFunction), transferRange);
  }
  const double* cellSize = grid->GetSpacing();
  double diagonal = 0.0;
  for (int c = 0; c < 3; ++c)
  {
    diagonal += std::pow(cellSize[c] * dims[c], 2);
  }
  diagonal = std::sqrt(diagonal);
  auto depthError = [&](double halfQuantum)
  { return std::max(halfQuantum * perValue * diagonal, halfQuantum * albedoPerValue); };
  // The same samples (the same memory, which the atlas's arrays keep) in
  // the same slots, filtered alike, within the tolerance under this
  // function: the atlas holds them already, checked.
  const bool sameAtlas = impl.AtlasSamples && source->GetNumberOfValues() > 0 &&
    !(depthError(impl.AtlasHalfQuantum) > this->ExtinctionDepthTolerance) &&
    impl.AtlasSamples->GetDataType() == source->GetDataType() &&
    impl.AtlasSamples->GetNumberOfValues() == source->GetNumberOfValues() &&
    impl.AtlasSamples->GetVoidPointer(0) == source->GetVoidPointer(0) &&
    vtkBrumeArrayBytes::Same(impl.AtlasSlots, slots) && impl.AtlasFilter == filter &&
    impl.Extinction->GetHandle() && impl.Extinction->GetContext() == renWin;
  auto value = [&](vtkIdType at) -> double
  {
    if (floats)
    {
      return floats->GetValue(at);
    }
    if (bytes)
    {
      return bytes->GetValue(at);
    }
    if (shorts)
    {
      return shorts->GetValue(at);
    }
    return signedShorts ? signedShorts->GetValue(at) : source->GetTuple1(at);
  };
  // Sample n (x fastest) of slot `slot`.
  auto sample = [&](vtkIdType slot, int n) -> double
  {
    if (!cellValues)
    {
      return value(slot * BrickCells + n);
    }
    // Cells past the grid's last take the last's.
    const int* first = &slotFirst[3 * static_cast<std::size_t>(slot)];
    const int x = std::min(first[0] + n % B, dims[0] - 1);
    const int y = std::min(first[1] + (n / B) % B, dims[1] - 1);
    const int z = std::min(first[2] + n / (B * B), dims[2] - 1);
    return value((static_cast<vtkIdType>(z) * dims[1] + y) * dims[0] + x);
  };
  // The B^3 samples of a slot, as sample() gives them: a row of the
  // field's own array at a time where it is read in place.
  auto readSlot = [&](vtkIdType slot, double* out)
  {
    auto rows = [&](const auto* data)
    {
      const int* first = &slotFirst[3 * static_cast<std::size_t>(slot)];
      int xs[B];
      for (int i = 0; i < B; ++i)
      {
        xs[i] = std::min(first[0] + i, dims[0] - 1);
      }
      for (int k = 0; k < B; ++k)
      {
        const vtkIdType z = std::min(first[2] + k, dims[2] - 1);
        for (int j = 0; j < B; ++j)
        {
          const vtkIdType y = std::min(first[1] + j, dims[1] - 1);
          const auto* row = data + (z * dims[1] + y) * dims[0];
          for (int i = 0; i < B; ++i)
          {
            *out++ = static_cast<double>(row[xs[i]]);
          }
        }
      }
    };
    if (cellValues && floats)
    {
      rows(floats->GetPointer(0));
    }
    else if (cellValues && bytes)
    {
      rows(bytes->GetPointer(0));
    }
    else if (cellValues && shorts)
    {
      rows(shorts->GetPointer(0));
    }
    else if (cellValues && signedShorts)
    {
      rows(signedShorts->GetPointer(0));
    }
    else
    {
      for (int n = 0; n < BrickCells; ++n)
      {
        out[n] = sample(slot, n);
      }
    }
  };
  auto check = [&](vtkIdType begin, vtkIdType end)
  {
    double brick[B * B * B];
    for (vtkIdType slot = begin; slot < end; ++slot)
    {
      readSlot(slot, brick);
      double most = 0.0, least = brick[0], high = least, steep = 0.0;
      bool bad = false, integers = true;
      for (int n = 0; n < BrickCells; ++n)
      {
        const double v = brick[n];
        bad = bad || invalidSample(v);
        most = std::max(most, v);
        least = std::min(least, v);
        high = std::max(high, v);
        integers = integers && v == std::floor(v);
        // The largest step between neighbouring samples, along any axis.
        const int i = n % B, j = (n / B) % B, k = n / (B * B);
        if (i > 0)
        {
          steep = std::max(steep, std::abs(v - brick[n - 1]));
        }
        if (j > 0)
        {
          steep = std::max(steep, std::abs(v - brick[n - B]));
        }
        if (k > 0)
        {
          steep = std::max(steep, std::abs(v - brick[n - B * B]));
        }
      }
      slotHigh[static_cast<std::size_t>(slot)] = static_cast<float>(high);
      slotTop[static_cast<std::size_t>(slot)] = high;
      slotSteep[static_cast<std::size_t>(slot)] = static_cast<float>(steep);
      slotLargest[static_cast<std::size_t>(slot)] = most;
      slotLeast[static_cast<std::size_t>(slot)] = least;
      slotIntegers[static_cast<std::size_t>(slot)] = integers ? 1 : 0;
      vtkIdType known = firstBad.load();
      while (bad && slot < known && !firstBad.compare_exchange_weak(known, slot))
      {
      }
    }
  };
  if (!sameAtlas)
  {
    // Until the atlas is filled anew, it holds nothing to compare with.
    impl.AtlasSamples = nullptr;
    impl.AtlasSlots = nullptr;
  }
  if (sameAtlas)
  {
    largest = impl.AtlasLargest;
  }
  else if (threads)
  {
    vtkSMPTools::For(0, slotCount, check);
  }
  else
  {
    check(0, slotCount); // vtkDataArray's GetTuple1 is not for threads
  }
  if (firstBad.load() < slotCount)
  {
    vtkErrorMacro("Cannot draw this medium: its extinction must be finite and "
                  "non-negative, its scalars finite (brick slot "
      << firstBad.load() << " of the extinction grid).");
    return false;
  }
  for (const double most : slotLargest)
  {
    largest = std::max(largest, most);
  }
  if (!sameAtlas)
  {
    // The slots' scalars' intervals, for this function and the next ones.
    impl.SlotLow.assign(slotLeast.begin(), slotLeast.end());
    impl.SlotHigh = std::move(slotHigh);
    impl.SlotSteep = std::move(slotSteep);
  }
  const double storedLargest = largest; // of the stored samples alone
  // Grids of integers (a scan's 8- or 16-bit values, read in place) go up
  // as 16-bit normalized integers less their least, which the shader scales
  // back, exactly. Floats go up so too, each slot's over its own interval
  // in 65,535 steps, where the largest step's half keeps within the
  // tolerance of optical depth (a smooth field, whose bricks span a little
  // of its range: half the memory and the upload); other grids as floats.
  // Not 8 bits: a software rasterizer filters those with 8-bit weights
  // (2.3 % off in Brume.SliceVolumeMapper under llvmpipe), 16-bit ones as
  // floats. Each stored brick's table entry gives the value of a texel t
  // of its slot as scale t + offset.
  if (!sameAtlas)
  {
    double least = 0.0;
    bool integers = slotCount > 0;
    double halfQuantum = 0.0;
    for (vtkIdType slot = 0; slot < slotCount; ++slot)
    {
      const std::size_t at = static_cast<std::size_t>(slot);
      least = slot == 0 ? slotLeast[0] : std::min(least, slotLeast[at]);
      integers = integers && slotIntegers[at];
      halfQuantum = std::max(halfQuantum, 0.5 * (slotTop[at] - slotLeast[at]) / 65535.0);
    }
    const bool exact = integers && storedLargest - least <= 65535.0;
    const bool quantized = !exact && slotCount > 0 && std::isfinite(halfQuantum) &&
      !(depthError(halfQuantum) > this->ExtinctionDepthTolerance);
    impl.AtlasBytes = exact || quantized ? 2 : 4;
    impl.AtlasHalfQuantum = quantized ? halfQuantum : 0.0;
    impl.SlotValue.assign(2 * static_cast<std::size_t>(slotCount), 0.f);
    for (vtkIdType slot = 0; slot < slotCount; ++slot)
    {
      const std::size_t at = static_cast<std::size_t>(slot);
      float* slotValue = &impl.SlotValue[2 * at];
      slotValue[0] = exact ? 65535.f
        : quantized        ? static_cast<float>(slotTop[at] - slotLeast[at])
                           : 1.f;
      slotValue[1] = exact ? static_cast<float>(least)
        : quantized        ? static_cast<float>(slotLeast[at])
                           : 0.f;
    }
  }
  impl.AtlasDepthError = depthError(impl.AtlasHalfQuantum);
  const int width = impl.AtlasBytes;
  std::vector<float> table(4 * static_cast<std::size_t>(bricks));
  vtkFloatArray* constants = vtkFloatArray::FastDownCast(values);
  for (vtkIdType b = 0; b < bricks; ++b)
  {
    const vtkIdType slot = slotOf[b];
    float* entry = &table[4 * static_cast<std::size_t>(b)];
    if (slot < 0)
    {
      const double v = constants ? constants->GetValue(b) : values->GetTuple1(b);
      if (invalidSample(v))
      {
        vtkErrorMacro("Cannot draw this medium: its extinction must be finite and non-negative "
                      "(brick "
          << b << " of the extinction grid).");
        return false;
      }
      entry[0] = static_cast<float>(v);
      entry[1] = -1.f;
      largest = std::max(largest, v);
      continue;
    }
    // The slot's place in the atlas, in slots: x + 2048 y (at most 16,384
    // texels, 2,048 slots, along x), and z; then its scale and offset.
    entry[0] = static_cast<float>(slot % atlas[0] + 2048 * ((slot / atlas[0]) % atlas[1]));
    entry[1] = static_cast<float>(slot / (static_cast<vtkIdType>(atlas[0]) * atlas[1]));
    entry[2] = impl.SlotValue[2 * static_cast<std::size_t>(slot)];
    entry[3] = impl.SlotValue[2 * static_cast<std::size_t>(slot) + 1];
  }
  for (int c = 0; c < 3; ++c)
  {
    const double f = scale->GetComponent(0, c);
    if (invalid(f))
    {
      vtkErrorMacro("Cannot draw this medium: 'ExtinctionScale' must be finite and non-negative.");
      return false;
    }
    impl.BrickScale[c] = static_cast<float>(f);
    impl.GridCells[c] = static_cast<float>(dims[c]);
    impl.BrickCount[c] = static_cast<float>(brickDims[c]);
    impl.AtlasSize[c] = static_cast<float>(texels[c]);
  }
  impl.ExtinctionGrey =
    impl.BrickScale[0] == impl.BrickScale[1] && impl.BrickScale[1] == impl.BrickScale[2];
  if (impl.Classified && !this->UploadTransferFunction(fd, renWin, largest))
  {
    return false;
  }
  // Stored bricks whose scalars' interval holds a point of the function
  // that one sample a fine cell may miss are sampled finer along the rays,
  // in the parts of 2^3 cells where it may (the shader's bendsAt). Across a
  // cell whose scalar changes by D (the largest step between neighbouring
  // samples), a point whose slope changes by K moves a midpoint sample's
  // optical depth by at most K D h / 8 (h the finest cell): where that
  // stays below 10^-2 samples are left as they are (a smooth field's cells
  // crossing a point). A brick is tested first with its slot's interval and
  // steepest step, then each of its 4^3 parts (the samples 2c to 2c + 2
  // along each axis, the last part's 6 and 7: those that the points of the
  // part interpolate) with its own: a bit each in the bend mask, four
  // floats of 16 bits a brick.
  impl.BendingBricks = 0;
  impl.BendingParts = 0;
  std::vector<float> bendMask;
  if (impl.Classified && impl.SlotLow.size() == static_cast<std::size_t>(slotCount) &&
    impl.SlotSteep.size() == impl.SlotLow.size())
  {
    double range[2];
    fd->GetArray(vtkBrumeNames::ExtinctionTransferRange)->GetTuple(0, range);
    const std::vector<Kink> kinks =
      TransferKinks(fd->GetArray(vtkBrumeNames::ExtinctionTransferFunction), range);
    const double* spacing = grid->GetSpacing();
    const double h = std::min({ spacing[0], spacing[1], spacing[2] });
    const double perUnit = std::max({ impl.BrickScale[0], impl.BrickScale[1], impl.BrickScale[2] });
    constexpr double Tolerance = 1e-2;
    // Whether samples over [low, high] whose steps reach `steep` may miss
    // the tolerance at a kink.
    auto bends = [&](double low, double high, double steep)
    {
      auto k = std::upper_bound(kinks.begin(), kinks.end(), low,
        [](double s, const Kink& kink) { return s < kink.Scalar; });
      double change = 0.0;
      for (; k != kinks.end() && k->Scalar < high; ++k)
      {
        change = std::max(change, k->SlopeChange);
      }
      return change * perUnit * steep * h / 8.0 > Tolerance;
    };
    // Per stored slot (a sparse grid's bricks are mostly not stored).
    std::vector<std::uint64_t> masks(kinks.empty() ? 0 : static_cast<std::size_t>(slotCount), 0);
    auto test = [&](vtkIdType begin, vtkIdType end)
    {
      double brick[B * B * B];
      for (vtkIdType slot = begin; slot < end; ++slot)
      {
        if (!bends(impl.SlotLow[static_cast<std::size_t>(slot)],
              impl.SlotHigh[static_cast<std::size_t>(slot)],
              impl.SlotSteep[static_cast<std::size_t>(slot)]))
        {
          continue;
        }
        readSlot(slot, brick);
        // Each part's interval, separably (x, then y, then z); its steepest
        // step only where the interval alone may miss the tolerance (a step
        // is at most the interval's width): the fog beside a sheet is let
        // go on its interval.
        double lowX[B][B][4], highX[B][B][4], lowXY[B][4][4], highXY[B][4][4];
        for (int k = 0; k < B; ++k)
          for (int j = 0; j < B; ++j)
          {
            const double* row = &brick[(k * B + j) * B];
            for (int c = 0; c < 4; ++c)
            {
              double lo = row[2 * c], hi = lo;
              for (int i = 2 * c + 1; i <= std::min(2 * c + 2, B - 1); ++i)
              {
                lo = std::min(lo, row[i]);
                hi = std::max(hi, row[i]);
              }
              lowX[k][j][c] = lo;
              highX[k][j][c] = hi;
            }
          }
        for (int k = 0; k < B; ++k)
          for (int cy = 0; cy < 4; ++cy)
            for (int cx = 0; cx < 4; ++cx)
            {
              double lo = lowX[k][2 * cy][cx], hi = highX[k][2 * cy][cx];
              for (int j = 2 * cy + 1; j <= std::min(2 * cy + 2, B - 1); ++j)
              {
                lo = std::min(lo, lowX[k][j][cx]);
                hi = std::max(hi, highX[k][j][cx]);
              }
              lowXY[k][cy][cx] = lo;
              highXY[k][cy][cx] = hi;
            }
        std::uint64_t mask = 0;
        for (int part = 0; part < 64; ++part)
        {
          const int c[3] = { part % 4, (part / 4) % 4, part / 16 };
          int from[3], to[3];
          for (int a = 0; a < 3; ++a)
          {
            from[a] = 2 * c[a];
            to[a] = std::min(2 * c[a] + 2, B - 1);
          }
          double low = lowXY[from[2]][c[1]][c[0]], high = highXY[from[2]][c[1]][c[0]];
          for (int k = from[2] + 1; k <= to[2]; ++k)
          {
            low = std::min(low, lowXY[k][c[1]][c[0]]);
            high = std::max(high, highXY[k][c[1]][c[0]]);
          }
          if (!bends(low, high, high - low))
          {
            continue;
          }
          double steep = 0.0;
          for (int k = from[2]; k <= to[2]; ++k)
            for (int j = from[1]; j <= to[1]; ++j)
              for (int i = from[0]; i <= to[0]; ++i)
              {
                const int n = (k * B + j) * B + i;
                const double v = brick[n];
                if (i > from[0])
                {
                  steep = std::max(steep, std::abs(v - brick[n - 1]));
                }
                if (j > from[1])
                {
                  steep = std::max(steep, std::abs(v - brick[n - B]));
                }
                if (k > from[2])
                {
                  steep = std::max(steep, std::abs(v - brick[n - B * B]));
                }
              }
          if (bends(low, high, steep))
          {
            mask |= std::uint64_t{ 1 } << part;
          }
        }
        masks[static_cast<std::size_t>(slot)] = mask;
      }
    };
    if (!masks.empty())
    {
      if (threads)
      {
        vtkSMPTools::For(0, slotCount, test);
      }
      else
      {
        test(0, slotCount); // the samples' vtkDataArray is not for threads
      }
    }
    for (std::size_t b = 0; !masks.empty() && b < static_cast<std::size_t>(bricks); ++b)
    {
      const int slot = slotOf[b];
      const std::uint64_t mask = slot < 0 ? 0 : masks[static_cast<std::size_t>(slot)];
      if (mask == 0)
      {
        continue;
      }
      if (bendMask.empty())
      {
        bendMask.assign(4 * static_cast<std::size_t>(bricks), 0.f);
      }
      for (int word = 0; word < 4; ++word)
      {
        bendMask[4 * b + static_cast<std::size_t>(word)] =
          static_cast<float>((mask >> (16 * word)) & 0xffffu);
      }
      ++impl.BendingBricks;
      impl.BendingParts += static_cast<vtkIdType>(std::bitset<64>(mask).count());
    }
  }
  if (!bendMask.empty() &&
    !Upload3D(impl.BendMask, renWin, brickDims, 4, vtkTextureObject::Nearest, bendMask.data()))
  {
    return false;
  }
  impl.MaxExtinction =
    largest * std::max({ impl.BrickScale[0], impl.BrickScale[1], impl.BrickScale[2] });
  if (sameAtlas)
  {
    return Upload3D(impl.BrickTable, renWin, brickDims, 4, vtkTextureObject::Nearest, table.data());
  }
  if (!this->CreateAtlas(renWin, texels, width, filter))
  {
    return false;
  }
  // The atlas is sent one layer of slots at a time, from a buffer of one
  // layer (a few MB), not packed whole first: a 512^3 field's atlas is
  // 0.5 GB, which the driver holds already.
  const vtkIdType layerSlots = static_cast<vtkIdType>(atlas[0]) * atlas[1];
  const std::size_t layerTexels = static_cast<std::size_t>(texels[0]) * texels[1] * B;
  std::vector<float> layer(width == 4 ? layerTexels : 0);
  std::vector<std::uint16_t> layer16(width == 2 ? layerTexels : 0);
  auto pack = [&](vtkIdType first, vtkIdType begin, vtkIdType end)
  {
    double brick[B * B * B];
    for (vtkIdType s = begin; s < end; ++s)
    {
      const vtkIdType slot = first + s;
      const int sx = static_cast<int>(s % atlas[0]), sy = static_cast<int>(s / atlas[0]);
      double offset = 0.0, perStep = 0.0; // the slot's steps of 1 / 65,535 per unit of value
      if (slot < slotCount)
      {
        readSlot(slot, brick);
        const float* slotValue = &impl.SlotValue[2 * static_cast<std::size_t>(slot)];
        offset = slotValue[1];
        perStep = slotValue[0] > 0.f ? 65535.0 / slotValue[0] : 0.0;
      }
      for (int k = 0; k < B; ++k)
        for (int j = 0; j < B; ++j)
        {
          const std::size_t row =
            (static_cast<std::size_t>(k) * texels[1] + (sy * B + j)) * texels[0] + sx * B;
          for (int i = 0; i < B; ++i)
          {
            // Zeros in the atlas's unused slots.
            const double v = slot < slotCount ? brick[(k * B + j) * B + i] : 0.0;
            if (width == 2)
            {
              layer16[row + i] = slot < slotCount
                ? static_cast<std::uint16_t>(
                    std::clamp(std::nearbyint((v - offset) * perStep), 0.0, 65535.0))
                : std::uint16_t{ 0 };
            }
            else
            {
              layer[row + i] = static_cast<float>(v);
            }
          }
        }
    }
  };
  impl.Extinction->Activate();
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  for (int sz = 0; sz < atlas[2]; ++sz)
  {
    const vtkIdType first = sz * layerSlots;
    if (threads)
    {
      vtkSMPTools::For(
        0, layerSlots, [&](vtkIdType begin, vtkIdType end) { pack(first, begin, end); });
    }
    else
    {
      pack(first, 0, layerSlots);
    }
    const void* texelData = width == 2 ? static_cast<const void*>(layer16.data())
                                       : static_cast<const void*>(layer.data());
    glTexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, sz * B, texels[0], texels[1], B, GL_RED,
      width == 2 ? GL_UNSIGNED_SHORT : GL_FLOAT, texelData);
  }
  impl.Extinction->Deactivate();
  impl.AtlasSamples = source;
  impl.AtlasSlots = slots;
  impl.AtlasFilter = filter;
  impl.AtlasLargest = storedLargest;
  ++impl.AtlasUploads;
  return Upload3D(impl.BrickTable, renWin, brickDims, 4, vtkTextureObject::Nearest, table.data());
}

bool vtkBrumeOpenGLSliceVolumeMapper::CreateAtlas(
  vtkOpenGLRenderWindow* renWin, const int texels[3], int bytes, int filter)
{
  vtkTextureObject* texture = this->Impl->Extinction;
  const int type = bytes == 2 ? VTK_UNSIGNED_SHORT : VTK_FLOAT;
  const unsigned int format = bytes == 2 ? GL_R16 : GL_R32F;
  texture->SetMinificationFilter(filter);
  texture->SetMagnificationFilter(filter);
  if (texture->GetHandle() && texture->GetContext() == renWin &&
    texture->GetTarget() == GL_TEXTURE_3D && static_cast<int>(texture->GetWidth()) == texels[0] &&
    static_cast<int>(texture->GetHeight()) == texels[1] &&
    static_cast<int>(texture->GetDepth()) == texels[2] && texture->GetComponents() == 1 &&
    texture->GetVTKDataType() == type)
  {
    return true; // the same storage, filled in place
  }
  // An atlas the GPU says it cannot hold (beside what the one it replaces
  // frees) fails here, with the sizes, rather than in the driver.
  const double needed = static_cast<double>(texels[0]) * texels[1] * texels[2] * bytes;
  const vtkTypeInt64 available = vtkBrumeOpenGLSliceVolumeMapper::GetFreeGPUMemory(renWin);
  const double replaced = texture->GetHandle() && texture->GetContext() == renWin
    ? static_cast<double>(texture->GetWidth()) * texture->GetHeight() * texture->GetDepth() *
      texture->GetComponents() * vtkAbstractArray::GetDataTypeSize(texture->GetVTKDataType())
    : 0.0;
  if (available >= 0 && needed > static_cast<double>(available) + replaced)
  {
    vtkErrorMacro("Cannot draw this medium: its bricks of extinction need a texture of "
      << std::llround(needed / 1048576.0) << " MB, more than the "
      << std::llround((static_cast<double>(available) + replaced) / 1048576.0)
      << " MB this GPU has free. A smaller NativeMemoryLimit coarsens it "
         "(vtkBrumeRadianceReconstruction; brume: --native-memory).");
    return false;
  }
  texture->SetContext(renWin);
  texture->SetWrapS(vtkTextureObject::ClampToEdge);
  texture->SetWrapT(vtkTextureObject::ClampToEdge);
  texture->SetWrapR(vtkTextureObject::ClampToEdge);
  texture->SetInternalFormat(format);
  const bool made = texture->Create3DFromRaw(static_cast<unsigned int>(texels[0]),
    static_cast<unsigned int>(texels[1]), static_cast<unsigned int>(texels[2]), 1, type, nullptr);
  texture->SetInternalFormat(0); // the default for the texture's next use
  return made;
}

double vtkBrumeOpenGLSliceVolumeMapper::GetExtinctionAtlasDepthError() const
{
  return this->Impl->AtlasDepthError;
}

int vtkBrumeOpenGLSliceVolumeMapper::GetNumberOfExtinctionAtlasUploads() const
{
  return this->Impl->AtlasUploads;
}

int vtkBrumeOpenGLSliceVolumeMapper::GetExtinctionAtlasTexelBytes() const
{
  return this->Impl->AtlasBytes;
}

int vtkBrumeOpenGLSliceVolumeMapper::GetNumberOfBendingBricks() const
{
  return this->Impl->BendingBricks;
}

vtkIdType vtkBrumeOpenGLSliceVolumeMapper::GetNumberOfBendingParts() const
{
  return this->Impl->BendingParts;
}

bool vtkBrumeOpenGLSliceVolumeMapper::UploadTransferFunction(
  vtkFieldData* fd, vtkOpenGLRenderWindow* renWin, double& largest)
{
  // One row of the table (resampled to the GPU's widest texture if need
  // be), filtered linearly; its largest value bounds sigma_t.
  Internals& impl = *this->Impl;
  vtkDataArray* transfer = fd->GetArray(vtkBrumeNames::ExtinctionTransferFunction);
  vtkDataArray* range = fd->GetArray(vtkBrumeNames::ExtinctionTransferRange);
  int maxWidth = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxWidth);
  // A varying albedo: in the same row, green to alpha.
  vtkDataArray* albedo = fd->GetArray(vtkBrumeNames::AlbedoTransferFunction);
  impl.Albedo = albedo != nullptr;
  const int channels = impl.Albedo ? 4 : 1;
  const vtkIdType n = transfer->GetNumberOfTuples();
  const int width = static_cast<int>(std::min<vtkIdType>(n, std::max(2, maxWidth)));
  std::vector<float> row(static_cast<std::size_t>(width) * channels);
  largest = 0.0;
  for (int i = 0; i < width; ++i)
  {
    const double x = static_cast<double>(i) * static_cast<double>(n - 1) / (width - 1);
    const vtkIdType at = std::min(static_cast<vtkIdType>(x), n - 2);
    const double f = x - static_cast<double>(at);
    float* texel = &row[static_cast<std::size_t>(i) * channels];
    texel[0] =
      static_cast<float>(transfer->GetTuple1(at) * (1.0 - f) + transfer->GetTuple1(at + 1) * f);
    largest = std::max(largest, static_cast<double>(texel[0]));
    for (int c = 1; c < channels; ++c)
    {
      texel[c] = static_cast<float>(
        albedo->GetComponent(at, c - 1) * (1.0 - f) + albedo->GetComponent(at + 1, c - 1) * f);
    }
  }
  impl.TransferRange[0] = static_cast<float>(range->GetComponent(0, 0));
  impl.TransferRange[1] = static_cast<float>(range->GetComponent(0, 1));
  impl.TransferSamples = static_cast<float>(width);
  vtkTextureObject* texture = impl.TransferTable;
  texture->SetContext(renWin);
  texture->SetWrapS(vtkTextureObject::ClampToEdge);
  texture->SetWrapT(vtkTextureObject::ClampToEdge);
  texture->SetMinificationFilter(vtkTextureObject::Linear);
  texture->SetMagnificationFilter(vtkTextureObject::Linear);
  return texture->Create2DFromRaw(
    static_cast<unsigned int>(width), 1, channels, VTK_FLOAT, row.data());
}

bool vtkBrumeOpenGLSliceVolumeMapper::UploadDirectional(vtkImageData* input,
  vtkOpenGLRenderWindow* renWin, const int dims[3], int filter, const std::vector<float>& e)
{
  Internals& impl = *this->Impl;
  const vtkIdType cells = static_cast<vtkIdType>(dims[0]) * dims[1] * dims[2];
  // Directional radiance: 3 (order + 1)^2 values per voxel, J-scaled like
  // the source; evaluated per voxel below, or per fragment from RGBA
  // textures (four values each).
  impl.Order = 0;
  impl.FragmentOrder = 0;
  impl.Voxels.clear();
  vtkSmartPointer<vtkDataArray> sh = DenseSourceArray(input, vtkBrumeNames::SourceRadianceSH);
  const int order = sh ? DirectionalOrder(sh->GetNumberOfComponents()) : -1;
  if (order <= 0)
  {
    return true;
  }
  const int values = sh->GetNumberOfComponents();
  std::vector<float> coefficients(static_cast<std::size_t>(values) * cells);
  for (vtkIdType i = 0; i < cells; ++i)
  {
    for (int v = 0; v < values; ++v)
    {
      float& value = coefficients[static_cast<std::size_t>(i) * values + v];
      value = static_cast<float>(sh->GetComponent(i, v)) * e[4 * i + v % 3];
      if (!std::isfinite(value))
      {
        vtkErrorMacro(
          "Cannot draw this medium: its directional radiance must be finite (cell " << i << ").");
        return false;
      }
    }
  }
  if (this->DirectionalEvaluation == PerFragment)
  {
    const int textures = (values + 3) / 4;
    std::vector<float> packed(4 * static_cast<std::size_t>(cells));
    impl.Coefficients.resize(static_cast<std::size_t>(textures));
    for (int t = 0; t < textures; ++t)
    {
      for (vtkIdType i = 0; i < cells; ++i)
      {
        for (int c = 0; c < 4; ++c)
        {
          const int value = 4 * t + c;
          packed[4 * i + c] =
            value < values ? coefficients[static_cast<std::size_t>(i) * values + value] : 0.f;
        }
      }
      auto& texture = impl.Coefficients[t];
      if (!texture)
      {
        texture = vtkSmartPointer<vtkTextureObject>::New();
      }
      if (!Upload3D(texture, renWin, dims, 4, filter, packed.data()))
      {
        vtkErrorMacro("Could not create the directional radiance textures: nothing drawn.");
        return false;
      }
    }
    impl.FragmentOrder = order;
  }
  else
  {
    impl.Voxels.swap(coefficients);
    impl.EvaluatedEye[0] = std::numeric_limits<float>::quiet_NaN(); // evaluate below
  }
  impl.Order = order;
  impl.G = static_cast<float>(
    input->GetFieldData()->GetArray(vtkBrumeNames::PhaseAsymmetry)->GetTuple1(0));
  return true;
}

bool vtkBrumeOpenGLSliceVolumeMapper::EvaluateTowardEye(
  vtkOpenGLRenderWindow* renWin, const int dims[3], int interpolation)
{
  Internals& impl = *this->Impl;
  if (impl.Order <= 0 || impl.FragmentOrder != 0 ||
    (impl.EvaluatedEye[0] == impl.EyeData[0] && impl.EvaluatedEye[1] == impl.EyeData[1] &&
      impl.EvaluatedEye[2] == impl.EyeData[2]))
  {
    return true;
  }
  // Directional radiance toward the eye, once per view and voxel centre.
  const int values = 3 * brume::ShCoefficients(impl.Order);
  const std::size_t cells = impl.Voxels.size() / values;
  std::vector<float>& source = impl.Scratch;
  source.assign(4 * cells, 0.f);
  const brume::Vec3 eyeData(impl.EyeData[0], impl.EyeData[1], impl.EyeData[2]);
  vtkSMPTools::For(0, static_cast<vtkIdType>(cells),
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType i = begin; i < end; ++i)
      {
        const vtkIdType x = i % dims[0], y = (i / dims[0]) % dims[1], z = i / (dims[0] * dims[1]);
        const brume::Vec3 centre(
          impl.BoundsLower[0] + (static_cast<float>(x) + 0.5f) * impl.BoundsExtent[0] / dims[0],
          impl.BoundsLower[1] + (static_cast<float>(y) + 0.5f) * impl.BoundsExtent[1] / dims[1],
          impl.BoundsLower[2] + (static_cast<float>(z) + 0.5f) * impl.BoundsExtent[2] / dims[2]);
        const brume::Vec3 toEye = brume::Normalize(eyeData - centre);
        for (int c = 0; c < 3; ++c)
        {
          source[4 * i + c] = std::max(0.f,
            brume::EvaluateHgFromSh(impl.Order, impl.G,
              &impl.Voxels[static_cast<std::size_t>(i) * values + c], 3, toEye));
        }
      }
    });
  const int filter = interpolation == VTK_NEAREST_INTERPOLATION ? vtkTextureObject::Nearest
                                                                : vtkTextureObject::Linear;
  if (!Upload3D(impl.Source, renWin, dims, 4, filter, source.data()))
  {
    vtkErrorMacro("Could not upload the directional radiance toward the eye: nothing drawn.");
    return false;
  }
  std::copy(impl.EyeData, impl.EyeData + 3, impl.EvaluatedEye);
  return true;
}
