// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeImageError
 * @brief   relative errors of a radiance image against a reference
 *
 * Both images are Brume float images: point array `Radiance` (3 components,
 * linear RGB, one point per pixel), as vtkBrumeReferencePathTracer,
 * vtkBrumeFloatImageCapture and vtkBrumeTimedPipeline make them, of the same
 * dimensions. With a = the image, r = the reference, sums over the compared
 * pixels p and the channels c (n = 3 x the number of compared pixels):
 *
 * - relative MAE = sum |a - r| / sum |r|;
 * - relative RMSE = sqrt(sum (a - r)^2 / n) / (sum |r| / n);
 * - block error = the relative MAE of BlockSize x BlockSize block means:
 *   the image is cropped to whole blocks (from pixel (0, 0)), each block's
 *   mean is taken per channel, and the error is
 *   sum over blocks and channels of |mean_a - mean_r| / sum |mean_r|.
 *   Averaging a block removes most of the Monte Carlo noise and keeps the
 *   bias; with BlockSize 8 it is the "block error" of
 *   ../shared/tools/image-error.py.
 *
 * A mask (a vtkImageData of the same dimensions; its point scalars, or its
 * first point array, non-zero where a pixel counts) restricts every sum to
 * its pixels; a block's means are then over its masked pixels, and blocks
 * without any are left out. With no compared pixel the errors are 0; with a
 * black reference (sum |r| = 0) they are 0 if the image is black too,
 * infinite otherwise.
 *
 * @code
 * vtkNew<vtkBrumeImageError> error;
 * if (error->Compare(image, reference, mediumMask))
 * {
 *   std::cout << error->GetRelativeMAE() << " " << error->GetBlockError() << "\n";
 * }
 * @endcode
 *
 * @sa vtkBrumeMediumMask vtkBrumeErrorChart
 */
#ifndef vtkBrumeImageError_h
#define vtkBrumeImageError_h

#include "vtkBrumeEvaluationModule.h" // For export macro
#include "vtkObject.h"

class vtkImageData;

class VTKBRUMEEVALUATION_EXPORT vtkBrumeImageError : public vtkObject
{
public:
  static vtkBrumeImageError* New();
  vtkTypeMacro(vtkBrumeImageError, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Side of the blocks of the block error, in pixels (default 8, at least 1).
  vtkSetClampMacro(BlockSize, int, 1, VTK_INT_MAX);
  vtkGetMacro(BlockSize, int);
  ///@}

  /**
   * Measures `image` against `reference` over the pixels where `mask` is
   * non-zero (every pixel without a mask). False, with an error saying
   * what is wrong, when an image lacks a 3-component `Radiance` point array
   * or the dimensions differ; the errors are then NaN.
   */
  bool Compare(vtkImageData* image, vtkImageData* reference, vtkImageData* mask = nullptr);

  ///@{
  /// The errors of the last Compare().
  vtkGetMacro(RelativeMAE, double);
  vtkGetMacro(RelativeRMSE, double);
  vtkGetMacro(BlockError, double);
  ///@}

  /// Pixels compared by the last Compare() (the mask's non-zero pixels).
  vtkGetMacro(NumberOfPixels, vtkIdType);

  /// True when `image` has a `Radiance` point array with only finite values.
  static bool IsFinite(vtkImageData* image);

protected:
  vtkBrumeImageError();
  ~vtkBrumeImageError() override;

  int BlockSize = 8;
  double RelativeMAE;
  double RelativeRMSE;
  double BlockError;
  vtkIdType NumberOfPixels = 0;

private:
  vtkBrumeImageError(const vtkBrumeImageError&) = delete;
  void operator=(const vtkBrumeImageError&) = delete;
};

#endif
