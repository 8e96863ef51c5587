// SPDX-License-Identifier: BSD-3-Clause
// The slice mapper's 3D textures: the source radiance, the extinction (at
// the source's resolution or its own), directional radiance and its
// evaluation toward the eye.
#include "vtkBrumeOpenGLSliceVolumeMapperInternals.h"

#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkSMPTools.h"
#include "vtk_glew.h"

#include "brume/SphericalHarmonics.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace
{
// Uploads `values` (`components` floats per voxel) as a 3D texture clamped
// at the edges and filtered with `filter` (nearest or linear).
bool Upload3D(vtkTextureObject* texture, vtkOpenGLRenderWindow* window, const int dims[3],
  int components, int filter, float* values)
{
  texture->SetContext(window);
  texture->SetWrapS(vtkTextureObject::ClampToEdge);
  texture->SetWrapT(vtkTextureObject::ClampToEdge);
  texture->SetWrapR(vtkTextureObject::ClampToEdge);
  texture->SetMinificationFilter(filter);
  texture->SetMagnificationFilter(filter);
  return texture->Create3DFromRaw(static_cast<unsigned int>(dims[0]),
    static_cast<unsigned int>(dims[1]), static_cast<unsigned int>(dims[2]), components, VTK_FLOAT,
    values);
}
}

bool vtkBrumeOpenGLSliceVolumeMapper::UploadTextures(
  vtkImageData* input, vtkOpenGLRenderWindow* renWin, const int dims[3], int interpolation)
{
  // Two RGB float 3D textures: source radiance and extinction.
  Internals& impl = *this->Impl;
  const vtkIdType cells = static_cast<vtkIdType>(dims[0]) * dims[1] * dims[2];
  vtkDataArray* source = input->GetCellData()->GetArray("SourceRadiance");
  vtkDataArray* extinction = input->GetCellData()->GetArray("Extinction");
  std::vector<float> s(3 * static_cast<std::size_t>(cells)), e(s.size());
  const int ne = extinction->GetNumberOfComponents();
  // With extinction at its own resolution the source texture holds S, which
  // the shader multiplies by the fine sigma_t; otherwise it holds J.
  impl.SourceIsRadiance = this->ExtinctionData != nullptr;
  for (vtkIdType i = 0; i < cells; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      // The texture holds J = S sigma_t: filtered between voxels, J and
      // sigma_t stay bounded where the medium thins out (S would not).
      e[3 * i + c] = static_cast<float>(extinction->GetComponent(i, ne == 3 ? c : 0));
      s[3 * i + c] = static_cast<float>(source->GetComponent(i, c)) *
        (impl.SourceIsRadiance ? 1.f : e[3 * i + c]);
      if (!(e[3 * i + c] >= 0.f) || !std::isfinite(e[3 * i + c]) || !std::isfinite(s[3 * i + c]))
      {
        vtkErrorMacro("Cannot draw this medium: its extinction must be finite and "
                      "non-negative and its source radiance finite (cell "
          << i << ").");
        return false;
      }
    }
  }
  const int filter = interpolation == VTK_NEAREST_INTERPOLATION ? vtkTextureObject::Nearest
                                                                : vtkTextureObject::Linear;
  if (!Upload3D(impl.Source, renWin, dims, 3, filter, s.data()) ||
    !(impl.SourceIsRadiance ? this->UploadExtinction(renWin, filter)
                            : Upload3D(impl.Extinction, renWin, dims, 3, filter, e.data())))
  {
    vtkErrorMacro("Could not create the 3D textures (" << dims[0] << " x " << dims[1] << " x "
                                                       << dims[2] << "): nothing drawn.");
    return false;
  }
  if (impl.SourceIsRadiance)
  {
    e.assign(e.size(), 1.f); // directional coefficients: S, like the source
  }
  else
  {
    impl.ExtinctionGrid = nullptr; // the extinction texture is the input's
    impl.Bricked = false;
  }
  if (!this->UploadDirectional(input, renWin, dims, filter, e))
  {
    return false;
  }
  impl.Interpolation = interpolation;
  impl.TextureTime.Modified();
  return true;
}

bool vtkBrumeOpenGLSliceVolumeMapper::UploadExtinction(vtkOpenGLRenderWindow* renWin, int filter)
{
  // The grid of its own changes seldom (it is the density's): uploaded only
  // when it is another grid, was modified, or is filtered otherwise.
  Internals& impl = *this->Impl;
  vtkImageData* grid = this->ExtinctionData;
  if (impl.ExtinctionGrid == grid && impl.ExtinctionTime > grid->GetMTime() &&
    impl.ExtinctionInterpolation == filter && impl.Extinction->GetHandle())
  {
    return true;
  }
  int pointDims[3];
  grid->GetDimensions(pointDims);
  const int dims[3] = { pointDims[0] - 1, pointDims[1] - 1, pointDims[2] - 1 };
  impl.Bricked = grid->GetFieldData()->GetArray("ExtinctionBrickSamples") != nullptr;
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
  const vtkIdType cells = static_cast<vtkIdType>(dims[0]) * dims[1] * dims[2];
  vtkDataArray* extinction = grid->GetCellData()->GetArray("Extinction");
  const int ne = extinction->GetNumberOfComponents();
  std::vector<float> e(3 * static_cast<std::size_t>(cells));
  for (vtkIdType i = 0; i < cells; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      const float value = static_cast<float>(extinction->GetComponent(i, ne == 3 ? c : 0));
      if (!(value >= 0.f) || !std::isfinite(value))
      {
        vtkErrorMacro("Cannot draw this medium: its extinction must be finite and non-negative "
                      "(cell "
          << i << " of the extinction grid).");
        return false;
      }
      e[3 * i + c] = value;
    }
  }
  return Upload3D(this->Impl->Extinction, renWin, dims, 3, filter, e.data());
}

