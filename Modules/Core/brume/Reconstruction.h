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
#ifndef brume_Reconstruction_h
#define brume_Reconstruction_h

#include "brume/BrickedGrid.h"
#include "brume/CentroidMatching.h"
#include "brume/DensityEstimation.h"
#include "brume/ExactHistogram.h"
#include "brume/Grouping.h"
#include "brume/Histogram.h"
#include "brume/HistogramReduction.h"
#include "brume/HitArrays.h"
#include "brume/Parallel.h"
#include "brume/Resolution.h"
#include "brume/Sampling.h"
#include "brume/Scene.h"
#include "brume/SurfaceChart.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace brume
{
class OpacityTransferFunction;

class DirectLight;

/// The radiance texture of one object, kept for cheap view updates.
class ObjectRadiance
{
public:
  ObjectRadiance(
    const Surface& surface, SurfaceChart chart, std::array<int, 2> resolution, int refinement);
  ObjectRadiance(const Medium& medium, std::array<int, 3> resolution, int refinement);

  /// Glossy surfaces and anisotropic media change with the viewpoint.
  bool IsViewDependent() const { return this->ViewDependent; }

  /**
   * One viewpoint only. A view-dependent object keeps its hits (40 bytes
   * each, up to 48: KeptHits) so that a new eye re-weights them (UpdateView(),
   * BuildDirectional()). Fixed toward `eye`, it bins each hit's flux
   * weighted toward that eye as the hit comes, as a view-independent object
   * bins its flux: nothing grows with its hits, batch after batch of a run,
   * and its texture is bitwise the one its kept hits give toward the same
   * eye (the same terms, in exact sums). Build() and Add() must then be
   * toward `eye`; UpdateView() toward another eye and BuildDirectional() are
   * refused. Call before Build(); no effect on view-independent objects.
   */
  void FixView(const Vec3& eye);
  bool IsViewFixed() const { return this->ViewFixed; }
  const Vec3& GetFixedEye() const { return this->FixedEye; }
  /// Whether the object keeps its hits for later views.
  bool KeepsHits() const { return this->ViewDependent && !this->ViewFixed; }

  /**
   * Strongly forward-scattering media: the phase function's peak beyond an
   * asymmetry the representation resolves is set apart (SplitForwardPeak in
   * brume/Sampling.h): ResolvedG for the per-view textures (directional
   * false), DirectionalResolvedG for the directional representation (true),
   * whose three bands lose more of a peaked phase function than the delta
   * approximation does. The texture then holds the light in-scattered by
   * the remainder, HG(GetPeak(directional).G), which rests on many particles
   * where HG(g) rests on the few travelling almost straight at the eye, and
   * the peak is drawn as transport: a renderer multiplies the medium's
   * sigma_t by GetExtinctionFactor(directional) (1 - Forward albedo per
   * channel), and the source radiance (GetOutputRadiance(), or
   * GetDirectional() evaluated with that G) is per unit of that reduced
   * extinction. Without a split (g at most the resolved asymmetry,
   * surfaces) the factor is 1.
   */
  static constexpr float ResolvedG = 0.7f;
  static constexpr float DirectionalResolvedG = 0.6f;
  const ForwardPeak& GetPeak(bool directional) const { return this->Peaks[directional ? 1 : 0]; }
  const Vec3& GetExtinctionFactor(bool directional) const
  {
    return this->ExtinctionFactors[directional ? 1 : 0];
  }

  /**
   * A medium whose albedo varies (Medium::AlbedoFactor) cannot fold it into
   * its texture: the albedo may step inside a texel where the light does
   * not. Its texture (GetOutputRadiance(), GetDirectional()) then holds the
   * source radiance X of an albedo of 1 with no peak set apart, and a
   * renderer applies the albedo a(x) where it draws: the emission is
   * sigma_t a X and the extinction sigma_t (1 - a Forward), Forward being
   * GetPeak(directional).Forward; GetExtinctionFactor() is then 1.
   * SourceAt() gives the source radiance S per unit of that extinction and
   * its factor, for any medium.
   */
  bool HasVaryingAlbedo() const { return this->AlbedoVaries; }
  Vec3 SourceAt(const Vec3& albedo, const Vec3& texel, bool directional, Vec3& factor) const;

  /**
   * Deterministic single scattering (brume/DirectLight.h), for media and
   * for planar surfaces without mirrors (SupportsDirect(); per-triangle
   * materials reflect it at each output texel by the triangle there).
   * Call before Build(): the object then leaves out every particle's first
   * interaction after a point, spot or directional light (the hits must
   * carry Emitter and Depth), and once ComputeDirect() has run, its output
   * (GetOutputRadiance()) is the texture resampled on a grid of
   * `resolution` texels plus, per texel, the direct light of those lights.
   * `light` is not owned.
   */
  void EnableDirect(const DirectLight* light, const std::array<int, 3>& resolution);
  bool SupportsDirect() const;
  bool IsDirectEnabled() const { return this->Direct != nullptr; }
  /**
   * The shadow ray of every light at every output texel, once per build;
   * needs the media's grids on the DirectLight (DirectLight::SetMediumGrid)
   * and the texture built. Re-evaluated toward each new eye by UpdateView().
   */
  void ComputeDirect(const ParallelFor& parallelFor);
  bool HasDirect() const { return !this->Arrivals.empty(); }

  /**
   * Mirrors: the texture toward the eye that brume::MirrorReflection cast
   * (RGB per texel of `dims`, x fastest), which the output then is; an
   * empty `radiance` removes it. The object's own texture (GetRadiance())
   * keeps what the particles give it: its emission.
   */
  void SetReflected(std::vector<float> radiance, const std::array<int, 3>& dims);
  bool HasReflected() const { return !this->Reflected.empty(); }
  /// The output without the reflection: with direct light, the output
  /// grid's texels, otherwise the texture's.
  const std::vector<float>& GetUnreflectedRadiance() const
  {
    return this->HasDirect() ? this->DirectRadiance : this->Radiance;
  }
  const std::array<int, 3>& GetUnreflectedResolution() const
  {
    return this->HasDirect() ? this->DirectDims : this->Resolution;
  }

  /**
   * Sharp glossy surfaces: the Phong lobes that brume::MirrorReflection
   * casts (exponent at least its CastExponent) are left out of the
   * particles' estimate, which keeps the diffuse part; the direct light of
   * delta lights (ComputeDirect()) keeps the whole BRDF, since cast rays
   * cannot meet a point. Call before Build(); only where every delta
   * light's direct light is computed (or there is none).
   */
  void SetLobeCast(bool cast) { this->LobeCast = cast; }
  bool IsLobeCast() const { return this->LobeCast; }

  /// Media: whether the texture is matched to where its estimates belong,
  /// its regions' sigma_t-weighted centroids (brume::CentroidMatching; the
  /// default), or holds the estimates as they are. Call before Estimate().
  void SetCentroidMatching(bool match) { this->MatchingCentroids = match; }
  bool GetCentroidMatching() const { return this->MatchingCentroids; }

  /// What a renderer shows: a mirror's reflection; with direct light, the
  /// output grid's texels (RGB, x fastest; media: the source radiance and
  /// sigma_t); otherwise the texture's (GetResolution(), GetRadiance(),
  /// GetExtinction()).
  const std::array<int, 3>& GetOutputResolution() const
  {
    return this->HasReflected() ? this->ReflectedDims
                                : (this->HasDirect() ? this->DirectDims : this->Resolution);
  }
  const std::vector<float>& GetOutputRadiance() const
  {
    return this->HasReflected() ? this->Reflected
                                : (this->HasDirect() ? this->DirectRadiance : this->Radiance);
  }
  const std::vector<float>& GetOutputExtinction() const
  {
    return this->HasDirect() ? this->DirectExtinction : this->Extinction;
  }

  /**
   * Distributed runs: every histogram this object builds from now on is
   * summed across processes through `reduction` (not owned; null: this
   * process holds every hit). Progressive Add() is not supported with one.
   */
  void SetReduction(HistogramReduction* reduction) { this->Reduction = reduction; }

  /**
   * Distributed runs: the process that estimates this object's texture
   * (SetOwner(r)), or every process (-1, the default). With an owner the
   * histograms are summed onto it alone; it alone builds the summed-area
   * tables, grows the regions and estimates, then gives the texture (and a
   * directional projection) to every process, bit for bit: every process
   * ends with the texture one process holding every hit would make, while
   * the per-texel work and the reduction's traffic are shared out. The
   * histograms and regions are then held by the owner only
   * (GetWeightHistogram() is empty elsewhere).
   */
  void SetOwner(int rank) { this->Owner = rank; }
  int GetOwner() const { return this->Owner; }
  /// Whether this process estimates the texture: always without a
  /// reduction or an owner.
  bool EstimatesHere() const;
  /**
   * What estimating the texture costs, about, in units of one homogeneous
   * medium's histogram cell: the summed-area tables (and a surface's
   * areas) per cell, a region per texel (AssignOwners() shares the objects
   * out by it). It depends on the resolutions alone, which every process
   * of a run chooses alike.
   */
  double EstimateCost() const;

  /**
   * The flux one particle of the run carries (the run's emitted power per
   * particle), which sets the quantum of the histograms' exact sums to
   * about 2^-40 of it (ExactHistogram::QuantumExponent) at the next Build()
   * or Add(). 0 (the default): the largest flux among the hits of Build()
   * (of all processes' hits, with a reduction), scaled by Add(); then a
   * Build() and Add()s are bitwise one Build() only when the largest flux
   * is among the first hits. vtkBrumeRadianceReconstruction sets it.
   */
  void SetParticleFlux(double flux) { this->ParticleFlux = flux; }

  /**
   * The share of the run's particles binned once the next Build() or Add()
   * is done (1, the default: the whole run). A view-dependent object whose
   * hits wait for the run's last batch makes room for the whole run's at
   * the first batch, from the hits it holds and this share, instead of
   * growing by doubling: each growth would copy the hits held so far into
   * fresh pages.
   */
  void SetRunShare(double share) { this->RunShare = share; }

  /**
   * Bins the object's hits (`count` indices into `hits`) and estimates the
   * texture toward `eye`. Empty on success, otherwise what is wrong.
   * With `estimate` false the hits are only binned: the texture is
   * estimated by a later Add() (batches of one run: only the last batch's
   * Add() estimates, IsEstimated() says whether it was).
   */
  std::string Build(const HitArrays& hits, const std::uint32_t* index, std::size_t count,
    const Vec3& eye, double thresholdFlux, const ParallelFor& parallelFor, bool estimate = true);

  /**
   * Build() in its four steps, for a distributed run that builds many
   * objects: BuildHistograms() bins this process's hits (no communication
   * when SetParticleFlux() is set, so objects may bin concurrently);
   * SumHistograms() sums them across the processes (every process, object
   * by object in the same order); EstimateTexture() estimates where
   * EstimatesHere() (objects concurrently) and does on every process what
   * the output needs of the object itself (a medium's extinction);
   * ShareTexture() gives the owner's texture to every process (every
   * process, in the same order). Doing each step for every object before
   * the next lets the owners estimate at once instead of in turn. Build()
   * is the four in a row; with `estimate` false, the first alone (a
   * batch of a run: a view-dependent object's hits then wait, unmerged,
   * for the batch that estimates).
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
   * the last.
   */
  std::string Add(const HitArrays& hits, const std::uint32_t* index, std::size_t count,
    double scale, const Vec3& eye, double thresholdFlux, const ParallelFor& parallelFor,
    bool estimate = true);
  /// Whether the texture was estimated (by Build() or Add()) since Build().
  bool IsEstimated() const { return this->Estimated; }

  /// Empty when Build() or Add() would accept these hits, otherwise why not.
  std::string Check(const HitArrays& hits, const std::uint32_t* index, std::size_t count) const;

  /// Re-weights the kept hits toward `eye` and re-estimates (view-dependent
  /// objects). Empty, or why not (a view fixed toward another eye).
  std::string UpdateView(const Vec3& eye, const ParallelFor& parallelFor);

  /**
   * Anisotropic media: per voxel, the spherical-harmonics projection up to
   * `order` (at most MaxShOrder) of the directions of travel of the light
   * received, normalized as the source radiance, so that the source radiance
   * toward any direction w_o is sum_lm g^l c_lm Y_lm(w_o) (see
   * brume/SphericalHarmonics.h) without reconstructing again; past
   * DirectionalResolvedG, g is GetPeak(true).G and S is per unit of the
   * reduced extinction. Regions are those of the per-view textures. Kept up
   * to date by Add().
   */
  std::string BuildDirectional(int order, const ParallelFor& parallelFor);
  /// -1 before BuildDirectional().
  int GetDirectionalOrder() const { return this->DirectionalOrder; }
  /// (order + 1)^2 RGB coefficients per voxel: [voxel][coefficient][channel].
  const std::vector<float>& GetDirectional() const { return this->Directional; }
  /// The source radiance toward `eye` from the directional representation,
  /// evaluated at voxel centres (clamped at zero), RGB per voxel.
  void EvaluateDirectional(const Vec3& eye, std::vector<float>& radiance) const;

  /// The histograms behind the current textures (incident flux; weighted flux, RGB).
  Histogram GetWeightHistogram() const;
  Histogram GetValueHistogram() const;

  /// RGB per texel, x fastest: surfaces L_o, media the source radiance S.
  const std::vector<float>& GetRadiance() const { return this->Radiance; }
  /// Media: sigma_t (RGB) per voxel.
  const std::vector<float>& GetExtinction() const { return this->Extinction; }

  /**
   * Heterogeneous media: the density per cell of its own grid
   * (brume::DensityField::NativeResolution over NativeBox, whose cell
   * centres are the field's own samples), independent of the texture's
   * resolution, so that a renderer draws the medium's structure (sigma_t =
   * the medium's SigmaT() times the density) at its own resolution with the
   * smooth source radiance of the texture. Each cell holds the density at
   * its centre: interpolated trilinearly, the grid is the field (an OpenVDB
   * grid's trilinear sampler, a point-valued image), not a smoothed copy.
   * Stored in bricks (brume::BrickedGrid): bricks where the density's
   * majorant is 0 are not evaluated and, with bricks of one value, not
   * stored, so memory follows the medium's occupied bricks, not its box.
   * Grids whose occupied bricks would store more than MaxNativeSamples
   * samples, or whose box holds more than MaxNativeBricks bricks or
   * MaxNativeAxis cells along an axis, are coarsened by one integer factor
   * on every axis (the smallest that fits; a coarsened cell averages 2^3
   * samples). The integral of sigma_t the texture is normalized by is summed
   * from this grid. Empty for homogeneous media and surfaces.
   */
  const BrickedGrid& GetNativeDensity() const { return this->NativeDensity; }
  /**
   * A density classified by a transfer function (ClassifiedDensity)
   * also keeps its scalars at the same centres, for a renderer that
   * interpolates them and classifies after, as the tracer does: bricks
   * whose extinction the majorants make 0 hold a scalar the function takes
   * to 0. Empty otherwise, and when the native grid is coarsened (a mean
   * of scalars is not what the function classified). GetClassification()
   * is then the function, else null.
   */
  const BrickedGrid& GetNativeScalars() const { return this->NativeScalars; }
  const OpacityTransferFunction* GetClassification() const { return this->Classification; }
  const std::array<int, 3>& GetNativeResolution() const { return this->NativeDensity.GetDims(); }
  /// The box of the native grid's cells (DensityField::NativeBox(), grown
  /// to whole coarsened cells): it holds the medium's bounds.
  const Box& GetNativeBox() const { return this->NativeDensity.GetBox(); }
  static constexpr std::size_t MaxNativeSamples = std::size_t(1) << 23; // 32 MB
  static constexpr std::size_t MaxNativeBricks = std::size_t(1) << 21;  // 16 MB of table
  static constexpr int MaxNativeAxis = 2048;
  const std::array<int, 3>& GetResolution() const { return this->Resolution; }
  const SurfaceChart& GetChart() const { return this->Chart; }

private:
  // Ranges of histogram cells that view-dependent objects weigh as tasks.
  static constexpr std::size_t Ranges = 64;

  bool FromFront(const HitArrays& hits, std::uint32_t i) const;
  void Bin(const HitArrays& hits, const std::uint32_t* index, std::size_t count,
    const ParallelFor& parallelFor);
  // Bin()'s two ways: view-independent objects add every hit to its cell;
  // view-dependent ones keep their hits by cell.
  template <typename Locator>
  void BinInPlace(
    const HitArrays& hits, const std::uint32_t* index, std::size_t count, const Locator& cellOfHit);
  template <typename Locator>
  void KeepHits(const HitArrays& hits, const std::uint32_t* index, std::size_t count,
    const Locator& cellOfHit, const ParallelFor& parallelFor);
  // Texels of the texture.
  std::size_t Texels() const;
  // The source radiance of a medium's region, per unit of the reduced
  // extinction (GetExtinctionFactor(directional)).
  void ToRadiance(
    std::size_t texel, const Region& region, const double* sum, float* out, bool directional) const;
  // Direct light: the output texel's world position, the sum of the
  // texture resampled there and the direct light toward the eye, and the
  // direct light projected on the directional representation's voxels.
  Vec3 OutputPosition(std::size_t texel) const;
  void CombineDirect(const ParallelFor& parallelFor);
  void LocateDirectTriangles();
  void AddDirectToDirectional(int order);
  // The kept hits' weighted flux toward `eye` into ValueSums, and with
  // `weights` their incident flux into WeightSums (the same for every eye).
  void WeighCells(const Vec3& eye, const ParallelFor& parallelFor, bool weights = false);
  // The flux of a hit arriving at `position` along `direction` weighted
  // toward `eye`: the phase function's remainder (media), or the BRDF of
  // its triangle (surfaces, with `normals` the triangles' unit normals);
  // WeighCells() and a fixed view's binning share it, term for term.
  inline void WeighHit(const Vec3& eye, const float* position, const float* direction,
    const float* flux, std::uint32_t triangle, const std::vector<Vec3>& normals,
    double* value) const;
  std::vector<Vec3> UnitNormals() const;
  // What a view-independent bin or a fixed view's adds for hit i at its cell.
  void AddTerms(const HitArrays& hits, std::uint32_t i, std::uint32_t cell);
  void Estimate(const ParallelFor& parallelFor);
  void BuildAreaTable();
  // Heterogeneous media: the density's integral over each histogram cell
  // (what a region's source radiance is divided by), and sigma_t at the
  // density's own resolution.
  void SampleNativeDensity(const ParallelFor& parallelFor);
  void BuildDensityTable();
  // Media: where each texel's estimate belongs (its region's sigma_t-weighted
  // centroid), for the texture whose interpolation meets it there.
  void FindCentroids(const ParallelFor& parallelFor);

  const Surface* SurfaceRef = nullptr;
  const Medium* MediumRef = nullptr;
  // Surfaces: each triangle's winding normal (not normalized), which
  // FromFront tests every hit against.
  std::vector<Vec3> TriangleNormals;
  SurfaceChart Chart;
  std::array<int, 3> Resolution;
  std::array<int, 3> Dims; // histogram
  int Refinement;
  bool ViewDependent = false;
  bool ViewFixed = false; // FixView(): binned toward FixedEye, no hits kept
  Vec3 FixedEye;
  std::vector<Vec3> FixedNormals; // surfaces with a fixed view: UnitNormals()
  double CellVolume = 0.0;        // media: one histogram cell's volume
  bool AlbedoVaries = false;
  Vec3 MediumAlbedo; // media: sigma_s / sigma_t (1 where it varies)
  // Media: the phase function's peak set apart, per view and directional.
  ForwardPeak Peaks[2];
  Vec3 ExtinctionFactors[2] = { Vec3(1.f), Vec3(1.f) };

public:
  // View-dependent objects keep their hits, grouped by ranges of histogram
  // cells and in hit order within a range: 40 bytes each, 4 more for a
  // surface's triangle (its BRDF toward the eye) and 4 more for the growth
  // scale (HitArrays::GrowthScale) once a light was aimed, kept beside them
  // in the same order, so that a fog under an unaimed light keeps 40.
  struct KeptHit
  {
    float Position[3], Direction[3], Flux[3];
    std::uint32_t Cell;
  };
  static_assert(sizeof(KeptHit) == 40, "KeptHit layout changed: update the documentation");
  template <typename T>
  using Uninitialized = std::vector<T, UninitializedAllocator<T>>;
  struct KeptHits
  {
    Uninitialized<KeptHit> Hits;
    Uninitialized<std::uint32_t> Triangle; // empty, or one per hit
    Uninitialized<float> Growth;           // empty (every scale 1), or one per hit

    std::size_t Size() const { return this->Hits.size(); }
    void Clear()
    {
      this->Hits.clear();
      this->Triangle.clear();
      this->Growth.clear();
    }
    bool Empty() const { return this->Hits.empty(); }
    std::uint32_t TriangleOf(std::size_t k) const
    {
      return this->Triangle.empty() ? 0 : this->Triangle[k];
    }
    float GrowthOf(std::size_t k) const { return this->Growth.empty() ? 1.f : this->Growth[k]; }
    // n hits, the new ones left for the caller to write: with triangles
    // when asked, with growth scales when asked or already kept (the hits
    // kept so far scale 1 when the first aimed ones come).
    void Resize(std::size_t n, bool triangles, bool growth);
    void Reserve(std::size_t n, bool triangles, bool growth);
    // Hit k of `from` into place `to` (its arrays, where this one has them).
    void Set(std::size_t to, const KeptHits& from, std::size_t k)
    {
      this->Hits[to] = from.Hits[k];
      if (!this->Triangle.empty())
      {
        this->Triangle[to] = from.TriangleOf(k);
      }
      if (!this->Growth.empty())
      {
        this->Growth[to] = from.GrowthOf(k);
      }
    }
  };

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
  KeptHits Kept;
  std::vector<std::size_t> RangeStart;
  // Batches that do not estimate: their hits in hit order, merged into
  // Kept's ranges once, by the batch that estimates (merging at every batch
  // would copy every hit kept so far each time).
  KeptHits Pending;
  bool DeferMerge = false;
  void MergePending(const ParallelFor& parallelFor);
  // Merges `count` new hits (cellOf(k), write(k, merged, position)) after
  // Kept's hits of each range of cells, stably; with growth scales where
  // `growth` (the new hits have them) or Kept has them.
  template <typename CellOf, typename Write>
  void MergeIntoRanges(
    std::size_t count, CellOf cellOf, Write write, bool growth, const ParallelFor& parallelFor);

  // The histograms' exact sums (view-independent objects: kept for Add()).
  ExactHistogram WeightSums;
  ExactHistogram ValueSums;

  SummedAreaTable WeightTable;    // incident flux (mean over channels): drives the growth
  SummedAreaTable ValueTable;     // weighted flux, RGB
  SummedAreaTable AreaTable;      // surfaces: world area per cell
  SummedAreaTable DensityTable;   // heterogeneous media: integral of the density per cell
  SummedAreaTable DensityMoments; // and its first moments (histogram-cell coordinates)
  CentroidMatching Matching;      // media: the regions' centroids
  bool MatchingCentroids = true;
  BrickedGrid NativeDensity; // the density's mean per native cell
  BrickedGrid NativeScalars; // a classified density's scalars at the same centres
  const OpacityTransferFunction* Classification = nullptr;
  double EmptyIntegral = 0.0; // regions below hold no medium
  const DirectLight* Direct = nullptr;
  std::array<int, 3> DirectDims{ 0, 0, 0 };
  std::vector<float> Arrivals; // per output texel and light: irradiance RGB, direction
  // Surfaces of per-triangle materials or per-vertex reflectance: the
  // triangle at each output texel's centre (-1 where none), whose material
  // (there) reflects its direct light.
  std::vector<std::int32_t> DirectTriangles;
  std::vector<float> DirectRadiance;
  std::vector<float> DirectExtinction;
  std::vector<float> Reflected; // mirrors
  bool LobeCast = false;
  std::array<int, 3> ReflectedDims{ 0, 0, 0 };
  Vec3 SurfaceNormal; // planar surfaces: the front side
  Vec3 Eye;
  std::vector<Region> Regions; // per texel, view independent
  double ThresholdFlux = 0.0;

  std::vector<float> Radiance;
  std::vector<float> Extinction;
  std::vector<float> Directional;
  int DirectionalOrder = -1;
  HistogramReduction* Reduction = nullptr;
  int Owner = -1;            // -1: every process estimates
  double ParticleFlux = 0.0; // as set
  double RunShare = 1.0;     // as set
  int SumsExponent = 0;      // the exact sums' quantum, 2^SumsExponent
  bool SumsClamped = false;  // a term beyond the exact sums' bound since Build()
  bool Built = false;        // Build() binned hits
  bool Estimated = false;    // the texture was estimated from them

  // Empty unless a term was clamped in the exact sums: why.
  std::string Saturation() const;
  // A new exact histogram of this run's quantum (SumsExponent).
  ExactHistogram NewSums(int channels) const;
  // Distributed runs: this process's share [first, last) of n items (all
  // of them without a reduction), and every process's shares of `data`
  // (`floats` per item) gathered on every process.
  std::array<std::size_t, 2> Share(std::size_t n) const;
  void GatherShares(std::size_t n, std::size_t floats, std::vector<float>& data);
  // Sums one histogram, or two as one message, across the processes when
  // there is a reduction.
  void Reduce(ExactHistogram& a, ExactHistogram* b = nullptr);
};

} // namespace brume

#endif
