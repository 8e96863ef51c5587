// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeEvaluationView.h"

#include "vtkBrumeSceneCamera.h"
#include "vtkCamera.h"

vtkSmartPointer<vtkCamera> vtkBrumeEvaluationView::Camera(vtkDataObject* scene, vtkCamera* camera)
{
  auto result = vtkSmartPointer<vtkCamera>::New();
  if (camera)
  {
    result->SetPosition(camera->GetPosition());
    result->SetFocalPoint(camera->GetFocalPoint());
    result->SetViewUp(camera->GetViewUp());
    result->SetViewAngle(camera->GetViewAngle());
  }
  else
  {
    // All four or none: a partial camera in the field data is not used.
    vtkBrumeSceneCamera::SetFromScene(scene, result);
  }
  return result;
}

brume::PinholeCamera vtkBrumeEvaluationView::Pinhole(vtkCamera* camera, int width, int height)
{
  double position[3], focalPoint[3], viewUp[3];
  camera->GetPosition(position);
  camera->GetFocalPoint(focalPoint);
  camera->GetViewUp(viewUp);
  brume::PinholeCamera pinhole;
  pinhole.Position = { static_cast<float>(position[0]), static_cast<float>(position[1]),
    static_cast<float>(position[2]) };
  pinhole.FocalPoint = { static_cast<float>(focalPoint[0]), static_cast<float>(focalPoint[1]),
    static_cast<float>(focalPoint[2]) };
  pinhole.ViewUp = { static_cast<float>(viewUp[0]), static_cast<float>(viewUp[1]),
    static_cast<float>(viewUp[2]) };
  pinhole.ViewAngle = static_cast<float>(camera->GetViewAngle());
  pinhole.Width = width;
  pinhole.Height = height;
  return pinhole;
}
