// SPDX-License-Identifier: BSD-3-Clause
// A scene built the VTK way for the pipeline module's tests: a ground, an
// actor of any source, VTK's Wavelet as a volume, a positional light.
#ifndef VtkSceneTesting_h
#define VtkSceneTesting_h

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkFixedPointVolumeRayCastMapper.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPlaneSource.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRTAnalyticSource.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

/// An actor of `source` in `renderer`, coloured (r, g, b).
inline vtkSmartPointer<vtkActor> AddActor(
  vtkRenderer* renderer, vtkAlgorithm* source, double r, double g, double b)
{
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(source->GetOutputPort());
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(r, g, b);
  renderer->AddActor(actor);
  return actor;
}

/// A 6 x 6 ground at y = -1 facing +y.
inline vtkSmartPointer<vtkActor> AddGround(vtkRenderer* renderer, double r, double g, double b)
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-3, -1, 3);
  plane->SetPoint1(3, -1, 3);
  plane->SetPoint2(-3, -1, -3);
  return AddActor(renderer, plane, r, g, b);
}

/// VTK's Wavelet over [-half, half]^3 as a volume with an opacity ramp from
/// `low` (0) to `high` (`opacity`), scaled and moved.
inline vtkSmartPointer<vtkVolume> AddWavelet(vtkRenderer* renderer, int half, double low,
  double high, double opacity, double scale, const double position[3])
{
  vtkNew<vtkRTAnalyticSource> wavelet;
  wavelet->SetWholeExtent(-half, half, -half, half, -half, half);
  vtkNew<vtkFixedPointVolumeRayCastMapper> mapper;
  mapper->SetInputConnection(wavelet->GetOutputPort());
  vtkNew<vtkPiecewiseFunction> ramp;
  ramp->AddPoint(low, 0.0);
  ramp->AddPoint(high, opacity);
  vtkNew<vtkColorTransferFunction> colour;
  colour->AddRGBPoint(low, 0.6, 0.7, 1.0);
  colour->AddRGBPoint(high, 1.0, 0.9, 0.8);
  vtkNew<vtkVolumeProperty> property;
  property->SetScalarOpacity(ramp);
  property->SetColor(colour);
  auto volume = vtkSmartPointer<vtkVolume>::New();
  volume->SetMapper(mapper);
  volume->SetProperty(property);
  volume->SetScale(scale);
  volume->SetPosition(position[0], position[1], position[2]);
  renderer->AddVolume(volume);
  return volume;
}

/// A positional light of `intensity` at `position`, toward the origin.
inline void AddPointLight(vtkRenderer* renderer, const double position[3], double intensity)
{
  vtkNew<vtkLight> light;
  light->SetLightTypeToSceneLight();
  light->SetPositional(true);
  light->SetConeAngle(180);
  light->SetPosition(position[0], position[1], position[2]);
  light->SetFocalPoint(0, 0, 0);
  light->SetIntensity(intensity);
  renderer->AddLight(light);
}

/// The scene of the render-pass issue: a grey ground, a glossy red sphere,
/// the Wavelet as a volume and one positional light, seen from (0, 2, 7);
/// the ground's actor.
inline vtkSmartPointer<vtkActor> AddPassScene(vtkRenderer* renderer)
{
  auto ground = AddGround(renderer, 0.7, 0.7, 0.7);
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(1, -0.4, 0);
  sphere->SetRadius(0.6);
  auto ball = AddActor(renderer, sphere, 0.9, 0.3, 0.2);
  ball->GetProperty()->SetSpecular(0.2);
  ball->GetProperty()->SetSpecularPower(30);
  const double where[3] = { -1, -0.2, 0 };
  AddWavelet(renderer, 6, 90, 280, 0.6, 0.1, where);
  const double lightPosition[3] = { 1, 4, 3 };
  AddPointLight(renderer, lightPosition, 30);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(0, 2, 7);
  camera->SetFocalPoint(0, -0.3, 0);
  camera->SetViewAngle(40);
  renderer->ResetCameraClippingRange();
  return ground;
}

#endif
