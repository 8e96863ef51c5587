// SPDX-License-Identifier: BSD-3-Clause
// The textures of vtkBrumeRadianceReconstruction and what they were built
// from, kept between executions (private to the module). Each step of the
// filter is one method here: Build (all textures from the hits), Add (more
// particles' hits into the same histograms), SetDirectional (directional
// media on or off), FollowView (view-dependent textures toward a new eye)
// and Emit (the output collection). Errors are reported on the filter.
#ifndef vtkBrumeRadianceTextures_h
#define vtkBrumeRadianceTextures_h

#include "vtkBrumeHistogramReduction.h" // For the distributed reduction
#include "vtkBrumeHitConversion.h"      // For RunInfo
#include "vtkBrumeSceneConversion.h"    // For ObjectSource
#include "vtkSmartPointer.h"
#include "vtkType.h"

#include "brume/DirectLight.h"
#include "brume/RayCaster.h"
#include "brume/Reconstruction.h"
#include "brume/SparseTexture.h"

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

class vtkAlgorithm;
class vtkDataObject;
class vtkImageData;
class vtkMultiProcessController;
class vtkPartitionedDataSet;
class vtkPartitionedDataSetCollection;
class vtkPolyData;

/// One execution's validated inputs.
struct vtkBrumeReconstructionRequest
{
  vtkDataObject* SceneInput = nullptr;                    // as given
  vtkSmartPointer<vtkPartitionedDataSetCollection> Scene; // as a collection
  vtkPolyData* HitData = nullptr;
  brume::HitArrays Hits; // views of HitData's arrays
  std::vector<float> PositionCopy;
  vtkBrumeHitConversion::RunInfo Run;
  brume::Vec3 Eye;
  double ParticleFlux = 0.0;  // one particle's flux: the run's mean power / particles
  double ThresholdFlux = 0.0; // RadiosityThreshold x one particle's flux
};

/// The filter's settings that the textures depend on.
struct vtkBrumeReconstructionSettings
{
  double RadiosityThreshold = 0.0;
  int SurfaceResolution = 0;
  int MediumResolution = 0;
  int HistogramRefinement = 0;
  int DirectLightResolution = 0; // 0: no deterministic single scattering
  int MirrorResolution = 0;
  bool CentroidMatching = true;
  bool SparseMedia = true;        // heterogeneous media's textures in the sparse form
  bool FixedView = false;         // view-dependent objects binned toward one eye
  bool DirectionalMedia = false;  // with FixedView: anisotropic media keep their hits
  double PlannedParticles = 0.0;  // resolutions chosen for this many particles, if more
  vtkTypeInt64 NativeMemory = 0;  // bytes each medium's own-resolution grids may take
  bool NativeMemoryOfGPU = false; // NativeMemory is the GPU's (for the warning)

  bool operator==(const vtkBrumeReconstructionSettings& o) const
  {
    return this->RadiosityThreshold == o.RadiosityThreshold &&
      this->SurfaceResolution == o.SurfaceResolution &&
      this->MediumResolution == o.MediumResolution &&
      this->HistogramRefinement == o.HistogramRefinement &&
      this->DirectLightResolution == o.DirectLightResolution &&
      this->MirrorResolution == o.MirrorResolution &&
      this->CentroidMatching == o.CentroidMatching && this->SparseMedia == o.SparseMedia &&
      this->FixedView == o.FixedView && this->DirectionalMedia == o.DirectionalMedia &&
      this->PlannedParticles == o.PlannedParticles && this->NativeMemory == o.NativeMemory &&
      this->NativeMemoryOfGPU == o.NativeMemoryOfGPU;
  }
};

/// What the steps did, added to the filter's counters.
struct vtkBrumeReconstructionWork
{
  vtkIdType TextureBuilds = 0;
  vtkIdType ViewUpdates = 0;
  vtkIdType ParticleAdditions = 0;
  vtkIdType DirectionalBuilds = 0;
  // Media's bricks at their own resolution: sampled, and taken from the
  // textures replaced (an edit of a transfer function).
  vtkIdType NativeBricksSampled = 0;
  vtkIdType NativeBricksReused = 0;
  // Objects whose direct light's arrivals were taken from the textures replaced.
  vtkIdType DirectArrivalsKept = 0;
};

