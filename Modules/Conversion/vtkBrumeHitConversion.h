// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeHitConversion
 * @brief   the particle-hit schema: stored hits as a vtkPolyData
 *
 * Phase 1 (vtkBrumeLightTracer) hands its hits to phase 2
 * (vtkBrumeRadianceReconstruction) as a vtkPolyData whose points are the hit
 * positions, with the point data
 *
 * - `Direction` (float[3]): the direction of travel on arrival;
 * - `Flux` (float[3], W): the flux carried on arrival, before the surface
 *   reflectance or the medium albedo is applied;
 * - `ObjectId`, `EmitterId` (unsigned short): the scene object (surfaces
 *   first, then media, see vtkBrumeSceneConversion) and the emitter;
 * - `Depth` (unsigned char): interactions before this one;
 * - `TriangleId` (unsigned int): for surface hits, the triangle in the
 *   surface's triangulation (polygons as fans, then strips);
 * - `Aim` (unsigned char, only where a light was aimed at the media,
 *   vtkBrumeLightTracer::MediumAimFraction): where the particle left its
 *   light (brume::Light::SampleEmission: 0 unaimed, 1 outside the aimed
 *   disk, 2 inside it), with the field array `AimWeights` (double[3], one
 *   tuple per emitter id: the weight of each class);
 *
 * and the field data of the run: `TotalPower` (double[3], W),
 * `NumberOfParticles` (the run's particle count), and where the tracer
 * wrote them `FirstParticle` and `EndParticle` (the run's particles
 * [first, end) these hits come from: a progressive step or a batch), `Seed`
 * and `PieceParticles` ([first, end) of a distributed piece).
 *
 * @sa vtkBrumeSceneConversion vtkBrumeRadianceConversion
 */
#ifndef vtkBrumeHitConversion_h
#define vtkBrumeHitConversion_h

#include "vtkBrumeConversionModule.h" // For export macro
#include "vtkSmartPointer.h"         // For return values

#include "brume/LightTracer.h"    // For brume::Hit
#include "brume/Reconstruction.h" // For brume::HitArrays

#include <string>
#include <vector>

class vtkPolyData;

class VTKBRUMECONVERSION_EXPORT vtkBrumeHitConversion
{
public:
  ///@{
  /// The array names of the schema.
  static const char* const DirectionName;
  static const char* const FluxName;
  static const char* const ObjectIdName;
  static const char* const EmitterIdName;
  static const char* const DepthName;
  static const char* const TriangleIdName;
  static const char* const AimName;
  static const char* const AimWeightsName;
  static const char* const TotalPowerName;
  static const char* const NumberOfParticlesName;
  static const char* const FirstParticleName;
  static const char* const EndParticleName;
  static const char* const SeedName;
  ///@}

  /// What a hit set says of the run it comes from.
  struct RunInfo
  {
    double TotalPower[3] = { 0.0, 0.0, 0.0 };
    double Particles = 0.0;     // NumberOfParticles
    double FirstParticle = 0.0; // 0 unless the hits continue a run
    double EndParticle = 0.0;   // where these hits' particles end (Particles unless a batch)
    double Seed = 0.0;
    /// 1 / AimWeights, three per emitter id (empty without `Aim`).
    std::vector<double> GrowthScales;
    /// Whether these hits end the run (its last batch, or the whole run).
    bool Completes() const { return this->EndParticle >= this->Particles; }
  };

  /// Stores hits in a vtkPolyData with the schema's arrays.
  static vtkSmartPointer<vtkPolyData> HitsToPolyData(
    const std::vector<brume::Hit>& hits, const brume::Vec3& totalPower, long long particles);

  /// Copies hits back; empty string on success, otherwise what is missing.
  static std::string HitsFromPolyData(vtkPolyData* data, std::vector<brume::Hit>& hits);

  /**
   * Views the hits in place for the reconstruction (no copy, except of
   * positions that are not float: into `positionCopy`), with what the field
   * data says of the run. Empty string on success, otherwise a sentence
   * saying what is wrong (without its final period).
   */
  static std::string ReadHits(
    vtkPolyData* data, brume::HitArrays& hits, RunInfo& run, std::vector<float>& positionCopy);
};

#endif
