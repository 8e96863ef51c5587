// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumePVRenderView
 * @brief   ParaView's render view with Brume's global illumination
 *
 * The "Brume Render View" of the plugin: a render view (everything
 * ParaView's render view does) whose scene is drawn by vtkBrumePass.
 * Whatever is shown in it — surfaces in a solid colour or coloured by an
 * array through its colour map, volumes with their colour map and opacity
 * function, the lights of the Light Inspector and the light kit, the
 * view's camera — is lit by Brume, with no Brume filter in the pipeline.
 * Outlines, points, lines, text and widgets are drawn by ParaView over
 * Brume's depth.
 *
 * The particles are traced again only when something shown changes; a
 * camera move only updates the view-dependent textures. Progressive (by
 * default in the GUI's window only, so that a script's screenshot holds
 * the whole budget): each render multiplies the particles by 4 until
 * IsConverged(), and the GUI renders again by itself until then.
 *
 * Client–server: where ParaView renders on the server (remote rendering,
 * which a volume asks for), the server's view traces and draws; the
 * client tells it, before each such render, whether to refine (the GUI's
 * window is the client's), and the server's root tells the client, after
 * it, what it traced, so that the counters, IsConverged() and
 * IsRefining() the client reports (and the GUI's renders that refine)
 * are the server's. Where ParaView renders on the client, the client's
 * view does both.
 *
 * Over several processes (mpirun pvserver or pvbatch), each holding a
 * piece of the data: the pass gathers the pieces (vtkBrumePass::
 * SetDistributedScene), the processes share the particles, and each draws
 * all that Brume lights; the view composites the processes' images by
 * depth, not in ParaView's order of the pieces (which would blend the same
 * media once per process), and does not refine progressively.
 *
 * @sa vtkBrumePass vtkBrumeRendererScene
 */
#ifndef vtkBrumePVRenderView_h
#define vtkBrumePVRenderView_h

#include "vtkBrumeParaViewRepresentationModule.h" // For export macro
#include "vtkNew.h"                               // For Pass
#include "vtkPVRenderView.h"

class vtkBrumePass;

class VTKBRUMEPARAVIEWREPRESENTATION_EXPORT vtkBrumePVRenderView : public vtkPVRenderView
{
public:
  static vtkBrumePVRenderView* New();
  vtkTypeMacro(vtkBrumePVRenderView, vtkPVRenderView);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The view's settings, forwarded to its vtkBrumePass and pipeline.
  void SetNumberOfParticles(vtkIdType particles);
  vtkIdType GetNumberOfParticles();
  void SetSeed(vtkIdType seed);
  void SetExposure(double exposure);
  /// 0 off, 1 on, 2 (the default) on in the GUI's window, off elsewhere.
  void SetProgressive(int mode);
  /// Previews of transfer-function edits while progressive (vtkBrumePass::SetPreviewEdits).
  void SetPreviewEdits(int preview);
  /// How much farther apart a preview's slices lie than a traced frame's
  /// (vtkBrumePass::SetPreviewSliceSpacingScale; 2 by default).
  void SetPreviewSliceSpacingScale(double scale);
  double GetPreviewSliceSpacingScale();
  /// The optical depth a volume's 16-bit copy on the GPU may be off by
  /// (vtkBrumeSceneActors::SetExtinctionDepthTolerance on the pass's props;
  /// 10^-3 by default, 0 keeps floats exactly).
  void SetExtinctionDepthTolerance(double tolerance);
  double GetExtinctionDepthTolerance();
  void SetVolumeAlbedo(double r, double g, double b);
  void SetPhysicalLights(int physical);
  void SetLightIntensityScale(double scale);
  ///@}

  /// FXAA stays off: it would smear Brume's image (and under mpirun
  /// ParaView applies it after compositing).
  void SetUseFXAA(bool) override;

#ifndef __VTK_WRAP__
  /// The pass that draws the view (its pipeline, its scene).
  vtkBrumePass* GetBrumePass();
#endif

  /// True when the textures hold the whole budget of what is shown.
  bool IsConverged();
  /// Whether renders refine step by step (SetProgressive()).
  bool RendersProgressively();
  /// Whether the next render would add particles (progressive, the last
  /// trace succeeded, the budget not reached): the GUI renders again then.
  bool IsRefining();

  ///@{
  /// The pass's counters (vtkBrumePass): traces, progressive steps,
  /// renders whose camera had moved, and previews of edits.
  int GetNumberOfTraces();
  int GetNumberOfSteps();
  int GetNumberOfViewUpdates();
  int GetNumberOfPreviews();
  ///@}

  /// Whether the server drew the last render (client–server with remote
  /// rendering): the counters and states above are then the server's.
  bool GetLastRenderOnServer()
  {
    return this->LastRenderOnServer;
  }

protected:
  vtkBrumePVRenderView();
  ~vtkBrumePVRenderView() override;
  void Render(bool interactive, bool skipRendering) override;
  /// Over several processes: no ordered compositing (every process draws
  /// all that Brume lights; see Update()).
  void Update() override;

private:
  vtkBrumePVRenderView(const vtkBrumePVRenderView&) = delete;
  void operator=(const vtkBrumePVRenderView&) = delete;

  /// Before a render drawn on a server for a client: whether it refines,
  /// as the client decided (on the client: its own decision, sent).
  bool ShareProgressive(bool progressive);
  /// After it: the server's root sends what it traced; the client keeps it.
  void ShareServerState();

  vtkNew<vtkBrumePass> Pass;
  int ProgressiveMode = 2;
  /// The server's pass, as its root last reported it (client side).
  struct PassState
  {
    int Traces = 0;
    int Steps = 0;
    int ViewUpdates = 0;
    int Converged = 1;
    int Refining = 0;
    int Previews = 0;
  };
  PassState ServerState;
  bool LastRenderOnServer = false;
};

#endif
