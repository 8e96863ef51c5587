// SPDX-License-Identifier: BSD-3-Clause
// A VTK volume property makes a Brume medium of any scalar field
// (vtkBrumeVolumePropertyMedium): the extinction is the scalar opacity's,
// classified after interpolation; a constant function is the constant
// density it stands for, through the whole pipeline, bit for bit; the
// colour transfer function colours the albedo, classified after
// interpolation too, and a constant colour draws the image of the same
// albedo given as one colour; bad functions, arrays and components fail
// with a clear error.
#include "BrumeExpectFailure.h"
#include "BrumeLitGroundScene.h"
#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeFloatImageCapture.h"
#include "vtkBrumeLightTracer.h"
#include "vtkBrumeRadianceConversion.h"
#include "vtkBrumeRadianceReconstruction.h"
#include "vtkBrumeSceneActors.h"
#include "vtkBrumeSceneConversion.h"
#include "vtkBrumeVolumePropertyMedium.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCellData.h"
#include "vtkColorTransferFunction.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"
#include "vtkStructuredGrid.h"
#include "vtkVolumeProperty.h"

#include "brume/Scene.h"
#include "brume/TransferFunction.h"

#include <cmath>
#include <cstring>
#include <functional>
#include <iostream>
#include <string>

namespace
{
int failures = 0;
void Check(bool ok, const std::string& what)
{
  if (!ok)
  {
    std::cerr << "FAILED: " << what << "\n";
    ++failures;
  }
}

// A simulation-like scalar on 17^3 points over [-0.5, 0.5]^3 (a warped
// blob with values in about [0, 100]) and a second, two-component array.
vtkSmartPointer<vtkImageData> Field()
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  const int n = 17;
  image->SetDimensions(n, n, n);
  image->SetOrigin(-0.5, -0.5, -0.5);
  image->SetSpacing(1.0 / (n - 1), 1.0 / (n - 1), 1.0 / (n - 1));
  vtkNew<vtkFloatArray> s, pair;
  s->SetName("temperature");
  pair->SetName("pair");
  pair->SetNumberOfComponents(2);
  for (vtkIdType i = 0; i < image->GetNumberOfPoints(); ++i)
  {
    double p[3];
    image->GetPoint(i, p);
    const double r2 = p[0] * p[0] + (p[1] + 0.1) * (p[1] + 0.1) + p[2] * p[2];
    const double v = 100.0 * std::exp(-5.0 * r2) * (1.0 + 0.2 * std::sin(9.0 * p[0]));
    s->InsertNextValue(static_cast<float>(v));
    pair->InsertNextTuple2(-v, v);
  }
  image->GetPointData()->SetScalars(s);
  image->GetPointData()->AddArray(pair);
  return image;
}

// The ground and the medium, lit by a point light in the scene's field
// data (or by none, for a tracer given a vtkLight).
vtkSmartPointer<vtkPartitionedDataSetCollection> Scene(vtkImageData* medium, bool lit = true)
{
  return BrumeLitGroundScene(medium, "field", lit);
}

vtkSmartPointer<vtkImageData> Render(
  vtkPartitionedDataSetCollection* scene, vtkLight* light = nullptr)
{
  vtkNew<vtkBrumeLightTracer> tracer;
  tracer->SetInputData(scene);
  if (light)
  {
    tracer->AddLight(light);
  }
  tracer->SetNumberOfParticles(40000);
  tracer->SetSeed(5);
  vtkNew<vtkBrumeRadianceReconstruction> reconstruction;
  reconstruction->SetInputDataObject(0, scene);
  reconstruction->SetInputConnection(1, tracer->GetOutputPort());
  reconstruction->SetEyePosition(0, 0.4, 3);
  if (!reconstruction->GetExecutive()->Update())
  {
    return nullptr;
  }
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->SetSize(64, 64);
  window->AddRenderer(renderer);
  vtkNew<vtkBrumeSceneActors> actors;
  actors->SetInputData(reconstruction->GetOutput());
  actors->AddToRenderer(renderer);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(0, 0.4, 3);
  camera->SetFocalPoint(0, -0.1, 0);
  camera->SetViewUp(0, 1, 0);
  camera->SetViewAngle(35);
  renderer->ResetCameraClippingRange();
  vtkNew<vtkBrumeFloatImageCapture> capture;
  capture->Attach(renderer);
  window->Render();
  return capture->Capture();
}

// The core scene's medium made of `image`, or the conversion's error.
std::string ConvertMedium(vtkImageData* image, brume::Medium& medium)
{
  brume::Scene scene;
  const std::string error = vtkBrumeSceneConversion::ToScene(Scene(image), scene);
  if (error.empty())
  {
    medium = scene.Media.at(0);
  }
  return error;
}

