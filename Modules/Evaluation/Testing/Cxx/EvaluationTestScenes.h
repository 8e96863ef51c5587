// SPDX-License-Identifier: BSD-3-Clause
// Small scenes built in code for the Evaluation tests, with object names of
// their own (none of the default scene's).
#ifndef EvaluationTestScenes_h
#define EvaluationTestScenes_h

#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeSceneConversion.h"
#include "vtkBrumeTimedPipeline.h"
#include "vtkCellArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"
#include "vtkXMLImageDataWriter.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

/// Per column of a `size`-wide image, the mean over rows [first, last] of
/// the channels' mean Radiance (or of one `channel`'s), and (with `error` and a Variance array, a
/// reference path tracer's) the standard error of that mean.
inline void RowProfile(vtkImageData* image, int size, int first, int last,
  std::vector<double>& mean, std::vector<double>* error, int channel = -1)
{
  vtkDataArray* radiance = image->GetPointData()->GetArray(vtkBrumeNames::Radiance);
  vtkDataArray* variance = image->GetPointData()->GetArray(vtkBrumeNames::Variance);
  const int rows = last - first + 1;
  mean.assign(size, 0.0);
  if (error)
  {
    error->assign(size, 0.0);
  }
  for (int x = 0; x < size; ++x)
  {
    double v2 = 0.0;
    for (int y = first; y <= last; ++y)
    {
      const vtkIdType p = static_cast<vtkIdType>(y) * size + x;
      for (int c = 0; c < 3; ++c)
      {
        if (channel >= 0 && c != channel)
        {
          continue;
        }
        const double share = channel >= 0 ? 1.0 : 1.0 / 3.0;
        mean[x] += radiance->GetComponent(p, c) * share / rows;
        // The channels' mean has at most their mean variance (correlated).
        v2 += variance ? variance->GetComponent(p, c) * share : 0.0;
      }
    }
    if (error)
    {
      (*error)[x] = std::sqrt(v2) / rows;
    }
  }
}

/// Column by column, whether `got` lies within four standard errors of the
/// reference's profile plus `slack` times its peak (the pipeline's own noise
/// and smoothing); prints the table.
inline bool WithinBand(const std::vector<double>& expected, const std::vector<double>& error,
  const std::vector<double>& got, double slack)
{
  double peak = 0.0;
  for (const double v : expected)
  {
    peak = std::max(peak, v);
  }
  bool ok = true;
  std::printf("%6s %12s %12s %12s\n", "column", "reference", "pipeline", "band");
  for (std::size_t x = 0; x < expected.size(); ++x)
  {
    const double band = 4.0 * error[x] + slack * peak;
    const bool pass = std::abs(got[x] - expected[x]) <= band;
    ok = ok && pass;
    std::printf("%6d %12.5g %12.5g %12.3g%s\n", static_cast<int>(x), expected[x], got[x], band,
      pass ? "" : "  FAIL");
  }
  return ok;
}

/// The channels' mean of `image`'s Radiance over the block of block x block
/// pixels at (bx, by), and (with a Variance array) its standard error.
inline double BlockMean(vtkImageData* image, int bx, int by, int block, double* error)
{
  vtkDataArray* radiance = image->GetPointData()->GetArray(vtkBrumeNames::Radiance);
  vtkDataArray* variance = image->GetPointData()->GetArray(vtkBrumeNames::Variance);
  const int width = image->GetDimensions()[0];
  double sum = 0.0, v2 = 0.0;
  for (int y = by; y < by + block; ++y)
  {
    for (int x = bx; x < bx + block; ++x)
    {
      const vtkIdType p = static_cast<vtkIdType>(y) * width + x;
      for (int c = 0; c < 3; ++c)
      {
        sum += radiance->GetComponent(p, c) / 3.0;
        // The channels' mean has at most their mean variance (correlated).
        v2 += variance ? variance->GetComponent(p, c) / 3.0 : 0.0;
      }
    }
  }
  const double n = static_cast<double>(block) * block;
  if (error)
  {
    *error = std::sqrt(v2) / n;
  }
  return sum / n;
}

