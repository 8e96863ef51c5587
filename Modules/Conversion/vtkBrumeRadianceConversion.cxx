// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeRadianceConversion.h"
#include "vtkBrumeSMP.h"
#include "vtkBrumeSceneConversionInternals.h"
#include "vtkBrumeSharedArray.h"

#include "vtkBrumeDataModelNames.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"

#include "brume/Density.h"
#include "brume/SparseTexture.h"
#include "brume/SphericalHarmonics.h"
#include "brume/TransferFunction.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

namespace
{
// The tables the slice mapper classifies scalars by (its ExtinctionData's
// ExtinctionTransferFunction, ExtinctionTransferRange and, with colours,
// AlbedoTransferFunction): the function's extinction at
// TransferFunctionSamples scalars evenly over its points' range (its end
// values beyond), and the albedo the colour function gives, over both
// functions' points. Replaces those arrays in `fd`.
void AddTransferTables(vtkFieldData* fd, const brume::OpacityTransferFunction& function,
  const brume::ColorTransferFunction* colors, const brume::Vec3& albedoScale)
{
  constexpr int samples = vtkBrumeRadianceConversion::TransferFunctionSamples;
  float lo = function.GetNodes().front().Scalar;
  float last = function.GetNodes().back().Scalar;
  if (colors)
  {
    lo = std::min(lo, colors->GetNodes().front().Scalar);
    last = std::max(last, colors->GetNodes().back().Scalar);
  }
  // One point (or all at one scalar): any range past it holds the end values.
  const float hi = last > lo ? last : lo + std::max(1.f, std::abs(lo));
  vtkNew<vtkFloatArray> table;
  table->SetName(vtkBrumeNames::ExtinctionTransferFunction);
  table->SetNumberOfValues(samples);
  vtkNew<vtkFloatArray> albedo;
  albedo->SetName(vtkBrumeNames::AlbedoTransferFunction);
  albedo->SetNumberOfComponents(3);
  albedo->SetNumberOfTuples(colors ? samples : 0);
  for (int i = 0; i < samples; ++i)
  {
    const float t = static_cast<float>(i) / static_cast<float>(samples - 1);
    const float s = lo + (hi - lo) * t;
    table->SetValue(i, function.Extinction(s));
    if (colors)
    {
      const brume::Vec3 a = albedoScale * colors->Color(s);
      albedo->SetTypedTuple(i, &a.x);
    }
  }
  fd->RemoveArray(vtkBrumeNames::ExtinctionTransferFunction);
  fd->RemoveArray(vtkBrumeNames::AlbedoTransferFunction);
  fd->RemoveArray(vtkBrumeNames::ExtinctionTransferRange);
  fd->AddArray(table);
  if (colors)
  {
    fd->AddArray(albedo);
  }
  vtkNew<vtkDoubleArray> range;
  range->SetName(vtkBrumeNames::ExtinctionTransferRange);
  range->SetNumberOfComponents(2);
  range->InsertNextTuple2(lo, hi);
  fd->AddArray(range);
}

void AddVec3(vtkFieldData* fd, const char* name, const brume::Vec3& v)
{
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->SetNumberOfComponents(3);
  a->InsertNextTuple3(v.x, v.y, v.z);
  fd->AddArray(a);
}

void AddString(vtkFieldData* fd, const char* name, const char* value)
{
  vtkNew<vtkStringArray> a;
  a->SetName(name);
  a->InsertNextValue(value);
  fd->AddArray(a);
}

vtkSmartPointer<vtkFloatArray> NewRGB(const char* name, const std::vector<float>& values)
{
  auto a = vtkSmartPointer<vtkFloatArray>::New();
  a->SetName(name);
  a->SetNumberOfComponents(3);
  a->SetNumberOfTuples(static_cast<vtkIdType>(values.size() / 3));
  std::copy(values.begin(), values.end(), a->GetPointer(0));
  return a;
}

const char* ChartName(brume::SurfaceChart::Kind kind)
{
  switch (kind)
  {
    case brume::SurfaceChart::Kind::Planar:
      return "planar";
    case brume::SurfaceChart::Kind::TextureCoordinates:
      return "texture coordinates";
    default:
      return "atlas";
  }
}

// The surface with separate points per triangle: each has its own chart.
// Written in place (not point by point: 2*10^6 triangles took 0.3 s that
// way), triangles on every thread.
void MapAtlas(const brume::Surface& surface, const brume::SurfaceChart& chart,
  vtkPolyData* sceneSurface, vtkPolyData* mapped, vtkFloatArray* tcoords)
{
  const auto count = static_cast<vtkIdType>(surface.Triangles.size());
  vtkNew<vtkFloatArray> xyz;
  xyz->SetNumberOfComponents(3);
  xyz->SetNumberOfTuples(3 * count);
  tcoords->SetNumberOfTuples(3 * count);
  vtkNew<vtkIdTypeArray> offsets, connectivity;
  offsets->SetNumberOfValues(count + 1);
  connectivity->SetNumberOfValues(3 * count);
  float* p = xyz->GetPointer(0);
  float* uv = tcoords->GetPointer(0);
  vtkIdType* offset = offsets->GetPointer(0);
  vtkIdType* ids = connectivity->GetPointer(0);
  offset[count] = 3 * count;
  vtkBrumeSMP::ParallelFor()(0, surface.Triangles.size(),
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t triangle = begin; triangle < end; ++triangle)
      {
        const auto t = static_cast<vtkIdType>(triangle);
        offset[t] = 3 * t;
        for (int k = 0; k < 3; ++k)
        {
          const brume::Vec3& v = surface.Vertices[surface.Triangles[triangle][k]];
          const vtkIdType id = 3 * t + k;
          p[3 * id] = v.x;
          p[3 * id + 1] = v.y;
          p[3 * id + 2] = v.z;
          uv[2 * id] = chart.TriangleUV[triangle][2 * k];
          uv[2 * id + 1] = chart.TriangleUV[triangle][2 * k + 1];
          ids[id] = id;
        }
      }
    });
  vtkNew<vtkPoints> points;
  points->SetData(xyz);
  vtkNew<vtkCellArray> triangles;
  triangles->SetData(offsets, connectivity);
  mapped->SetPoints(points);
  mapped->SetPolys(triangles);
  mapped->GetFieldData()->ShallowCopy(sceneSurface->GetFieldData());
}