// The trilinear interpolation of the image's array `name` at p.
double Interpolate(vtkImageData* image, const char* name, const double p[3])
{
  vtkDataArray* s = image->GetPointData()->GetArray(name);
  int ijk[3];
  double pc[3];
  image->ComputeStructuredCoordinates(p, ijk, pc);
  double value = 0.0;
  for (int c = 0; c < 8; ++c)
  {
    int idx[3] = { ijk[0] + (c & 1), ijk[1] + ((c >> 1) & 1), ijk[2] + ((c >> 2) & 1) };
    double w = 1.0;
    for (int a = 0; a < 3; ++a)
    {
      w *= (idx[a] > ijk[a]) ? pc[a] : 1.0 - pc[a];
    }
    value += w * s->GetTuple1(image->ComputePointId(idx));
  }
  return value;
}

// The largest channel difference of two images, and their peak.
void Compare(vtkImageData* a, vtkImageData* b, double& worst, double& peak)
{
  vtkDataArray* x = a->GetPointData()->GetScalars();
  vtkDataArray* y = b->GetPointData()->GetScalars();
  worst = 0.0;
  peak = 0.0;
  for (vtkIdType i = 0; i < x->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      peak = std::max(peak, y->GetComponent(i, c));
      worst = std::max(worst, std::abs(x->GetComponent(i, c) - y->GetComponent(i, c)));
    }
  }
}

