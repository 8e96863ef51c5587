// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeRadianceReconstruction
 * @brief   phase 2: per-object radiance textures toward a viewpoint
 *
 * Jimenez & Pueyo (2003), section 3. For every object of the scene, the hits
 * stored by vtkBrumeLightTracer are binned into a histogram finer than the
 * texture, a summed-area table is built, and every texel's value is the
 * adaptive nearest-neighbour density estimate of its region: the region
 * starts as the texel's own histogram cells and grows until the flux it holds
 * reaches the threshold (the paper's Figure 1), then its sum is divided by
 * its own area or volume. The normalizations are documented in
 * brume/Reconstruction.h:
 *
 * - surfaces (Lambertian): L_o = rho/pi * E + L_e, view independent;
 * - media: source radiance S = J / sigma_t with
 *   J = (sigma_s/sigma_t) * sum(p(w_p, w_o) Phi_p) / V, w_o toward the eye
 *   (view dependent unless g = 0).
 *
 * Input port 0: the scene collection. Input port 1: the particle hits.
 * Output: a vtkPartitionedDataSetCollection with one partitioned dataset per
 * object, named as in the scene:
 *
 * - surfaces: partition 0 is a 2D vtkImageData in texture space ([0,1]^2,
 *   point data `Radiance`, float[3], W m^-2 sr^-1) whose field data
 *   `BrumeTextureOrigin`, `BrumeTextureU`, `BrumeTextureV` place it in the
 *   world (x = Origin + s U + t V); partition 1 is the surface with texture
 *   coordinates `TextureCoordinates` that map the image with a vtkTexture;
 * - media: partition 0 is a 3D vtkImageData over the medium's box with cell
 *   data `SourceRadiance` (float[3], W m^-2 sr^-1) and `Extinction`
 *   (float[3], sigma_t in m^-1), ready for vtkBrumeSliceVolumeMapper; a
 *   heterogeneous medium adds partition 1, its extinction at the density's
 *   own resolution, and its source radiance is the sigma_t-weighted mean
 *   over each voxel's region, kept by default only near the density
 *   (SparseMedia; vtkBrumeRadianceConversion has the details).
 *
 * Every partition's field data holds `BrumeObjectKind` ("surface" or
 * "medium"). The collection's field data holds `BrumeEyePosition` (the
 * viewpoint the textures radiate toward, double[3]) and
 * `BrumeViewDependentObjects` (how many textures depend on it: glossy
 * surfaces, anisotropic media held per view); a renderer that follows its
 * camera updates the filter when the two positions differ and that count
 * is not 0 (ParaView's "Brume Radiance" representation does).
 *
 * Surfaces are parameterized by their plane when planar, else by their
 * texture coordinates, else by an automatic atlas of one chart per triangle
 * (the output surface then has separate points per triangle). A texel's
 * region is divided by the world area it covers (an area map of the
 * parameterization), so edges and charts keep the right units.
 *
 * Model no more than the scene needs: textures are cached between
 * executions. When only the viewpoint changes, diffuse surfaces and
 * isotropic media are not recomputed (their output images are the same
 * objects); glossy surfaces and anisotropic media are updated, incrementally
 * by default (their hits stay sorted by histogram cell, only the weights
 * toward the eye are recomputed). GetNumberOfTextureBuilds() and
 * GetNumberOfViewUpdates() count the work done.
 *
 * Per object, the field array `BrumeTextureResolution` (1 component) of the
 * scene object overrides the texture resolution along its longest axis.
 *
 * @sa vtkBrumeLightTracer vtkBrumeSliceVolumeMapper
 */
#ifndef vtkBrumeRadianceReconstruction_h
#define vtkBrumeRadianceReconstruction_h

#include "vtkBrumeReconstructionModule.h" // For export macro
#include "vtkPartitionedDataSetCollectionAlgorithm.h"

#include <memory> // For the cache

class vtkCamera;
class vtkMultiProcessController;
class vtkBrumeRadianceTextures;
struct vtkBrumeReconstructionRequest;
struct vtkBrumeReconstructionWork;

class VTKBRUMERECONSTRUCTION_EXPORT vtkBrumeRadianceReconstruction
  : public vtkPartitionedDataSetCollectionAlgorithm
{
public:
  static vtkBrumeRadianceReconstruction* New();
  vtkTypeMacro(vtkBrumeRadianceReconstruction, vtkPartitionedDataSetCollectionAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The viewpoint the textures radiate toward (default (0, 0, 4)).
  vtkSetVector3Macro(EyePosition, double);
  vtkGetVector3Macro(EyePosition, double);
  ///@}

  ///@{
  /// A camera whose position, when set, is the viewpoint (default none).
  void SetCamera(vtkCamera* camera);
  vtkGetObjectMacro(Camera, vtkCamera);
  ///@}

  ///@{
  /**
   * Update view-dependent textures incrementally when only the viewpoint
   * changed (default on); off rebuilds their histograms from the hits.
   */
  vtkSetMacro(IncrementalUpdate, bool);
  vtkGetMacro(IncrementalUpdate, bool);
  vtkBooleanMacro(IncrementalUpdate, bool);
  ///@}

  ///@{
  /**
   * Progressive refinement (default off). When on, hits traced from a
   * FirstParticle > 0 (vtkBrumeLightTracer) are added to the histograms the
   * textures were made from instead of replacing them: they must continue
   * the run the textures hold (FirstParticle equal to its particle count,
   * same seed, scene and settings), else RequestData fails. The particles
   * already binned are rescaled to the new count; when the count doubles
   * the result is bitwise that of one run with all the particles. Texture
   * resolutions stay those of the first run (set them to compare with one).
   *
   * Batches of one run (vtkBrumeLightTracer's [FirstParticle, EndParticle)
   * of the same NumberOfParticles, one after the other) are binned as they
   * come, and their hits released when the tracer runs again: only the last
   * batch estimates the textures; until then the output holds no textures,
   * only the field array `BrumeParticlesBinned` (binned so far, of the run).
   * Resolutions follow the run's expected hits (the first batch's, scaled).
   */
  vtkSetMacro(AccumulateParticles, bool);
  vtkGetMacro(AccumulateParticles, bool);
  vtkBooleanMacro(AccumulateParticles, bool);
  ///@}

  ///@{
  /**
   * One viewpoint only (default off). View-dependent objects (glossy
   * surfaces, anisotropic media held per view) keep their hits (40 bytes
   * each, up to 48 with a surface's triangle and an aimed light's scale) so
   * that a new viewpoint re-weights them without new particles: in a run
   * traced in batches (AccumulateParticles) their hits are the memory that
   * grows with the particles. On, they bin each hit's flux
   * weighted toward the viewpoint as it comes, as view-independent objects
   * do, and keep nothing: a batched run holds one batch's hits at a time
   * whatever its count, and the textures are bitwise those of kept hits
   * toward the same viewpoint. What `brume render` uses for its one image.
   * A new viewpoint then rebuilds them from the hits input; where that
   * input no longer holds the run (batches, added particles), RequestData
   * fails, asking to trace again. Objects stay as without it where a
   * mirror or a cast glossy lobe reflects them (each reflection sees them
   * from another point) and, with DirectionalRadiance, anisotropic media.
   */
  vtkSetMacro(FixedView, bool);
  vtkGetMacro(FixedView, bool);
  vtkBooleanMacro(FixedView, bool);
  ///@}

  ///@{
  /**
   * Deterministic single scattering (default on): the light of point, spot
   * and directional lights reaching each texel directly is computed with a
   * shadow ray (through Embree and the media's own density) instead of
   * being estimated from the particles' first interactions, which are then
   * left out. Shafts, self-shadowing and shadows are as sharp as the output
   * grid: media and planar surfaces (of one non-mirror material) are output
   * at DirectLightResolution texels along their longest axis (heterogeneous
   * media: at most their density's own resolution, its voxels cut in two
   * where they hold 1.5 mean free paths and the particles' texture is finer,
   * brume::MediumVoxelRefinement; at most 2^18 texels per object, 2^21 so
   * cut), holding the particles' texture resampled plus the direct light.
   * Other surfaces, and scenes lit only by emissive surfaces, are as
   * without it. The hits must carry the tracer's `EmitterId` and `Depth`.
   * ../shared/RADIOMETRY.md, "Two resolutions in one medium", states the
   * relations.
   */
  vtkSetMacro(DirectLighting, bool);
  vtkGetMacro(DirectLighting, bool);
  vtkBooleanMacro(DirectLighting, bool);
  vtkSetClampMacro(DirectLightResolution, int, 1, 4096);
  vtkGetMacro(DirectLightResolution, int);
  ///@}

  ///@{
  /**
   * Directional radiance for anisotropic media (default off): instead of a
   * texture toward the viewpoint, each voxel holds the spherical-harmonics
   * projection (up to DirectionalOrder, in [1, 3], default 3) of the light
   * it receives, as the cell array `SourceRadianceSH` (3 (order + 1)^2
   * components: coefficient-major, RGB within), with the phase function's g
   * as field data `BrumePhaseAsymmetry`; `SourceRadiance` then holds the
   * mean over directions. vtkBrumeSliceVolumeMapper evaluates the source
   * radiance toward the eye per fragment (brume/SphericalHarmonics.h), so a
   * view change costs only the render. Accurate where |g| is moderate (see
   * Documentation/evaluation.md, the sweep table); the per-view mode stays exact for any g.
   * Glossy surfaces stay per view.
   */
  vtkSetMacro(DirectionalRadiance, bool);
  vtkGetMacro(DirectionalRadiance, bool);
  vtkBooleanMacro(DirectionalRadiance, bool);
  vtkSetMacro(DirectionalOrder, int);
  vtkGetMacro(DirectionalOrder, int);
  ///@}

  ///@{
  /**
   * Distributed runs (default: the global controller). With more than one
   * process, each holds a piece of the run's hits (vtkBrumeLightTracer
   * pieces: process r the r-th consecutive share of the particles); every
   * process bins its own hits into exact fixed-point histograms, whose sums
   * do not depend on the order of their terms; each object's histograms
   * are summed onto the one process that estimates its texture (the
   * objects shared out among the processes by their cost,
   * brume::AssignOwners), which then broadcasts the texture
   * (vtkBrumeHistogramReduction), so that every process ends with the
   * textures, bitwise those of one process with all the hits, and the
   * per-texel work is divided among the processes. Hits are never shipped,
   * only histograms and textures: the view-independent ones once, those
   * of view-dependent objects at every view change. Every process must
   * execute the filter; every process outputs the textures (the same on
   * each: renderers that composite, as IceT under mpirun pvbatch, draw them
   * on every process). The shadow rays of the direct light are shared out
   * among the processes and gathered. AccumulateParticles is not supported
   * across processes.
   */
  void SetController(vtkMultiProcessController* controller);
  vtkGetObjectMacro(Controller, vtkMultiProcessController);
  ///@}

  ///@{
  /**
   * Bytes this process sent and received summing histograms in the last
   * execution, and the seconds it spent doing so (waiting for the slowest
   * process included).
   */
  vtkGetMacro(LastReductionBytes, vtkTypeInt64);
  vtkGetMacro(LastReductionSeconds, double);
  ///@}

  ///@{
  /**
   * Work done so far: object textures built from the hits, incremental view
   * updates, objects that received added particles, directional projections.
   */
  vtkGetMacro(NumberOfTextureBuilds, vtkIdType);
  vtkGetMacro(NumberOfViewUpdates, vtkIdType);
  vtkGetMacro(NumberOfParticleAdditions, vtkIdType);
  vtkGetMacro(NumberOfDirectionalBuilds, vtkIdType);
  ///@}

  ///@{
  /**
   * Classified media's bricks of extinction at their own resolution
   * (brume::NativeMediumGrid), so far: evaluated from the scalars, and
   * taken from the textures a rebuild replaced, where an edit of the
   * opacity function left the function over the brick's scalars as it was
   * (all of them after an edit of the colour alone). Either way the same
   * floats.
   */
  vtkGetMacro(NumberOfNativeBricksSampled, vtkIdType);
  vtkGetMacro(NumberOfNativeBricksReused, vtkIdType);
  ///@}

  /**
   * Objects whose direct light (of point, spot and directional lights) was
   * taken from the textures a rebuild replaced instead of casting its
   * shadow rays again, so far: where the lights, the surfaces and every
   * medium's extinction were the same (an edit of a colour, an albedo or a
   * reflectance). The same floats either way.
   */
  vtkGetMacro(NumberOfDirectLightsKept, vtkIdType);

  /**
   * Frees what the filter keeps between executions beyond its output, for
   * a program that draws the output and reconstructs no more (`brume
   * render` before drawing its last image): the state a rebuild would take
   * from (each medium's extinction at its own resolution, 0.8 GB for a
   * classified 512^3 field, the direct light's shadow rays, the ray
   * caster, kept hits and histograms), and the mappings the freed grids
   * would have been sampled into again (brume::FloatBuffer::ReleaseKept()).
   * The output is not changed, and what it shares (a grid's samples, a
   * field's own values) stays with it. The next execution rebuilds in
   * full from its hits input, as a first one does; where that input holds
   * only a run's last batch it fails, asking to trace again. Returns the
   * bytes of mappings given back to the system.
   */
  vtkTypeInt64 ReleaseBuildState();

  vtkMTimeType GetMTime() override;

  ///@{
  /**
   * Radiosity threshold of the adaptive regions, in units of one emitted
   * particle's flux (default 128): a texel's region grows until it holds the
   * incident flux of this many particles leaving the lights. Must be > 0.
   */
  vtkSetMacro(RadiosityThreshold, double);
  vtkGetMacro(RadiosityThreshold, double);
  ///@}

  ///@{
  /**
   * Texels along each axis of surface textures and voxels along each axis of
   * medium textures. 0 (the default) chooses them from the object's size and
   * hit count so that a texel holds about RadiosityThreshold hits: on
   * average over a surface (where the direct light is computed, over the
   * part of a plane its scattered light gathers on, once that is
   * concentrated enough, brume::MinSurfaceConcentration), and where the
   * hits are in a medium (over the volume they effectively fill,
   * brume::HitConcentration, and finer for a dense medium,
   * brume::MediumHitsPerTexel); otherwise at most 4096 (surfaces) or 512
   * (media).
   */
  vtkSetMacro(SurfaceResolution, int);
  vtkGetMacro(SurfaceResolution, int);
  vtkSetMacro(MediumResolution, int);
  vtkGetMacro(MediumResolution, int);
  ///@}

  ///@{
  /**
   * The run the automatic resolutions are chosen for (default 0: the run
   * being reconstructed). A progressive run keeps its first step's
   * resolutions (AccumulateParticles): given the count it will reach,
   * its first step's textures get the texels that count's hits call for,
   * as a run traced in batches does from its first batch (its hits
   * scaled to the count), and its last step is estimated as finely as one
   * run of that count. Counts below the run's own are ignored.
   */
  vtkSetClampMacro(PlannedParticles, vtkTypeInt64, 0, VTK_TYPE_INT64_MAX);
  vtkGetMacro(PlannedParticles, vtkTypeInt64);
  ///@}

  ///@{
  /**
   * Texels along the longer axis of a mirror's texture (default 512, at
   * most 4096): its reflection toward the eye, cast from every texel
   * through the scene's textures and media (brume::MirrorReflection), is
   * recast at each new eye.
   */
  vtkSetMacro(MirrorResolution, int);
  vtkGetMacro(MirrorResolution, int);
  ///@}

  ///@{
  /// Histogram cells per texel along each axis (default 2, in [1, 16]).
  vtkSetMacro(HistogramRefinement, int);
  vtkGetMacro(HistogramRefinement, int);
  ///@}

  ///@{
  /**
   * Media: match the texture to where its estimates belong (default on).
   * A texel's estimate is a mean over its region, exact for a linearly
   * varying source at the region's sigma_t-weighted centroid; across a
   * cloud's edge that centroid lies inside the cloud, and interpolating the
   * estimates at the texels' centres made a dense cloud's visible skin too
   * bright. On, the texture is the one whose trilinear interpolation meets
   * every estimate at its centroid (brume::CentroidMatching). Off, the
   * texture holds the estimates themselves, as the paper's does.
   */
  vtkSetMacro(CentroidMatching, bool);
  vtkGetMacro(CentroidMatching, bool);
  vtkBooleanMacro(CentroidMatching, bool);
  ///@}

  ///@{
  /**
   * Heterogeneous media: their textures in the sparse form (default on).
   * On, a medium whose density has its own grid (partition 1) keeps its
   * source radiance only in the bricks of 8^3 cells that the slice mapper
   * reads, those near the density (brume::SparseTexture), as field arrays
   * (`SourceBrickSlots`, `SourceRadianceBrickSamples`,
   * `SourceRadianceSHBrickSamples`) with no cell arrays, and drops the
   * texture-resolution `Extinction` that partition 1 replaces: memory
   * follows the medium, not its box.
   * vtkBrumeSliceVolumeMapper::DenseSourceArray() expands an array. Off,
   * partition 0 holds the cell arrays `SourceRadiance`, `Extinction` (and
   * `SourceRadianceSH`), for filters that slice or probe it. Images are
   * the same either way.
   */
  vtkSetMacro(SparseMedia, bool);
  vtkGetMacro(SparseMedia, bool);
  vtkBooleanMacro(SparseMedia, bool);
  ///@}

  ///@{
  /**
   * Heterogeneous media: the bytes each medium's density at its own
   * resolution may take (its bricks of samples and their tables, twice for
   * a field classified by a transfer function: its extinction and its
   * scalars; brume::NativeMediumGrid). 0, the default: a quarter of the
   * memory this machine can use (vtkBrumeSMP::UsableMemory(), half its
   * physical memory), so that a 512^3 field keeps its own resolution on a
   * machine of 16 GB. A medium whose grids do not fit is coarsened by the
   * smallest integer factor that fits, and a warning says so once per
   * build. The slice mapper uploads the same samples.
   */
  vtkSetClampMacro(NativeMemoryLimit, vtkTypeInt64, 0, VTK_TYPE_INT64_MAX);
  vtkGetMacro(NativeMemoryLimit, vtkTypeInt64);
  /// NativeMemoryLimit, or its automatic value where 0.
  vtkTypeInt64 GetEffectiveNativeMemoryLimit() const;
  ///@}

  ///@{
  /**
   * The bytes of GPU memory a medium's grid at its own resolution may take
   * (the slice mapper's atlas holds its samples); 0, the default: not
   * known. A renderer that knows its GPU sets it: vtkBrumePass and brume's
   * commands, to three quarters of what the GPU reports free
   * (vtkBrumeOpenGLSliceVolumeMapper::GetFreeGPUMemory(): drivers with
   * GL_NVX_gpu_memory_info or GL_ATI_meminfo; Mesa's llvmpipe has
   * neither). Where NativeMemoryLimit is 0 the automatic limit is the
   * smaller of the machine's and this one, and the warning of a medium
   * coarsened to fit it names the GPU; an explicit NativeMemoryLimit
   * overrides both.
   */
  vtkSetClampMacro(GPUMemoryLimit, vtkTypeInt64, 0, VTK_TYPE_INT64_MAX);
  vtkGetMacro(GPUMemoryLimit, vtkTypeInt64);
  /// Whether GetEffectiveNativeMemoryLimit() is GPUMemoryLimit.
  bool IsNativeMemoryLimitedByGPU() const;
  ///@}

protected:
  vtkBrumeRadianceReconstruction();
  ~vtkBrumeRadianceReconstruction() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  // Memory that cannot be had fails the request with a message (in one
  // process: across processes the others would wait in a collective).
  vtkTypeBool ProcessRequest(
    vtkInformation* request, vtkInformationVector** inputs, vtkInformationVector* outputs) override;

  double EyePosition[3]; // the default view's position (brume::PinholeCamera)
  double RadiosityThreshold = 128.0;
  int SurfaceResolution = 0;
  int MediumResolution = 0;
  int MirrorResolution = 512;
  vtkTypeInt64 PlannedParticles = 0;
  int HistogramRefinement = 2;
  bool CentroidMatching = true;
  bool SparseMedia = true;
  vtkTypeInt64 NativeMemoryLimit = 0;
  vtkTypeInt64 GPUMemoryLimit = 0;
  vtkCamera* Camera = nullptr;
  vtkMultiProcessController* Controller = nullptr;
  vtkTypeInt64 LastReductionBytes = 0;
  double LastReductionSeconds = 0.0;
  bool IncrementalUpdate = true;
  bool AccumulateParticles = false;
  bool FixedView = false;
  bool DirectionalRadiance = false;
  int DirectionalOrder = 3;
  bool DirectLighting = true;
  int DirectLightResolution = 256;
  vtkIdType NumberOfTextureBuilds = 0;
  vtkIdType NumberOfViewUpdates = 0;
  vtkIdType NumberOfParticleAdditions = 0;
  vtkIdType NumberOfDirectionalBuilds = 0;
  vtkIdType NumberOfNativeBricksSampled = 0;
  vtkIdType NumberOfNativeBricksReused = 0;
  vtkIdType NumberOfDirectLightsKept = 0;

private:
  // The steps of RequestData: validate the inputs, plan (build, add or
  // keep the textures), then directional media, the view, the output.
  bool Validate(vtkInformationVector** inputVector, vtkBrumeReconstructionRequest& request);
  bool ValidateSettings();
  bool Plan(const vtkBrumeReconstructionRequest& request);
  bool Agree(bool ok);
  void CountWork();

  std::unique_ptr<vtkBrumeRadianceTextures> Textures; // kept between executions
  std::unique_ptr<vtkBrumeReconstructionWork> WorkDone;

  vtkBrumeRadianceReconstruction(const vtkBrumeRadianceReconstruction&) = delete;
  void operator=(const vtkBrumeRadianceReconstruction&) = delete;
};

#endif