class vtkBrumeRadianceTextures
{
public:
  static constexpr int MaxSurfaceResolution = 4096;
  static constexpr int MaxMediumResolution = 512;
  /// Texels of an object's output grid with direct light, at most (2^18,
  /// 64^3): one shadow ray each (a march through heterogeneous media), one
  /// evaluation per view change, and what the renderer samples. Finer grids
  /// measured no better: god-rays.json at 128^3, 4.78 % block error against
  /// 4.74 % at 64^3, with 3.7 times the reconstruction's time.
  static constexpr double MaxDirectTexels = 262144.0;
  /// Texels x lights of an object's direct light, at most (2^23: 192 MB of
  /// arrivals, as many shadow rays): with many lights the grid is coarser,
  /// and below MinDirectTexels the particles carry the object's direct
  /// light instead (a scene of thousands of small lights then costs the
  /// particles' memory, not texels x lights).
  static constexpr double MaxDirectArrivals = 8388608.0;
  static constexpr double MinDirectTexels = 1024.0;
  /// Texels x lights of the whole scene's direct light, at most: as much as
  /// one object's (2^23: about 330 MB with the output grids). Where the
  /// objects' grids would hold more (hundreds of objects), the grids take
  /// one texel size, the finest that fits (a large ground keeps its
  /// texels, a small tile gets few), so that memory and shadow rays do not
  /// grow with the number of objects. Scenes under it keep their grids as
  /// they are (the shipped scenes hold under a million).
  static constexpr double MaxSceneDirectArrivals = 8388608.0;
  /// Texels x lights under which an object's direct light is computed on
  /// one thread, beside other such objects, rather than on every thread.
  static constexpr std::size_t SmallDirectArrivals = 4096;

  /// Errors and warnings go to `filter`; `controller` may be null.
  vtkBrumeRadianceTextures(vtkAlgorithm* filter, vtkMultiProcessController* controller);
  ~vtkBrumeRadianceTextures();

  /// Whether these textures were made from this scene with these settings.
  bool SameSceneAndSettings(
    const vtkBrumeReconstructionRequest& request, const vtkBrumeReconstructionSettings& s) const;
  /// Whether the hits are those the textures hold.
  bool HoldsHits(vtkPolyData* hits) const;
  /// Whether the hits are the last progressive step added (nothing new).
  bool HoldsStep(const vtkBrumeHitConversion::RunInfo& run) const;
  /**
   * Whether `run` continues the run the textures hold: the next batch of
   * the same run (it starts where the particles binned end), or, once that
   * run is complete, the particles that extend it to a larger count.
   */
  bool Continues(const vtkBrumeHitConversion::RunInfo& run) const;
  double GetParticles() const { return this->Particles; }
  /// Where the particles binned end (GetParticles() once the run is complete).
  double GetEndParticle() const { return this->EndParticle; }
  /// Whether every batch of the run is binned: only then are there textures.
  bool IsComplete() const { return this->EndParticle >= this->Particles; }
  double GetSeed() const { return this->Seed; }

  /**
   * Every texture from the hits. False (errors reported) on failure.
   * `spare`: the kept hits' buffers of the textures this build replaces
   * (ReleaseKeptMemory()), object by object, for the objects that keep
   * hits to write into (brume::ObjectRadiance::ReuseKeptMemory).
   */
  bool Build(const vtkBrumeReconstructionRequest& request,
    const vtkBrumeReconstructionSettings& settings, vtkBrumeReconstructionWork& work,
    std::vector<brume::KeptHits> spare = {});

  /// The kept hits' buffers of every object, emptied, for the textures
  /// that replace these (Build()'s `spare`).
  std::vector<brume::KeptHits> ReleaseKeptMemory();

  /**
   * Every medium's grid at its own resolution, moved out of these textures
   * (which must not be used after), for the textures that replace them:
   * given to those by OfferNativeGrids() before their Build(), each medium
   * of the same scalar field takes from its grid what an edit of the
   * transfer function left as it was (brume::NativeMediumGrid::Sample()).
   */
  std::vector<brume::NativeMediumGrid> ReleaseNativeGrids();
  void OfferNativeGrids(std::vector<brume::NativeMediumGrid> grids)
  {
    this->PreviousNatives = std::move(grids);
  }

