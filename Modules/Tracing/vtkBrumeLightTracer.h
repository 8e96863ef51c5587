// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeLightTracer
 * @brief   phase 1: Monte Carlo light tracing from the scene's emitters
 *
 * Jimenez & Pueyo (2003), section 2. Particles leave the emissive surfaces in
 * proportion to their power, are reflected by Lambertian surfaces (Embree ray
 * casting) and scattered by homogeneous media (exact free-flight sampling,
 * Henyey-Greenstein phase sampling), with Russian roulette. Every interaction
 * is stored: the output vtkPolyData holds one point per hit with the arrays
 * documented in vtkBrumeSceneConversion (48 bytes per hit internally).
 *
 * Input: a scene collection (vtkBrumeSceneConversion) and, optionally,
 * vtkLight objects. Output: the hits, plus field data with the run's energy
 * balance (`EmittedFlux`, `AbsorbedFlux`, `EscapedFlux`, `TruncatedFlux`,
 * `EstimatorNetFlux`, W per channel; emitted = the sum of the others) and
 * `NumberOfRays`.
 *
 * Memory: hits are appended batch by batch to the output arrays (45 bytes
 * per hit), so the peak stays near 49 bytes per stored hit. An execution
 * writes its hits into the buffers of the last output's arrays (the next
 * batch of a run, or a new run after a change of seed, count or scene), so
 * that re-tracing does not pay the first touch of fresh memory again: the
 * arrays free their buffers through the tracer, and a buffer VTK frees
 * while the output lets go of its data, just before the execution, comes
 * back to it (a much smaller run keeps room for at most twice the hits a
 * particle of the last run stored, four at least). A buffer still referenced, by an array a
 * consumer holds or one sharing its vtkBuffer (vtkDataArray::ShallowCopy), is never freed, so never
 * written; the tracer holds none of them between executions, and one freed then (ReleaseDataFlag)
 * is freed indeed.
 *
 * Particles are traced in fixed blocks with vtkSMPTools; each particle's
 * random stream depends only on (Seed, particle index), so the output is
 * identical whatever the number of threads. Piece requests (UpdatePiece,
 * or a parallel ParaView pipeline with one piece per process) split the
 * particles: piece p of P traces the p-th consecutive share, and the pieces
 * together are exactly the one-piece run (field data `PieceParticles`).
 *
 * @sa vtkBrumeDefaultSceneSource vtkBrumeRadianceReconstruction
 */
#ifndef vtkBrumeLightTracer_h
#define vtkBrumeLightTracer_h

#include "vtkBrumeTracingModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"
#include "vtkSmartPointer.h" // For Lights

#include <memory> // For the reused batch memory
#include <vector> // For Densities

class vtkLight;
class vtkLightCollection;
class vtkBrumeLightTracerOutput;
struct vtkBrumeLightTracerReturnedBuffers;
namespace brume
{
class DensityField;
class LightTracer;
struct TraceCounters;
}

