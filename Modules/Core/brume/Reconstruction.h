// SPDX-License-Identifier: BSD-3-Clause
// Phase 2 of Jimenez & Pueyo (2003), section 3: radiance textures from the
// stored particle hits, per object, through a histogram, its summed-area
// tables and adaptive nearest-neighbour density estimation.
//
// Radiometric normalization (units agree with a path tracer's radiance):
//  - Surface textures show the front side (the side the triangles' winding
//    normal points to): light arriving on the back is reflected by the
//    tracer but not shown.
//  - Surface texel, region of world area A holding hits of incident flux
//    Phi_p arriving from w_p (pointing away from the surface), toward the
//    eye w_o:  L_o = sum f_r(w_p, w_o) Phi_p / A  +  L_e.
//    Lambertian: f_r = rho/pi, so L_o = rho/pi * E + L_e with E = sum Phi_p / A.
//  - Medium voxel, region of volume V holding the hits stored at real
//    collisions (flux before the albedo weighting), phase function p,
//    direction of travel w_p, direction toward the eye w_o:
//      J = (sigma_s/sigma_t) * sum(p(w_p, w_o) Phi_p) / V   (W m^-3 sr^-1)
//    and the texture holds the slab source radiance S = J / sigma_t
//    (W m^-2 sr^-1), which the slice renderer composites with
//    alpha = 1 - exp(-sigma_t * Delta).
//  - The growth threshold is a flux (W): a texel's region grows from its own
//    histogram cells until the incident flux it holds (mean over channels)
//    reaches it (the paper's "accumulated radiosity"). The region's sum is
//    divided by the region's own area (summed from a per-cell area map, so
//    texels at a polygon's edge or on an atlas chart count only the surface)
//    or volume.
//
// What a view change costs: a view-dependent object (glossy surface,
// anisotropic medium) keeps its hits' indices and histogram cells; a new eye
// only re-weights them, rebuilds the value table and re-evaluates the cached
// regions (whose growth depends on the view-independent flux alone). Other
// objects are never recomputed. Per-cell sums follow hit order, so results
// do not depend on the number of threads.
//
// ObjectRadiance runs the steps; its collaborators, each in a header of its
// own, do the work:
//   ObjectLayout        what the texture covers, its resolutions, how a
//                       medium scatters (the forward peak set apart)
//   HitBinning          each hit's cell and the histograms' exact sums;
//                       view-dependent objects' kept hits (KeptHits.h)
//   NativeMediumGrid    a heterogeneous medium's density at its own
//                       resolution, its integrals and centroids
//   DirectTexture       the direct light of point, spot and directional
//                       lights on an output grid
//   DirectionalRadiance the spherical-harmonics projection of anisotropic
//                       media
//   ObjectDistribution  sums across processes, the owner that estimates
#ifndef brume_Reconstruction_h
#define brume_Reconstruction_h

