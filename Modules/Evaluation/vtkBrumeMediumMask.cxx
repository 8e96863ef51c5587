// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeMediumMask.h"

#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeEvaluationView.h"
#include "vtkBrumeSceneConversion.h"
#include "vtkCamera.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPartitionedDataSetCollection.h"
#include "vtkPointData.h"
#include "vtkSMPTools.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <vector>

vtkStandardNewMacro(vtkBrumeMediumMask);

namespace
{
// The bounds of every medium (image data object) of the scene.
std::vector<brume::Box> MediumBoxes(vtkPartitionedDataSetCollection* scene)
{
  std::vector<brume::Box> boxes;
  for (unsigned int i = 0; i < scene->GetNumberOfPartitionedDataSets(); ++i)
  {
    vtkPartitionedDataSet* object = scene->GetPartitionedDataSet(i);
    for (unsigned int p = 0; object && p < object->GetNumberOfPartitions(); ++p)
    {
      if (auto* image = vtkImageData::SafeDownCast(object->GetPartition(p)))
      {
        double b[6];
        image->GetBounds(b);
        boxes.push_back(
          { { static_cast<float>(b[0]), static_cast<float>(b[2]), static_cast<float>(b[4]) },
            { static_cast<float>(b[1]), static_cast<float>(b[3]), static_cast<float>(b[5]) } });
      }
    }
  }
  return boxes;
}
}

vtkBrumeMediumMask::vtkBrumeMediumMask() = default;

vtkBrumeMediumMask::~vtkBrumeMediumMask() = default;

int vtkBrumeMediumMask::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkDataObject* input = vtkDataObject::GetData(inputVector[0], 0);
  const auto scene = vtkBrumeSceneConversion::AsCollection(input);
  if (!scene)
  {
    vtkErrorMacro("The input must be a Brume scene (a vtkPartitionedDataSetCollection), not "
      << (input ? input->GetClassName() : "nothing") << ".");
    return 0;
  }
  const int w = this->Size[0], h = this->Size[1];
  if (w < 1 || h < 1 || w > 16384 || h > 16384)
  {
    vtkErrorMacro("Size must be in [1, 16384] on each axis, not " << w << " x " << h << ".");
    return 0;
  }
  const std::vector<brume::Box> boxes = MediumBoxes(scene);
  const brume::PinholeCamera camera =
    vtkBrumeEvaluationView::Pinhole(vtkBrumeEvaluationView::Camera(scene, this->Camera), w, h);

  vtkNew<vtkUnsignedCharArray> mask;
  mask->SetName(vtkBrumeNames::MediumMask);
  mask->SetNumberOfTuples(static_cast<vtkIdType>(w) * h);
  unsigned char* inside = mask->GetPointer(0);
  vtkSMPTools::For(0, h,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType y = begin; y < end; ++y)
      {
        for (int x = 0; x < w; ++x)
        {
          brume::Vec3 o, d;
          camera.Ray(x + 0.5f, static_cast<float>(y) + 0.5f, o, d);
          unsigned char crosses = 0;
          for (const brume::Box& box : boxes)
          {
            float t0 = 0.f, t1 = 1e30f;
            crosses = crosses || box.Intersect(o, d, t0, t1);
          }
          inside[y * w + x] = crosses;
        }
      }
    });
  auto* output = vtkImageData::GetData(outputVector, 0);
  output->SetExtent(0, w - 1, 0, h - 1, 0, 0);
  output->GetPointData()->SetScalars(mask);
  return 1;
}

void vtkBrumeMediumMask::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