/// Appends the quad p0 p1 p2 p3 (its front: counter-clockwise seen from it),
/// Lambertian of reflectance 0.6, emitting `emission` from its front.
inline void AddQuad(vtkPartitionedDataSetCollection* scene, const std::string& name,
  const double p0[3], const double p1[3], const double p2[3], const double p3[3],
  double emission = 0.0)
{
  vtkNew<vtkPoints> points;
  for (const double* p : { p0, p1, p2, p3 })
  {
    points->InsertNextPoint(p);
  }
  vtkNew<vtkCellArray> polys;
  const vtkIdType quad[4] = { 0, 1, 2, 3 };
  polys->InsertNextCell(4, quad);
  vtkNew<vtkPolyData> surface;
  surface->SetPoints(points);
  surface->SetPolys(polys);
  const double reflectance[3] = { 0.6, 0.6, 0.6 }, emitted[3] = { emission, emission, emission };
  vtkBrumeSceneConversion::AppendTuple(
    surface->GetFieldData(), vtkBrumeNames::Reflectance, reflectance, 3);
  vtkBrumeSceneConversion::AppendTuple(
    surface->GetFieldData(), vtkBrumeNames::Emission, emitted, 3);
  vtkBrumeSceneConversion::AddObject(scene, surface, name);
}

/// Appends a homogeneous medium filling the box [lower, upper].
inline void AddMedium(vtkPartitionedDataSetCollection* scene, const std::string& name,
  const double lower[3], const double upper[3])
{
  vtkNew<vtkImageData> box;
  box->SetOrigin(lower[0], lower[1], lower[2]);
  box->SetSpacing(upper[0] - lower[0], upper[1] - lower[1], upper[2] - lower[2]);
  box->SetDimensions(2, 2, 2);
  const double sigmaA[3] = { 0.1, 0.1, 0.1 }, sigmaS[3] = { 0.9, 0.9, 0.9 }, g = 0.3;
  vtkBrumeSceneConversion::AppendTuple(box->GetFieldData(), vtkBrumeNames::SigmaA, sigmaA, 3);
  vtkBrumeSceneConversion::AppendTuple(box->GetFieldData(), vtkBrumeNames::SigmaS, sigmaS, 3);
  vtkBrumeSceneConversion::AppendTuple(box->GetFieldData(), vtkBrumeNames::G, &g, 1);
  vtkBrumeSceneConversion::AddObject(scene, box, name);
}

/// Appends a heterogeneous medium: `points`^3 density samples (point
/// values) over [-1, 1]^3, density(x, y, z) at each, with sigma_a and
/// sigma_s per unit density (RGB) and asymmetry g.
template <typename Density>
inline void AddDensityGrid(vtkPartitionedDataSetCollection* scene, const std::string& name,
  int points, Density density, const double sigmaA[3], const double sigmaS[3], double g)
{
  vtkNew<vtkImageData> grid;
  grid->SetOrigin(-1, -1, -1);
  const double spacing = 2.0 / (points - 1);
  grid->SetSpacing(spacing, spacing, spacing);
  grid->SetDimensions(points, points, points);
  vtkNew<vtkFloatArray> values;
  values->SetName("density");
  values->SetNumberOfTuples(static_cast<vtkIdType>(points) * points * points);
  for (int k = 0; k < points; ++k)
    for (int j = 0; j < points; ++j)
      for (int i = 0; i < points; ++i)
      {
        values->SetValue((static_cast<vtkIdType>(k) * points + j) * points + i,
          static_cast<float>(density(-1 + i * spacing, -1 + j * spacing, -1 + k * spacing)));
      }
  grid->GetPointData()->SetScalars(values);
  vtkBrumeSceneConversion::AppendTuple(grid->GetFieldData(), vtkBrumeNames::SigmaA, sigmaA, 3);
  vtkBrumeSceneConversion::AppendTuple(grid->GetFieldData(), vtkBrumeNames::SigmaS, sigmaS, 3);
  vtkBrumeSceneConversion::AppendTuple(grid->GetFieldData(), vtkBrumeNames::G, &g, 1);
  vtkBrumeSceneConversion::AddObject(scene, grid, name);
}

/// Adds a light of `type` ("point", "spot", "directional") to the scene's
/// field data: `intensity` W/sr per channel (W/m^2 for a directional light),
/// travelling along `direction` (a directional light's beam covers the
/// scene, its position is unused), a cone of 180 degrees.
inline void AddLight(vtkPartitionedDataSetCollection* scene, const char* kind,
  const double position[3], const double direction[3], double intensity)
{
  vtkFieldData* fd = scene->GetFieldData();
  vtkNew<vtkStringArray> type;
  type->SetName(vtkBrumeNames::LightType);
  type->InsertNextValue(kind);
  fd->AddArray(type);
  const double power[3] = { intensity, intensity, intensity }, cone = 180;
  vtkBrumeSceneConversion::AppendTuple(fd, vtkBrumeNames::LightPosition, position, 3);
  vtkBrumeSceneConversion::AppendTuple(fd, vtkBrumeNames::LightDirection, direction, 3);
  vtkBrumeSceneConversion::AppendTuple(fd, vtkBrumeNames::LightIntensity, power, 3);
  vtkBrumeSceneConversion::AppendTuple(fd, vtkBrumeNames::LightConeAngle, &cone, 1);
}