void TestClassification()
{
  // A step at 40 (opacity 0 -> 0.5; VTK keeps one point per scalar) rising
  // to 0.9 at 80, per unit 0.25.
  vtkNew<vtkVolumeProperty> property;
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0, 0);
  opacity->AddPoint(40, 0);
  opacity->AddPoint(40.001, 0.5);
  opacity->AddPoint(80, 0.9);
  property->SetScalarOpacity(opacity);
  property->SetScalarOpacityUnitDistance(0.25);
  property->SetScatteringAnisotropy(0.6f);
  property->SetInterpolationTypeToLinear();
  vtkNew<vtkBrumeVolumePropertyMedium> filter;
  filter->SetInputData(Field());
  filter->SetVolumeProperty(property);
  filter->SetAlbedo(0.9, 0.8, 0.7);
  Check(filter->GetExecutive()->Update() == 1, "the filter runs");
  brume::Medium m;
  Check(ConvertMedium(filter->GetOutput(), m).empty(), "the medium converts");
  Check(!m.IsHomogeneous(), "a classified medium is heterogeneous");
  Check(std::abs(m.G - 0.6f) < 1e-6f, "g is the property's ScatteringAnisotropy");
  Check(std::abs(m.Albedo().y - 0.8f) < 1e-6f && std::abs(m.SigmaT().x - 1.f) < 1e-6f,
    "albedo 0.8 in green, sigma_a + sigma_s = 1");

  // The extinction at a point is the function's at the interpolated scalar.
  vtkImageData* image = filter->GetOutput();
  vtkDataArray* s = image->GetPointData()->GetArray("temperature");
  int checked = 0;
  for (double x = -0.45; x < 0.5; x += 0.1)
  {
    const double p[3] = { x, -0.07, 0.13 };
    const double value = Interpolate(image, "temperature", p);
    const double alpha = opacity->GetValue(value);
    const double expected = -std::log1p(-alpha) / 0.25;
    const double got = m.SigmaTAt(
      brume::Vec3(static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2])))[0];
    Check(std::abs(got - expected) <= 1e-4 * (1.0 + expected),
      "extinction at x = " + std::to_string(x) + ": " + std::to_string(got) + " against " +
        std::to_string(expected));
    checked += alpha > 0.0 ? 1 : 0;
  }
  Check(checked >= 3, "the line crosses the classified blob");

  // Nearest interpolation: the nearest point's scalar is classified.
  property->SetInterpolationTypeToNearest();
  Check(filter->GetExecutive()->Update() == 1, "the filter follows the property");
  Check(ConvertMedium(filter->GetOutput(), m).empty(), "nearest converts");
  const double p[3] = { 0.02, -0.07, 0.13 };
  const vtkIdType nearest = filter->GetOutput()->FindPoint(p[0], p[1], p[2]);
  const double v = s->GetTuple1(nearest);
  const double alpha = opacity->GetValue(v);
  Check(
    std::abs(m.SigmaTAt(brume::Vec3(0.02f, -0.07f, 0.13f))[0] + std::log1p(-alpha) / 0.25) < 1e-4,
    "nearest: the nearest point's scalar");

  // A function with midpoints off 0.5 is not piecewise linear: sampled at
  // SampledFunctionPoints points, linear in between.
  vtkNew<vtkPiecewiseFunction> curved;
  curved->AddPoint(0, 0, 0.2, 0.0);
  curved->AddPoint(100, 0.8, 0.5, 0.0);
  property->SetScalarOpacity(curved);
  Check(filter->GetExecutive()->Update() == 1, "a curved function runs");
  Check(filter->GetOutput()
          ->GetFieldData()
          ->GetArray(vtkBrumeNames::ScalarOpacity)
          ->GetNumberOfTuples() == filter->GetSampledFunctionPoints(),
    "a curved function is sampled");
  brume::Medium curvedMedium;
  Check(ConvertMedium(filter->GetOutput(), curvedMedium).empty(), "the curved function converts");
  double sample[3] = { 0.1, 0.0, 0.0 };
  const vtkIdType at = filter->GetOutput()->FindPoint(sample);
  double centre[3];
  filter->GetOutput()->GetPoint(at, centre);
  const double sv = s->GetTuple1(at);
  Check(std::abs(curvedMedium.SigmaTAt(brume::Vec3(static_cast<float>(centre[0]),
                   static_cast<float>(centre[1]), static_cast<float>(centre[2])))[0] +
          std::log1p(-curved->GetValue(sv)) / 0.25) < 1e-3,
    "the sampled curve's extinction at a grid point");
  property->SetScalarOpacity(opacity);

  // The reconstruction hands the slice mapper the scalars and the
  // function's table (it classifies after interpolating); expanded, each
  // native cell (centred on a point) holds the function's extinction of
  // that point's scalar.
  {
    Check(filter->GetExecutive()->Update() == 1, "the step function again");
    vtkNew<vtkBrumeLightTracer> tracer;
    vtkSmartPointer<vtkPartitionedDataSetCollection> scene = Scene(filter->GetOutput());
    tracer->SetInputData(scene);
    tracer->SetNumberOfParticles(2000);
    vtkNew<vtkBrumeRadianceReconstruction> reconstruction;
    reconstruction->SetInputDataObject(0, scene);
    reconstruction->SetInputConnection(1, tracer->GetOutputPort());
    Check(reconstruction->GetExecutive()->Update() == 1, "the classified medium reconstructs");
    vtkPartitionedDataSet* medium = reconstruction->GetOutput()->GetPartitionedDataSet(1);
    auto* native = medium && medium->GetNumberOfPartitions() > 1
      ? vtkImageData::SafeDownCast(medium->GetPartition(1))
      : nullptr;
    Check(native && native->GetFieldData()->GetArray(vtkBrumeNames::ExtinctionTransferFunction) &&
        native->GetFieldData()->GetArray(vtkBrumeNames::ExtinctionTransferRange),
      "partition 1 holds the transfer function's table");
    vtkSmartPointer<vtkImageData> dense =
      native ? vtkBrumeRadianceConversion::DenseExtinction(native) : nullptr;
    Check(dense && dense->GetNumberOfCells() == image->GetNumberOfPoints(),
      "one native cell per point of the field");
    int compared = 0;
    for (vtkIdType point = 0; dense && point < image->GetNumberOfPoints(); point += 37)
    {
      const double scalar = s->GetTuple1(point);
      if (std::abs(scalar - 40.0) < 0.1)
      {
        continue; // the step: one table sample wide
      }
      const double expected = -std::log1p(-opacity->GetValue(scalar)) / 0.25;
      const double got =
        dense->GetCellData()->GetArray(vtkBrumeNames::Extinction)->GetComponent(point, 0);
      Check(std::abs(got - expected) <= 1e-4 * expected + 1e-6,
        "native cell " + std::to_string(point) + ": " + std::to_string(got) + " against " +
          std::to_string(expected));
      ++compared;
    }
    Check(compared > 50, "native cells compared");
  }

  // Component 1 of the two-component array.
  property->SetInterpolationTypeToLinear();
  filter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "pair");
  filter->SetComponent(1);
  property->SetScalarOpacity(1, opacity);
  property->SetScalarOpacityUnitDistance(1, 0.25);
  Check(filter->GetExecutive()->Update() == 1, "component 1 runs");
  brume::Medium pair;
  Check(ConvertMedium(filter->GetOutput(), pair).empty(), "component 1 converts");
  filter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "temperature");
  filter->SetComponent(0);
  filter->GetExecutive()->Update();
  ConvertMedium(filter->GetOutput(), m);
  const brume::Vec3 q(0.05f, -0.1f, 0.02f);
  Check(pair.SigmaTAt(q).x == m.SigmaTAt(q).x && m.SigmaTAt(q).x > 0.f,
    "component 1 of (-s, s) classifies as s");
}

