// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeSceneCamera.h"

#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeFieldTuple.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkFieldData.h"
#include "vtkObjectFactory.h"

#include "brume/Camera.h"

vtkStandardNewMacro(vtkBrumeSceneCamera);

namespace
{
// One tuple of `n` components of the field array `name`; false when absent
// or of another shape (the value is then left as it was).
bool ReadTuple(vtkFieldData* fd, const char* name, int n, double* values)
{
  vtkDataArray* a = fd ? vtkDataArray::SafeDownCast(fd->GetAbstractArray(name)) : nullptr;
  if (!a || a->GetNumberOfTuples() < 1 || a->GetNumberOfComponents() != n)
  {
    return false;
  }
  a->GetTuple(0, values);
  return true;
}

void DefaultView(double position[3], double focalPoint[3], double viewUp[3], double& viewAngle)
{
  const brume::PinholeCamera view;
  for (int a = 0; a < 3; ++a)
  {
    position[a] = view.Position[a];
    focalPoint[a] = view.FocalPoint[a];
    viewUp[a] = view.ViewUp[a];
  }
  viewAngle = view.ViewAngle;
}
}

void vtkBrumeSceneCamera::GetDefault(
  double position[3], double focalPoint[3], double viewUp[3], double& viewAngle)
{
  DefaultView(position, focalPoint, viewUp, viewAngle);
}

void vtkBrumeSceneCamera::SetToDefault(vtkCamera* camera)
{
  double position[3], focalPoint[3], viewUp[3], viewAngle;
  DefaultView(position, focalPoint, viewUp, viewAngle);
  camera->SetPosition(position);
  camera->SetFocalPoint(focalPoint);
  camera->SetViewUp(viewUp);
  camera->SetViewAngle(viewAngle);
}

bool vtkBrumeSceneCamera::GetSceneCamera(vtkDataObject* scene, double position[3],
  double focalPoint[3], double viewUp[3], double& viewAngle)
{
  DefaultView(position, focalPoint, viewUp, viewAngle);
  vtkFieldData* fd = scene ? scene->GetFieldData() : nullptr;
  return ReadTuple(fd, vtkBrumeNames::CameraPosition, 3, position) &&
    ReadTuple(fd, vtkBrumeNames::CameraFocalPoint, 3, focalPoint) &&
    ReadTuple(fd, vtkBrumeNames::CameraViewUp, 3, viewUp) &&
    ReadTuple(fd, vtkBrumeNames::CameraViewAngle, 1, &viewAngle);
}

bool vtkBrumeSceneCamera::SetFromScene(vtkDataObject* scene, vtkCamera* camera)
{
  double position[3], focalPoint[3], viewUp[3], viewAngle;
  const bool named = GetSceneCamera(scene, position, focalPoint, viewUp, viewAngle);
  if (!named)
  {
    DefaultView(position, focalPoint, viewUp, viewAngle);
  }
  camera->SetPosition(position);
  camera->SetFocalPoint(focalPoint);
  camera->SetViewUp(viewUp);
  camera->SetViewAngle(viewAngle);
  return named;
}

void vtkBrumeSceneCamera::WriteToScene(vtkCamera* camera, vtkFieldData* fieldData)
{
  const double angle = camera->GetViewAngle();
  vtkBrumeFieldTuple::Set(fieldData, vtkBrumeNames::CameraPosition, camera->GetPosition(), 3);
  vtkBrumeFieldTuple::Set(fieldData, vtkBrumeNames::CameraFocalPoint, camera->GetFocalPoint(), 3);
  vtkBrumeFieldTuple::Set(fieldData, vtkBrumeNames::CameraViewUp, camera->GetViewUp(), 3);
  vtkBrumeFieldTuple::Set(fieldData, vtkBrumeNames::CameraViewAngle, &angle, 1);
}