  /**
   * The direct light's shadow rays of every object (their arrivals) and
   * what they were cast through (the lights, the surfaces' caster, the
   * media's extinction), moved out for the textures that replace these:
   * given to those by OfferDirect() before their Build(), they take the
   * arrivals where all of that is the same (an edit of a colour, an
   * albedo or a reflectance; not a light, a surface or an opacity) instead
   * of casting the rays again. Call before ReleaseNativeGrids().
   */
  struct KeptDirect;
  std::shared_ptr<KeptDirect> ReleaseDirect();
  void OfferDirect(std::shared_ptr<KeptDirect> kept) { this->PreviousDirect = std::move(kept); }

  /// The ray caster of the shadow and mirror rays (null without them):
  /// held while the textures that replace these are built, it is found
  /// again by vtkBrumeSceneConversion::SharedRayCaster where the surfaces
  /// did not change.
  std::shared_ptr<const brume::RayCaster> GetCaster() const { return this->Caster; }

  /// The hits of a progressive step, added to every texture's histograms.
  bool Add(const vtkBrumeReconstructionRequest& request, vtkBrumeReconstructionWork& work);

  /// Anisotropic media as directional radiance of `order` (or per view).
  bool SetDirectional(bool directional, int order, vtkBrumeReconstructionWork& work);

  /**
   * View-dependent textures toward `request.Eye`: incrementally, or rebuilt
   * from the hits (textures holding added particles are always updated
   * incrementally: no single hits input holds them); then the mirrors'
   * reflections toward it (brume::MirrorReflection). Textures binned
   * toward a fixed view are rebuilt from the hits; false (reported) where
   * the hits no longer hold their run.
   */
  bool FollowView(const vtkBrumeReconstructionRequest& request, bool incremental,
    vtkBrumeReconstructionWork& work);

  /// The textures as the output collection (unchanged textures: the same datasets).
  void Emit(vtkPartitionedDataSetCollection* output);

  /// Objects whose output texture depends on the viewpoint (glossy
  /// surfaces, anisotropic media held per view).
  int NumberOfViewDependentOutputs() const;

  /// Bytes moved and seconds spent summing histograms since the last call.
  void TakeReduction(vtkTypeInt64& bytes, double& seconds);

private:
  bool CreateObjects(const vtkBrumeReconstructionSettings& settings, const brume::HitArrays& hits,
    const brume::ObjectHits& groups, const vtkBrumeHitConversion::RunInfo& run);
  // concentration: brume::HitConcentration of a medium's or a planar
  // surface's hits (1 for other surfaces).
  std::unique_ptr<brume::ObjectRadiance> CreateObject(std::size_t o, std::size_t hitCount,
    double concentration, const vtkBrumeReconstructionSettings& settings);
  bool CheckHits(const brume::HitArrays& hits, const brume::ObjectHits& groups);
  bool BuildObjects(const vtkBrumeReconstructionRequest& request, const brume::ObjectHits& groups,
    vtkBrumeReconstructionWork& work);
  // Distributed runs: BuildObjects()'s steps, each for every object in
  // turn. False (reported, on every process) when a process failed.
  bool BuildDistributed(const vtkBrumeReconstructionRequest& request,
    const brume::ObjectHits& groups, std::vector<std::string>& errors);
  // step(o, parallelFor) for every object: the view-independent ones
  // concurrently, each on one thread (a single pass in hit order), those
  // with the most hits in `groups` first, then the view-dependent ones,
  // each on every thread.
  void ForEachObject(const brume::ObjectHits& groups,
    const std::function<void(std::size_t, const brume::ParallelFor&)>& step);
  // bin(o, parallelFor) on every thread (ObjectOptions::BinOnEveryThread),
  // one object after another, for the view-independent objects with more
  // than a thread's even share of their hits (and WideObjectHits at
  // least), when there are two threads or more; flags them.
  static constexpr std::size_t WideObjectHits = 131072;
  std::vector<char> BinWide(const brume::ObjectHits& groups,
    const std::function<void(std::size_t, const brume::ParallelFor&)>& bin);
  bool Agree(bool ok);
  // Reports each object's error ("what 'name': error.") and agrees with the
  // other processes: true when no process had one.
  // Samples every medium's grid at its own resolution on every thread,
  // and says where one is coarsened.
  void SampleMedia(vtkBrumeReconstructionWork& work);
  bool AgreeOnObjects(const std::vector<std::string>& errors, const char* what);
  bool Distributed() const;
  // Deterministic single scattering: the light, the objects' output grids,
  // and the shadow rays once every texture is built.
  bool CreateDirectLight(
    const vtkBrumeReconstructionSettings& settings, const brume::HitArrays& hits);
  std::array<int, 3> DirectResolution(std::size_t o, int resolution) const;
  // Coarsens the objects' direct-light grids (zero where none) to the
  // finest texel size common to the scene (no finer than each grid) that
  // keeps texels x `lights` within MaxSceneDirectArrivals; their texels x
  // lights after.
  double FitDirectGrids(std::vector<std::array<int, 3>>& grids, double lights) const;
  // Resolution along the longer axis `n` of `extent`, the others in proportion.
  static std::array<int, 3> FixedResolution(const brume::Vec3& extent, int n);
  void ComputeDirect(vtkBrumeReconstructionWork& work);
  // Mirrors and sharp glossy surfaces (brume::MirrorReflection::Casts):
  // which are cast, before the build; then their reflections toward `eye`,
  // for which view-dependent objects are seen from a planar mirror's
  // mirrored eye: those it turned (true) must be turned back.
  bool PlanReflections();
  // FixedView: the view-dependent objects no reflection sees from
  // elsewhere (and, with DirectionalMedia, no medium) bin toward `eye`.
  void FixViews(const vtkBrumeReconstructionSettings& settings, const brume::Vec3& eye);
  std::vector<bool> ReflectMirrors(const brume::Vec3& eye);

