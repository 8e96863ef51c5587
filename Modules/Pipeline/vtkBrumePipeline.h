// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumePipeline
 * @brief   the three phases as one object: scene to image
 *
 * Wires a Brume scene (vtkBrumeSceneReader, vtkBrumeDefaultSceneSource or
 * any scene collection) through the light tracer (phase 1), the radiance
 * reconstruction (phase 2) and the scene actors (phase 3), as `brume
 * render`, `brume view`, `brume bench` and vtkBrumeTimedPipeline use it:
 *
 * @code
 * vtkNew<vtkBrumeSceneReader> reader;
 * reader->SetFileName("god-rays.json");
 * vtkNew<vtkBrumePipeline> pipeline;
 * pipeline->SetInputConnection(reader->GetOutputPort());
 * pipeline->UpdateScene();
 * pipeline->ApplySceneSettings();             // the file's render settings and camera
 * pipeline->GetTracer()->SetNumberOfParticles(2000000);
 * pipeline->Update();                          // phases 1 and 2
 * vtkSmartPointer<vtkImageData> image = pipeline->RenderImage(); // phase 3, off screen
 * @endcode
 *
 * Every setting of a phase is the phase's own, set on the filter that owns
 * it and defaulted there once: GetTracer() (particles, seed, depth, aiming,
 * memory limit), GetReconstruction() (threshold, direct light, directional
 * media, fixed view), GetActors() (slice spacing, sample distance). What
 * belongs to the pipeline itself is here: the image's Size and Exposure,
 * BatchSize, Progressive, the camera.
 *
 * Under an MPI launcher (vtkBrumeProcesses) every process traces its share
 * of the particles, the reconstruction sums the histograms across them,
 * and any process failing stops all at the next agreement; only process 0
 * should render.
 */
#ifndef vtkBrumePipeline_h
#define vtkBrumePipeline_h

#include "vtkBrumePipelineModule.h" // For export macro
#include "vtkNew.h"                 // For members
#include "vtkObject.h"
#include "vtkSmartPointer.h" // For members and return values

class vtkAlgorithm;
class vtkAlgorithmOutput;
class vtkBrumeFloatImageCapture;
class vtkBrumeLightTracer;
class vtkBrumeRadianceReconstruction;
class vtkMultiProcessController;
class vtkBrumeSceneActors;
class vtkCamera;
class vtkDataObject;
class vtkImageData;
class vtkPartitionedDataSetCollection;
class vtkRenderWindow;
class vtkRenderer;
class vtkTrivialProducer;