bool vtkBrumeOpenGLSliceVolumeMapper::UploadBricks(
  vtkImageData* grid, const int dims[3], vtkOpenGLRenderWindow* renWin, int filter)
{
  // The slots side by side in a 3D atlas (at least one, so that the
  // sampler has a texture), about cubic in slots; the brick table beside it.
  Internals& impl = *this->Impl;
  vtkFieldData* fd = grid->GetFieldData();
  vtkDataArray* slots = fd->GetArray("ExtinctionBrickSlots");
  vtkDataArray* values = fd->GetArray("ExtinctionBrickValues");
  vtkDataArray* samples = fd->GetArray("ExtinctionBrickSamples");
  vtkDataArray* scale = fd->GetArray("ExtinctionScale");
  constexpr int B = ExtinctionBrickSize;
  constexpr vtkIdType BrickCells = B * B * B;
  const vtkIdType slotCount = samples->GetNumberOfTuples() / BrickCells;
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
  if (texels[0] > maxSize || texels[1] > maxSize || texels[2] > maxSize)
  {
    vtkErrorMacro("Cannot draw this medium: its "
      << slotCount << " bricks of extinction need a 3D texture of " << texels[0] << " x "
      << texels[1] << " x " << texels[2] << ", beyond this GPU's " << maxSize << ".");
    return false;
  }
  std::vector<float> packed(static_cast<std::size_t>(texels[0]) * texels[1] * texels[2], 0.f);
  auto invalid = [](double v) { return !(v >= 0.0) || !std::isfinite(v); };
  for (vtkIdType slot = 0; slot < slotCount; ++slot)
  {
    const int sx = static_cast<int>(slot % atlas[0]),
              sy = static_cast<int>((slot / atlas[0]) % atlas[1]),
              sz = static_cast<int>(slot / (static_cast<vtkIdType>(atlas[0]) * atlas[1]));
    for (int k = 0; k < B; ++k)
      for (int j = 0; j < B; ++j)
        for (int i = 0; i < B; ++i)
        {
          const double v = samples->GetTuple1(slot * BrickCells + (k * B + j) * B + i);
          if (invalid(v))
          {
            vtkErrorMacro("Cannot draw this medium: its extinction must be finite and "
                          "non-negative (brick slot "
              << slot << " of the extinction grid).");
            return false;
          }
          packed[(static_cast<std::size_t>(sz * B + k) * texels[1] + (sy * B + j)) * texels[0] +
            (sx * B + i)] = static_cast<float>(v);
        }
  }
  const vtkIdType bricks = slots->GetNumberOfTuples();
  const int brickDims[3] = { ExtinctionBricksAlong(dims[0]), ExtinctionBricksAlong(dims[1]),
    ExtinctionBricksAlong(dims[2]) };
  std::vector<float> table(4 * static_cast<std::size_t>(bricks));
  for (vtkIdType b = 0; b < bricks; ++b)
  {
    const vtkIdType slot = static_cast<vtkIdType>(slots->GetTuple1(b));
    float* entry = &table[4 * static_cast<std::size_t>(b)];
    if (slot < 0)
    {
      const double v = values->GetTuple1(b);
      if (invalid(v))
      {
        vtkErrorMacro("Cannot draw this medium: its extinction must be finite and non-negative "
                      "(brick "
          << b << " of the extinction grid).");
        return false;
      }
      entry[0] = static_cast<float>(v);
      entry[3] = -1.f;
      continue;
    }
    entry[0] = static_cast<float>(B * (slot % atlas[0]));
    entry[1] = static_cast<float>(B * ((slot / atlas[0]) % atlas[1]));
    entry[2] = static_cast<float>(B * (slot / (static_cast<vtkIdType>(atlas[0]) * atlas[1])));
    entry[3] = 1.f;
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
  return Upload3D(impl.Extinction, renWin, texels, 1, filter, packed.data()) &&
    Upload3D(impl.BrickTable, renWin, brickDims, 4, vtkTextureObject::Nearest, table.data());
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
  vtkDataArray* sh = input->GetCellData()->GetArray("SourceRadianceSH");
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
      value = static_cast<float>(sh->GetComponent(i, v)) * e[3 * i + v % 3];
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
  impl.G = static_cast<float>(input->GetFieldData()->GetArray("BrumePhaseAsymmetry")->GetTuple1(0));
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
  std::vector<float> source(3 * cells);
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
          source[3 * i + c] = std::max(0.f,
            brume::EvaluateHgFromSh(impl.Order, impl.G,
              &impl.Voxels[static_cast<std::size_t>(i) * values + c], 3, toEye));
        }
      }
    });
  const int filter = interpolation == VTK_NEAREST_INTERPOLATION ? vtkTextureObject::Nearest
                                                                : vtkTextureObject::Linear;
  if (!Upload3D(impl.Source, renWin, dims, 3, filter, source.data()))
  {
    vtkErrorMacro("Could not upload the directional radiance toward the eye: nothing drawn.");
    return false;
  }
  std::copy(impl.EyeData, impl.EyeData + 3, impl.EvaluatedEye);
  return true;
}
