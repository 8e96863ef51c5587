// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeSliceVolumeMapper
 * @brief   renders participating media as view-aligned 3D-texture slices
 *
 * Jimenez & Pueyo (2003), section 4, after Van Gelder & Kim (1996): the
 * medium's box is cut by planes perpendicular to the view direction (the
 * slices of a cube of side the medium's diagonal, clipped to the medium),
 * drawn back to front. Each slice is a slab of thickness Delta along the
 * viewing ray radiating the voxel's source radiance S with, per colour
 * channel, opacity alpha = 1 - exp(-sigma_t Delta); premultiplied compositing
 * gives L = sum T_before S (1 - exp(-sigma_t Delta)) + T_total L_behind,
 * colour by colour (chromatic extinction through dual-source blending).
 * Delta is corrected per fragment for perspective (1/cos of the angle to the
 * view direction). Slices are depth tested against the opaque geometry
 * already drawn, without writing depth, and start at the near plane when the
 * camera is inside the medium. All the slice volumes of a renderer are
 * composited together, their slices merged in depth order, so overlapping
 * media blend correctly.
 *
 * Directional radiance (beyond the paper): when the image also has the cell
 * array `SourceRadianceSH` (spherical-harmonics coefficients of the source
 * radiance, see vtkBrumeRadianceReconstruction::DirectionalRadiance) and
 * the field array `BrumePhaseAsymmetry` (g), the source radiance toward the
 * eye is evaluated per fragment from them (Henyey-Greenstein is diagonal in
 * spherical harmonics, plus a lobe for the bands beyond the order, see
 * brume/SphericalHarmonics.h), so an anisotropic medium follows the camera
 * with no reconstruction: per voxel once per view (the default) or per
 * fragment in the slice shader, see DirectionalEvaluation. Coefficients are
 * multiplied by sigma_t like J.
 *
 * Input: a vtkImageData whose cells are the voxels, with cell data
 * `SourceRadiance` (3 components, W m^-2 sr^-1) and `Extinction` (1 or 3
 * components, m^-1), as vtkBrumeRadianceReconstruction produces; they are
 * filtered as J = S sigma_t and sigma_t, which stay bounded where a medium
 * thins out (S alone would not). With ExtinctionData, sigma_t comes from
 * that grid instead, at its own resolution, and the input's source radiance
 * is filtered as S itself: the smooth source radiance of a coarse texture
 * times a sharp sigma_t (heterogeneous media). The
 * volume property's interpolation type (nearest or linear) is honoured; its
 * transfer functions are not used: the data are physical.
 *
 * Sparse input (with ExtinctionData only): the source radiance kept only
 * where it is read, in bricks that do not overlap, SourceBrickEdge(n)
 * cells along an axis of n cells (SourceBrickSize, or n when fewer; brick
 * b holds cells SourceBrickEdge(n) b ... SourceBrickEdge(n) (b + 1) - 1,
 * the last one padded; SourceBricksAlong(n) bricks, x fastest), as field
 * arrays with no cell arrays:
 * - `SourceBrickSlots` (integers, one per brick): the brick's slot, or -1
 *   when the brick is not stored (its cells read as 0: the extinction is 0
 *   wherever they would be interpolated);
 * - `SourceRadianceBrickSamples` (3 components) and, for directional
 *   radiance, `SourceRadianceSHBrickSamples`: a brick's cells' tuples per
 *   slot, x fastest within a brick.
 * vtkBrumeRadianceReconstruction produces it for heterogeneous media
 * (SparseMedia); DenseSourceArray() expands one array. The mapper's own
 * textures are dense.
 *
 * This class is the interface; New() returns the OpenGL implementation
 * (vtkBrumeOpenGLSliceVolumeMapper) through VTK's object factory.
 *
 * @sa vtkBrumeRadianceReconstruction vtkBrumeSceneActors
 */
#ifndef vtkBrumeSliceVolumeMapper_h
#define vtkBrumeSliceVolumeMapper_h

#include "vtkBrumeRenderingModule.h" // For export macro
#include "vtkVolumeMapper.h"

