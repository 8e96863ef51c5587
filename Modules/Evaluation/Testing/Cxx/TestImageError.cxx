// SPDX-License-Identifier: BSD-3-Clause
// vtkBrumeImageError on synthetic images with known errors.
#include "vtkBrumeDataModelNames.h"
#include "vtkBrumeImageError.h"
#include "vtkCallbackCommand.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkUnsignedCharArray.h"

#include <cmath>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <limits>

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

void ExpectNear(double value, double expected, const char* what, double tolerance = 1e-6)
{
  if (!(std::abs(value - expected) <= tolerance))
  {
    std::cerr << "FAILED: " << what << ": " << value << " instead of " << expected << "\n";
    ++Failures;
  }
}

// A w x h radiance image (float or double) whose pixel (x, y) channel c is f(x, y, c).
vtkSmartPointer<vtkImageData> Image(
  int w, int h, const std::function<double(int, int, int)>& f, bool asDouble = false)
{
  vtkSmartPointer<vtkDataArray> radiance;
  if (asDouble)
  {
    radiance = vtkSmartPointer<vtkDoubleArray>::New();
  }
  else
  {
    radiance = vtkSmartPointer<vtkFloatArray>::New();
  }
  radiance->SetName(vtkBrumeNames::Radiance);
  radiance->SetNumberOfComponents(3);
  radiance->SetNumberOfTuples(static_cast<vtkIdType>(w) * h);
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      for (int c = 0; c < 3; ++c)
      {
        radiance->SetComponent(static_cast<vtkIdType>(y) * w + x, c, f(x, y, c));
      }
    }
  }
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(w, h, 1);
  image->GetPointData()->AddArray(radiance);
  return image;
}

vtkSmartPointer<vtkImageData> Mask(int w, int h, const std::function<bool(int, int)>& inside)
{
  vtkNew<vtkUnsignedCharArray> mask;
  mask->SetName(vtkBrumeNames::MediumMask);
  mask->SetNumberOfTuples(static_cast<vtkIdType>(w) * h);
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      mask->SetValue(static_cast<vtkIdType>(y) * w + x, inside(x, y) ? 1 : 0);
    }
  }
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(w, h, 1);
  image->GetPointData()->SetScalars(mask);
  return image;
}

// A varied positive reference: every pixel and channel different.
double Varied(int x, int y, int c)
{
  return 1.0 + 0.5 * std::sin(0.7 * x + 1.3 * y + 2.1 * c);
}

// A constant offset of 10 % of the mean: 0.1 for every measure.
void TestConstantOffset(bool asDouble)
{
  const int w = 32, h = 24; // whole 8 x 8 blocks: the block means average to the mean
  double mean = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c)
        mean += Varied(x, y, c) / (3.0 * w * h);
  const auto reference = Image(w, h, Varied, asDouble);
  const auto image = Image(
    w, h, [&](int x, int y, int c) { return Varied(x, y, c) + 0.1 * mean; }, asDouble);
  vtkNew<vtkBrumeImageError> error;
  Expect(error->Compare(image, reference), "an offset image compares");
  ExpectNear(error->GetRelativeMAE(), 0.1, "relative MAE of a 10 % offset");
  ExpectNear(error->GetRelativeRMSE(), 0.1, "relative RMSE of a 10 % offset");
  ExpectNear(error->GetBlockError(), 0.1, "block error of a 10 % offset");
  Expect(error->GetNumberOfPixels() == w * h, "every pixel compared");
}

// Zero-mean noise finer than the blocks: a per-pixel error, no block error.
void TestCheckerboard()
{
  const int w = 40, h = 16;
  const auto reference = Image(w, h, [](int x, int, int) { return 1.0 + (x / 8) * 0.5; });
  const auto image = Image(
    w, h, [](int x, int y, int) { return 1.0 + (x / 8) * 0.5 + ((x + y) % 2 ? 0.25 : -0.25); });
  vtkNew<vtkBrumeImageError> error;
  Expect(error->Compare(image, reference), "a checkerboard compares");
  Expect(error->GetBlockError() == 0.0, "a checkerboard finer than the blocks has no block error");
  Expect(error->GetRelativeMAE() > 0.1, "a checkerboard has a per-pixel error");
  // The blocks must be finer than the pattern's period for it to vanish.
  error->SetBlockSize(1);
  error->Compare(image, reference);
  ExpectNear(error->GetBlockError(), error->GetRelativeMAE(), "1 x 1 blocks are pixels");
}