void TestResampledDataset()
{
  // The field as a curvilinear grid (the image's points, moved nowhere): it
  // is resampled at one point per cell, which here is the image's own
  // points, so the medium is the image's, scalar for scalar.
  vtkNew<vtkVolumeProperty> property;
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(20, 0);
  opacity->AddPoint(90, 0.7);
  property->SetScalarOpacity(opacity);
  vtkSmartPointer<vtkImageData> field = Field();
  vtkNew<vtkStructuredGrid> grid;
  grid->SetDimensions(field->GetDimensions());
  vtkNew<vtkPoints> points;
  for (vtkIdType i = 0; i < field->GetNumberOfPoints(); ++i)
  {
    points->InsertNextPoint(field->GetPoint(i));
  }
  grid->SetPoints(points);
  grid->GetPointData()->ShallowCopy(field->GetPointData());
  int dims[3];
  Check(vtkBrumeVolumePropertyMedium::ChooseSamplingDimensions(grid, vtkIdType(1) << 24, dims) &&
      dims[0] == 17 && dims[1] == 17 && dims[2] == 17,
    "one point per cell: 17^3 points for 16^3 cells");
  int capped[3];
  Check(vtkBrumeVolumePropertyMedium::ChooseSamplingDimensions(grid, 1000, capped) &&
      capped[0] * capped[1] * capped[2] <= 1000 && capped[0] >= 2,
    "the cap on the sampled points");
  Check(!vtkBrumeVolumePropertyMedium::ChooseSamplingDimensions(grid, 7, capped),
    "fewer than 2^3 points cannot be chosen");
  brume::Medium fromImage, fromGrid;
  vtkNew<vtkBrumeVolumePropertyMedium> filter;
  filter->SetVolumeProperty(property);
  filter->SetInputData(field);
  Check(
    filter->GetExecutive()->Update() == 1 && ConvertMedium(filter->GetOutput(), fromImage).empty(),
    "the image's medium");
  filter->SetInputData(grid);
  Check(filter->GetExecutive()->Update() == 1, "a curvilinear grid is resampled");
  int got[3];
  filter->GetOutput()->GetDimensions(got);
  Check(got[0] == 17 && got[1] == 17 && got[2] == 17, "resampled on 17^3 points");
  Check(ConvertMedium(filter->GetOutput(), fromGrid).empty(), "the resampled medium converts");
  double worst = 0.0;
  for (double x = -0.45; x < 0.5; x += 0.05)
  {
    const brume::Vec3 p(static_cast<float>(x), 0.04f, -0.11f);
    worst = std::max(
      worst, static_cast<double>(std::abs(fromGrid.SigmaTAt(p).x - fromImage.SigmaTAt(p).x)));
  }
  Check(worst < 1e-4, "resampled and image media agree: " + std::to_string(worst));

  // Points with scalars but no cells have no volume to resample.
  vtkNew<vtkPolyData> flat;
  vtkNew<vtkPoints> scattered;
  scattered->InsertNextPoint(0, 0, 0);
  scattered->InsertNextPoint(1, 1, 1);
  flat->SetPoints(scattered);
  vtkNew<vtkFloatArray> values;
  values->SetName("temperature");
  values->InsertNextValue(30.f);
  values->InsertNextValue(60.f);
  flat->GetPointData()->SetScalars(values);
  vtkNew<vtkBrumeVolumePropertyMedium> bad;
  bad->SetVolumeProperty(property);
  bad->SetInputData(flat);
  Check(
    ExpectFailure("a dataset without cells", bad, "cannot resample"), "a dataset without cells");
}