#include "vtkSmartPointer.h" // For ExtinctionData
#include "vtkWeakPointer.h"  // For VolumeGroup

#include <string> // For ValidateInput

class vtkDataArray;
class vtkFieldData;
class vtkImageData;
class vtkRenderer;
class vtkVolumeCollection;

class VTKBRUMERENDERING_EXPORT vtkBrumeSliceVolumeMapper : public vtkVolumeMapper
{
public:
  static vtkBrumeSliceVolumeMapper* New();
  vtkTypeMacro(vtkBrumeSliceVolumeMapper, vtkVolumeMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Distance between slices along the view direction, in world units.
   * 0 (the default) chooses it: half the input's smallest voxel, but no
   * closer than 1/40 of the medium's longest side; with an extinction grid
   * of its own (SetExtinctionData), also at most four of its cells apart
   * and at most two optical depths at its largest extinction, but no closer
   * than one of its cells (an optically thick medium's lit skin is then
   * sampled where it is). Negative values are an error.
   *
   * With an extinction grid of its own finer than the spacing, each slab
   * takes the mean of its extinction at one sample per fine cell of the
   * spacing along each ray (at most 8; GetLastSlabSamples()), so that a
   * structure one cell thin is integrated across the slab instead of
   * falling between slices or being drawn a slab thick. Quick draws take
   * one: SliceSpacingScale or a reduced ImageSampleDistance above 1, or a
   * render window whose desired update rate is 1 frame a second or more
   * (what VTK's interactor styles ask for while the camera moves).
   */
  vtkSetMacro(SliceSpacing, double);
  vtkGetMacro(SliceSpacing, double);
  ///@}

  ///@{
  /**
   * The media's resolution on screen, as vtkGPUVolumeRayCastMapper's
   * ImageSampleDistance: 1 (the default) draws the slices at the window's
   * own resolution; D > 1 (at most 16) draws them into a buffer D times
   * coarser along each axis (about 1/D^2 of the fragments, which the
   * slices' cost follows), then upsamples it over the window: each pixel
   * takes the four nearest coarse pixels bilinearly where their depths
   * agree with its own, else the one nearest in depth, so opaque objects'
   * silhouettes in front of or inside a medium stay sharp. What the medium
   * itself holds finer than D pixels is blurred. For interaction, as
   * `brume view` does while the camera moves; images to compare keep 1.
   *
   * All the slice volumes of a renderer are drawn together, at the largest
   * distance any of them asks for. Drawn at full resolution all the same
   * (GetLastImageSampleDistance() tells): media whose extinction differs
   * between colour channels (their transmittance is three numbers a pixel),
   * WriteDepth on, or a context where the coarse buffer fails (a warning,
   * once).
   *
   * Clamped to [1, 16]. A drawing setting only: it does not mark the mapper
   * modified, so switching it (at every start and end of an interaction)
   * uploads no texture again.
   */
  void SetImageSampleDistance(double distance);
  vtkGetMacro(ImageSampleDistance, double);
  /// The image sample distance the last render drew this volume at.
  vtkGetMacro(LastImageSampleDistance, double);
  ///@}

  ///@{
  /**
   * A factor on the distance between slices, the automatic one or
   * SliceSpacing (default 1; clamped to [1, 16]): fewer slices, each a
   * thicker slab, for a quicker draw (vtkBrumePass's previews of edits
   * draw at 2). Each slab still takes exp(-sigma_t delta) of its own
   * thickness, but its sigma_t and source only at its slice: a structure
   * thinner than a slab may fall between slices or be drawn a slab thick.
   * A drawing setting only, as SetImageSampleDistance: it does not mark
   * the mapper modified. GetLastNumberOfSlices() gives its effect.
   */
  void SetSliceSpacingScale(double scale);
  vtkGetMacro(SliceSpacingScale, double);
  ///@}
  ///@{
  /**
   * Whether slabs take several extinction samples along each ray where the
   * extinction grid of its own is finer than the spacing (SetSliceSpacing;
   * default on). Off, one sample a slab: a quicker draw, as vtkBrumePass
   * draws its progressive frames before the last. A drawing setting only,
   * as SetImageSampleDistance.
   */
  void SetSlabSampling(bool sampling) { this->SlabSampling = sampling; }
  bool GetSlabSampling() const { return this->SlabSampling; }
  ///@}
  ///@{
  /**
   * Whether, with slab sampling, bricks of classified scalars whose
   * interval holds a point of the transfer function (a change of its
   * slope K) and whose scalar changes by D between neighbouring cells,
   * where one sample a cell h wide may miss K D h / 8 of optical depth,
   * more than 10^-2, are sampled four times a fine cell (default on).
   * Classified after interpolation, a structure one cell thin (a sheet, a
   * narrow peak of the function) has an extinction that one sample a fine
   * cell does not integrate: a one-voxel sheet through a step of the
   * function took 0.79 to 1.51 of its optical depth by where the samples
   * fell, within 1 % with four. It costs frame time where the function
   * bends so (the shells' 512^3 under llvmpipe: 1.3 s a still frame
   * without, 3 s with); frames drawn without slab sampling are not
   * affected. A drawing setting only, as SetImageSampleDistance.
   */
  void SetBendSampling(bool sampling) { this->BendSampling = sampling; }
  bool GetBendSampling() const { return this->BendSampling; }
  ///@}
  ///@{
  /**
   * The largest error of optical depth, along any ray across a bricked
   * extinction grid (SetExtinctionData), that the GPU's copy of its floats
   * may make by holding them as 16-bit values, each brick's over its own
   * interval (default 10^-3; at least 0). Where half the largest brick's
   * step, times the largest extinction per unit of value (a transfer
   * function's steepest slope for classified scalars) and the grid's
   * diagonal, stays within it, and a classified albedo moves by no more
   * than it, the atlas takes half the memory (a 512^3 float field's
   * 0.80 GB, 0.40 GB); otherwise it keeps 32-bit floats. Within that
   * bound each pixel moves by at most twice the tolerance times the
   * largest source radiance. 0 keeps floats exactly. Grids of integers
   * spanning at most 65,535 go up as 16 bits exactly whatever it is. A
   * drawing setting: a grid already on the GPU is sent again when its
   * bound exceeds a new tolerance or the bound under a new transfer
   * function does.
   */
  void SetExtinctionDepthTolerance(double tolerance)
  {
    tolerance = tolerance > 0.0 ? tolerance : 0.0;
    if (this->ExtinctionDepthTolerance != tolerance)
    {
      this->ExtinctionDepthTolerance = tolerance;
      this->Modified(); // the next render checks the grid on the GPU against it
    }
  }
  double GetExtinctionDepthTolerance() const { return this->ExtinctionDepthTolerance; }
  ///@}
  ///@{
  /**
   * Multiplies the radiance the slices emit, not their transmittance
   * (default 1, at least 0): an exposure for displays of linear radiance
   * (the "Brume Radiance" representation's Exposure). Light from behind a
   * medium is attenuated as before; scale it with its own props.
   */
  vtkSetClampMacro(RadianceScale, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(RadianceScale, double);
  ///@}

  ///@{
  /**
   * The slices write their depth (default off: they blend without it).
   * For sort-last compositing, as ParaView's IceT does under mpirun, which
   * counts a pixel at the far plane as background: a medium drawn over the
   * background would be dropped. With identical images on every process
   * and the slices' depth written, the composite is each process's image.
   */
  vtkSetMacro(WriteDepth, bool);
  vtkGetMacro(WriteDepth, bool);
  vtkBooleanMacro(WriteDepth, bool);
  ///@}

  /// Where directional radiance is evaluated toward the eye.
  enum DirectionalEvaluationModes
  {
    /// Once per view and voxel (at its centre), into the source texture the
    /// slices sample: a view change costs a pass over the voxels (on the
    /// CPU, threaded) and a 3-channel upload; the slices cost what plain
    /// ones do. The default: fastest where fragments are expensive (Mesa).
    PerVoxel = 0,
    /// Per fragment, in the slice shader, from the interpolated
    /// coefficients (12 RGBA textures for order 3): exact direction to the
    /// eye everywhere, no work at all on a view change, heavier fragments.
    PerFragment = 1
  };

  ///@{
  /// How directional radiance (`SourceRadianceSH`) is evaluated (default PerVoxel).
  vtkSetClampMacro(DirectionalEvaluation, int, PerVoxel, PerFragment);
  vtkGetMacro(DirectionalEvaluation, int);
  ///@}

  ///@{
  /**
   * The medium's extinction at another resolution (default none): a
   * vtkImageData over the input's box or a larger one (a grid whose cell
   * centres are a density's own samples reaches half a cell beyond the
   * medium; only the part inside the input's box is drawn), whose cells'
   * extinction (m^-1) is interpolated between their centres. Given densely,
   * as the cell array `Extinction` (1 or 3 components), or sparsely, in
   * bricks (below). When set, it replaces the input's `Extinction`, the
   * input's `SourceRadiance` (and `SourceRadianceSH`) is taken as the
   * source radiance S itself, and the default slice spacing follows this
   * grid too (SetSliceSpacing). The grid is uploaded
   * again only when it is another one or was modified.
   * vtkBrumeSceneActors sets it from a medium's partition 1
   * (vtkBrumeRadianceReconstruction's extinction at the density's own
   * resolution, which is sparse).
   *
   * The sparse form (no cell arrays; field arrays): the cells' values are
   * grouped in bricks of ExtinctionBrickSize^3 cells, brick b along an axis
   * holding cells (ExtinctionBrickSize - 1) b ... (ExtinctionBrickSize - 1) b
   * + ExtinctionBrickSize - 1 (neighbours share a layer, so the cells any
   * point interpolates lie in one brick; cells past the last repeat it),
   * ExtinctionBricksAlong(n) bricks along an axis of n cells, x fastest:
   * - `ExtinctionBrickSlots` (integers, one per brick): the brick's slot in
   *   `ExtinctionBrickSamples`, or -1 when all its cells hold one value;
   * - `ExtinctionBrickValues` (one per brick): that value (brick slot -1);
   * - `ExtinctionBrickSamples` (1 component): ExtinctionBrickSize^3 values
   *   per slot, x fastest within a brick;
   * - or instead `ExtinctionCellValues` (1 component, float or 8- or 16-bit
   *   integers): one value per cell of the grid, x fastest, a stored
   *   brick's samples read from its own cells; its slot is then only where
   *   the brick goes in the atlas, each brick a slot of its own (a field's
   *   array read in place: vtkBrumeRadianceConversion::NativeExtinction
   *   gives classified scalars so, not a bricked copy of them);
   * - `ExtinctionScale` (3 components): the extinction per unit of the
   *   values, per colour channel (a density's sigma_t);
   * - optionally `ExtinctionTransferFunction` (n >= 2 values) and
   *   `ExtinctionTransferRange` (2 components): the values are scalars,
   *   classified after interpolation by the table (n samples evenly over
   *   the range, linear between them, its end values beyond), as the light
   *   tracer classifies a transfer-function medium
   *   (vtkBrumeRadianceConversion::NativeExtinction); the table's value
   *   times `ExtinctionScale` is sigma_t;
   * - with those, optionally `AlbedoTransferFunction` (3 components, as
   *   many tuples, each in [0, 1]): the albedo a of the same scalars, for a
   *   medium whose albedo varies. The input's source radiance is then X,
   *   the radiance of an albedo of 1 (brume::ObjectRadiance::
   *   HasVaryingAlbedo), drawn per fragment as the emission sigma_t a X
   *   with the extinction sigma_t (1 - a F), F the input's field array
   *   `BrumeForwardFraction` (the share of a forward peak drawn as
   *   transport; 0 without it).
   * The GPU holds the same: the slots in one 3D atlas texture and the brick
   * table, so memory follows the bricks where the medium varies, not its box.
   */
  void SetExtinctionData(vtkImageData* extinction);
  vtkImageData* GetExtinctionData();
  ///@}

  /// The sparse extinction's bricks: cells per side, and bricks along an axis of `cells`.
  static constexpr int ExtinctionBrickSize = 8;
  static int ExtinctionBricksAlong(int cells)
  {
    return cells > 1 ? (cells - 2) / (ExtinctionBrickSize - 1) + 1 : 1;
  }

  vtkMTimeType GetMTime() override;

  /**
   * Empty when `extinction` can serve as the ExtinctionData of `image`:
   * the arrays (dense or sparse, their sizes and slots consistent), at
   * least one cell per axis, and the same box (within a millionth of its
   * size); otherwise why not.
   */
  static std::string ValidateExtinction(vtkImageData* image, vtkImageData* extinction);

  /// Number of slices of this volume drawn by the last render.
  vtkGetMacro(LastNumberOfSlices, int);
  /// Extinction samples each slab of this volume took along a ray in the
  /// last render (SetSliceSpacing).
  vtkGetMacro(LastSlabSamples, int);

  /**
   * Empty when `image` has what the mapper draws, otherwise why not (missing
   * arrays, no cells, non-positive spacing, sparse arrays that do not fit
   * the grid). Values are checked when they are uploaded (negative or
   * non-finite extinction is an error). An image in the sparse form also
   * needs ExtinctionData, which the mapper checks when it draws.
   */
  static std::string ValidateInput(vtkImageData* image);

  /// The sparse source radiance's bricks: cells per side, and bricks along an axis of `cells`.
  static constexpr int SourceBrickSize = 8;
  static int SourceBricksAlong(int cells)
  {
    return (cells + SourceBrickSize - 1) / SourceBrickSize;
  }
  static int SourceBrickEdge(int cells)
  {
    return cells < SourceBrickSize ? cells : SourceBrickSize;
  }

  /// Whether `image` holds its source radiance in the sparse form (`SourceBrickSlots`).
  static bool IsSparseSource(vtkImageData* image);

  /**
   * The cell array `name` of a medium image (`SourceRadiance`,
   * `SourceRadianceSH`) with one tuple per cell: the array itself, or in the
   * sparse form a new float array expanded from `name` + "BrickSamples"
   * (cells of bricks not stored are 0). Null when the image has neither or
   * the sparse arrays do not fit the grid (ValidateInput says why).
   */
  static vtkSmartPointer<vtkDataArray> DenseSourceArray(vtkImageData* image, const char* name);

  /// The order of a `SourceRadianceSH` array of so many components, or -1.
  static int DirectionalOrder(int components);

  ///@{
  /**
   * The volumes a frame draws together, their slices merged far to near
   * (default none: the renderer's volumes). For volumes drawn without
   * being in the renderer: vtkBrumePass draws its own (held weakly).
   */
  void SetVolumeGroup(vtkVolumeCollection* volumes);
  vtkVolumeCollection* GetVolumeGroup();
  ///@}

protected:
  vtkBrumeSliceVolumeMapper();
  ~vtkBrumeSliceVolumeMapper() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  /// The VolumeGroup, or the renderer's volumes without one.
  vtkVolumeCollection* GetDrawnVolumes(vtkRenderer* ren);

  double SliceSpacing = 0.0;
  double SliceSpacingScale = 1.0;
  bool SlabSampling = true;
  bool BendSampling = true;
  double ExtinctionDepthTolerance = 1e-3;
  double ImageSampleDistance = 1.0;
  double LastImageSampleDistance = 1.0;
  double RadianceScale = 1.0;
  int DirectionalEvaluation = PerVoxel;
  bool WriteDepth = false;
  int LastNumberOfSlices = 0;
  int LastSlabSamples = 1;
  vtkSmartPointer<vtkImageData> ExtinctionData;
  vtkWeakPointer<vtkVolumeCollection> VolumeGroup;

private:
  // ValidateInput's sparse form: the source radiance's brick arrays
  // against the grid.
  static std::string ValidateSourceBricks(vtkImageData* image, const int cells[3]);
  // ValidateExtinction's sparse form: the brick arrays against the grid.
  static std::string ValidateBricks(
    const int pointDims[3], vtkFieldData* fd, vtkDataArray* samples);

  vtkBrumeSliceVolumeMapper(const vtkBrumeSliceVolumeMapper&) = delete;
  void operator=(const vtkBrumeSliceVolumeMapper&) = delete;
};

#endif
