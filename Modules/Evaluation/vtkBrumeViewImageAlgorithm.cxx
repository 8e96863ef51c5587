// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeViewImageAlgorithm.h"

#include "vtkCamera.h"
#include "vtkDataObject.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>

vtkCxxSetObjectMacro(vtkBrumeViewImageAlgorithm, Camera, vtkCamera);

vtkBrumeViewImageAlgorithm::vtkBrumeViewImageAlgorithm()
{
  this->SetNumberOfInputPorts(1);
}

vtkBrumeViewImageAlgorithm::~vtkBrumeViewImageAlgorithm()
{
  this->SetCamera(nullptr);
}

vtkMTimeType vtkBrumeViewImageAlgorithm::GetMTime()
{
  vtkMTimeType t = this->Superclass::GetMTime();
  return this->Camera ? std::max(t, this->Camera->GetMTime()) : t;
}

int vtkBrumeViewImageAlgorithm::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataObject");
  return 1;
}

int vtkBrumeViewImageAlgorithm::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  const int extent[6] = { 0, std::max(1, this->Size[0]) - 1, 0, std::max(1, this->Size[1]) - 1, 0,
    0 };
  const double origin[3] = { 0, 0, 0 }, spacing[3] = { 1, 1, 1 };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  outInfo->Set(vtkDataObject::ORIGIN(), origin, 3);
  outInfo->Set(vtkDataObject::SPACING(), spacing, 3);
  return 1;
}

void vtkBrumeViewImageAlgorithm::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Size: " << this->Size[0] << " x " << this->Size[1] << "\n";
  os << indent << "Camera: " << this->Camera << "\n";
}
