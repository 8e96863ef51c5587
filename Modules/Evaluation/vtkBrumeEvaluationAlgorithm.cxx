// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeEvaluationAlgorithm.h"

#include "vtkBrumeEvaluationTable.h"
#include "vtkBrumeRadianceReconstruction.h"
#include "vtkCamera.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkTable.h"

#include <algorithm>
#include <string>

vtkCxxSetObjectMacro(vtkBrumeEvaluationAlgorithm, Camera, vtkCamera);

vtkBrumeEvaluationAlgorithm::vtkBrumeEvaluationAlgorithm()
  : RadiosityThreshold(vtkNew<vtkBrumeRadianceReconstruction>()->GetRadiosityThreshold())
{
  this->SetSceneName("scene");
}

vtkBrumeEvaluationAlgorithm::~vtkBrumeEvaluationAlgorithm()
{
  this->SetCamera(nullptr);
  this->SetCacheDirectory(nullptr);
  this->SetSceneName(nullptr);
  this->SetCacheKey(nullptr);
}

vtkMTimeType vtkBrumeEvaluationAlgorithm::GetMTime()
{
  vtkMTimeType t = this->Superclass::GetMTime();
  return this->Camera ? std::max(t, this->Camera->GetMTime()) : t;
}

int vtkBrumeEvaluationAlgorithm::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataObject");
  return 1;
}

bool vtkBrumeEvaluationAlgorithm::CheckCommonSettings()
{
  if (this->Size[0] < 1 || this->Size[1] < 1 || this->Size[0] > 16384 || this->Size[1] > 16384)
  {
    vtkErrorMacro("Size must be in [1, 16384] on each axis, not " << this->Size[0] << " x "
                                                                  << this->Size[1] << ".");
    return false;
  }
  if (this->Seed < 0)
  {
    vtkErrorMacro("Seed must be non-negative, not " << this->Seed << ".");
    return false;
  }
  return true;
}

bool vtkBrumeEvaluationAlgorithm::WriteCsv(const char* fileName)
{
  std::string error;
  if (!vtkBrumeEvaluationTable::WriteCsv(this->GetOutput(), fileName, error))
  {
    vtkErrorMacro("The " << this->GetClassName() << " CSV: " << error << ".");
    return false;
  }
  return true;
}

void vtkBrumeEvaluationAlgorithm::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  auto text = [](const char* s) { return s ? s : ""; };
  os << indent << "Size: " << this->Size[0] << " x " << this->Size[1] << "\n";
  os << indent << "MinParticles: " << this->MinParticles << "\n";
  os << indent << "MaxParticles: " << this->MaxParticles << "\n";
  os << indent << "ReferenceSamples: " << this->ReferenceSamples << "\n";
  os << indent << "RadiosityThreshold: " << this->RadiosityThreshold << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "DirectionalOrder: " << this->DirectionalOrder << "\n";
  os << indent << "Supersampling: " << this->Supersampling << "\n";
  os << indent << "Camera: " << this->Camera << "\n";
  os << indent << "CacheDirectory: " << text(this->CacheDirectory) << "\n";
  os << indent << "SceneName: " << text(this->SceneName) << "\n";
  os << indent << "CacheKey: " << text(this->CacheKey) << "\n";
}