class VTKBRUMETRACING_EXPORT vtkBrumeLightTracer : public vtkPolyDataAlgorithm
{
public:
  static vtkBrumeLightTracer* New();
  vtkTypeMacro(vtkBrumeLightTracer, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Number of particles emitted (default 1,000,000). Must be in
   * [1, 10^10]; the expected memory of the hits is checked before tracing.
   */
  vtkSetMacro(NumberOfParticles, vtkTypeInt64);
  vtkGetMacro(NumberOfParticles, vtkTypeInt64);
  ///@}

  ///@{
  /**
   * Progressive tracing: trace only the particles [FirstParticle,
   * EndParticle) of a run of NumberOfParticles (defaults 0 and 0: all, the
   * end being NumberOfParticles). Each particle's flux is normalized by
   * NumberOfParticles, so these hits are exactly that part of the full
   * run's; vtkBrumeRadianceReconstruction with AccumulateParticles adds
   * them to the hits it already holds. Two uses:
   * - progressive refinement: [old count, NumberOfParticles) after a run of
   *   the old count (the particles already binned are rescaled);
   * - batches: [0, B), [B, 2B), ... of one run, so that only one batch's
   *   hits are in memory at a time (see vtkBrumeRadianceReconstruction).
   * The output's field data records `FirstParticle`, `EndParticle` and `Seed`.
   */
  vtkSetMacro(FirstParticle, vtkTypeInt64);
  vtkGetMacro(FirstParticle, vtkTypeInt64);
  vtkSetMacro(EndParticle, vtkTypeInt64);
  vtkGetMacro(EndParticle, vtkTypeInt64);
  ///@}

  ///@{
  /// Seed of the particles' random streams (default 0, non-negative).
  vtkSetMacro(Seed, vtkIdType);
  vtkGetMacro(Seed, vtkIdType);
  ///@}

  ///@{
  /**
   * Interactions after which a particle is stopped (default 1024, in
   * [1, 10^6]); Russian roulette normally ends particles long before.
   */
  vtkSetClampMacro(MaximumDepth, int, 1, 1000000);
  vtkGetMacro(MaximumDepth, int);
  ///@}

  ///@{
  /**
   * Interactions after which Russian roulette may end a particle (default 3).
   * A value above MaximumDepth turns Russian roulette off.
   */
  vtkSetClampMacro(RouletteDepth, int, 0, 1000001);
  vtkGetMacro(RouletteDepth, int);
  ///@}

  ///@{
  /**
   * Fraction of a directional light's particles aimed at the part of its
   * beam that reaches the scene's media (brume::AimAtMedia: pilot rays),
   * where that part covers at most a quarter of the beam: a cloud over a
   * wide ground, or the haze of a room the sun enters through a window,
   * gets the particles the ground or the walls would otherwise take, and
   * every flux is weighted so that the light is the same. The hits then
   * carry the point array `Aim` and the field array `AimWeights`, with which the reconstruction
   * sizes the textures as a uniform emission would have and grows its regions as if every particle
   * weighed alike. Default 0.2 (measured best among 0.1-0.8 on the clouds
   * and the dragon: more leaves the ground's fewer, heavier particles to
   * carry the light it reflects into the medium); 0 emits every beam
   * uniformly. In [0, 0.99].
   */
  vtkSetClampMacro(MediumAimFraction, double, 0.0, 0.99);
  vtkGetMacro(MediumAimFraction, double);
  ///@}

  ///@{
  /**
   * Under an aimed light, a particle emitted outside the aimed disk weighs
   * w1 / w2 aimed particles (`AimWeights`); where its next segment crosses
   * a medium's box before a surface (the sun's light the ground reflects
   * into a cloud), it splits into that many aimed particles, each of its
   * flux / (w1 / w2) on a random stream of its own, at most
   * brume::MaxSplit (brume::TraceSettings::SplitHeavyParticles). Unbiased:
   * the medium's light is no longer carried by a few heavy particles.
   * Default on; off, aimed runs are traced as before.
   */
  vtkSetMacro(SplitHeavyParticles, bool);
  vtkGetMacro(SplitHeavyParticles, bool);
  vtkBooleanMacro(SplitHeavyParticles, bool);
  ///@}

  ///@{
  /**
   * Point, spot and directional lights, in addition to the emissive surfaces
   * of the scene (see vtkBrumeSceneConversion::ConvertLights for units).
   */
  void AddLight(vtkLight* light);
  void RemoveAllLights();
  vtkLightCollection* GetLights();
  ///@}

  ///@{
  /**
   * Memory the stored hits may take, in bytes (default 8 GiB). The tracer
   * refuses particle counts whose expected hits would not fit
   * (ExpectedHitBytes() of the particles it traces at once): trace larger
   * runs in batches (FirstParticle, EndParticle).
   */
  vtkSetMacro(MemoryLimit, vtkTypeInt64);
  vtkGetMacro(MemoryLimit, vtkTypeInt64);
  /// What the hits of `particles` particles are expected to take, in bytes:
  /// four hits a particle (the default scene stores 2.7).
  static double ExpectedHitBytes(vtkTypeInt64 particles);
  ///@}

  vtkMTimeType GetMTime() override;

  /// Rays cast by the last execution (for benchmarks).
  vtkGetMacro(LastRayCount, vtkTypeInt64);

  /**
   * Bytes of the last output's hit arrays that the last execution wrote its
   * hits into again (for benchmarks and tests): those whose buffers VTK
   * freed, no array referencing them any more, when the output let go of
   * them just before the execution.
   */
  vtkGetMacro(LastReusedBytes, vtkTypeInt64);

  /// Lets the output go of its data just before an execution, taking back
  /// the hit buffers that no one references any more.
  vtkTypeBool ProcessRequest(
    vtkInformation* request, vtkInformationVector** inInfo, vtkInformationVector* outInfo) override;

protected:
  vtkBrumeLightTracer();
  ~vtkBrumeLightTracer() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  vtkTypeInt64 NumberOfParticles = 1000000;
  vtkTypeInt64 FirstParticle = 0;
  vtkTypeInt64 EndParticle = 0;
  vtkIdType Seed = 0;
  int MaximumDepth = 1024;
  int RouletteDepth = 3;
  double MediumAimFraction = 0.2;
  bool SplitHeavyParticles = true;
  vtkTypeInt64 MemoryLimit = vtkTypeInt64(8) << 30;
  vtkTypeInt64 LastRayCount = 0;
  vtkTypeInt64 LastReusedBytes = 0;
  double LastHitsPerParticle = 0.0;
  vtkSmartPointer<vtkLightCollection> Lights;

private:
  // Between the batches of one run: the block buffers, reused by the next
  // batch (their pages already mapped).
  struct BatchMemory;
  // The particles of a run and of this piece: [First, End) of Particles,
  // this piece's [PieceFirst, PieceEnd).
  struct ParticleRange
  {
    vtkTypeInt64 Particles = 0, First = 0, End = 0, PieceFirst = 0, PieceEnd = 0;
  };
  bool PlanParticles(vtkInformation* outInfo, ParticleRange& range);
  bool TraceBatches(const brume::LightTracer& tracer, const ParticleRange& range,
    BatchMemory& memory, vtkBrumeLightTracerOutput& out, brume::TraceCounters& sum,
    vtkIdType& stored);
  std::unique_ptr<BatchMemory> Reused;
  // The output's hit buffers that came back when it let go of them, for the
  // execution that follows to write into (their pages already mapped).
  std::unique_ptr<vtkBrumeLightTracerReturnedBuffers> Returned;
  // The last trace's media's densities, held until the next: the
  // reconstruction that follows converts the same scene and finds the same
  // OpenVDB grid instead of reading its file again (vtkBrumeSceneConversion
  // keeps a grid while someone holds it).
  std::vector<std::shared_ptr<const brume::DensityField>> Densities;

  vtkBrumeLightTracer(const vtkBrumeLightTracer&) = delete;
  void operator=(const vtkBrumeLightTracer&) = delete;
};

#endif