void TestConstantFunctionIsTheConstantDensity()
{
  // Opacity 0.35 per unit 0.5 everywhere: the extinction is a constant,
  // which the same grid of constant densities has too. The two pipelines
  // must draw the very same image.
  vtkNew<vtkVolumeProperty> property;
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0, 0.35);
  opacity->AddPoint(100, 0.35);
  property->SetScalarOpacity(opacity);
  property->SetScalarOpacityUnitDistance(0.5);
  vtkNew<vtkBrumeVolumePropertyMedium> filter;
  filter->SetInputData(Field());
  filter->SetVolumeProperty(property);
  filter->SetAlbedo(0.8, 0.8, 0.8);
  filter->Update();
  vtkSmartPointer<vtkImageData> classified = Render(Scene(filter->GetOutput()));

  auto constant = vtkSmartPointer<vtkImageData>::New();
  constant->CopyStructure(filter->GetOutput());
  vtkNew<vtkFloatArray> density;
  density->SetName("density");
  density->SetNumberOfTuples(constant->GetNumberOfPoints());
  density->Fill(-std::log1p(-0.35f) / 0.5f);
  constant->GetPointData()->SetScalars(density);
  const double sa[3] = { 0.2, 0.2, 0.2 }, ss[3] = { 0.8, 0.8, 0.8 };
  vtkBrumeSceneConversion::AppendTuple(constant->GetFieldData(), vtkBrumeNames::SigmaA, sa, 3);
  vtkBrumeSceneConversion::AppendTuple(constant->GetFieldData(), vtkBrumeNames::SigmaS, ss, 3);
  vtkSmartPointer<vtkImageData> reference = Render(Scene(constant));

  Check(classified && reference, "both pipelines render");
  if (!classified || !reference)
  {
    return;
  }
  vtkDataArray* a = classified->GetPointData()->GetScalars();
  vtkDataArray* b = reference->GetPointData()->GetScalars();
  double sum = 0.0;
  vtkIdType differing = 0;
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      sum += b->GetComponent(i, c);
      differing += a->GetComponent(i, c) != b->GetComponent(i, c) ? 1 : 0;
    }
  }
  Check(sum > 0.0, "the image is lit");
  Check(differing == 0,
    "constant function against constant density: " + std::to_string(differing) +
      " channel values differ");

  // The same point light given to the tracer as a vtkLight: the hits name
  // it, so the reconstruction lights the texels with it too.
  vtkNew<vtkLight> light;
  light->SetPositional(true);
  light->SetConeAngle(180);
  light->SetPosition(0.8, 1.5, 0.9);
  light->SetFocalPoint(0.8, 0.5, 0.9);
  light->SetIntensity(4);
  light->SetDiffuseColor(1, 1, 1);
  vtkSmartPointer<vtkImageData> given = Render(Scene(filter->GetOutput(), false), light);
  Check(given != nullptr, "a scene lit by a vtkLight given to the tracer reconstructs");
  if (given)
  {
    vtkDataArray* g = given->GetPointData()->GetScalars();
    differing = 0;
    for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        differing += a->GetComponent(i, c) != g->GetComponent(i, c) ? 1 : 0;
      }
    }
    Check(differing == 0,
      "a vtkLight given to the tracer against the same light in the scene: " +
        std::to_string(differing) + " channel values differ");
  }
}

