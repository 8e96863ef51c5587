// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeSceneActors
 * @brief   turns reconstructed radiance textures into actors and volumes
 *
 * Scene assembly for phase 3. For every object of the output of
 * vtkBrumeRadianceReconstruction it makes a prop: surfaces become unlit
 * textured actors (a vtkTexture of the float `Radiance` image on the surface's
 * texture coordinates, so the framebuffer receives radiance), media become
 * vtkVolume props drawn by vtkBrumeSliceVolumeMapper. Opaque surfaces are
 * drawn first with the z-buffer, then the volumes.
 *
 * @code
 * vtkNew<vtkBrumeSceneActors> actors;
 * actors->SetInputData(reconstruction->GetOutput());
 * actors->AddToRenderer(renderer);
 * @endcode
 *
 * @sa vtkBrumeRadianceReconstruction vtkBrumeSliceVolumeMapper
 */
#ifndef vtkBrumeSceneActors_h
#define vtkBrumeSceneActors_h

#include "vtkBrumeRenderingModule.h" // For export macro
#include "vtkObject.h"
#include "vtkSmartPointer.h" // For members
#include "vtkWeakPointer.h"  // For the renderer

#include <functional> // For ApplyToMedia
#include <string>     // For GetObjectKind
#include <vector>     // For the entries

class vtkBrumeSliceVolumeMapper;

class vtkActor;
class vtkDataObject;
class vtkImageData;
class vtkPolyData;
class vtkPolyDataMapper;
class vtkTexture;
class vtkInformationIntegerKey;
class vtkPartitionedDataSetCollection;
class vtkPropCollection;
class vtkRenderer;

