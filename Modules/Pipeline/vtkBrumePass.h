// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumePass
 * @brief   a render pass that lights the renderer's own scene with Brume
 *
 * As VTK's OSPRay pass does for path tracing: set it on a renderer and the
 * renderer's actors, volumes and lights are drawn with Brume's global
 * illumination (the three phases, through vtkBrumePipeline), shown with
 * Brume's display transform (exposure, clamp, sRGB: vtkBrumeDisplayPass).
 *
 * @code
 * vtkNew<vtkBrumePass> brume;
 * renderer->SetPass(brume);   // the program is otherwise unchanged
 * window->Render();
 * @endcode
 *
 * - What the scene is made of: vtkBrumeRendererScene (GetScene(): its
 *   LightScale and Albedo). Props it does not translate (translucent
 *   actors, 2D actors, other props) are drawn by VTK as usual, in the same
 *   frame, against Brume's depth.
 * - What is redone: the particles are traced and the textures rebuilt only
 *   when the scene changed (a prop, its data, a property, a volume
 *   property, a scene light, props added or removed); a camera move only
 *   updates the view-dependent textures (glossy surfaces, anisotropic
 *   media). GetNumberOfTraces() and GetNumberOfViewUpdates() count them;
 *   the reconstruction's own counters (GetPipeline()->GetReconstruction())
 *   count the textures built and updated.
 * - The phases' settings: GetPipeline() (particles, seed, threshold,
 *   exposure...). The renderer's active camera is the pipeline's.
 * - A failed phase leaves the frame black and says why (vtkErrorMacro).
 *
 * Not yet: progressive refinement across frames, scalar colouring and
 * textures of surfaces (a surface has its property's colour).
 *
 * @sa vtkBrumePipeline vtkBrumeRendererScene vtkBrumeDisplayPass
 */
#ifndef vtkBrumePass_h
#define vtkBrumePass_h

#include "vtkBrumePipelineModule.h" // For export macro
#include "vtkRenderPass.h"

class vtkBrumePipeline;
class vtkBrumeRendererScene;

class VTKBRUMEPIPELINE_EXPORT vtkBrumePass : public vtkRenderPass
{
public:
  static vtkBrumePass* New();
  vtkTypeMacro(vtkBrumePass, vtkRenderPass);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  void Render(const vtkRenderState* s) override;
  void ReleaseGraphicsResources(vtkWindow* w) override;

  /// The phases and their settings (the camera is the renderer's).
  vtkBrumePipeline* GetPipeline();

  /// How the renderer's scene becomes Brume's (LightScale, Albedo).
  vtkBrumeRendererScene* GetScene();

  ///@{
  /**
   * How many times the particles were traced (once, then once per edit of
   * the scene), and how many frames updated the textures toward a new eye
   * position without tracing (a camera orbit of N frames: N).
   */
  vtkGetMacro(NumberOfTraces, int);
  vtkGetMacro(NumberOfViewUpdates, int);
  ///@}

protected:
  vtkBrumePass();
  ~vtkBrumePass() override;

  int NumberOfTraces = 0;
  int NumberOfViewUpdates = 0;

private:
  vtkBrumePass(const vtkBrumePass&) = delete;
  void operator=(const vtkBrumePass&) = delete;

  bool Prepare(vtkRenderer* renderer);

  struct vtkInternals;
  vtkInternals* Internals;
};

#endif