/// Adds a point light (radiant intensity `intensity` W/sr per channel).
inline void AddPointLight(
  vtkPartitionedDataSetCollection* scene, const double position[3], double intensity)
{
  const double down[3] = { 0, -1, 0 };
  AddLight(scene, "point", position, down, intensity);
}

/// Adds a directional light (irradiance `irradiance` W/m^2 per channel).
inline void AddDirectionalLight(
  vtkPartitionedDataSetCollection* scene, const double direction[3], double irradiance)
{
  const double origin[3] = { 0, 0, 0 };
  AddLight(scene, "directional", origin, direction, irradiance);
}

/// The fast pipeline over `scene`: size x size pixels, `particles`,
/// anisotropic media per view or as spherical harmonics, no new view timed.
inline vtkSmartPointer<vtkBrumeTimedPipeline> MakePipeline(
  vtkPartitionedDataSetCollection* scene, int size, vtkTypeInt64 particles, bool directional)
{
  auto pipeline = vtkSmartPointer<vtkBrumeTimedPipeline>::New();
  pipeline->SetInputData(scene);
  pipeline->SetSize(size, size);
  pipeline->SetNumberOfParticles(particles);
  pipeline->SetDirectionalRadiance(directional);
  pipeline->MeasureNewViewOff();
  return pipeline;
}

/// Writes `image` as DIRECTORY/NAME.vti (test output to look at).
inline void SaveImage(const std::string& directory, const std::string& name, vtkImageData* image)
{
  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetFileName((directory + "/" + name + ".vti").c_str());
  writer->SetInputData(image);
  writer->Write();
}

/// Names the scene's camera in its field data.
inline void SetSceneCamera(vtkPartitionedDataSetCollection* scene, const double position[3],
  const double focalPoint[3], double viewAngle)
{
  vtkFieldData* fd = scene->GetFieldData();
  const double up[3] = { 0, 1, 0 };
  vtkBrumeSceneConversion::AppendTuple(fd, vtkBrumeNames::CameraPosition, position, 3);
  vtkBrumeSceneConversion::AppendTuple(fd, vtkBrumeNames::CameraFocalPoint, focalPoint, 3);
  vtkBrumeSceneConversion::AppendTuple(fd, vtkBrumeNames::CameraViewUp, up, 3);
  vtkBrumeSceneConversion::AppendTuple(fd, vtkBrumeNames::CameraViewAngle, &viewAngle, 1);
}

/// A gallery: a floor ("stage"), a back wall ("backdrop"), a small emitter
/// ("lamp") and, with `medium`, a box of mist ("mist") on the stage, seen
/// by the scene's own camera.
inline vtkSmartPointer<vtkPartitionedDataSetCollection> Gallery(bool medium)
{
  auto scene = vtkSmartPointer<vtkPartitionedDataSetCollection>::New();
  const double f0[3] = { -2, -1, -2 }, f1[3] = { -2, -1, 2 }, f2[3] = { 2, -1, 2 },
               f3[3] = { 2, -1, -2 };
  AddQuad(scene, "stage", f0, f1, f2, f3);
  const double b0[3] = { -2, -1, -1.5 }, b1[3] = { 2, -1, -1.5 }, b2[3] = { 2, 2, -1.5 },
               b3[3] = { -2, 2, -1.5 };
  AddQuad(scene, "backdrop", b0, b1, b2, b3);
  const double l0[3] = { -0.3, 1.5, -0.3 }, l1[3] = { 0.3, 1.5, -0.3 }, l2[3] = { 0.3, 1.5, 0.3 },
               l3[3] = { -0.3, 1.5, 0.3 };
  AddQuad(scene, "lamp", l0, l1, l2, l3, 20.0);
  if (medium)
  {
    const double lower[3] = { -0.6, -1, -0.6 }, upper[3] = { 0.6, 0.2, 0.6 };
    AddMedium(scene, "mist", lower, upper);
  }
  const double eye[3] = { 0, 0.3, 4 }, target[3] = { 0, -0.2, 0 };
  SetSceneCamera(scene, eye, target, 40);
  return scene;
}

#endif