void TestColour()
{
  vtkNew<vtkVolumeProperty> property;
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0, 0.1);
  opacity->AddPoint(100, 0.6);
  property->SetScalarOpacity(opacity);
  property->SetScalarOpacityUnitDistance(0.25);
  property->SetInterpolationTypeToLinear();
  vtkNew<vtkColorTransferFunction> colour;
  colour->AddRGBPoint(10, 1.0, 0.2, 0.1);
  colour->AddRGBPoint(45, 0.9, 0.9, 0.3);
  colour->AddRGBPoint(90, 0.1, 0.3, 1.0);
  property->SetColor(colour);
  vtkNew<vtkBrumeVolumePropertyMedium> filter;
  filter->SetInputData(Field());
  filter->SetVolumeProperty(property);
  filter->SetAlbedo(0.9, 0.8, 0.5);
  Check(filter->GetExecutive()->Update() == 1, "the filter runs with a colour");
  vtkDataArray* points = filter->GetOutput()->GetFieldData()->GetArray(vtkBrumeNames::ScalarColor);
  Check(points && points->GetNumberOfTuples() == 3 && points->GetNumberOfComponents() == 4 &&
      points->GetComponent(1, 0) == 45 && points->GetComponent(2, 3) == 1.0,
    "an RGB function's points are taken node for node");
  // The same functions and settings given one by one, without a property
  // (as ParaView's filter gives them): the same field data.
  vtkNew<vtkBrumeVolumePropertyMedium> byParts;
  byParts->SetInputData(Field());
  byParts->SetScalarOpacity(opacity);
  byParts->SetColor(colour);
  byParts->SetScalarOpacityUnitDistance(0.25);
  byParts->SetInterpolationType(VTK_LINEAR_INTERPOLATION);
  byParts->SetAlbedo(0.9, 0.8, 0.5);
  Check(byParts->GetExecutive()->Update() == 1, "the filter runs with functions set one by one");
  for (const char* name : { vtkBrumeNames::ScalarOpacity, vtkBrumeNames::ScalarColor,
         vtkBrumeNames::ScalarOpacityUnitDistance, vtkBrumeNames::SigmaS, vtkBrumeNames::G })
  {
    vtkDataArray* x = filter->GetOutput()->GetFieldData()->GetArray(name);
    vtkDataArray* y = byParts->GetOutput()->GetFieldData()->GetArray(name);
    bool same = x && y && x->GetNumberOfValues() == y->GetNumberOfValues();
    for (vtkIdType i = 0; same && i < x->GetNumberOfValues(); ++i)
    {
      const int c = x->GetNumberOfComponents();
      same = x->GetComponent(i / c, static_cast<int>(i % c)) ==
        y->GetComponent(i / c, static_cast<int>(i % c));
    }
    Check(same, std::string("functions set one by one give the property's ") + name);
  }
  const auto modified = byParts->GetMTime();
  colour->AddRGBPoint(95, 0.1, 0.3, 1.0);
  Check(byParts->GetMTime() > modified, "editing the colour function modifies the filter");

  brume::Medium m;
  Check(ConvertMedium(filter->GetOutput(), m).empty(), "the coloured medium converts");
  Check(m.HasVaryingAlbedo(), "the colour makes the albedo vary");

  // The albedo at a point is Albedo times the colour of the interpolated
  // scalar; sigma_t is the opacity's alone.
  const double scale[3] = { 0.9, 0.8, 0.5 };
  auto checkAlong = [&](vtkColorTransferFunction* f, double tolerance, const std::string& what)
  {
    int checked = 0;
    for (double x = -0.45; x < 0.5; x += 0.1)
    {
      const double p[3] = { x, 0.05, -0.11 };
      const double value = Interpolate(filter->GetOutput(), "temperature", p);
      double rgb[3];
      f->GetColor(value, rgb);
      const brume::Vec3 q(
        static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2]));
      const brume::Vec3 got = m.AlbedoAt(q);
      bool near = true;
      for (int c = 0; c < 3; ++c)
      {
        near = near && std::abs(got[c] - scale[c] * rgb[c]) <= tolerance;
      }
      Check(near,
        what + ": albedo at x = " + std::to_string(x) + " is " + std::to_string(got.x) + " " +
          std::to_string(got.y) + " " + std::to_string(got.z));
      const double sigma = -std::log1p(-opacity->GetValue(value)) / 0.25;
      Check(std::abs(m.SigmaTAt(q).x - sigma) <= 1e-4 * (1.0 + sigma),
        what + ": the colour leaves sigma_t as the opacity gives it");
      checked += value > 10 && value < 90 ? 1 : 0;
    }
    Check(checked >= 3, what + ": the line crosses the colour ramp");
  };
  checkAlong(colour, 1e-5, "RGB points");

  // ParaView's colour maps interpolate in other spaces: sampled.
  colour->SetColorSpaceToDiverging();
  filter->Update();
  points = filter->GetOutput()->GetFieldData()->GetArray(vtkBrumeNames::ScalarColor);
  Check(points && points->GetNumberOfTuples() == filter->GetSampledFunctionPoints(),
    "a diverging function is sampled");
  Check(ConvertMedium(filter->GetOutput(), m).empty(), "the sampled colour converts");
  checkAlong(colour, 2e-3, "diverging, sampled");
  colour->SetColorSpaceToRGB();

  // Off, or a grey function: one albedo everywhere.
  filter->ColorAsAlbedoOff();
  filter->Update();
  Check(!filter->GetOutput()->GetFieldData()->GetArray(vtkBrumeNames::ScalarColor) &&
      ConvertMedium(filter->GetOutput(), m).empty() && !m.HasVaryingAlbedo(),
    "ColorAsAlbedo off: no colour");
  filter->ColorAsAlbedoOn();
  vtkNew<vtkPiecewiseFunction> grey;
  grey->AddPoint(0, 0.5);
  property->SetColor(grey);
  filter->Update();
  Check(!filter->GetOutput()->GetFieldData()->GetArray(vtkBrumeNames::ScalarColor),
    "a grey function does not colour the albedo");

  // A constant colour with Albedo 1 draws the image of that colour given
  // as the Albedo, with g = 0.85 (part of the peak set apart, whose share
  // of the extinction the mapper takes per fragment from the albedo).
  // Colours exactly representable with 1 - colour: the two media have the
  // same sigma_t and albedo to the bit, so the tracers trace the same hits.
  vtkNew<vtkColorTransferFunction> constant;
  constant->AddRGBPoint(0, 0.75, 0.5, 0.25);
  property->SetColor(constant);
  property->SetScatteringAnisotropy(0.85f);
  filter->SetAlbedo(1, 1, 1);
  filter->Update();
  auto coloured = vtkSmartPointer<vtkImageData>::New();
  coloured->DeepCopy(filter->GetOutput());
  filter->ColorAsAlbedoOff();
  filter->SetAlbedo(0.75, 0.5, 0.25);
  filter->Update();
  vtkSmartPointer<vtkImageData> a = Render(Scene(coloured));
  vtkSmartPointer<vtkImageData> b = Render(Scene(filter->GetOutput()));
  Check(a && b, "both coloured pipelines render");
  if (!a || !b)
  {
    return;
  }
  double worst = 0.0, peak = 0.0;
  Compare(a, b, worst, peak);
  Check(peak > 0.0 && worst <= 1e-5 * peak,
    "a constant colour against the same albedo: differs by " + std::to_string(worst) +
      " of a peak " + std::to_string(peak));
  filter->ColorAsAlbedoOn();

  // Bad colours, named.
  vtkNew<vtkColorTransferFunction> bright;
  bright->AddRGBPoint(0, 1.5, 0.2, 0.2);
  property->SetColor(bright);
  Check(ExpectFailure("a colour above 1", filter, "colour component outside [0, 1]"),
    "a colour above 1");
  property->SetColor(colour);
  filter->Update();
  auto edit = [&](const std::function<void(vtkFieldData*)>& change)
  {
    auto image = vtkSmartPointer<vtkImageData>::New();
    image->DeepCopy(filter->GetOutput());
    change(image->GetFieldData());
    brume::Medium medium;
    return ConvertMedium(image, medium);
  };
  Check(
    edit(
      [](vtkFieldData* fd) {
        fd->GetArray(vtkBrumeNames::ScalarColor)->SetComponent(0, 0, std::nan(""));
      }).find("BrumeScalarColor transfer function that colour point 0") != std::string::npos,
    "a NaN colour scalar");
  Check(
    edit(
      [](vtkFieldData* fd)
      {
        fd->RemoveArray(vtkBrumeNames::ScalarOpacity);
        fd->RemoveArray(vtkBrumeNames::ScalarOpacityUnitDistance);
      }).find("BrumeScalarColor without a BrumeScalarOpacity") != std::string::npos,
    "a colour without an opacity");
  Check(
    edit(
      [](vtkFieldData* fd)
      {
        vtkNew<vtkDoubleArray> three;
        three->SetName(vtkBrumeNames::ScalarColor);
        three->SetNumberOfComponents(3);
        three->InsertNextTuple3(0, 1, 1);
        fd->RemoveArray(vtkBrumeNames::ScalarColor);
        fd->AddArray(three);
      }).find("(scalar, red, green, blue) tuples") != std::string::npos,
    "a colour of three components");
}