class VTKBRUMERENDERING_EXPORT vtkBrumeSceneActors : public vtkObject
{
public:
  static vtkBrumeSceneActors* New();
  vtkTypeMacro(vtkBrumeSceneActors, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The reconstruction output to show.
  void SetInputData(vtkPartitionedDataSetCollection* textures);
  vtkPartitionedDataSetCollection* GetInputData();
  ///@}

  ///@{
  /// Show the media (default on).
  vtkSetMacro(ShowMedia, bool);
  vtkGetMacro(ShowMedia, bool);
  vtkBooleanMacro(ShowMedia, bool);
  ///@}

  /**
   * The kind a reconstructed texture declares (its field data's
   * `BrumeObjectKind`): "surface", "medium", or "" when it is none.
   */
  static std::string GetObjectKind(vtkDataObject* texture);

  /**
   * Set in the property keys (vtkProp::GetPropertyKeys()) of every prop
   * made here: the prop shows radiance Brume computed, and a renderer
   * lit by Brume (vtkBrumePass, vtkBrumeRendererScene) draws it as it is
   * instead of lighting it again.
   */
  static vtkInformationIntegerKey* RADIANCE_PROP();

  ///@{
  /**
   * Cull the back of surfaces (default on). Their textures hold the light
   * leaving their front side (the side their triangles' winding normal
   * points to); seen from behind, a wall of a room is then cut away, and
   * the inside stays visible from outside. Off shows the front's texture on
   * both sides.
   */
  void SetBackfaceCulling(bool cull);
  vtkGetMacro(BackfaceCulling, bool);
  vtkBooleanMacro(BackfaceCulling, bool);
  ///@}

  /**
   * Builds the props and adds them to the renderer. Returns false, with an
   * error, when an object of the input is not a reconstructed texture.
   */
  bool AddToRenderer(vtkRenderer* renderer);

  /// The props made by the last AddToRenderer().
  vtkPropCollection* GetProps();

  ///@{
  /**
   * Surfaces share texture atlases when the input holds at least this many
   * that can (default 64; 0 or 1: always; VTK_INT_MAX: never), taking
   * effect at the next AddToRenderer(). An atlas packs many surfaces'
   * radiance textures into one image (a slot each, its edge texels
   * repeated around it so that filtering reads what the texture alone
   * gives) and their triangles into one actor: a scene of thousands of
   * small objects is drawn with a few actors instead of thousands. Scenes
   * of fewer surfaces keep an actor each. A surface whose texture is over
   * 4,094 texels a side, or that holds lines, vertices or strips, keeps its own.
   */
  vtkSetMacro(SurfaceAtlasMinimum, int);
  vtkGetMacro(SurfaceAtlasMinimum, int);
  ///@}

  ///@{
  /// The atlases the last AddToRenderer() made, and the image of the k-th (null if none).
  int GetNumberOfSurfaceAtlases();
  vtkImageData* GetSurfaceAtlas(int k);
  ///@}

  /**
   * Points the props made by AddToRenderer() at `textures`, a newer output
   * of the same reconstruction (same objects, in the same order), and makes
   * it the input. Only the data sets that changed are uploaded again: after
   * a view change, those of the view-dependent objects. A new object that
   * holds the same geometry and bytes as the one a prop shows (the same
   * textures sent again by a ParaView server) leaves the prop as it is.
   * Surfaces in an atlas get their new texels copied into their slots; a
   * new texture size or surface builds every prop again in the renderer
   * they were added to.
   * Returns false, with an error, when the objects do not match the props.
   */
  bool UpdateInputs(vtkPartitionedDataSetCollection* textures);

  /**
   * Whether UpdateInputs() would take `textures` (quietly): props were
   * added to a renderer, and `textures` holds as many objects as the input,
   * each of the same kind, each shown object in the form its prop draws.
   * A program that builds the textures anew for an edited scene (a
   * transfer function, a colour) keeps its props this way, and with them
   * what their mappers hold on the GPU that did not change.
   */
  bool CanUpdateInputs(vtkPartitionedDataSetCollection* textures);

  /// The slice mapper AddToRenderer() made for the object `index` of the
  /// input (null when that object is not a medium shown).
  vtkBrumeSliceVolumeMapper* GetMediumMapper(unsigned int index);

  /// The data sets (images, surfaces, extinction grids) the last
  /// UpdateInputs() changed in the props; -1 before the first.
  vtkGetMacro(NumberOfChangedDataSets, int);

  /// Shows or hides the media's volumes made by AddToRenderer().
  void SetMediaVisibility(bool visible);

  /// Shows or hides the surfaces' actors made by AddToRenderer().
  void SetSurfaceVisibility(bool visible);

  ///@{
  /**
   * The slice spacing of the media's mappers (vtkBrumeSliceVolumeMapper;
   * default 0: half the smallest voxel), those made already included.
   */
  void SetSliceSpacing(double spacing);
  vtkGetMacro(SliceSpacing, double);
  ///@}

  ///@{
  /**
   * Interpolate the textures linearly (default on) or show their texels
   * and voxels as they are (nearest), those made already included.
   */
  void SetInterpolate(bool interpolate);
  vtkGetMacro(Interpolate, bool);
  ///@}

  ///@{
  /**
   * Multiplies the radiance shown (default 1, at least 0): the surfaces'
   * colour and the media's emitted radiance (not their transmittance), an
   * exposure for windows that show linear radiance, those made included.
   */
  void SetExposure(double exposure);
  vtkGetMacro(Exposure, double);
  ///@}

  ///@{
  /**
   * The media's resolution on screen (vtkBrumeSliceVolumeMapper::
   * SetImageSampleDistance; default 1, the window's), those made already
   * included: 2 draws a quarter of the slices' fragments, for interaction.
   */
  void SetImageSampleDistance(double distance);
  vtkGetMacro(ImageSampleDistance, double);
  /// The image sample distance the media were last drawn at (their
  /// largest; 1 without media): 1 where they could not be drawn coarser.
  double GetLastImageSampleDistance();
  ///@}

  ///@{
  /**
   * A factor on the distance between the media's slices
   * (vtkBrumeSliceVolumeMapper::SetSliceSpacingScale; default 1), those
   * made already included: 2 draws about half the slices, for a quick draw.
   */
  void SetSliceSpacingScale(double scale);
  vtkGetMacro(SliceSpacingScale, double);
  ///@}

  ///@{
  /**
   * Whether the media's slabs take several extinction samples along each
   * ray (vtkBrumeSliceVolumeMapper::SetSlabSampling; default on), those
   * made already included.
   */
  void SetSlabSampling(bool sampling);
  bool GetSlabSampling() const { return this->SlabSampling; }
  ///@}

  ///@{
  /**
   * The optical depth the GPU's 16-bit copy of a float extinction grid may
   * be off by (vtkBrumeSliceVolumeMapper::SetExtinctionDepthTolerance;
   * default 10^-3, 0 keeps floats exactly), those made already included:
   * a grid on the GPU goes up again where its bound exceeds it.
   */
  void SetExtinctionDepthTolerance(double tolerance);
  vtkGetMacro(ExtinctionDepthTolerance, double);
  ///@}

  ///@{
  /**
   * The media's slices write their depth (vtkBrumeSliceVolumeMapper::
   * SetWriteDepth; default off), those made already included.
   */
  void SetMediaWriteDepth(bool write);
  vtkGetMacro(MediaWriteDepth, bool);
  ///@}

  /// Removes the props made by AddToRenderer() from `renderer`, and forgets them.
  void RemoveFromRenderer(vtkRenderer* renderer);

protected:
  vtkBrumeSceneActors();
  ~vtkBrumeSceneActors() override;

  /// The first object of `textures` that does not match the input and the props, or -1.
  int FirstMismatch(vtkPartitionedDataSetCollection* textures);

  vtkSmartPointer<vtkPartitionedDataSetCollection> Input;
  int NumberOfChangedDataSets = -1;
  vtkSmartPointer<vtkPropCollection> Props;
  bool ShowMedia = true;
  bool BackfaceCulling = true;
  double SliceSpacing = 0.0;
  double SliceSpacingScale = 1.0;
  bool SlabSampling = true;
  double ExtinctionDepthTolerance = 1e-3;
  bool Interpolate = true;
  double Exposure = 1.0;
  bool MediaWriteDepth = false;
  double ImageSampleDistance = 1.0;
  int SurfaceAtlasMinimum = 64;

private:
  struct Entry;
  std::vector<Entry> Entries;
  struct Atlas;
  std::vector<Atlas> Atlases;
  vtkWeakPointer<vtkRenderer> Renderer;
  // Makes a surface's unlit textured actor from the given texture and
  // mapper, and adds it to the renderer and the props.
  vtkActor* AddSurfaceActor(vtkRenderer* renderer, vtkImageData* image, vtkPolyData* surface,
    vtkTexture* texture, vtkPolyDataMapper* mapper);
  // Calls `apply` on the mapper of every medium made, then Modified().
  void ApplyToMedia(const std::function<void(vtkBrumeSliceVolumeMapper*)>& apply);

  vtkBrumeSceneActors(const vtkBrumeSceneActors&) = delete;
  void operator=(const vtkBrumeSceneActors&) = delete;
};

#endif
