// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeFloatImageCapture
 * @brief   renders a renderer into a float framebuffer and reads it back
 *
 * Installs on a renderer a vtkFramebufferPass with a 32-bit float colour
 * buffer around the standard render steps, so that radiance above 1 is kept,
 * and after a render reads the linear RGB radiance back into a vtkImageData
 * (point data `Radiance`, float[3], one point per pixel, row 0 at the
 * bottom). No tone mapping is applied.
 *
 * @code
 * vtkNew<vtkBrumeFloatImageCapture> capture;
 * capture->Attach(renderer);
 * renderWindow->Render();
 * vtkSmartPointer<vtkImageData> radiance = capture->Capture();
 * @endcode
 */
#ifndef vtkBrumeFloatImageCapture_h
#define vtkBrumeFloatImageCapture_h

#include "vtkBrumeRenderingOpenGL2Module.h" // For export macro
#include "vtkObject.h"
#include "vtkSmartPointer.h" // For return value

#include <functional> // For Read

class vtkFramebufferPass;
class vtkImageData;
class vtkRenderer;

class VTKBRUMERENDERINGOPENGL2_EXPORT vtkBrumeFloatImageCapture : public vtkObject
{
public:
  static vtkBrumeFloatImageCapture* New();
  vtkTypeMacro(vtkBrumeFloatImageCapture, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Makes `renderer` draw into a float framebuffer.
  void Attach(vtkRenderer* renderer);

  /// The last frame's radiance, or nullptr (with an error) before a render.
  vtkSmartPointer<vtkImageData> Capture();

  /**
   * Pixel areas, as a path tracer integrates them: the mean of k^2 frames of
   * the attached renderer's window, its active camera's projection shifted
   * in each by a sub-pixel offset (vtkCamera::SetWindowCenter) on a rotated
   * grid, k^2 distinct offsets along each axis (a regular k x k grid has k:
   * an edge along an axis then covers a pixel in steps of 1/k, not 1/k^2).
   * The camera's window centre is restored. k = 1 renders nothing and is
   * Capture(): the last frame, at the pixels' centres. Null (with an
   * error) if a frame cannot be read.
   */
  vtkSmartPointer<vtkImageData> CaptureSupersampled(int k);

  /**
   * Brume's display transform of a radiance image (point array `Radiance`):
   * multiply by `exposure`, clamp to [0, 1], apply the sRGB transfer curve,
   * quantize to 8 bits. Returns an unsigned char RGB image of the same size.
   */
  static vtkSmartPointer<vtkImageData> ToneMap(vtkImageData* radiance, double exposure);

protected:
  vtkBrumeFloatImageCapture();
  ~vtkBrumeFloatImageCapture() override;

  // Reads the last frame's float buffer: `use(data, components)` with
  // size[0] x size[1] pixels of `components` floats, row 0 at the bottom.
  bool Read(int size[2], const std::function<void(const float*, int)>& use);

  vtkSmartPointer<vtkFramebufferPass> Pass;
  vtkRenderer* Renderer = nullptr;

private:
  vtkBrumeFloatImageCapture(const vtkBrumeFloatImageCapture&) = delete;
  void operator=(const vtkBrumeFloatImageCapture&) = delete;
};

#endif