// The scene's surface itself, with its plane's (u, v) or its own texture
// coordinates.
void MapInPlace(const brume::SurfaceChart& chart, vtkPolyData* sceneSurface, vtkPolyData* mapped,
  vtkFloatArray* tcoords)
{
  mapped->ShallowCopy(sceneSurface);
  tcoords->SetNumberOfTuples(mapped->GetNumberOfPoints());
  const float uu = Dot(chart.Frame.U, chart.Frame.U), vv = Dot(chart.Frame.V, chart.Frame.V);
  vtkDataArray* given = sceneSurface->GetPointData()->GetTCoords();
  for (vtkIdType i = 0; i < mapped->GetNumberOfPoints(); ++i)
  {
    if (chart.Type == brume::SurfaceChart::Kind::Planar)
    {
      double p[3];
      mapped->GetPoint(i, p);
      const brume::Vec3 d =
        brume::Vec3(static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2])) -
        chart.Frame.Origin;
      tcoords->SetTuple2(i, Dot(d, chart.Frame.U) / uu, Dot(d, chart.Frame.V) / vv);
    }
    else
    {
      tcoords->SetTuple2(i, given->GetComponent(i, 0), given->GetComponent(i, 1));
    }
  }
}

// A medium texture's source array: a cell array, or in the sparse form
// (`bricks` given) the field array BrickSamplesName(name).
void AddSourceArray(vtkImageData* texture, const brume::SparseTexture* bricks, const char* name,
  const std::vector<float>& values, int components)
{
  auto a = vtkSmartPointer<vtkFloatArray>::New();
  a->SetNumberOfComponents(components);
  if (bricks)
  {
    a->SetName(vtkBrumeNames::BrickSamplesName(name).c_str());
    const std::vector<float> gathered = bricks->Gather(values, components);
    a->SetNumberOfTuples(static_cast<vtkIdType>(gathered.size() / components));
    std::copy(gathered.begin(), gathered.end(), a->GetPointer(0));
    texture->GetFieldData()->AddArray(a);
  }
  else
  {
    a->SetName(name);
    a->SetNumberOfTuples(static_cast<vtkIdType>(values.size() / components));
    std::copy(values.begin(), values.end(), a->GetPointer(0));
    texture->GetCellData()->AddArray(a);
  }
}

