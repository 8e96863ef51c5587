// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBrumeImageError.h"

#include "vtkBrumeDataModelNames.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"

#include <cmath>
#include <limits>
#include <vector>

vtkStandardNewMacro(vtkBrumeImageError);

namespace
{
constexpr double NaN = std::numeric_limits<double>::quiet_NaN();

// sum |a - r|, sum (a - r)^2, sum |r| and the count of the compared values.
struct Sums
{
  double Abs = 0, Square = 0, Reference = 0;
  long long Count = 0;
};

// |a - r| summed against |r|: 0 when both sums vanish, infinite when only
// the reference's does.
double Relative(double difference, double reference)
{
  if (reference > 0)
  {
    return difference / reference;
  }
  return difference > 0 ? std::numeric_limits<double>::infinity() : 0.0;
}

// Per-pixel sums over the masked pixels; the difference is taken in the
// images' own precision, as the chart always did.
template <typename T>
Sums PixelSums(const T* a, const T* r, const std::vector<char>& mask, vtkIdType pixels)
{
  Sums s;
  for (vtkIdType p = 0; p < pixels; ++p)
  {
    if (!mask.empty() && !mask[p])
    {
      continue;
    }
    for (int c = 0; c < 3; ++c)
    {
      const double d = a[3 * p + c] - r[3 * p + c];
      s.Abs += std::abs(d);
      s.Square += d * d;
      s.Reference += std::abs(r[3 * p + c]);
      ++s.Count;
    }
  }
  return s;
}

// Relative MAE of k x k block means (blocks of the image cropped to whole
// blocks; means over a block's masked pixels; empty blocks left out).
template <typename T>
double BlockError(
  const T* a, const T* r, const std::vector<char>& mask, int width, int height, int k)
{
  double difference = 0, reference = 0;
  for (int by = 0; by < height / k; ++by)
  {
    for (int bx = 0; bx < width / k; ++bx)
    {
      double sumA[3] = { 0, 0, 0 }, sumR[3] = { 0, 0, 0 };
      int count = 0;
      for (int j = 0; j < k; ++j)
      {
        for (int i = 0; i < k; ++i)
        {
          const vtkIdType p = static_cast<vtkIdType>(by * k + j) * width + bx * k + i;
          if (!mask.empty() && !mask[p])
          {
            continue;
          }
          ++count;
          for (int c = 0; c < 3; ++c)
          {
            sumA[c] += a[3 * p + c];
            sumR[c] += r[3 * p + c];
          }
        }
      }
      for (int c = 0; count > 0 && c < 3; ++c)
      {
        difference += std::abs(sumA[c] - sumR[c]) / count;
        reference += std::abs(sumR[c]) / count;
      }
    }
  }
  return Relative(difference, reference);
}

vtkDataArray* Radiance(vtkImageData* image)
{
  vtkDataArray* a = image ? image->GetPointData()->GetArray(vtkBrumeNames::Radiance) : nullptr;
  return a && a->GetNumberOfComponents() == 3 ? a : nullptr;
}

// The radiance as doubles, for images that are not both float.
vtkSmartPointer<vtkDoubleArray> AsDouble(vtkDataArray* a)
{
  auto d = vtkSmartPointer<vtkDoubleArray>::New();
  d->DeepCopy(a);
  return d;
}
}

vtkBrumeImageError::vtkBrumeImageError()
  : RelativeMAE(NaN)
  , RelativeRMSE(NaN)
  , BlockError(NaN)
{
}

vtkBrumeImageError::~vtkBrumeImageError() = default;

bool vtkBrumeImageError::Compare(vtkImageData* image, vtkImageData* reference, vtkImageData* mask)
{
  this->RelativeMAE = this->RelativeRMSE = this->BlockError = NaN;
  this->NumberOfPixels = 0;
  vtkDataArray* a = Radiance(image);
  vtkDataArray* r = Radiance(reference);
  if (!a || !r)
  {
    vtkErrorMacro(<< (a ? "The reference" : "The image")
                  << " has no 3-component point array 'Radiance' (a Brume float image).");
    return false;
  }
  int dims[3], refDims[3];
  image->GetDimensions(dims);
  reference->GetDimensions(refDims);
  if (dims[0] != refDims[0] || dims[1] != refDims[1] || dims[2] != refDims[2] || dims[2] != 1)
  {
    vtkErrorMacro("The image (" << dims[0] << " x " << dims[1] << " x " << dims[2]
                                << ") and the reference (" << refDims[0] << " x " << refDims[1]
                                << " x " << refDims[2] << ") must be 2-D images of the same size.");
    return false;
  }
  const vtkIdType pixels = static_cast<vtkIdType>(dims[0]) * dims[1];
  if (a->GetNumberOfTuples() != pixels || r->GetNumberOfTuples() != pixels)
  {
    vtkErrorMacro("The 'Radiance' arrays must hold one tuple per pixel (" << pixels << ").");
    return false;
  }
  std::vector<char> selected;
  if (mask)
  {
    int maskDims[3];
    mask->GetDimensions(maskDims);
    vtkDataArray* m = mask->GetPointData()->GetScalars();
    m = m ? m : mask->GetPointData()->GetArray(0);
    if (maskDims[0] != dims[0] || maskDims[1] != dims[1] || maskDims[2] != 1 || !m ||
      m->GetNumberOfTuples() != pixels)
    {
      vtkErrorMacro(
        "The mask must be a " << dims[0] << " x " << dims[1] << " image with a point array.");
      return false;
    }
    selected.resize(pixels);
    for (vtkIdType p = 0; p < pixels; ++p)
    {
      selected[p] = m->GetComponent(p, 0) != 0.0;
    }
  }

  Sums s;
  auto* fa = vtkFloatArray::SafeDownCast(a);
  auto* fr = vtkFloatArray::SafeDownCast(r);
  if (fa && fr)
  {
    s = PixelSums(fa->GetPointer(0), fr->GetPointer(0), selected, pixels);
    this->BlockError = ::BlockError(
      fa->GetPointer(0), fr->GetPointer(0), selected, dims[0], dims[1], this->BlockSize);
  }
  else
  {
    const auto da = AsDouble(a), dr = AsDouble(r);
    s = PixelSums(da->GetPointer(0), dr->GetPointer(0), selected, pixels);
    this->BlockError = ::BlockError(
      da->GetPointer(0), dr->GetPointer(0), selected, dims[0], dims[1], this->BlockSize);
  }
  this->NumberOfPixels = s.Count / 3;
  if (s.Count == 0)
  {
    this->RelativeMAE = this->RelativeRMSE = this->BlockError = 0.0;
    return true;
  }
  this->RelativeMAE = Relative(s.Abs, s.Reference);
  this->RelativeRMSE = Relative(std::sqrt(s.Square / s.Count), s.Reference / s.Count);
  return true;
}

bool vtkBrumeImageError::IsFinite(vtkImageData* image)
{
  vtkDataArray* a = image ? image->GetPointData()->GetArray(vtkBrumeNames::Radiance) : nullptr;
  if (!a)
  {
    return false;
  }
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < a->GetNumberOfComponents(); ++c)
    {
      if (!std::isfinite(a->GetComponent(i, c)))
      {
        return false;
      }
    }
  }
  return true;
}

void vtkBrumeImageError::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "BlockSize: " << this->BlockSize << "\n";
  os << indent << "RelativeMAE: " << this->RelativeMAE << "\n";
  os << indent << "RelativeRMSE: " << this->RelativeRMSE << "\n";
  os << indent << "BlockError: " << this->BlockError << "\n";
  os << indent << "NumberOfPixels: " << this->NumberOfPixels << "\n";
}
