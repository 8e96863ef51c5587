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
 * - Progressive (on by default): after a change, the first frame shows
 *   a small step of the budget (NumberOfParticles; the first step at most
 *   FirstStepParticles), and each later Render() traces three times as
 *   many particles as the textures hold (the count grows fourfold) until
 *   the budget is reached: IsConverged() says when, and a
 *   vtkCommand::ProgressEvent
 *   (call data: a double, the fraction of the budget traced) follows each
 *   step. Each step's textures are bitwise those of one run of its count
 *   at the same texture resolutions (chosen once per change for the budget,
 *   vtkBrumeRadianceReconstruction::SetPlannedParticles) when the budget
 *   is the first step's count times a power of four (10^6 is 15625 x 4^3),
 *   otherwise to float rounding at the last step. The frames before the
 *   last draw the media with one extinction sample a slab, a quicker draw
 *   (vtkBrumeSliceVolumeMapper::SetSlabSampling); the converged frame with
 *   their full count. Keep rendering while !IsConverged() (a timer in an
 *   interactive program).
 * - The phases' other settings: GetPipeline() (seed, threshold,
 *   exposure...). The renderer's active camera is the pipeline's.
 * - A failed phase leaves the frame black and says why (vtkErrorMacro).
 *
 * Surfaces coloured by scalars (the mapper's ScalarVisibility, its lookup
 * table and scalar range, point or cell scalars) have those colours as
 * their reflectance, per vertex or per cell (vtkBrumeRendererScene). Textures of
 * actors are not read.
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
  /// The particles traced per change of the scene (default 10^6, at least 1).
  vtkSetClampMacro(NumberOfParticles, vtkTypeInt64, 1, VTK_TYPE_INT64_MAX);
  vtkGetMacro(NumberOfParticles, vtkTypeInt64);
  ///@}

  ///@{
  /// Progressive refinement across frames (default on); off, each change
  /// traces the whole budget before its first frame.
  vtkSetMacro(Progressive, bool);
  vtkGetMacro(Progressive, bool);
  vtkBooleanMacro(Progressive, bool);
  ///@}

  ///@{
  /**
   * The first step's particles at most (default 2^17 = 131072: about 0.05 s
   * of tracing for the default scene on two cores). The first step is the
   * budget divided by 4 until it is no more than this.
   */
  vtkSetClampMacro(FirstStepParticles, vtkTypeInt64, 1, VTK_TYPE_INT64_MAX);
  vtkGetMacro(FirstStepParticles, vtkTypeInt64);
  ///@}

  ///@{
  /**
   * Preview an edit of a medium's transfer functions (default off; with
   * Progressive only). On, the first frame after an edit that changes only
   * what the slice mappers classify (a volume property's scalar opacity or
   * colour, the scene's albedo of a classified medium) draws the light of
   * the last trace under the new functions, which the GPU applies to the
   * scalars it holds: nothing is traced and no texture is built, so the
   * frame costs a draw. The next Render() traces the edited scene, and the
   * frames after it are those of Progressive, bitwise. The preview is not
   * the edited scene's light: where the edit makes the medium denser or
   * thinner, its shadows and glow are those of the old one until the trace.
   * An edit the mappers cannot show so (the scene's objects, their data, a
   * function that gives an extinction where the old one left bricks out)
   * is traced at once. IsConverged() is false while a trace is pending;
   * GetNumberOfPreviews() counts the previews drawn.
   */
  vtkSetMacro(PreviewEdits, bool);
  vtkGetMacro(PreviewEdits, bool);
  vtkBooleanMacro(PreviewEdits, bool);
  vtkGetMacro(NumberOfPreviews, int);
  ///@}

  ///@{
  /**
   * The image sample distance of a preview's media (default 2: drawn at
   * half the window's resolution and scaled up, as VTK's volume mappers
   * draw while the camera moves; vtkBrumeSliceVolumeMapper::
   * SetImageSampleDistance). The frames after it are drawn at the distance
   * the pipeline's actors had (vtkBrumeSceneActors).
   */
  vtkSetClampMacro(PreviewImageSampleDistance, double, 1.0, 16.0);
  vtkGetMacro(PreviewImageSampleDistance, double);
  ///@}

  ///@{
  /**
   * The factor on the distance between a preview's slices (default 2:
   * about half the slices, each slab twice as thick;
   * vtkBrumeSliceVolumeMapper::SetSliceSpacingScale), as VTK's volume
   * mappers sample farther apart while the camera moves. A structure
   * thinner than a slab may flicker in the preview. The frames after it
   * are drawn at the actors' own spacing.
   */
  vtkSetClampMacro(PreviewSliceSpacingScale, double, 1.0, 16.0);
  vtkGetMacro(PreviewSliceSpacingScale, double);
  ///@}

  ///@{
  /**
   * Whether each process holds only a part of the renderer's scene
   * (default off: under mpirun every process holds all of it), as in
   * ParaView's parallel views. On, with the pipeline's controller holding
   * several processes (vtkBrumePipeline::SetController), every process
   * gathers the others' parts and traces its share of the particles of the
   * whole scene; every process draws all that Brume lights (the same
   * image: a parallel compositing keeps of each process's image the region
   * of its own piece), and the props Brume does not light, for a
   * compositing by depth to put together (vtkBrumeDisplayPass writes the
   * depth). Each change then traces its
   * whole budget at once (no progressive steps). Collective: every process
   * renders in step.
   */
  vtkSetMacro(DistributedScene, bool);
  vtkGetMacro(DistributedScene, bool);
  vtkBooleanMacro(DistributedScene, bool);
  ///@}

  /// True when the textures hold the whole budget of the current scene.
  bool IsConverged();
  /// Whether more steps would add particles: the last trace succeeded and
  /// the budget is not reached (false after a failure, unlike
  /// !IsConverged(): a program that renders until converged stops there).
  bool IsRefining();

  ///@{
  /**
   * How many times tracing started anew (once, then once per edit of the
   * scene), how many progressive steps added particles to a trace, how
   * many times the textures were reconstructed (traces and steps), and how
   * many frames updated the textures toward a new eye position (a camera
   * orbit of N frames: N).
   */
  vtkGetMacro(NumberOfTraces, int);
  vtkGetMacro(NumberOfSteps, int);
  int GetNumberOfReconstructions() { return this->NumberOfTraces + this->NumberOfSteps; }
  vtkGetMacro(NumberOfViewUpdates, int);
  ///@}

protected:
  vtkBrumePass();
  ~vtkBrumePass() override;

  vtkTypeInt64 NumberOfParticles = 1000000;
  bool Progressive = true;
  bool DistributedScene = false;
  bool PreviewEdits = false;
  int NumberOfPreviews = 0;
  double PreviewImageSampleDistance = 2.0;
  double PreviewSliceSpacingScale = 2.0;
  vtkTypeInt64 FirstStepParticles = 131072;
  int NumberOfTraces = 0;
  int NumberOfSteps = 0;
  int NumberOfViewUpdates = 0;

private:
  vtkBrumePass(const vtkBrumePass&) = delete;
  void operator=(const vtkBrumePass&) = delete;

  bool Prepare(vtkRenderer* renderer);
  bool Trace(bool built); // `built`: whether the scene was made
  /// DistributedScene, over several processes.
  bool Gathers();
  bool Step();
  /// Sets the media's mappers to the scene's new functions (PreviewEdits);
  /// false when it cannot show the edit.
  bool Preview();
  void ReportProgress();

  struct vtkInternals;
  vtkInternals* Internals;
};

#endif