// A varying albedo baked into a medium's texture (on a grid without the
// albedo's table): per texel, and the extinction's factor.
struct BakedAlbedo
{
  std::vector<brume::Vec3> Texel;
  brume::Vec3 Factor = brume::Vec3(1.f);
};

// Per texel, the albedo's sigma_t-weighted mean over 2^3 points of the
// texel, so that the emission sigma_t a X is kept; the extinction takes one
// factor, that of the medium's sigma_t-weighted mean albedo.
BakedAlbedo BakeAlbedo(const brume::ObjectRadiance& radiance, const brume::Medium& medium,
  bool directional, const std::array<int, 3>& res, const brume::Vec3& extent)
{
  BakedAlbedo baked;
  std::vector<brume::Vec3>& texelAlbedo = baked.Texel;
  const std::size_t texels = static_cast<std::size_t>(res[0]) * res[1] * res[2];
  const brume::Vec3 cell(extent.x / res[0], extent.y / res[1], extent.z / res[2]);
  texelAlbedo.resize(texels);
  std::vector<double> texelWeight(texels);
  vtkBrumeSMP::ParallelFor()(0, texels,
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t t = begin; t < end; ++t)
      {
        const int i = static_cast<int>(t % res[0]), j = static_cast<int>((t / res[0]) % res[1]),
                  k = static_cast<int>(t / (static_cast<std::size_t>(res[0]) * res[1]));
        double sum[3] = { 0.0, 0.0, 0.0 }, weight = 0.0;
        for (int q = 0; q < 8; ++q)
        {
          const brume::Vec3 p = medium.Bounds.lower +
            cell *
              brume::Vec3(static_cast<float>(i) + ((q & 1) ? 0.75f : 0.25f),
                static_cast<float>(j) + ((q & 2) ? 0.75f : 0.25f),
                static_cast<float>(k) + ((q & 4) ? 0.75f : 0.25f));
          const double w = medium.SigmaTAt(p).x;
          const brume::Vec3 a = medium.AlbedoAt(p);
          for (int c = 0; c < 3; ++c)
          {
            sum[c] += w * a[c];
          }
          weight += w;
        }
        const brume::Vec3 centre = medium.AlbedoAt(medium.Bounds.lower +
          cell *
            brume::Vec3(static_cast<float>(i) + 0.5f, static_cast<float>(j) + 0.5f,
              static_cast<float>(k) + 0.5f));
        texelAlbedo[t] = weight > 0.0
          ? brume::Vec3(static_cast<float>(sum[0] / weight), static_cast<float>(sum[1] / weight),
              static_cast<float>(sum[2] / weight))
          : centre;
        texelWeight[t] = weight;
      }
    });
  double sum[3] = { 0.0, 0.0, 0.0 }, weight = 0.0;
  for (std::size_t t = 0; t < texels; ++t)
  {
    for (int c = 0; c < 3; ++c)
    {
      sum[c] += texelWeight[t] * texelAlbedo[t][c];
    }
    weight += texelWeight[t];
  }
  const float forward = radiance.GetLayout().Scattering.GetPeak(directional).Forward;
  for (int c = 0; c < 3; ++c)
  {
    baked.Factor[c] = 1.f - (weight > 0.0 ? static_cast<float>(sum[c] / weight) : 1.f) * forward;
  }
  return baked;
}