void TestCoarsenedColour()
{
  // A field of 2,050 points along x: more native cells along an axis than
  // the reconstruction keeps (NativeMediumGrid::MaxAxis), so its grid is coarsened and
  // has no scalars to classify; the conversion then applies the albedo to
  // the texture itself. A constant colour with Albedo 1 must draw the image
  // of that colour given as the Albedo there too (g = 0.85: with the
  // forward peak's factor of the mean albedo).
  auto field = vtkSmartPointer<vtkImageData>::New();
  const int n = 2050;
  field->SetDimensions(n, 3, 3);
  field->SetOrigin(-0.5, -0.5, -0.5);
  field->SetSpacing(1.0 / (n - 1), 0.5, 0.5);
  vtkNew<vtkFloatArray> s;
  s->SetName("temperature");
  for (vtkIdType i = 0; i < field->GetNumberOfPoints(); ++i)
  {
    double p[3];
    field->GetPoint(i, p);
    s->InsertNextValue(static_cast<float>(50.0 + 40.0 * std::sin(7.0 * p[0])));
  }
  field->GetPointData()->SetScalars(s);
  vtkNew<vtkVolumeProperty> property;
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0, 0.05);
  opacity->AddPoint(100, 0.5);
  property->SetScalarOpacity(opacity);
  property->SetScalarOpacityUnitDistance(0.5);
  property->SetInterpolationTypeToLinear();
  property->SetScatteringAnisotropy(0.85f);
  vtkNew<vtkColorTransferFunction> constant;
  constant->AddRGBPoint(0, 0.75, 0.5, 0.25);
  property->SetColor(constant);
  vtkNew<vtkBrumeVolumePropertyMedium> filter;
  filter->SetInputData(field);
  filter->SetVolumeProperty(property);
  filter->SetAlbedo(1, 1, 1);
  filter->Update();
  auto coloured = vtkSmartPointer<vtkImageData>::New();
  coloured->DeepCopy(filter->GetOutput());
  filter->ColorAsAlbedoOff();
  filter->SetAlbedo(0.75, 0.5, 0.25);
  filter->Update();
  vtkSmartPointer<vtkImageData> a = Render(Scene(coloured));
  vtkSmartPointer<vtkImageData> b = Render(Scene(filter->GetOutput()));
  Check(a && b, "both coarsened pipelines render");
  if (!a || !b)
  {
    return;
  }
  double worst = 0.0, peak = 0.0;
  Compare(a, b, worst, peak);
  Check(peak > 0.0 && worst <= 1e-5 * peak,
    "coarsened: a constant colour against the same albedo differs by " + std::to_string(worst) +
      " of a peak " + std::to_string(peak));
}

