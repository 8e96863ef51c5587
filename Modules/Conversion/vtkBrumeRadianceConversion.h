// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeRadianceConversion
 * @brief   the radiance-texture schema: the core's textures as VTK data
 *
 * The inverse of vtkBrumeSceneConversion: phase 2's textures
 * (brume::ObjectRadiance) become the partitioned datasets that
 * vtkBrumeRadianceReconstruction outputs, one per scene object:
 *
 * - a surface: partition 0 is a 2D vtkImageData in texture space ([0,1]^2,
 *   point data `Radiance`, float[3], W m^-2 sr^-1), with field data
 *   `BrumeTextureChart` ("planar", "texture coordinates" or "atlas") and,
 *   for planar charts, `BrumeTextureOrigin`, `BrumeTextureU`,
 *   `BrumeTextureV` that place it in the world (x = Origin + s U + t V);
 *   partition 1 is the surface with texture coordinates
 *   `TextureCoordinates` that map the image (an atlas gets separate points
 *   per triangle);
 * - a medium: partition 0 is a 3D vtkImageData over the medium's box with
 *   cell data `SourceRadiance` (float[3], W m^-2 sr^-1) and `Extinction`
 *   (float[3], sigma_t in m^-1); directional media add `SourceRadianceSH`
 *   (3 (order + 1)^2 components, coefficient-major, RGB within; then
 *   `SourceRadiance` is the mean over directions) and the field value
 *   `BrumePhaseAsymmetry`. The source radiance of a heterogeneous medium is
 *   its sigma_t-weighted mean over each voxel's region (smooth where the
 *   light is), and partition 1 is a second 3D vtkImageData over the
 *   density's own grid (its box holds the medium's) with the extinction at
 *   the density's own resolution (brume::NativeMediumGrid times the
 *   medium's sigma_t) in vtkBrumeSliceVolumeMapper's sparse form
 *   (field arrays `ExtinctionBrickSlots`, `ExtinctionBrickValues`,
 *   `ExtinctionBrickSamples`, `ExtinctionScale`; classified scalars that
 *   are a grid's own values give `ExtinctionCellValues`, the field's array
 *   itself, instead of the samples; see
 *   vtkBrumeSliceVolumeMapper::SetExtinctionData): memory follows the
 *   bricks where the density varies, not the box. The mapper draws the
 *   medium's structure with it; DenseExtinction() expands it.
 * - a heterogeneous medium's partition 0 in the sparse form (FromMedium
 *   given the layout of SourceBricks()): its source radiance only where
 *   the mapper reads it (near the density), as the field arrays
 *   `SourceBrickSlots`, `SourceRadianceBrickSamples` and, for directional
 *   media, `SourceRadianceSHBrickSamples`, with no cell arrays and no
 *   texture-resolution `Extinction` (partition 1 replaces it); see
 *   vtkBrumeSliceVolumeMapper's input and its DenseSourceArray().
 *
 * Every partition's field data holds `BrumeObjectKind` ("surface" or
 * "medium").
 *
 * @sa vtkBrumeRadianceReconstruction vtkBrumeSceneConversion
 */
#ifndef vtkBrumeRadianceConversion_h
#define vtkBrumeRadianceConversion_h

#include "vtkBrumeConversionModule.h" // For export macro
#include "vtkSmartPointer.h"          // For return values

#include "brume/Reconstruction.h" // For brume::ObjectRadiance
#include "brume/SparseTexture.h"  // For SourceBricks

#include <string> // For Reclassified's reason

class vtkDataArray;
class vtkFieldData;
class vtkImageData;
class vtkPartitionedDataSet;
class vtkPolyData;

class VTKBRUMECONVERSION_EXPORT vtkBrumeRadianceConversion
{
public:
  /**
   * A surface's texture and the surface mapped to it. `sceneSurface` is the
   * scene's polydata of the object, whose field data the mapped surface
   * keeps.
   */
  static vtkSmartPointer<vtkPartitionedDataSet> FromSurface(const brume::ObjectRadiance& radiance,
    const brume::Surface& surface, vtkPolyData* sceneSurface);