// A medium texture's source radiance (toward the eye, or the directional
// projection), with `albedo` applied where it is baked (given).
void AddSourceRadiance(vtkImageData* texture, const brume::SparseTexture* bricks,
  const brume::ObjectRadiance& radiance, bool directional, const BakedAlbedo* albedo)
{
  // The source's values, the albedo applied where it is baked.
  std::vector<float> bakedValues;
  auto baked = [&](const std::vector<float>& values, int components) -> const std::vector<float>&
  {
    if (!albedo)
    {
      return values;
    }
    bakedValues = values;
    for (std::size_t t = 0; t < albedo->Texel.size(); ++t)
    {
      for (int c = 0; c < components; ++c)
      {
        bakedValues[t * components + c] *= albedo->Texel[t][c % 3] / albedo->Factor[c % 3];
      }
    }
    return bakedValues;
  };
  if (directional)
  {
    // The projection, and as SourceRadiance its mean over directions (the
    // l = 0 term: c_00 Y_00).
    const int order = radiance.GetDirectional().GetOrder();
    const int components = 3 * brume::ShCoefficients(order);
    const std::vector<float>& coefficients =
      baked(radiance.GetDirectional().GetCoefficients(), components);
    std::vector<float> mean(3 * (coefficients.size() / components));
    for (std::size_t t = 0; t < mean.size() / 3; ++t)
    {
      for (int c = 0; c < 3; ++c)
      {
        mean[3 * t + c] = std::max(0.f, brume::ShY00 * coefficients[t * components + c]);
      }
    }
    AddSourceArray(texture, bricks, vtkBrumeNames::SourceRadiance, mean, 3);
    AddSourceArray(texture, bricks, vtkBrumeNames::SourceRadianceSH, coefficients, components);
    vtkNew<vtkDoubleArray> g;
    g->SetName(vtkBrumeNames::PhaseAsymmetry);
    g->InsertNextValue(radiance.GetLayout().Scattering.GetPeak(true).G); // the remainder's, past
                                                                         // DirectionalResolvedG
    texture->GetFieldData()->AddArray(g);
  }
  else
  {
    AddSourceArray(
      texture, bricks, vtkBrumeNames::SourceRadiance, baked(radiance.GetOutput().Radiance, 3), 3);
  }
}

// A dense texture's Extinction cell array: `previous`'s where it holds the
// same values (renderers then see the same array), a new one otherwise.
void AddTextureExtinction(
  vtkCellData* cd, const brume::ObjectRadiance& radiance, bool directional, vtkImageData* previous)
{
  const std::vector<float>& sigmaT =
    directional ? radiance.GetTexture().Extinction : radiance.GetOutput().Extinction;
  auto* kept = previous
    ? vtkFloatArray::SafeDownCast(previous->GetCellData()->GetArray(vtkBrumeNames::Extinction))
    : nullptr;
  if (kept && kept->GetNumberOfComponents() == 3 &&
    static_cast<std::size_t>(kept->GetNumberOfValues()) == sigmaT.size() &&
    std::equal(sigmaT.begin(), sigmaT.end(), kept->GetPointer(0)))
  {
    cd->AddArray(kept);
  }
  else
  {
    cd->AddArray(NewRGB(vtkBrumeNames::Extinction, sigmaT));
  }
}
}

vtkSmartPointer<vtkPartitionedDataSet> vtkBrumeRadianceConversion::FromSurface(
  const brume::ObjectRadiance& radiance, const brume::Surface& surface, vtkPolyData* sceneSurface)
{
  const auto& res = radiance.GetOutput().Dims;
  const brume::SurfaceChart& chart = radiance.GetLayout().Chart;
  vtkNew<vtkImageData> texture;
  texture->SetDimensions(res[0], res[1], 1);
  texture->SetSpacing(1.0 / res[0], 1.0 / res[1], 1.0);
  texture->SetOrigin(0.5 / res[0], 0.5 / res[1], 0.0);
  texture->GetPointData()->SetScalars(
    NewRGB(vtkBrumeNames::Radiance, radiance.GetOutput().Radiance));
  if (chart.Type == brume::SurfaceChart::Kind::Planar)
  {
    AddVec3(texture->GetFieldData(), vtkBrumeNames::TextureOrigin, chart.Frame.Origin);
    AddVec3(texture->GetFieldData(), vtkBrumeNames::TextureU, chart.Frame.U);
    AddVec3(texture->GetFieldData(), vtkBrumeNames::TextureV, chart.Frame.V);
  }
  AddString(texture->GetFieldData(), vtkBrumeNames::TextureChart, ChartName(chart.Type));
  AddString(texture->GetFieldData(), vtkBrumeNames::ObjectKind, "surface");

  vtkNew<vtkPolyData> mapped;
  vtkNew<vtkFloatArray> tcoords;
  tcoords->SetName(vtkBrumeNames::TextureCoordinates);
  tcoords->SetNumberOfComponents(2);
  if (chart.Type == brume::SurfaceChart::Kind::Atlas)
  {
    MapAtlas(surface, chart, sceneSurface, mapped, tcoords);
  }
  else
  {
    MapInPlace(chart, sceneSurface, mapped, tcoords);
  }
  mapped->GetPointData()->SetTCoords(tcoords);
  AddString(mapped->GetFieldData(), vtkBrumeNames::ObjectKind, "surface");

  auto pds = vtkSmartPointer<vtkPartitionedDataSet>::New();
  pds->SetNumberOfPartitions(2);
  pds->SetPartition(0, texture);
  pds->SetPartition(1, mapped);
  return pds;
}