#include "brume/CentroidMatching.h"
#include "brume/DensityEstimation.h"
#include "brume/DirectTexture.h"
#include "brume/DirectionalRadiance.h"
#include "brume/Histogram.h"
#include "brume/HitArrays.h"
#include "brume/HitBinning.h"
#include "brume/KeptHits.h"
#include "brume/NativeMediumGrid.h"
#include "brume/ObjectDistribution.h"
#include "brume/ObjectLayout.h"
#include "brume/Parallel.h"
#include "brume/Resolution.h"
#include "brume/Scene.h"
#include "brume/SummedAreaTable.h"
#include "brume/SurfaceChart.h"

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace brume
{

class DirectLight;

/// How an object's texture is made; set before Build().
struct ObjectOptions
{
  /// Media: whether the texture is matched to where its estimates belong,
  /// its regions' sigma_t-weighted centroids (brume::CentroidMatching), or
  /// holds the estimates as they are.
  bool CentroidMatching = true;
  /**
   * Sharp glossy surfaces: the Phong lobes that brume::MirrorReflection
   * casts (exponent at least its CastExponent) are left out of the
   * particles' estimate, which keeps the diffuse part; the direct light of
   * delta lights (ComputeDirect()) keeps the whole BRDF, since cast rays
   * cannot meet a point. Only where every delta light's direct light is
   * computed (or there is none).
   */
  bool LobeCast = false;
  /**
   * The flux one particle of the run carries (the run's emitted power per
   * particle), which sets the quantum of the histograms' exact sums to
   * about 2^-40 of it (ExactHistogram::QuantumExponent) at the next Build()
   * or Add(). 0: the largest flux among the hits of Build() (of all
   * processes' hits, with a reduction), scaled by Add(); then a Build() and
   * Add()s are bitwise one Build() only when the largest flux is among the
   * first hits. vtkBrumeRadianceReconstruction sets it.
   */
  double ParticleFlux = 0.0;
  /**
   * The share of the run's particles binned once the next Build() or Add()
   * is done (1: the whole run). A view-dependent object whose hits wait for
   * the run's last batch makes room for the whole run's at the first batch,
   * from the hits it holds and this share, instead of growing by doubling:
   * each growth would copy the hits held so far into fresh pages.
   */
  double RunShare = 1.0;
  /**
   * A view-independent object (or a fixed view) bins its hits on every
   * thread of the ParallelFor it is given, each adding atomically into the
   * same exact sums (the same bits), instead of on the calling thread.
   * For a caller that builds one object with many hits on every thread
   * rather than each object on one (vtkBrumeRadianceTextures).
   */
  bool BinOnEveryThread = false;
  /**
   * Media: the bytes the density's grid at its own resolution may take
   * (NativeMediumGrid::Sample()); past them it is coarsened.
   * vtkBrumeRadianceReconstruction derives it from the machine's memory.
   */
  std::size_t NativeMemory = NativeMediumGrid::DefaultMemory;
};

/// A texture as a renderer reads it: RGB per texel, x fastest (surfaces
/// L_o, media the source radiance S), and a medium's sigma_t (RGB).
struct TextureView
{
  const std::array<int, 3>& Dims;
  const std::vector<float>& Radiance;
  const std::vector<float>& Extinction;
};

/// The radiance texture of one object, kept for cheap view updates.
class ObjectRadiance
{
public:
  ObjectRadiance(
    const Surface& surface, SurfaceChart chart, std::array<int, 2> resolution, int refinement);
  ObjectRadiance(const Medium& medium, std::array<int, 3> resolution, int refinement);

  /// The object, its resolutions and how it scatters.
  const ObjectLayout& GetLayout() const { return this->Layout; }
  ObjectOptions& Options() { return this->Settings; }
  const ObjectOptions& Options() const { return this->Settings; }

  /**
   * One viewpoint only. A view-dependent object keeps its hits (40 bytes
   * each, up to 48: KeptHit) so that a new eye re-weights them (UpdateView(),
   * BuildDirectional()). Fixed toward `eye`, it bins each hit's flux
   * weighted toward that eye as the hit comes, as a view-independent object
   * bins its flux: nothing grows with its hits, batch after batch of a run,
   * and its texture is bitwise the one its kept hits give toward the same
   * eye (the same terms, in exact sums). Build() and Add() must then be
   * toward `eye`; UpdateView() toward another eye and BuildDirectional() are
   * refused. Call before Build(); no effect on view-independent objects.
   */
  void FixView(const Vec3& eye);
  /// The histograms behind the current textures, the view fixed or not,
  /// the hits kept.
  const HitBinning& GetBinning() const { return this->Binning; }

  /// Distributed runs: the reduction and the owner (brume/ObjectDistribution.h).
  ObjectDistribution& Distribution() { return this->Distributed; }
  const ObjectDistribution& Distribution() const { return this->Distributed; }

  /**
   * Bins the object's hits (`count` indices into `hits`) and estimates the
   * texture toward `eye`. Empty on success, otherwise what is wrong.
   * With `estimate` false the hits are only binned: the texture is
   * estimated by a later Add() (batches of one run: only the last batch's
   * Add() estimates).
   */
  std::string Build(const HitArrays& hits, const std::uint32_t* index, std::size_t count,
    const Vec3& eye, double thresholdFlux, const ParallelFor& parallelFor, bool estimate = true);
  /**
   * Build() in two halves, which may run on different threads: BuildHits()
   * bins (a view fixed toward another eye is an error, as in Build()),
   * Finish() estimates the texture after a BuildHits() with `estimate`
   * that returned no error. A caller bins an object with many hits on
   * every thread, then estimates it beside the others, one thread each.
   */
  std::string BuildHits(const HitArrays& hits, const std::uint32_t* index, std::size_t count,
    const Vec3& eye, double thresholdFlux, const ParallelFor& parallelFor, bool estimate = true);
  std::string Finish(const Vec3& eye, const ParallelFor& parallelFor);

  /**
   * Build() in its four steps, for a distributed run that builds many
   * objects: BuildHistograms() bins this process's hits (no communication
   * when ObjectOptions::ParticleFlux is set, so objects may bin
   * concurrently); SumHistograms() sums them across the processes (every
   * process, object by object in the same order); EstimateTexture()
   * estimates where Distribution().EstimatesHere() (objects concurrently)
   * and does on every process what the output needs of the object itself
   * (a medium's extinction); ShareTexture() gives the owner's texture to
   * every process (every process, in the same order). Doing each step for
   * every object before the next lets the owners estimate at once instead
   * of in turn. Build() is the four in a row; with `estimate` false, the
   * first alone (a batch of a run: a view-dependent object's hits then
   * wait, unmerged, for the batch that estimates).
   */
  std::string BuildHistograms(const HitArrays& hits, const std::uint32_t* index, std::size_t count,
    double thresholdFlux, const ParallelFor& parallelFor, bool estimate = true);
  void SumHistograms(const Vec3& eye, const ParallelFor& parallelFor);
  /// Empty, or what is wrong (a term beyond the exact sums' bound).
  std::string EstimateTexture(const ParallelFor& parallelFor);
  void ShareTexture(const ParallelFor& parallelFor);

  /**
   * Progressive refinement: adds more particles' hits to the histograms of
   * Build() (and earlier Add() calls) instead of starting over. The hits
   * already binned are multiplied by `scale` (old particle count / new
   * count, since every particle's flux is normalized by the count), then the
   * new hits are binned after them, and the regions are regrown with
   * `thresholdFlux`. When the count grows by a power of two (scale 1/2,
   * 1/4, ...) and the new hits are those of the particles that follow, the
   * histograms are bitwise those of one Build() with all the hits. The
   * batches of one run are added with scale 1, `estimate` false but for
   * the last. Not with a reduction.
   */
  std::string Add(const HitArrays& hits, const std::uint32_t* index, std::size_t count,
    double scale, const Vec3& eye, double thresholdFlux, const ParallelFor& parallelFor,
    bool estimate = true);

  /// Empty when Build() or Add() would accept these hits, otherwise why not.
  std::string Check(const HitArrays& hits, const std::uint32_t* index, std::size_t count) const;

  /// Re-weights the kept hits toward `eye` and re-estimates (view-dependent
  /// objects). Empty, or why not (a view fixed toward another eye).
  std::string UpdateView(const Vec3& eye, const ParallelFor& parallelFor);

  /**
   * Deterministic single scattering (brume/DirectTexture.h), where
   * DirectTexture::Supports() the object. Call before Build(): the object
   * then leaves out every particle's first interaction after a point, spot
   * or directional light (the hits must carry Emitter and Depth), and once
   * ComputeDirect() has run, its output (GetOutput()) is the texture
   * resampled on a grid of `resolution` texels plus, per texel, the direct
   * light of those lights. `light` is not owned.
   */
  void EnableDirect(const DirectLight* light, const std::array<int, 3>& resolution);
  /**
   * The shadow ray of every light at every output texel, once per build;
   * needs the media's grids on the DirectLight (DirectLight::SetMediumGrid)
   * and the texture built. Re-evaluated toward each new eye by UpdateView().
   */
  void ComputeDirect(const ParallelFor& parallelFor);
  /// The same, taking `kept` arrivals (DirectTexture::Compute()) where given.
  void ComputeDirect(const ParallelFor& parallelFor, const std::vector<float>* kept);
  const DirectTexture& GetDirect() const { return this->Direct; }

  /**
   * Anisotropic media: per voxel, the spherical-harmonics projection up to
   * `order` (at most MaxShOrder) of the directions of travel of the light
   * received (brume/DirectionalRadiance.h). Regions are those of the
   * per-view textures. Kept up to date by Add().
   */
  std::string BuildDirectional(int order, const ParallelFor& parallelFor);
  const DirectionalRadiance& GetDirectional() const { return this->Directional; }

  /**
   * Heterogeneous media: the density at its own resolution
   * (brume/NativeMediumGrid.h), sampled once per object, which the integral
   * of sigma_t the texture is normalized by is summed from. Empty for
   * homogeneous media and surfaces.
   */
  const NativeMediumGrid& GetNative() const { return this->Native; }
  /**
   * Media: what the output needs of the medium itself, independent of the
   * particles and the view: sigma_t per texel and the density at its own
   * resolution (GetNative()), with ObjectOptions::NativeMemory. Made once,
   * by the first estimate where not before; a scene's objects are built
   * concurrently, one thread each, so the driver samples its media first,
   * one after the other on every thread. No effect on surfaces.
   */
  void SampleMedium(const ParallelFor& parallelFor);
  /**
   * A grid an earlier object of the same scalar field sampled
   * (NativeMediumGrid::SameField()), before an edit of its transfer
   * function: SampleMedium() takes from it what the edit left as it was
   * (NativeMediumGrid::Sample()), then lets it go.
   */
  void OfferNative(NativeMediumGrid&& previous);
  /// The grid, moved out for the next object of the same medium (empty after).
  NativeMediumGrid ReleaseNative() { return std::move(this->Native); }

  /// The texture the particles give: GetLayout().Resolution texels.
  TextureView GetTexture() const
  {
    return { this->Layout.Resolution, this->Radiance, this->Extinction };
  }
  /// What a renderer shows: a mirror's reflection; with direct light, the
  /// output grid's texels; otherwise the texture's.
  TextureView GetOutput() const
  {
    const TextureView unreflected = this->GetUnreflected();
    return this->Reflected.empty()
      ? unreflected
      : TextureView{ this->ReflectedDims, this->Reflected, unreflected.Extinction };
  }
  /// The output without the reflection.
  TextureView GetUnreflected() const
  {
    return this->Direct.HasArrivals() ? TextureView{ this->Direct.GetDims(),
      this->Direct.GetRadiance(), this->Direct.GetExtinction() }
                                      : this->GetTexture();
  }
  /**
   * Mirrors: the texture toward the eye that brume::MirrorReflection cast
   * (RGB per texel of `dims`, x fastest), which the output then is; an
   * empty `radiance` removes it. The object's own texture keeps what the
   * particles give it: its emission.
   */
  void SetReflected(std::vector<float> radiance, const std::array<int, 3>& dims);

  /**
   * The buffers of the hits this object keeps, emptied (their capacity
   * kept), for the same object of a later build: a rebuild after new hits
   * (another seed or count) then writes its kept hits where the last
   * build's were, their pages already mapped (a fresh page costs a fault on
   * first touch). The object keeps none afterwards.
   */
  KeptHits ReleaseKeptMemory();
  /**
   * Takes buffers ReleaseKeptMemory() gave, where this object keeps hits
   * and they hold room for no more than twice its `hits`, four thousand at
   * least; otherwise they are freed. Call before Build().
   */
  void ReuseKeptMemory(KeptHits&& memory, std::size_t hits);

private:
  // The source radiance of a medium's region, per unit of the reduced
  // extinction (MediumScattering::GetExtinctionFactor(directional)).
  void ToRadiance(
    std::size_t texel, const Region& region, const double* sum, float* out, bool directional) const;
  void Estimate(const ParallelFor& parallelFor);
  void BuildAreaTable();
  // Sums one histogram, or two as one message, across the processes,
  // noting a term clamped in either.
  void Reduce(ExactHistogram& a, ExactHistogram* b = nullptr);
  // The output toward the current eye, where there is direct light.
  void CombineDirect(const ParallelFor& parallelFor);

  ObjectLayout Layout;
  ObjectOptions Settings;
  HitBinning Binning;
  ObjectDistribution Distributed;
  NativeMediumGrid Native;
  std::unique_ptr<NativeMediumGrid> PreviousNative; // OfferNative()'s, until sampled
  DirectTexture Direct;
  DirectionalRadiance Directional;

  SummedAreaTable WeightTable;  // incident flux (mean over channels) a half: drives the growth
  SummedAreaTable ValueTable;   // weighted flux, RGB a half
  SummedAreaTable AreaTable;    // surfaces: world area per cell
  CentroidMatching Matching;    // media: the regions' centroids
  std::vector<float> Reflected; // mirrors
  std::array<int, 3> ReflectedDims{ 0, 0, 0 };
  Vec3 Eye;
  // Per texel, view independent: the region each half's hits grow
  // (HitHalf()), over which the other half's are averaged.
  std::vector<std::array<Region, 2>> Regions;
  double ThresholdFlux = 0.0;

  std::vector<float> Radiance;
  std::vector<float> Extinction;
  bool Built = false;     // Build() binned hits
  bool Estimated = false; // the texture was estimated from them
};

} // namespace brume

#endif