void TestBadInput()
{
  vtkNew<vtkBrumeVolumePropertyMedium> filter;
  filter->SetInputData(Field());
  Check(ExpectFailure("no property", filter, "has no opacity transfer function"), "no property");

  vtkNew<vtkVolumeProperty> property;
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0, 0.2);
  opacity->AddPoint(50, -0.5);
  property->SetScalarOpacity(opacity);
  filter->SetVolumeProperty(property);
  Check(ExpectFailure("negative opacity", filter, "opacity outside [0, 1]"), "negative opacity");

  vtkNew<vtkPiecewiseFunction> empty;
  property->SetScalarOpacity(empty);
  Check(ExpectFailure("empty function", filter, "has no opacity points"), "empty function");

  vtkNew<vtkPiecewiseFunction> good;
  good->AddPoint(0, 0.2);
  property->SetScalarOpacity(good);
  filter->SetComponent(2);
  Check(
    ExpectFailure("component out of range", filter, "has Component 2"), "component out of range");
  filter->SetComponent(0);
  filter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "no such");
  Check(ExpectFailure("missing array", filter, "finds no array"), "missing array");
  filter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "temperature");
  filter->SetAlbedo(1.2, 0.5, 0.5);
  Check(ExpectFailure("albedo above 1", filter, "Albedo outside [0, 1]"), "albedo above 1");
  filter->SetAlbedo(0.5, 0.5, 0.5);
  Check(filter->GetExecutive()->Update() == 1, "a good function runs");

  // Field data written by hand: each bad array named in the error.
  auto edit = [&](const std::function<void(vtkFieldData*)>& change)
  {
    auto image = vtkSmartPointer<vtkImageData>::New();
    image->DeepCopy(filter->GetOutput());
    change(image->GetFieldData());
    brume::Medium m;
    return ConvertMedium(image, m);
  };
  auto setPoints = [](vtkFieldData* fd, double s0, double a0)
  {
    vtkDataArray* points = fd->GetArray(vtkBrumeNames::ScalarOpacity);
    points->SetTuple2(0, s0, a0);
  };
  Check(
    edit([&](vtkFieldData* fd) { setPoints(fd, std::nan(""), 0.2); }).find("non-finite scalar") !=
      std::string::npos,
    "a NaN scalar in BrumeScalarOpacity");
  Check(
    edit([&](vtkFieldData* fd) { setPoints(fd, 0.0, INFINITY); }).find("opacity outside [0, 1]") !=
      std::string::npos,
    "an infinite opacity");
  Check(
    edit(
      [](vtkFieldData* fd) {
        fd->GetArray(vtkBrumeNames::ScalarComponent)->SetTuple1(0, 1);
      }).find("BrumeScalarComponent 1, but its array") != std::string::npos,
    "component out of range in field data");
  Check(
    edit(
      [](vtkFieldData* fd) {
        fd->GetArray(vtkBrumeNames::ScalarOpacityUnitDistance)->SetTuple1(0, 0);
      }).find("unit distance") != std::string::npos,
    "a zero unit distance");
  Check(
    edit(
      [](vtkFieldData* fd)
      {
        vtkStringArray::SafeDownCast(fd->GetAbstractArray(vtkBrumeNames::Interpolation))
          ->SetValue(0, "cubic");
      }).find("BrumeInterpolation 'cubic'") != std::string::npos,
    "an unknown interpolation");
  Check(
    edit(
      [](vtkFieldData* fd)
      {
        vtkStringArray::SafeDownCast(fd->GetAbstractArray(vtkBrumeNames::DensityArray))
          ->SetValue(0, "absent");
      }).find("no density array 'absent'") != std::string::npos,
    "an array that does not exist");
  const std::string nan = edit([](vtkFieldData*) {});
  Check(nan.empty(), "the unedited medium converts: " + nan);
  // Non-finite scalars are refused; negative ones are fine with a function.
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->DeepCopy(filter->GetOutput());
  image->GetPointData()->GetArray("temperature")->SetTuple1(7, std::nan(""));
  brume::Medium m;
  Check(ConvertMedium(image, m).find("non-finite scalars") != std::string::npos,
    "a NaN scalar in the field");
  image->GetPointData()->GetArray("temperature")->SetTuple1(7, -3.0);
  Check(ConvertMedium(image, m).empty(), "negative scalars are classified");
}
}

int TestTransferFunctionMedium(int, char*[])
{
  TestClassification();
  TestResampledDataset();
  TestConstantFunctionIsTheConstantDensity();
  TestColour();
  TestCoarsenedColour();
  TestBadInput();
  if (failures)
  {
    std::cerr << failures << " check(s) failed\n";
    return 1;
  }
  return 0;
}