vtkSmartPointer<vtkImageData> vtkBrumeRadianceConversion::NativeExtinction(
  const brume::ObjectRadiance& radiance, const brume::Medium& medium)
{
  // A classified density gives its scalars and the function that
  // classifies them (the mapper classifies after interpolation, as the
  // tracer does); another gives sigma_t per unit density.
  const brume::OpacityTransferFunction* function = radiance.GetNative().GetClassification();
  const brume::BrickedGrid& density =
    function ? radiance.GetNative().GetScalars() : radiance.GetNative().GetDensity();
  if (density.Empty())
  {
    return nullptr;
  }
  // sigma_t at the density's own resolution, over its own box (which holds
  // the medium's: its cell centres are the density's samples), in the
  // density's bricks: the sparse form of vtkBrumeSliceVolumeMapper's
  // ExtinctionData, sigma_t per unit density beside it.
  const auto& native = density.GetDims();
  const brume::Box& box = density.GetBox();
  const brume::Vec3 extent = box.Extent();
  auto extinction = vtkSmartPointer<vtkImageData>::New();
  extinction->SetDimensions(native[0] + 1, native[1] + 1, native[2] + 1);
  extinction->SetOrigin(box.lower.x, box.lower.y, box.lower.z);
  extinction->SetSpacing(extent.x / native[0], extent.y / native[1], extent.z / native[2]);
  vtkFieldData* fd = extinction->GetFieldData();
  vtkNew<vtkIntArray> slots;
  slots->SetName(vtkBrumeNames::ExtinctionBrickSlots);
  slots->SetNumberOfValues(static_cast<vtkIdType>(density.GetSlots().size()));
  std::copy(density.GetSlots().begin(), density.GetSlots().end(), slots->GetPointer(0));
  fd->AddArray(slots);
  vtkNew<vtkFloatArray> values;
  values->SetName(vtkBrumeNames::ExtinctionBrickValues);
  values->SetNumberOfValues(static_cast<vtkIdType>(density.GetConstants().size()));
  std::copy(density.GetConstants().begin(), density.GetConstants().end(), values->GetPointer(0));
  fd->AddArray(values);
  // The grid's own samples (10^8 of them for a 512^3 field), shared, not
  // copied; scalars read in place are the field's own array, lent with the
  // medium's density, which holds it.
  if (const brume::GridDensity* field = radiance.GetNative().GetScalarField())
  {
    fd->AddArray(vtkBrumeSharedArray::Lend(field->GetValues(),
      std::shared_ptr<const void>(medium.Density), vtkBrumeNames::ExtinctionCellValues));
  }
  else
  {
    fd->AddArray(
      vtkBrumeSharedArray::Share(density.GetSamples(), vtkBrumeNames::ExtinctionBrickSamples));
  }
  vtkNew<vtkDoubleArray> scale;
  scale->SetName(vtkBrumeNames::ExtinctionScale);
  scale->SetNumberOfComponents(3);
  const brume::Vec3 sigmaT = medium.SigmaT();
  scale->InsertNextTuple3(sigmaT.x, sigmaT.y, sigmaT.z);
  fd->AddArray(scale);
  if (function)
  {
    // A colour of other scalars than the density's cannot share its table.
    const auto* colors = dynamic_cast<const brume::ClassifiedAlbedo*>(medium.AlbedoFactor.get());
    const auto* classified = dynamic_cast<const brume::ClassifiedDensity*>(medium.Density.get());
    if (colors && !(classified && &colors->GetScalars() == &classified->GetScalars()))
    {
      colors = nullptr;
    }
    AddTransferTables(fd, *function, colors ? &colors->GetColors() : nullptr, medium.Albedo());
  }
  AddString(fd, vtkBrumeNames::ObjectKind, "medium extinction");
  return extinction;
}

double vtkBrumeRadianceConversion::Classify(vtkDataArray* table, const double range[2], double s)
{
  const vtkIdType n = table->GetNumberOfTuples();
  const double x =
    std::clamp((s - range[0]) / (range[1] - range[0]), 0.0, 1.0) * static_cast<double>(n - 1);
  const vtkIdType i = std::min(static_cast<vtkIdType>(x), n - 2);
  const double f = x - static_cast<double>(i);
  return table->GetTuple1(i) * (1.0 - f) + table->GetTuple1(i + 1) * f;
}