  /**
   * A medium's texture: toward the eye, or the directional projection when
   * `directional` (the object holds one: ObjectRadiance::BuildDirectional).
   * `previous`, when given, is an earlier texture of the same medium: its
   * `Extinction` array is kept where the values are the same (a view
   * update changes only the radiance), so that renderers see the same
   * array and need not convert or compare it again. With `bricks` (the
   * texture's SourceBricks(), of the same resolution) a heterogeneous
   * medium's texture is in the sparse form.
   */
  static vtkSmartPointer<vtkPartitionedDataSet> FromMedium(const brume::ObjectRadiance& radiance,
    const brume::Medium& medium, bool directional, vtkImageData* nativeExtinction = nullptr,
    vtkImageData* previous = nullptr, const brume::SparseTexture* bricks = nullptr);

  /**
   * The bricks of a heterogeneous medium's texture (toward the eye, or
   * directional) that the slice mapper reads: those near the density
   * (brume::SparseTexture::WhereDensity). It depends on the texture's
   * resolution and the density alone: a caller may keep it while the
   * resolution stays. Taken from the cells the object's direct light read
   * (brume::DirectTexture::GetCellsRead()) where it found them on the same
   * grid, so that a reconstruction reads the density's bricks for them once.
   */
  static brume::SparseTexture SourceBricks(
    const brume::ObjectRadiance& radiance, const brume::Medium& medium, bool directional);

  /**
   * A heterogeneous medium's extinction at the density's own resolution
   * (partition 1 of FromMedium), null for other objects. It does not change
   * with the view or the particles: a caller may keep it and pass it to
   * FromMedium again, so that renderers do not upload it again.
   */
  static vtkSmartPointer<vtkImageData> NativeExtinction(
    const brume::ObjectRadiance& radiance, const brume::Medium& medium);

  /**
   * The sparse extinction of NativeExtinction() as a dense image: cell data
   * `Extinction` (float[3], m^-1) on the same grid, for filters that need
   * every cell (and to check the sparse form). Null when `sparse` is not
   * in that form.
   */
  static vtkSmartPointer<vtkImageData> DenseExtinction(vtkImageData* sparse);

  /**
   * A classified medium's extinction (brume::ClassifiedDensity) is given
   * as its scalars, in the same bricks, with `ExtinctionTransferFunction`
   * (TransferFunctionSamples values: the function's extinction at scalars
   * evenly spaced over `ExtinctionTransferRange`, its first and last
   * points' scalars; the end values beyond), which the slice mapper
   * applies after interpolating the scalars. Classify() is that lookup
   * (linear between the table's samples).
   *
   * A medium whose albedo varies (brume::ClassifiedAlbedo of the same
   * scalars) adds `AlbedoTransferFunction` (3 components, the albedo at the
   * same samples) there, and its texture's SourceRadiance is then X, the
   * radiance of an albedo of 1, with the field array BrumeForwardFraction:
   * the mapper draws sigma_t a X with the extinction sigma_t (1 - a F). A
   * grid without the table (a coarsened one) gets the albedo baked into its
   * texture instead: per texel, its sigma_t-weighted mean over 2^3 points.
   */
  static constexpr int TransferFunctionSamples = 4096;
  static double Classify(vtkDataArray* table, const double range[2], double scalar);

  /**
   * A preview of an edit of a classified medium's transfer functions:
   * `extinction` (a NativeExtinction of classified scalars, made for the
   * medium `before`) with the tables and the extinction scale of `medium`;
   * both are a scene medium's field data as vtkBrumeSceneConversion reads
   * it (BrumeScalarOpacity, BrumeScalarColor, the coefficients). The
   * scalars' bricks are shared, not copied. What the slice mapper draws
   * from it is the new functions applied to the old light. Null, with
   * `why`, when the old light cannot be drawn so: the extinction is not of
   * classified scalars; a medium's functions are invalid or absent; the
   * albedo varies in one and not the other (the source radiance then means
   * another thing); or the new opacity is above 0 somewhere the old one is
   * 0, where bricks were left out and hold no scalars of their own.
   */
  static vtkSmartPointer<vtkImageData> Reclassified(
    vtkImageData* extinction, vtkFieldData* before, vtkFieldData* medium, std::string& why);
};

#endif