// An error on the left half only: the mask picks it out.
void TestMask()
{
  const int w = 32, h = 16;
  const auto reference = Image(w, h, [](int, int, int) { return 2.0; });
  const auto image = Image(w, h, [](int x, int, int) { return x < 16 ? 2.4 : 2.0; });
  vtkNew<vtkBrumeImageError> error;
  Expect(error->Compare(image, reference), "compares without a mask");
  ExpectNear(error->GetRelativeMAE(), 0.1, "half the image 20 % off");
  const auto left = Mask(w, h, [](int x, int) { return x < 16; });
  Expect(error->Compare(image, reference, left), "compares on the left half");
  ExpectNear(error->GetRelativeMAE(), 0.2, "relative MAE on the masked half");
  ExpectNear(error->GetRelativeRMSE(), 0.2, "relative RMSE on the masked half");
  ExpectNear(error->GetBlockError(), 0.2, "block error on the masked half");
  Expect(error->GetNumberOfPixels() == 16 * h, "the masked pixels counted");
  const auto right = Mask(w, h, [](int x, int) { return x >= 16; });
  error->Compare(image, reference, right);
  Expect(error->GetRelativeMAE() == 0.0 && error->GetBlockError() == 0.0, "no error on the right");
  const auto none = Mask(w, h, [](int, int) { return false; });
  error->Compare(image, reference, none);
  Expect(error->GetNumberOfPixels() == 0 && error->GetRelativeMAE() == 0.0, "an empty mask");
}

// Bad input fails with an error, never a crash.
void TestBadInput()
{
  int errors = 0;
  vtkNew<vtkCallbackCommand> count;
  count->SetClientData(&errors);
  count->SetCallback([](vtkObject*, unsigned long, void* n, void*) { ++*static_cast<int*>(n); });
  vtkNew<vtkBrumeImageError> error;
  error->AddObserver(vtkCommand::ErrorEvent, count);
  const auto one = [](int, int, int) { return 1.0; };
  Expect(!error->Compare(Image(16, 16, one), Image(16, 8, one)), "different sizes fail");
  Expect(std::isnan(error->GetRelativeMAE()), "a failed comparison gives NaN");
  vtkNew<vtkImageData> bare;
  bare->SetDimensions(16, 16, 1);
  Expect(!error->Compare(bare, Image(16, 16, one)), "an image without radiance fails");
  Expect(!error->Compare(Image(16, 16, one), nullptr), "no reference fails");
  Expect(!error->Compare(
           Image(16, 16, one), Image(16, 16, one), Mask(8, 8, [](int, int) { return true; })),
    "a mask of another size fails");
  Expect(errors == 4, "each failure reports an error");
  Expect(error->Compare(Image(4, 4, one), Image(4, 4, one)) && error->GetBlockError() == 0.0,
    "an image smaller than a block has no blocks");
}

void TestFinite()
{
  const auto good = Image(8, 8, [](int, int, int) { return 1.0; });
  Expect(vtkBrumeImageError::IsFinite(good), "a finite image");
  const auto nan = Image(8, 8,
    [](int x, int y, int c)
    { return x == 3 && y == 5 && c == 2 ? std::numeric_limits<double>::quiet_NaN() : 1.0; });
  Expect(!vtkBrumeImageError::IsFinite(nan), "a NaN is found");
  const auto inf = Image(
    8, 8, [](int x, int, int) { return x == 7 ? std::numeric_limits<double>::infinity() : 1.0; });
  Expect(!vtkBrumeImageError::IsFinite(inf), "an infinity is found");
  vtkNew<vtkImageData> bare;
  Expect(!vtkBrumeImageError::IsFinite(bare), "no radiance is not finite radiance");
}
}

int TestImageError(int, char*[])
{
  TestConstantOffset(false);
  TestConstantOffset(true);
  TestCheckerboard();
  TestMask();
  TestBadInput();
  TestFinite();
  return Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
