// SPDX-License-Identifier: BSD-3-Clause
// Scenes and comparisons shared by the cross-module tests.
#ifndef BrumeTestScenes_h
#define BrumeTestScenes_h

#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeDefaultSceneSource.h"
#include "vtkCellData.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"

#include <cstring>
#include <iostream>

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
      type->SetName(vtkBrumeNames::Material);
      type->InsertNextValue("phong");
      fd->AddArray(type);
      vtkNew<vtkDoubleArray> specular;
      specular->SetName(vtkBrumeNames::Specular);
      specular->SetNumberOfComponents(3);
      specular->InsertNextTuple3(0.2, 0.2, 0.2);
      fd->AddArray(specular);
      fd->GetArray(vtkBrumeNames::Reflectance)->SetTuple3(0, 0.5, 0.5, 0.5);
    }
  }
  return scene;
}

/// The default scene with a mirror floor (rho_s 0.9, no diffuse part).
inline vtkSmartPointer<vtkPartitionedDataSetCollection> DefaultSceneWithMirrorFloor()
{
  auto scene = DefaultSceneWithGlossyFloor();
  for (unsigned int i = 0; i < scene->GetNumberOfPartitionedDataSets(); ++i)
  {
    if (std::string(scene->GetMetaData(i)->Get(vtkCompositeDataSet::NAME())) == "floor")
    {
      vtkFieldData* fd = scene->GetPartitionedDataSet(i)->GetPartition(0)->GetFieldData();
      vtkStringArray::SafeDownCast(fd->GetAbstractArray(vtkBrumeNames::Material))
        ->SetValue(0, "mirror");
      fd->GetArray(vtkBrumeNames::Specular)->SetTuple3(0, 0.9, 0.9, 0.9);
      fd->GetArray(vtkBrumeNames::Reflectance)->SetTuple3(0, 0, 0, 0);
    }
  }
  return scene;
}

// Every array of every texture (partition 0) of `a` has the bits of `b`'s.
inline bool SameTextures(
  vtkPartitionedDataSetCollection* a, vtkPartitionedDataSetCollection* b, const std::string& what)
{
  bool ok = a->GetNumberOfPartitionedDataSets() == b->GetNumberOfPartitionedDataSets();
  for (unsigned int i = 0; ok && i < a->GetNumberOfPartitionedDataSets(); ++i)
  {
    auto* ta = vtkImageData::SafeDownCast(a->GetPartitionedDataSet(i)->GetPartition(0));
    auto* tb = vtkImageData::SafeDownCast(b->GetPartitionedDataSet(i)->GetPartition(0));
    for (vtkFieldData* fa : { static_cast<vtkFieldData*>(ta->GetPointData()),
           static_cast<vtkFieldData*>(ta->GetCellData()) })
    {
      vtkFieldData* fb = fa == ta->GetPointData() ? static_cast<vtkFieldData*>(tb->GetPointData())
                                                  : static_cast<vtkFieldData*>(tb->GetCellData());
      for (int k = 0; k < fa->GetNumberOfArrays(); ++k)
      {
        vtkDataArray* x = fa->GetArray(k);
        vtkDataArray* y = fb->GetArray(x->GetName());
        if (!y || x->GetNumberOfValues() != y->GetNumberOfValues() ||
          std::memcmp(x->GetVoidPointer(0), y->GetVoidPointer(0),
            x->GetNumberOfValues() * x->GetDataTypeSize()) != 0)
        {
          std::cerr << what << ": object " << i << ", array " << x->GetName() << " differs\n";
          ok = false;
        }
      }
    }
  }
  return ok;
}

#endif
