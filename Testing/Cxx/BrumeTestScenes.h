// SPDX-License-Identifier: BSD-3-Clause
// Scenes shared by the cross-module tests.
#ifndef BrumeTestScenes_h
#define BrumeTestScenes_h

#include "vtkBrumeDefaultSceneSource.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"

#include <string>

/// The default scene with a glossy (Phong) floor: two view-dependent
/// objects, the floor and the fog.
inline vtkSmartPointer<vtkPartitionedDataSetCollection> DefaultSceneWithGlossyFloor()
{
  vtkNew<vtkBrumeDefaultSceneSource> source;
  source->Update();
  auto scene = vtkSmartPointer<vtkPartitionedDataSetCollection>::New();
  scene->DeepCopy(source->GetOutput());
  for (unsigned int i = 0; i < scene->GetNumberOfPartitionedDataSets(); ++i)
  {
    if (std::string(scene->GetMetaData(i)->Get(vtkCompositeDataSet::NAME())) == "floor")
    {
      vtkFieldData* fd = scene->GetPartitionedDataSet(i)->GetPartition(0)->GetFieldData();
      vtkNew<vtkStringArray> type;
      type->SetName("BrumeMaterial");
      type->InsertNextValue("phong");
      fd->AddArray(type);
      vtkNew<vtkDoubleArray> specular;
      specular->SetName("BrumeSpecular");
      specular->SetNumberOfComponents(3);
      specular->InsertNextTuple3(0.2, 0.2, 0.2);
      fd->AddArray(specular);
      fd->GetArray("BrumeReflectance")->SetTuple3(0, 0.5, 0.5, 0.5);
    }
  }
  return scene;
}

#endif