  vtkAlgorithm* Filter;
  vtkMultiProcessController* Controller;
  std::unique_ptr<vtkBrumeHistogramReduction> Reduction; // distributed runs

  vtkDataObject* SceneData = nullptr; // the input as given
  vtkSmartPointer<vtkPartitionedDataSetCollection> SceneCollection;
  vtkMTimeType SceneTime = 0;
  vtkPolyData* HitsData = nullptr;
  vtkMTimeType HitsTime = 0;
  vtkBrumeReconstructionSettings Settings;
  bool NativeMemoryOfGPU = false; // the objects' NativeMemory is the GPU's (for the warning)
  brume::Scene Scene;
  std::shared_ptr<const brume::RayCaster> Caster; // shadow rays and mirrors' rays
  std::unique_ptr<brume::DirectLight> Direct;     // null: no direct light
  std::vector<vtkBrumeSceneConversion::ObjectSource> Sources;
  std::vector<std::unique_ptr<brume::ObjectRadiance>> Objects;
  std::vector<brume::NativeMediumGrid> PreviousNatives; // OfferNativeGrids(), until sampled
  std::shared_ptr<KeptDirect> PreviousDirect;           // OfferDirect(), until computed
  /// PreviousDirect's arrivals for object o where they hold for this scene, else null.
  const std::vector<float>* KeptArrivals(std::size_t o) const;
  bool DirectKeptHolds() const;
  std::vector<vtkSmartPointer<vtkPartitionedDataSet>> Outputs;
  std::vector<vtkSmartPointer<vtkImageData>> NativeExtinction;   // media: made once
  std::vector<vtkSmartPointer<vtkImageData>> LastMediumTextures; // media: the last emitted
  std::vector<brume::SparseTexture> SourceBricks; // media: kept while the resolution stays
  std::vector<brume::Vec3> ObjectEye;             // the eye each texture was estimated toward
  std::vector<bool> ObjectDirectional;            // whose output holds directional radiance
  double Particles = 0.0, Seed = 0.0;
  double EndParticle = 0.0;         // the particles binned are [0, EndParticle)
  bool Accumulated = false;         // particles were added after the build
  double LastFirstParticle = 0.0;   // the first particle of the last step added
  std::vector<std::size_t> Mirrors; // the surfaces whose reflections are cast
  brume::Vec3 MirrorEye;            // the eye their reflections were cast from
  bool MirrorsCurrent = false;      // false: cast again at the next FollowView
};

#endif