vtkSmartPointer<vtkImageData> vtkBrumeRadianceConversion::Reclassified(
  vtkImageData* extinction, vtkFieldData* before, vtkFieldData* medium, std::string& why)
{
  vtkFieldData* old = extinction ? extinction->GetFieldData() : nullptr;
  if (!old || !old->GetArray(vtkBrumeNames::ExtinctionTransferFunction) ||
    !(old->GetArray(vtkBrumeNames::ExtinctionBrickSamples) ||
      old->GetArray(vtkBrumeNames::ExtinctionCellValues)))
  {
    why = "the extinction is not of classified scalars in bricks";
    return nullptr;
  }
  brume::Medium m, was;
  std::optional<brume::OpacityTransferFunction> opacity, wasOpacity;
  std::optional<brume::ColorTransferFunction> colors, wasColors;
  why = vtkBrumeSceneConversionInternals::ReadMediumFunctions(medium, m, opacity, colors);
  if (why.empty())
  {
    why = vtkBrumeSceneConversionInternals::ReadMediumFunctions(before, was, wasOpacity, wasColors);
  }
  if (!why.empty())
  {
    return nullptr;
  }
  if (!opacity || !wasOpacity)
  {
    why = "the medium has no opacity transfer function";
    return nullptr;
  }
  if (colors.has_value() != (old->GetArray(vtkBrumeNames::AlbedoTransferFunction) != nullptr))
  {
    why = colors ? "the medium's albedo now varies" : "the medium's albedo no longer varies";
    return nullptr;
  }
  // Where the old function gave nothing, bricks were left out: they hold
  // one scalar, not their own. The new function must give nothing there
  // too, over each interval of scalars where the old one is 0 (linear
  // between its points, its end values beyond).
  const auto& nodes = wasOpacity->GetNodes();
  const float inf = std::numeric_limits<float>::infinity();
  auto givesSomething = [&](float a, float b)
  {
    if (opacity->Opacity(std::max(a, -std::numeric_limits<float>::max())) > 0.f ||
      opacity->Opacity(std::min(b, std::numeric_limits<float>::max())) > 0.f)
    {
      return true;
    }
    for (const auto& n : opacity->GetNodes())
    {
      if (n.Scalar > a && n.Scalar < b && n.Opacity > 0.f)
      {
        return true;
      }
    }
    return false;
  };
  for (std::size_t k = 0; k <= nodes.size(); ++k)
  {
    const float a = k == 0 ? -inf : nodes[k - 1].Scalar;
    const float b = k == nodes.size() ? inf : nodes[k].Scalar;
    const bool zero =
      (k == 0 || nodes[k - 1].Opacity == 0.f) && (k == nodes.size() || nodes[k].Opacity == 0.f);
    if (zero && givesSomething(a, b))
    {
      why = "the new function gives an extinction where the old one left bricks out";
      return nullptr;
    }
  }
  vtkNew<vtkFieldData> fd;
  fd->ShallowCopy(old);
  AddTransferTables(fd, *opacity, colors ? &*colors : nullptr, m.Albedo());
  vtkNew<vtkDoubleArray> scale;
  scale->SetName(vtkBrumeNames::ExtinctionScale);
  scale->SetNumberOfComponents(3);
  const brume::Vec3 sigmaT = m.SigmaT();
  scale->InsertNextTuple3(sigmaT.x, sigmaT.y, sigmaT.z);
  fd->RemoveArray(vtkBrumeNames::ExtinctionScale);
  fd->AddArray(scale);
  auto preview = vtkSmartPointer<vtkImageData>::New();
  preview->CopyStructure(extinction);
  preview->SetFieldData(fd);
  return preview;
}

