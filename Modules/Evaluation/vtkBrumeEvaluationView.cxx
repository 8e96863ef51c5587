// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeEvaluationView.h"

#include "vtkBrumeSceneConversion.h"
#include "vtkCamera.h"

#include <algorithm>

vtkSmartPointer<vtkCamera> vtkBrumeEvaluationView::Camera(vtkDataObject* scene, vtkCamera* camera)
{
  double position[3] = { 0, 0, 4 }, focalPoint[3] = { 0, 0, 0 }, viewUp[3] = { 0, 1, 0 };
  double viewAngle = 40;
  if (camera)
  {
    camera->GetPosition(position);
    camera->GetFocalPoint(focalPoint);
    camera->GetViewUp(viewUp);
    viewAngle = camera->GetViewAngle();
  }
  else
  {
    // All four or none: a partial camera in the field data is not used.
    double p[3], f[3], u[3], a = 0;
    if (scene && vtkBrumeSceneConversion::GetCamera(scene, p, f, u, a))
    {
      std::copy(p, p + 3, position);
      std::copy(f, f + 3, focalPoint);
      std::copy(u, u + 3, viewUp);
      viewAngle = a;
    }
  }
  // In this order, as the chart always built its cameras.
  auto result = vtkSmartPointer<vtkCamera>::New();
  result->SetPosition(position);
  result->SetFocalPoint(focalPoint);
  result->SetViewUp(viewUp);
  result->SetViewAngle(viewAngle);
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
