// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file    vtkBrumeDataModelNames.h
 * @brief   the names of the arrays the phases exchange, in one place
 *
 * The field-data, point-data and cell-data array names that Brume's phases
 * exchange (the schemas of vtkBrumeSceneConversion, vtkBrumeHitConversion
 * and vtkBrumeRadianceConversion, and the evaluation's images) as named
 * constants: `vtkBrumeNames::SigmaS` is "BrumeSigmaS". A constant's name is
 * its string without the leading "Brume". Python scripts and Brume.xml
 * spell the strings out: a string changed here changes there too.
 *
 * Not wrapped (NOWRAP_HEADERS): include it from .cxx files only.
 */
#ifndef vtkBrumeDataModelNames_h
#define vtkBrumeDataModelNames_h

#include <string>

namespace vtkBrumeNames
{
/// @name Scene objects and materials
/// A surface's vtkPolyData field data (the whole object, one tuple of
/// doubles) or cell data of the same name (per cell, overriding).
///@{
/// The material: a string in field data ("lambertian", "phong", "mirror"),
/// an integer per cell in cell data (0, 1, 2).
inline constexpr const char* Material = "BrumeMaterial";
/// Diffuse reflectance rho_d, 3 components.
inline constexpr const char* Reflectance = "BrumeReflectance";
/// Specular reflectance rho_s of the Phong lobe or the mirror, 3 components.
inline constexpr const char* Specular = "BrumeSpecular";
/// Phong exponent, 1 component.
inline constexpr const char* Exponent = "BrumeExponent";
/// Emitted radiance (W m^-2 sr^-1), 3 components.
inline constexpr const char* Emission = "BrumeEmission";
/// Any scene object's field data: its texture resolution along its longest
/// axis (1 component), overriding the reconstruction's.
inline constexpr const char* TextureResolution = "BrumeTextureResolution";
///@}

/// @name Media
/// A medium's vtkImageData field data, one tuple each (the transfer
/// functions: one tuple per point).
///@{
/// Absorption coefficient sigma_a (m^-1), double[3].
inline constexpr const char* SigmaA = "BrumeSigmaA";
/// Scattering coefficient sigma_s (m^-1), double[3].
inline constexpr const char* SigmaS = "BrumeSigmaS";
/// Henyey-Greenstein asymmetry g in (-1, 1), 1 component.
inline constexpr const char* G = "BrumeG";
/// Factor on both coefficients, 1 component.
inline constexpr const char* DensityScale = "BrumeDensityScale";
/// The OpenVDB file of a sparse density (string array).
inline constexpr const char* VDBFile = "BrumeVDBFile";
/// The float grid of VDBFile (string array; default: the first float grid).
inline constexpr const char* VDBGrid = "BrumeVDBGrid";
/// The point or cell array holding the density or scalars (string array).
inline constexpr const char* DensityArray = "BrumeDensityArray";
/// Scalar-opacity transfer function: (scalar, opacity) tuples, double[2].
inline constexpr const char* ScalarOpacity = "BrumeScalarOpacity";
/// The distance over which ScalarOpacity's opacity holds, 1 component.
inline constexpr const char* ScalarOpacityUnitDistance = "BrumeScalarOpacityUnitDistance";
/// The component of the scalars that are classified, 1 component.
inline constexpr const char* ScalarComponent = "BrumeScalarComponent";
/// Interpolation of the scalars (string array: "linear" or "nearest").
inline constexpr const char* Interpolation = "BrumeInterpolation";
/// Colour transfer function, a factor on the albedo: (scalar, red, green,
/// blue) tuples, double[4].
inline constexpr const char* ScalarColor = "BrumeScalarColor";
///@}

/// @name Lights
/// The scene collection's field data (and a light tracer's output field
/// data: the vtkLights it was given), one tuple per light.
///@{
/// The light's type (string array: "point", "spot", "directional").
inline constexpr const char* LightType = "BrumeLightType";
/// Position, double[3].
inline constexpr const char* LightPosition = "BrumeLightPosition";
/// Direction, double[3].
inline constexpr const char* LightDirection = "BrumeLightDirection";
/// Radiant intensity (W/sr), irradiance (W/m^2) for a directional light,
/// double[3].
inline constexpr const char* LightIntensity = "BrumeLightIntensity";
/// Spot half-angle in degrees, 1 component.
inline constexpr const char* LightConeAngle = "BrumeLightConeAngle";
///@}

/// @name Camera
/// The scene collection's field data, one tuple each (all four or none, see
/// vtkBrumeSceneCamera).
///@{
/// Position, double[3].
inline constexpr const char* CameraPosition = "BrumeCameraPosition";
/// Focal point, double[3].
inline constexpr const char* CameraFocalPoint = "BrumeCameraFocalPoint";
/// View up, double[3].
inline constexpr const char* CameraViewUp = "BrumeCameraViewUp";
/// View angle in degrees, 1 component.
inline constexpr const char* CameraViewAngle = "BrumeCameraViewAngle";
///@}

/// @name Scene render settings
/// The scene collection's field data, one tuple of doubles each, from a
/// scene file's "render" section (the brume command's defaults).
///@{
/// Particles to trace, 1 component.
inline constexpr const char* RenderParticles = "BrumeRenderParticles";
/// Image width and height, 2 components.
inline constexpr const char* RenderSize = "BrumeRenderSize";
/// The reconstruction's radiosity threshold, 1 component.
inline constexpr const char* RenderThreshold = "BrumeRenderThreshold";
/// The tracer's seed, 1 component.
inline constexpr const char* RenderSeed = "BrumeRenderSeed";
/// The image's exposure, 1 component.
inline constexpr const char* RenderExposure = "BrumeRenderExposure";
///@}

/// @name Hits
/// The light tracer's output vtkPolyData (see vtkBrumeHitConversion, whose
/// *Name members are these): point data, one tuple per hit, and field data.
///@{
/// Direction of travel on arrival, float[3].
inline constexpr const char* Direction = "Direction";
/// Flux carried on arrival (W), float[3].
inline constexpr const char* Flux = "Flux";
/// The scene object hit (surfaces first, then media), unsigned short.
inline constexpr const char* ObjectId = "ObjectId";
/// The emitter (objects' ids, then the lights'), unsigned short.
inline constexpr const char* EmitterId = "EmitterId";
/// Interactions before this one, unsigned char.
inline constexpr const char* Depth = "Depth";
/// The triangle of a surface hit in the surface's triangulation, unsigned int.
inline constexpr const char* TriangleId = "TriangleId";
/// Where the particle left an aimed light (0, 1, 2), unsigned char.
inline constexpr const char* Aim = "Aim";
/// Field data: the weight of each Aim class, double[3] per emitter id.
inline constexpr const char* AimWeights = "AimWeights";
/// Field data: the run's total emitted power (W), double[3].
inline constexpr const char* TotalPower = "TotalPower";
/// Field data: the run's particle count, 1 component.
inline constexpr const char* NumberOfParticles = "NumberOfParticles";
/// Field data: the first of the run's particles these hits come from.
inline constexpr const char* FirstParticle = "FirstParticle";
/// Field data: the end of the run's particles these hits come from.
inline constexpr const char* EndParticle = "EndParticle";
/// Field data: the tracer's seed, 1 component.
inline constexpr const char* Seed = "Seed";
/// Field data: [first, end) of the particles a distributed piece traced,
/// double[2].
inline constexpr const char* PieceParticles = "PieceParticles";
/// Field data: the rays the run cast, 1 component.
inline constexpr const char* NumberOfRays = "NumberOfRays";
/// Field data: the run's energy balance (W per channel, double[3]):
/// emitted = absorbed + escaped + truncated + the estimator's net.
inline constexpr const char* EmittedFlux = "EmittedFlux";
inline constexpr const char* AbsorbedFlux = "AbsorbedFlux";
inline constexpr const char* EscapedFlux = "EscapedFlux";
inline constexpr const char* TruncatedFlux = "TruncatedFlux";
inline constexpr const char* EstimatorNetFlux = "EstimatorNetFlux";
///@}

/// @name Radiance textures
/// The partitions of the reconstruction's output (see
/// vtkBrumeRadianceConversion), the slice mapper's input.
///@{
/// Radiance (W m^-2 sr^-1), float[3] point data: a surface's texture image;
/// also the float images of the reference path tracer and of
/// vtkBrumeFloatImageCapture, one point per pixel.
inline constexpr const char* Radiance = "Radiance";
/// A mapped surface's texture coordinates, float[2] point data.
inline constexpr const char* TextureCoordinates = "TextureCoordinates";
/// A surface texture's chart (string field array: "planar", "texture
/// coordinates" or "atlas").
inline constexpr const char* TextureChart = "BrumeTextureChart";
/// A planar chart's place in the world, x = Origin + s U + t V: double[3]
/// field arrays.
inline constexpr const char* TextureOrigin = "BrumeTextureOrigin";
inline constexpr const char* TextureU = "BrumeTextureU";
inline constexpr const char* TextureV = "BrumeTextureV";
/// Every partition's kind (string field array: "surface", "medium" or
/// "medium extinction").
inline constexpr const char* ObjectKind = "BrumeObjectKind";
/// A medium's source radiance (W m^-2 sr^-1), float[3] cell data; the mean
/// over directions for directional media.
inline constexpr const char* SourceRadiance = "SourceRadiance";
/// A directional medium's spherical-harmonics projection, float cell data
/// of 3 (order + 1)^2 components (coefficient-major, RGB within).
inline constexpr const char* SourceRadianceSH = "SourceRadianceSH";
/// A medium's extinction sigma_t (m^-1), float[3] cell data (the mapper
/// also takes 1 component).
inline constexpr const char* Extinction = "Extinction";
/// Field data: the phase function's g of a directional medium's remainder,
/// 1 component.
inline constexpr const char* PhaseAsymmetry = "BrumePhaseAsymmetry";
/// Field data: the forward fraction F of a medium whose albedo varies (the
/// mapper extinguishes sigma_t (1 - a F)), 1 component in [0, 1).
inline constexpr const char* ForwardFraction = "BrumeForwardFraction";
/// Field data: the factor on the extinction of a strongly forward medium's
/// peak drawn as transport, double[3].
inline constexpr const char* ExtinctionFactor = "BrumeExtinctionFactor";
///@}

/// @name Sparse bricks
/// Field arrays of a medium's partitions in the sparse form (see
/// vtkBrumeSliceVolumeMapper): partition 0's source radiance, partition 1's
/// extinction.
///@{
/// The source radiance's slot per brick (-1: none), int.
inline constexpr const char* SourceBrickSlots = "SourceBrickSlots";
/// What a sparse cell array's name is followed by: its samples per slot.
inline constexpr const char* BrickSamplesSuffix = "BrickSamples";
/// SourceRadiance's samples, float[3], one brick of cells per slot.
inline constexpr const char* SourceRadianceBrickSamples = "SourceRadianceBrickSamples";
/// SourceRadianceSH's samples, as many tuples as SourceRadianceBrickSamples.
inline constexpr const char* SourceRadianceSHBrickSamples = "SourceRadianceSHBrickSamples";
/// The extinction's slot per brick (-1: constant, in ExtinctionBrickValues),
/// int.
inline constexpr const char* ExtinctionBrickSlots = "ExtinctionBrickSlots";
/// The extinction's constant per brick, float.
inline constexpr const char* ExtinctionBrickValues = "ExtinctionBrickValues";
/// The extinction's samples (density or scalars), float, one brick of
/// cells per slot.
inline constexpr const char* ExtinctionBrickSamples = "ExtinctionBrickSamples";
/// Instead of ExtinctionBrickSamples: a value per cell of the grid (x
/// fastest; float, 8- or 16-bit integers), a stored brick's samples read
/// from its cells (classified scalars read in place from the field's own
/// array); a slot is then only where a brick goes.
inline constexpr const char* ExtinctionCellValues = "ExtinctionCellValues";
/// sigma_t per unit density, double[3].
inline constexpr const char* ExtinctionScale = "ExtinctionScale";
/// A classified medium's extinction at scalars evenly over
/// ExtinctionTransferRange, float (one value per sample).
inline constexpr const char* ExtinctionTransferFunction = "ExtinctionTransferFunction";
/// The scalars of ExtinctionTransferFunction's first and last samples,
/// double[2].
inline constexpr const char* ExtinctionTransferRange = "ExtinctionTransferRange";
/// The albedo at ExtinctionTransferFunction's samples, float[3].
inline constexpr const char* AlbedoTransferFunction = "AlbedoTransferFunction";

/// The field array that holds the samples of the cell array `cellArray` in
/// the sparse form: `cellArray` followed by BrickSamplesSuffix.
inline std::string BrickSamplesName(const char* cellArray)
{
  return std::string(cellArray) + BrickSamplesSuffix;
}
///@}

/// @name View state
/// The reconstruction's output collection's field data.
///@{
/// The viewpoint the textures radiate toward, double[3].
inline constexpr const char* EyePosition = "BrumeEyePosition";
/// How many textures depend on the viewpoint, int, 1 value.
inline constexpr const char* ViewDependentObjects = "BrumeViewDependentObjects";
/// A batch of a run binned (no textures yet): the particles binned so far
/// and the run's, double[2].
inline constexpr const char* ParticlesBinned = "BrumeParticlesBinned";
///@}

/// @name Evaluation images
/// Point data of float images, one point per pixel (Radiance above is their
/// radiance).
///@{
/// The variance of the reference path tracer's pixel mean, float[3].
inline constexpr const char* Variance = "Variance";
/// 1 where the pixel's ray crosses a medium, else 0: unsigned char.
inline constexpr const char* MediumMask = "MediumMask";
///@}

namespace Detail
{
// Whether `whole` is `head` followed by `tail` (for the checks below).
constexpr bool Concatenates(const char* whole, const char* head, const char* tail)
{
  while (*head)
  {
    if (*whole++ != *head++)
    {
      return false;
    }
  }
  while (*tail)
  {
    if (*whole++ != *tail++)
    {
      return false;
    }
  }
  return *whole == '\0';
}
static_assert(Concatenates(SourceRadianceBrickSamples, SourceRadiance, BrickSamplesSuffix),
  "a sparse array's name is its cell array's followed by BrickSamplesSuffix");
static_assert(Concatenates(SourceRadianceSHBrickSamples, SourceRadianceSH, BrickSamplesSuffix),
  "a sparse array's name is its cell array's followed by BrickSamplesSuffix");
}
}

#endif
