// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeSceneActors.h"

#include "vtkActor.h"
#include "vtkBrumeSliceVolumeMapper.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkObjectFactory.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkPropCollection.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkStringArray.h"
#include "vtkTexture.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

vtkStandardNewMacro(vtkBrumeSceneActors);

namespace
{
std::string KindOf(vtkDataObject* data)
{
  auto* kind = data
    ? vtkStringArray::SafeDownCast(data->GetFieldData()->GetAbstractArray("BrumeObjectKind"))
    : nullptr;
  return kind && kind->GetNumberOfValues() > 0 ? kind->GetValue(0) : std::string();
}
}

vtkBrumeSceneActors::vtkBrumeSceneActors()
  : Props(vtkSmartPointer<vtkPropCollection>::New())
{
}

vtkBrumeSceneActors::~vtkBrumeSceneActors() = default;

void vtkBrumeSceneActors::SetInputData(vtkPartitionedDataSetCollection* textures)
{
  if (this->Input != textures)
  {
    this->Input = textures;
    this->Modified();
  }
}

vtkPartitionedDataSetCollection* vtkBrumeSceneActors::GetInputData()
{
  return this->Input;
}

vtkPropCollection* vtkBrumeSceneActors::GetProps()
{
  return this->Props;
}

bool vtkBrumeSceneActors::AddToRenderer(vtkRenderer* renderer)
{
  this->Props->RemoveAllItems();
  if (!this->Input || !renderer)
  {
    vtkErrorMacro("AddToRenderer needs an input collection and a renderer.");
    return false;
  }
  for (unsigned int i = 0; i < this->Input->GetNumberOfPartitionedDataSets(); ++i)
  {
    vtkPartitionedDataSet* pds = this->Input->GetPartitionedDataSet(i);
    vtkDataObject* first = pds && pds->GetNumberOfPartitions() > 0 ? pds->GetPartition(0) : nullptr;
    const std::string kind = KindOf(first);
    if (kind == "surface" && pds->GetNumberOfPartitions() >= 2)
    {
      auto* image = vtkImageData::SafeDownCast(first);
      auto* surface = vtkPolyData::SafeDownCast(pds->GetPartition(1));
      if (!image || !surface)
      {
        vtkErrorMacro("Object " << i << " is not a reconstructed surface texture.");
        return false;
      }
      vtkNew<vtkTexture> texture;
      texture->SetInputData(image);
      texture->InterpolateOn();
      texture->RepeatOff();
      texture->EdgeClampOn();
      // Float radiance goes to the texture unchanged (no lookup table).
      texture->SetColorModeToDirectScalars();
      vtkNew<vtkPolyDataMapper> mapper;
      mapper->SetInputData(surface);
      mapper->ScalarVisibilityOff();
      vtkNew<vtkActor> actor;
      actor->SetMapper(mapper);
      actor->SetTexture(texture);
      // Unlit: the fragment is the texture's radiance.
      actor->GetProperty()->LightingOff();
      actor->GetProperty()->SetColor(1.0, 1.0, 1.0);
      actor->GetProperty()->SetAmbient(1.0);
      actor->GetProperty()->SetDiffuse(0.0);
      actor->GetProperty()->SetSpecular(0.0);
      renderer->AddActor(actor);
      this->Props->AddItem(actor);
    }
    else if (kind == "medium")
    {
      if (!this->ShowMedia)
      {
        continue;
      }
      auto* image = vtkImageData::SafeDownCast(first);
      vtkNew<vtkBrumeSliceVolumeMapper> mapper;
      mapper->SetInputData(image);
      vtkNew<vtkVolume> volume;
      volume->SetMapper(mapper);
      volume->GetProperty()->SetInterpolationTypeToLinear();
      renderer->AddVolume(volume);
      this->Props->AddItem(volume);
    }
    else
    {
      vtkErrorMacro("Object " << i << " is not a Brume radiance texture (no BrumeObjectKind).");
      return false;
    }
  }
  return true;
}

void vtkBrumeSceneActors::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ShowMedia: " << this->ShowMedia << "\n";
  os << indent << "Input: " << this->Input.Get() << "\n";
}
