// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeDisplayPass
 * @brief   shows radiance on screen with Brume's display transform
 *
 * A render pass that draws its delegate (by default the standard render
 * steps) into a 32-bit float framebuffer, then shows it with the transform
 * `brume render` applies to PNG files (vtkBrumeFloatImageCapture::ToneMap):
 * multiply by Exposure, clamp to [0, 1], apply the sRGB transfer curve. An
 * interactive window then looks like the images Brume writes. The
 * renderer's background (and gradient) keeps the colours it was given: it
 * is drawn as the radiance the transform shows as them. The alpha channel
 * is the delegate's (the background's alpha where nothing is drawn, the
 * opacity of what is): a ParaView server that draws on a transparent black
 * for its client to composite over the client's background, or a
 * screenshot with a transparent background, gets what the scene covers.
 * The depth is the delegate's too, written to the window (ParaView's
 * parallel compositing reads it), but where something is drawn at the far
 * plane (a medium over the empty sky): there just before it, as a parallel
 * compositing by depth counts the far plane as empty.
 *
 * @code
 * vtkNew<vtkBrumeDisplayPass> display;
 * display->SetExposure(1.5);
 * renderer->SetPass(display);
 * @endcode
 */
#ifndef vtkBrumeDisplayPass_h
#define vtkBrumeDisplayPass_h

#include "vtkBrumeRenderingOpenGL2Module.h" // For export macro
#include "vtkImageProcessingPass.h"

#include <memory> // For the internals

class VTKBRUMERENDERINGOPENGL2_EXPORT vtkBrumeDisplayPass : public vtkImageProcessingPass
{
public:
  static vtkBrumeDisplayPass* New();
  vtkTypeMacro(vtkBrumeDisplayPass, vtkImageProcessingPass);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Multiplier of the radiance before clamping (default 1, non-negative).
  vtkSetClampMacro(Exposure, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(Exposure, double);
  ///@}

  void Render(const vtkRenderState* s) override;
  void ReleaseGraphicsResources(vtkWindow* w) override;

protected:
  vtkBrumeDisplayPass();
  ~vtkBrumeDisplayPass() override;

  double Exposure = 1.0;

private:
  struct Internals;
  std::unique_ptr<Internals> Impl;

  vtkBrumeDisplayPass(const vtkBrumeDisplayPass&) = delete;
  void operator=(const vtkBrumeDisplayPass&) = delete;
};

#endif