class VTKBRUMEPIPELINE_EXPORT vtkBrumePipeline : public vtkObject
{
public:
  static vtkBrumePipeline* New();
  vtkTypeMacro(vtkBrumePipeline, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The scene: a Brume scene collection (the output of vtkBrumeSceneReader,
  /// vtkBrumeDefaultSceneSource, vtkBrumeVolumePropertyMedium's scenes...).
  void SetInputConnection(vtkAlgorithmOutput* scene);
  void SetInputData(vtkDataObject* scene);
  vtkAlgorithmOutput* GetInputConnection();
  ///@}

  /**
   * Brings the scene up to date; false when it cannot be produced (its
   * source said why). Update() does it too; call it first to report a bad
   * scene before anything else, or to read the scene's settings.
   */
  bool UpdateScene();

  /// The scene, once UpdateScene() or Update() produced it (else null).
  vtkDataObject* GetScene();

  /**
   * Takes the scene's render settings where it has them (a scene file's
   * `render` block: particles, seed, threshold, size, exposure) into the
   * tracer, the reconstruction and this pipeline, and its camera
   * (vtkBrumeSceneCamera) into GetCamera(). Call it after UpdateScene() and
   * before setting what the user chose, which then takes precedence; false
   * when the scene cannot be produced.
   */
  bool ApplySceneSettings();

  ///@{
  /// The phases, owned by the pipeline; their settings are set on them.
  vtkBrumeLightTracer* GetTracer();
  vtkBrumeRadianceReconstruction* GetReconstruction();
  vtkBrumeSceneActors* GetActors();
  ///@}

  /**
   * The processes that share the particles and sum the histograms (VTK's
   * global controller by default: under mpirun every process holds the
   * same scene). Null: this process alone, with its own scene (a
   * ParaView Brume Render View, whose processes each hold a part of the
   * data). Also the reconstruction's controller.
   */
  void SetController(vtkMultiProcessController* controller);
  vtkMultiProcessController* GetController();

  ///@{
  /**
   * The camera the textures radiate toward and the image is seen from. The
   * first Update() sets it to the scene's own camera (vtkBrumeSceneCamera),
   * unless one was set, this one was moved (GetCamera()->SetPosition...) or
   * ApplySceneSettings() took the scene's before.
   */
  void SetCamera(vtkCamera* camera);
  vtkCamera* GetCamera();
  ///@}

  ///@{
  /**
   * The time of a scene that changes over time (a scene file whose media
   * list a file per time step, or any source announcing VTK's TIME_STEPS):
   * every phase is brought up to date at this time, and a source reads the
   * step it covers. Unset (the default), the source chooses (a scene file:
   * its first step). GetNumberOfTimeSteps() and GetTimeStep() list the
   * source's steps once UpdateScene() ran (none: the scene does not change).
   */
  void SetTime(double time);
  double GetTime() { return this->Time; }
  bool GetTimeSet() { return this->TimeSet; }
  int GetNumberOfTimeSteps();
  double GetTimeStep(int step);
  ///@}

  ///@{
  /// The image's size in pixels (default 512 x 512, each in [1, 16384]).
  vtkSetVector2Macro(Size, int);
  vtkGetVector2Macro(Size, int);
  ///@}

  ///@{
  /// The display's exposure multiplier (default 1): the tone map of
  /// ToneMap() and of the viewer's display pass.
  vtkSetClampMacro(Exposure, double, 0.0, 1e12);
  vtkGetMacro(Exposure, double);
  ///@}

  ///@{
  /**
   * Particles traced and binned at a time (default 0: all at once, or, on
   * one process, batches of at most GetLargestAutomaticBatch() that fit the
   * tracer's MemoryLimit where the run's hits would not). Only one batch's
   * hits are held; the reconstruction then keeps no hits (set its FixedView
   * on for one image). Batches run on one process only.
   */
  vtkSetClampMacro(BatchSize, vtkTypeInt64, 0, VTK_TYPE_INT64_MAX);
  vtkGetMacro(BatchSize, vtkTypeInt64);
  /// The batch size Update() will use for the tracer's particle count.
  vtkTypeInt64 GetPlannedBatchSize();
  /// Whether GetPlannedBatchSize() chose batches that the user did not ask for.
  bool IsBatchedForMemory();
  /// The largest batch chosen for memory (10^7 particles, about 1.3 GB of
  /// hits in the default scene; larger batches were no faster).
  static vtkTypeInt64 GetLargestAutomaticBatch();
  ///@}

  ///@{
  /**
   * Progressive refinement (default off): the reconstruction accumulates
   * the particles, so that AddParticles() adds to the textures those of a
   * longer run (the viewer's `p`).
   */
  vtkSetMacro(Progressive, bool);
  vtkGetMacro(Progressive, bool);
  vtkBooleanMacro(Progressive, bool);
  ///@}

  /**
   * Phases 1 and 2: traces the tracer's NumberOfParticles (in batches as
   * above, on every process) and reconstructs the textures toward the
   * camera. False when a phase fails on any process (GetFailedPhase()).
   */
  bool Update();

  /**
   * Progressive step: traces `count` more particles, continuing the run
   * (Progressive must be on), and brings the textures and the actors up to
   * date. On failure the pipeline keeps the run it had. One process only.
   */
  bool AddParticles(vtkTypeInt64 count);

  /**
   * Brings the view-dependent textures up to date with the camera and the
   * reconstruction's settings (only what changed is recomputed), then the
   * actors' inputs (only what changed is uploaded). Textures of other
   * objects than the actors show (a scene with objects added or removed,
   * updated since) get new actors, in the renderer the last ones were in.
   */
  bool UpdateView();

  /// The textures (the reconstruction's output), after Update().
  vtkPartitionedDataSetCollection* GetTextures();

  /**
   * Adds the scene's props (textured surfaces, slice volumes) to
   * `renderer` and makes the pipeline's camera its active camera. After
   * Update(); false when the textures cannot be shown. Again after another
   * Update(), with the same renderer: the props there take the new
   * textures where the objects are the same ones (an edit of a transfer
   * function, a colour, a light: the slice mappers keep on the GPU what
   * did not change), otherwise they are made again.
   */
  bool AddToRenderer(vtkRenderer* renderer);

  /**
   * Phase 3 off screen: renders the textures at Size from the camera and
   * reads back the linear radiance (point array `Radiance`, float RGB, row
   * 0 at the bottom): the second frame's (the first uploads the textures
   * and compiles the shaders), or, with `supersample` K > 1, the mean of
   * K^2 frames over each pixel's area (vtkBrumeFloatImageCapture). After
   * Update(); null on failure. It draws in a window of its own: the props
   * move there from a renderer AddToRenderer() gave.
   */
  vtkSmartPointer<vtkImageData> RenderImage(int supersample = 1);

  /**
   * For a program that draws its image once: frees what the
   * reconstruction keeps for a rebuild beyond its textures (a large
   * volume's extinction at its own resolution, the direct light's rays:
   * vtkBrumeRadianceReconstruction::ReleaseBuildState()), before
   * RenderImage() has the GPU take its copy of the textures. `brume
   * render` does so before its last image (a 512^3 volume's peak memory
   * 2.1 -> 1.6 GB). A later Update() or camera move rebuilds the textures
   * in full. Returns the bytes given back to the system.
   */
  vtkTypeInt64 ReleaseBuildState();

  /**
   * Limits each medium's grids at their own resolution to three quarters
   * of the memory the GPU of `window` had free when first asked
   * (vtkBrumeOpenGLSliceVolumeMapper::GetFreeGPUMemory(),
   * vtkBrumeRadianceReconstruction::SetGPUMemoryLimit()): a volume the GPU
   * cannot hold is coarsened to fit, with a warning, instead of failing to
   * draw. No limit where the driver does not say. With a controller every
   * process takes the smallest of the processes' limits, so that all
   * sample alike (collective: a process without a window passes null).
   * `window` must have its context: within a render, or after one
   * (GetImageWindow() makes RenderImage()'s). Returns the limit (0: none).
   */
  vtkTypeInt64 LimitToGPUMemory(vtkRenderWindow* window);
  /// RenderImage()'s window, off screen, its context made.
  vtkRenderWindow* GetImageWindow();

  /// The 8-bit sRGB image of `radiance` at Exposure.
  vtkSmartPointer<vtkImageData> ToneMap(vtkImageData* radiance);

  /// The phase that failed last ("particle tracing", "reconstruction",
  /// "the scene", "rendering"), or "" when the last step succeeded.
  const char* GetFailedPhase();

  ///@{
  /**
   * Figures of the last Update(): seconds of tracing (the slowest
   * process's) and of reconstruction, this process's hits and rays over
   * every batch, the histograms' reduction across processes (bytes summed,
   * seconds of the slowest) and of the last RenderImage() (first frame,
   * then per frame).
   */
  vtkGetMacro(TracingSeconds, double);
  vtkGetMacro(ReconstructionSeconds, double);
  vtkGetMacro(NumberOfHits, vtkTypeInt64);
  vtkGetMacro(NumberOfRays, vtkTypeInt64);
  vtkGetMacro(ReductionBytes, vtkTypeInt64);
  vtkGetMacro(ReductionSeconds, double);
  vtkGetMacro(FirstFrameSeconds, double);
  vtkGetMacro(FrameSeconds, double);
  ///@}

  ///@{
  /**
   * Whether RenderImage() (without supersampling) draws a second frame,
   * after the one it returns, to time a frame whose textures are resident
   * (GetFrameSeconds(); 0 otherwise). Off by default: the image is the
   * first frame's, and a second would only be timed (`brume render
   * --timings` turns it on).
   */
  vtkSetMacro(MeasureFrame, bool);
  vtkGetMacro(MeasureFrame, bool);
  vtkBooleanMacro(MeasureFrame, bool);
  ///@}

protected:
  vtkBrumePipeline();
  ~vtkBrumePipeline() override;

  bool Fail(const char* phase);
  /// The textures in props in `renderer`: those there already take them
  /// where their objects are the same, otherwise they are made again.
  bool ShowTextures(vtkRenderer* renderer);
  // Updates `algorithm`'s output `port` as piece `piece` of `pieces`, at
  // the Time when one was set.
  bool UpdateAt(vtkAlgorithm* algorithm, int port, int piece, int pieces);
  void ConnectPhases();
  bool TakeSceneCamera();

  int Size[2] = { 512, 512 };
  double Exposure = 1.0;
  double Time = 0.0;
  bool TimeSet = false;
  vtkTypeInt64 BatchSize = 0;
  bool Progressive = false;

  double TracingSeconds = 0.0;
  double ReconstructionSeconds = 0.0;
  vtkTypeInt64 NumberOfHits = 0;
  vtkTypeInt64 NumberOfRays = 0;
  vtkTypeInt64 ReductionBytes = 0;
  double ReductionSeconds = 0.0;
  double FirstFrameSeconds = 0.0;
  double FrameSeconds = 0.0;
  bool MeasureFrame = false;

private:
  vtkBrumePipeline(const vtkBrumePipeline&) = delete;
  void operator=(const vtkBrumePipeline&) = delete;

  vtkSmartPointer<vtkAlgorithmOutput> SceneOutput;
  vtkNew<vtkTrivialProducer> SceneData;
  vtkNew<vtkBrumeLightTracer> Tracer;
  vtkNew<vtkBrumeRadianceReconstruction> Reconstruction;
  vtkSmartPointer<vtkMultiProcessController> Controller;
  vtkNew<vtkBrumeSceneActors> Actors;
  vtkSmartPointer<vtkCamera> Camera;
  bool CameraChosen = false;          // SetCamera(), ApplySceneSettings() or a first Update()
  vtkMTimeType CameraDefaultTime = 0; // the camera's, until someone moves it
  vtkSmartPointer<vtkRenderer> ActorsRenderer; // where AddToRenderer() put the props
  void MakeImageWindow();
  vtkSmartPointer<vtkRenderWindow> ImageWindow; // RenderImage()'s
  // The window whose GPU LimitToGPUMemory() asked, and what it said.
  vtkRenderWindow* AskedWindow = nullptr;
  vtkTypeInt64 AskedFree = -1;
  vtkSmartPointer<vtkBrumeFloatImageCapture> ImageCapture;
  const char* FailedPhase = "";
};

#endif
