// SPDX-License-Identifier: BSD-3-Clause
// vtkBrumeMediumMask: the silhouette of a medium box against its analytic size.
#include "EvaluationTestScenes.h"

#include "vtkBrumeMediumMask.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkPointData.h"

#include <cmath>
#include <cstdlib>
#include <iostream>

namespace
{
int Failures = 0;

void Expect(bool ok, const char* what)
{
  if (!ok)
  {
    std::cerr << "FAILED: " << what << "\n";
    ++Failures;
  }
}

// Pixels of the mask, and whether pixel (x, y) is in it.
long long Count(vtkImageData* mask)
{
  vtkDataArray* a = mask->GetPointData()->GetScalars();
  long long n = 0;
  for (vtkIdType p = 0; p < a->GetNumberOfTuples(); ++p)
  {
    n += a->GetComponent(p, 0) != 0.0;
  }
  return n;
}

bool Inside(vtkImageData* mask, int x, int y)
{
  return mask->GetScalarComponentAsDouble(x, y, 0, 0) != 0.0;
}

// The cube [-0.5, 0.5]^3 seen face-on from `distance` along an axis: its
// near face, at distance - 0.5, is a square of side
// size * (0.5 / (distance - 0.5)) / tan(angle / 2) pixels; only the pixels
// on its edge may go either way.
void ExpectSquare(vtkImageData* mask, int size, double distance, double angle, const char* what)
{
  const double side =
    size * (0.5 / (distance - 0.5)) / std::tan(vtkMath::RadiansFromDegrees(angle / 2));
  const long long n = Count(mask);
  const double edge = 4 * side + 4;
  if (!(std::abs(n - side * side) <= edge))
  {
    std::cerr << "FAILED: " << what << ": " << n << " pixels, expected " << side * side
              << " within " << edge << "\n";
    ++Failures;
  }
  if (!Inside(mask, size / 2, size / 2) || Inside(mask, 0, 0) || Inside(mask, size - 1, size - 1))
  {
    std::cerr << "FAILED: " << what << ": the square is not centred\n";
    ++Failures;
  }
}
}

int TestMediumMask(int, char*[])
{
  const int size = 64;
  auto scene = vtkSmartPointer<vtkPartitionedDataSetCollection>::New();
  const double lower[3] = { -0.5, -0.5, -0.5 }, upper[3] = { 0.5, 0.5, 0.5 };
  AddMedium(scene, "cube of smoke", lower, upper);

  // Brume's default view: from (0, 0, 4), 40 degrees.
  vtkNew<vtkBrumeMediumMask> mask;
  mask->SetInputData(scene);
  mask->SetSize(size, size);
  mask->Update();
  auto* image = mask->GetOutput();
  Expect(image->GetDimensions()[0] == size && image->GetDimensions()[1] == size, "mask size");
  ExpectSquare(image, size, 4, 40, "default view");

  // An explicit camera from the side: the same square.
  vtkNew<vtkCamera> side;
  side->SetPosition(4, 0, 0);
  side->SetFocalPoint(0, 0, 0);
  side->SetViewUp(0, 1, 0);
  side->SetViewAngle(40);
  mask->SetCamera(side);
  mask->Update();
  ExpectSquare(mask->GetOutput(), size, 4, 40, "camera from the side");

  // The scene's own camera, farther away and narrower.
  mask->SetCamera(nullptr);
  const double eye[3] = { 0, 0, 8 }, target[3] = { 0, 0, 0 };
  SetSceneCamera(scene, eye, target, 30);
  mask->Modified();
  mask->Update();
  ExpectSquare(mask->GetOutput(), size, 8, 30, "the scene's camera");

  // A scene without a medium masks nothing.
  auto empty = vtkSmartPointer<vtkPartitionedDataSetCollection>::New();
  const double p0[3] = { -1, -1, 0 }, p1[3] = { 1, -1, 0 }, p2[3] = { 1, 1, 0 },
               p3[3] = { -1, 1, 0 };
  AddQuad(empty, "wall", p0, p1, p2, p3, 1.0);
  mask->SetInputData(empty);
  mask->Update();
  Expect(Count(mask->GetOutput()) == 0, "no medium, no mask");
  return Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
