// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeDefaultSceneSource.h"

#include "vtkBrumeSceneCamera.h"
#include "vtkBrumeSceneConversion.h"

#include "vtkBrumeDataModelNames.h"
#include "vtkCellArray.h"
#include "vtkCompositeDataSet.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include "brume/Scene.h"

vtkStandardNewMacro(vtkBrumeDefaultSceneSource);

namespace
{
void AddVec3(vtkFieldData* fd, const char* name, double x, double y, double z)
{
  const double v[3] = { x, y, z };
  vtkBrumeSceneConversion::AppendTuple(fd, name, v, 3);
}

void AddScalar(vtkFieldData* fd, const char* name, double v)
{
  vtkBrumeSceneConversion::AppendTuple(fd, name, &v, 1);
}
}

vtkBrumeDefaultSceneSource::vtkBrumeDefaultSceneSource()
{
  this->SetNumberOfInputPorts(0);
}

int vtkBrumeDefaultSceneSource::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  // A scene is replicated, not split: every piece (every process of a
  // distributed run) gets all of it.
  outputVector->GetInformationObject(0)->Set(CAN_HANDLE_PIECE_REQUEST(), 1);
  return 1;
}

int vtkBrumeDefaultSceneSource::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  auto* output = vtkPartitionedDataSetCollection::GetData(outputVector, 0);
  // The specification lives in the core so that every front end shares it.
  const brume::Scene scene = brume::MakeDefaultScene();
  for (const brume::Surface& s : scene.Surfaces)
  {
    vtkNew<vtkPoints> points;
    for (const brume::Vec3& v : s.Vertices)
    {
      points->InsertNextPoint(v.x, v.y, v.z);
    }
    // Every default surface is one quad: keep it a single polygon.
    vtkNew<vtkCellArray> polys;
    polys->InsertNextCell(4);
    const vtkIdType quad[4] = { 0, 1, 2, 3 };
    for (vtkIdType id : quad)
    {
      polys->InsertCellPoint(id);
    }
    vtkNew<vtkPolyData> pd;
    pd->SetPoints(points);
    pd->SetPolys(polys);
    AddVec3(pd->GetFieldData(), vtkBrumeNames::Reflectance, s.Mat.Reflectance.x,
      s.Mat.Reflectance.y, s.Mat.Reflectance.z);
    AddVec3(pd->GetFieldData(), vtkBrumeNames::Emission, s.Mat.Emission.x, s.Mat.Emission.y,
      s.Mat.Emission.z);
    vtkBrumeSceneConversion::AddObject(output, pd, s.Name);
  }
  if (this->IncludeMedium)
  {
    for (const brume::Medium& m : scene.Media)
    {
      vtkNew<vtkImageData> box;
      box->SetOrigin(m.Bounds.lower.x, m.Bounds.lower.y, m.Bounds.lower.z);
      const brume::Vec3 e = m.Bounds.Extent();
      box->SetSpacing(e.x, e.y, e.z);
      box->SetDimensions(2, 2, 2);
      AddVec3(box->GetFieldData(), vtkBrumeNames::SigmaA, m.SigmaA.x, m.SigmaA.y, m.SigmaA.z);
      AddVec3(box->GetFieldData(), vtkBrumeNames::SigmaS, m.SigmaS.x, m.SigmaS.y, m.SigmaS.z);
      AddScalar(box->GetFieldData(), vtkBrumeNames::G, m.G);
      vtkBrumeSceneConversion::AddObject(output, box, m.Name);
    }
  }
  vtkFieldData* fd = output->GetFieldData();
  double position[3], focal[3], up[3], angle;
  vtkBrumeSceneCamera::GetDefault(position, focal, up, angle);
  vtkBrumeSceneConversion::AppendTuple(fd, vtkBrumeNames::CameraPosition, position, 3);
  vtkBrumeSceneConversion::AppendTuple(fd, vtkBrumeNames::CameraFocalPoint, focal, 3);
  vtkBrumeSceneConversion::AppendTuple(fd, vtkBrumeNames::CameraViewUp, up, 3);
  AddScalar(fd, vtkBrumeNames::CameraViewAngle, angle);
  return 1;
}

void vtkBrumeDefaultSceneSource::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "IncludeMedium: " << this->IncludeMedium << "\n";
}
