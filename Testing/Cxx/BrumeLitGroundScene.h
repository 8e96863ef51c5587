// SPDX-License-Identifier: BSD-3-Clause
// The scene the media tests light a medium in: a 4 x 4 ground at y = -0.6
// and the medium, lit by a point light (in the scene's field data) at
// (0.8, 1.5, 0.9).
#ifndef BrumeLitGroundScene_h
#define BrumeLitGroundScene_h

#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeSceneConversion.h"
#include "vtkCellArray.h"
#include "vtkDataObject.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"

/// The ground and `medium` (named `name`), lit unless `lit` is false (for
/// a tracer given a vtkLight instead).
inline vtkSmartPointer<vtkPartitionedDataSetCollection> BrumeLitGroundScene(
  vtkDataObject* medium, const char* name, bool lit = true)
{
  auto ground = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(-2, -0.6, -2);
  points->InsertNextPoint(-2, -0.6, 2);
  points->InsertNextPoint(2, -0.6, 2);
  points->InsertNextPoint(2, -0.6, -2);
  ground->SetPoints(points);
  vtkNew<vtkCellArray> polys;
  const vtkIdType quad[4] = { 0, 1, 2, 3 };
  polys->InsertNextCell(4, quad);
  ground->SetPolys(polys);
  auto scene = vtkSmartPointer<vtkPartitionedDataSetCollection>::New();
  vtkBrumeSceneConversion::AddObject(scene, ground, "ground");
  vtkBrumeSceneConversion::AddObject(scene, medium, name);
  if (!lit)
  {
    return scene;
  }
  vtkNew<vtkStringArray> types;
  types->SetName(vtkBrumeNames::LightType);
  types->InsertNextValue("point");
  vtkFieldData* fd = scene->GetFieldData();
  fd->AddArray(types);
  const double position[3] = { 0.8, 1.5, 0.9 }, direction[3] = { 0, -1, 0 },
               intensity[3] = { 4, 4, 4 }, cone = 180;
  vtkBrumeSceneConversion::AppendTuple(fd, vtkBrumeNames::LightPosition, position, 3);
  vtkBrumeSceneConversion::AppendTuple(fd, vtkBrumeNames::LightDirection, direction, 3);
  vtkBrumeSceneConversion::AppendTuple(fd, vtkBrumeNames::LightIntensity, intensity, 3);
  vtkBrumeSceneConversion::AppendTuple(fd, vtkBrumeNames::LightConeAngle, &cone, 1);
  return scene;
}

#endif