vtkSmartPointer<vtkImageData> vtkBrumeRadianceConversion::DenseExtinction(vtkImageData* sparse)
{
  vtkFieldData* fd = sparse ? sparse->GetFieldData() : nullptr;
  vtkDataArray* slots = fd ? fd->GetArray(vtkBrumeNames::ExtinctionBrickSlots) : nullptr;
  vtkDataArray* values = fd ? fd->GetArray(vtkBrumeNames::ExtinctionBrickValues) : nullptr;
  vtkDataArray* samples = fd ? fd->GetArray(vtkBrumeNames::ExtinctionBrickSamples) : nullptr;
  // Or the stored bricks' cells' own values.
  vtkDataArray* cellValues = fd ? fd->GetArray(vtkBrumeNames::ExtinctionCellValues) : nullptr;
  vtkDataArray* scale = fd ? fd->GetArray(vtkBrumeNames::ExtinctionScale) : nullptr;
  if (!slots || !values || !(samples || cellValues) || !scale ||
    scale->GetNumberOfComponents() != 3)
  {
    return nullptr;
  }
  // Classified scalars: sigma_t of each cell's scalar (at the centres).
  vtkDataArray* table = fd->GetArray(vtkBrumeNames::ExtinctionTransferFunction);
  vtkDataArray* rangeArray = fd->GetArray(vtkBrumeNames::ExtinctionTransferRange);
  double range[2] = { 0.0, 1.0 };
  if (table && rangeArray)
  {
    rangeArray->GetTuple(0, range);
  }
  int pointDims[3];
  sparse->GetDimensions(pointDims);
  int dims[3], bricks[3];
  vtkIdType count = 1;
  for (int a = 0; a < 3; ++a)
  {
    dims[a] = pointDims[a] - 1;
    bricks[a] = brume::BrickedGrid::BricksAlong(dims[a]);
    count *= bricks[a];
  }
  constexpr int B = brume::BrickedGrid::Size, S = brume::BrickedGrid::Stride;
  if (dims[0] < 1 || dims[1] < 1 || dims[2] < 1 || slots->GetNumberOfTuples() != count ||
    values->GetNumberOfTuples() != count ||
    (!samples &&
      cellValues->GetNumberOfTuples() != static_cast<vtkIdType>(dims[0]) * dims[1] * dims[2]))
  {
    return nullptr;
  }
  auto dense = vtkSmartPointer<vtkImageData>::New();
  dense->SetDimensions(pointDims);
  dense->SetOrigin(sparse->GetOrigin());
  dense->SetSpacing(sparse->GetSpacing());
  vtkNew<vtkFloatArray> sigmaT;
  sigmaT->SetName(vtkBrumeNames::Extinction);
  sigmaT->SetNumberOfComponents(3);
  sigmaT->SetNumberOfTuples(static_cast<vtkIdType>(dims[0]) * dims[1] * dims[2]);
  for (int k = 0; k < dims[2]; ++k)
    for (int j = 0; j < dims[1]; ++j)
      for (int i = 0; i < dims[0]; ++i)
      {
        const int b[3] = { std::min(i / S, bricks[0] - 1), std::min(j / S, bricks[1] - 1),
          std::min(k / S, bricks[2] - 1) };
        const vtkIdType brick =
          (static_cast<vtkIdType>(b[2]) * bricks[1] + b[1]) * bricks[0] + b[0];
        const vtkIdType slot = static_cast<vtkIdType>(slots->GetTuple1(brick));
        const vtkIdType cell = (static_cast<vtkIdType>(k) * dims[1] + j) * dims[0] + i;
        double v = slot < 0 ? values->GetTuple1(brick)
          : samples         ? samples->GetTuple1(slot * B * B * B +
                                ((k - S * b[2]) * B + (j - S * b[1])) * B + (i - S * b[0]))
                            : cellValues->GetTuple1(cell);
        if (table && rangeArray)
        {
          v = Classify(table, range, v);
        }
        for (int c = 0; c < 3; ++c)
        {
          sigmaT->SetTypedComponent(cell, c, static_cast<float>(v * scale->GetComponent(0, c)));
        }
      }
  dense->GetCellData()->SetScalars(sigmaT);
  AddString(dense->GetFieldData(), vtkBrumeNames::ObjectKind, "medium extinction");
  return dense;
}

brume::SparseTexture vtkBrumeRadianceConversion::SourceBricks(
  const brume::ObjectRadiance& radiance, const brume::Medium& medium, bool directional)
{
  const auto& dims = directional ? radiance.GetLayout().Resolution : radiance.GetOutput().Dims;
  // The direct light found the same cells for its texels where it cast
  // their rays (the output grid).
  const brume::DirectTexture& direct = radiance.GetDirect();
  if (!direct.GetCellsRead().empty() && direct.GetDims() == dims)
  {
    return brume::SparseTexture::FromCellsRead(dims, direct.GetCellsRead());
  }
  return brume::SparseTexture::WhereDensity(
    dims, medium.Bounds, radiance.GetNative().GetDensity(), vtkBrumeSMP::ParallelFor());
}

vtkSmartPointer<vtkPartitionedDataSet> vtkBrumeRadianceConversion::FromMedium(
  const brume::ObjectRadiance& radiance, const brume::Medium& medium, bool directional,
  vtkImageData* nativeExtinction, vtkImageData* previous, const brume::SparseTexture* bricks)
{
  // Directional radiance stays on the texture's grid; per-view radiance is
  // on the output grid (finer, with direct light).
  const auto& res = directional ? radiance.GetLayout().Resolution : radiance.GetOutput().Dims;
  const brume::Vec3 extent = medium.Bounds.Extent();
  vtkNew<vtkImageData> texture;
  texture->SetDimensions(res[0] + 1, res[1] + 1, res[2] + 1);
  texture->SetOrigin(medium.Bounds.lower.x, medium.Bounds.lower.y, medium.Bounds.lower.z);
  texture->SetSpacing(extent.x / res[0], extent.y / res[1], extent.z / res[2]);
  vtkSmartPointer<vtkImageData> extinction = nativeExtinction;
  if (!extinction)
  {
    extinction = NativeExtinction(radiance, medium);
  }
  // The sparse form needs the extinction at the density's own resolution:
  // it replaces the texture's, and says where the source radiance is read.
  const bool sparse = bricks && extinction && bricks->GetDims() == res;
  vtkCellData* cd = texture->GetCellData();
  vtkFieldData* fd = texture->GetFieldData();
  if (sparse)
  {
    vtkNew<vtkIntArray> slots;
    slots->SetName(vtkBrumeNames::SourceBrickSlots);
    slots->SetNumberOfValues(static_cast<vtkIdType>(bricks->GetSlots().size()));
    std::copy(bricks->GetSlots().begin(), bricks->GetSlots().end(), slots->GetPointer(0));
    fd->AddArray(slots);
  }
  // A varying albedo is applied by the mapper where its extinction carries
  // the albedo's table. On a grid that has none (a coarsened one) it is
  // baked into the texture here (BakeAlbedo).
  const bool albedoTable = radiance.GetLayout().Scattering.HasVaryingAlbedo() && extinction &&
    extinction->GetFieldData()->GetArray(vtkBrumeNames::AlbedoTransferFunction);
  const bool bake = radiance.GetLayout().Scattering.HasVaryingAlbedo() && !albedoTable;
  BakedAlbedo albedo;
  if (bake)
  {
    albedo = BakeAlbedo(radiance, medium, directional, res, extent);
  }
  AddSourceRadiance(
    texture, sparse ? bricks : nullptr, radiance, directional, bake ? &albedo : nullptr);
  if (albedoTable)
  {
    // The mapper draws sigma_t a X and extinguishes sigma_t (1 - a Forward).
    vtkNew<vtkDoubleArray> forward;
    forward->SetName(vtkBrumeNames::ForwardFraction);
    forward->InsertNextValue(radiance.GetLayout().Scattering.GetPeak(directional).Forward);
    fd->AddArray(forward);
  }
  if (!sparse)
  {
    cd->SetActiveScalars(vtkBrumeNames::SourceRadiance);
  }
  // A strongly forward medium's peak is drawn as transport: at the
  // extinction times this factor, with S per unit of it.
  const brume::Vec3 factor =
    bake ? albedo.Factor : radiance.GetLayout().Scattering.GetExtinctionFactor(directional);
  if (factor.x != 1.f || factor.y != 1.f || factor.z != 1.f)
  {
    vtkNew<vtkDoubleArray> f;
    f->SetName(vtkBrumeNames::ExtinctionFactor);
    f->SetNumberOfComponents(3);
    f->InsertNextTuple3(factor.x, factor.y, factor.z);
    fd->AddArray(f);
  }
  if (!sparse)
  {
    AddTextureExtinction(cd, radiance, directional, previous);
  }
  AddString(fd, vtkBrumeNames::ObjectKind, "medium");
  auto pds = vtkSmartPointer<vtkPartitionedDataSet>::New();
  pds->SetNumberOfPartitions(extinction ? 2 : 1);
  pds->SetPartition(0, texture);
  if (extinction)
  {
    pds->SetPartition(1, extinction);
  }
  return pds;
}
