// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeRadianceRepresentation
 * @brief   ParaView's "Brume Radiance": the reconstruction's textures in a
 *          render view, following its camera
 *
 * The representation ParaView gives the output of Brume's Radiance
 * Reconstruction (the default in render views; any Brume texture
 * collection can be shown with it): textured surfaces and media drawn by
 * vtkBrumeSliceVolumeMapper, the props of vtkBrumeSceneActors, in the
 * view's renderer. The surfaces show radiance unlit (W m^-2 sr^-1, clamped
 * to [0, 1] by the framebuffer, as VTK shows float textures).
 *
 * Camera following (FollowCamera, default on): when the textures depend on
 * the viewpoint (glossy surfaces, anisotropic media held per view: the
 * collection's `BrumeViewDependentObjects`), the plugin's client side
 * (vtkBrumeCameraFollower) sets the reconstruction's EyePosition to the
 * view's camera before each render, so that the render's update
 * recomputes the view-dependent textures wherever the reconstruction runs
 * (built-in session, pvserver, every process under mpirun). What is left
 * here: in one process, textures that do not radiate toward the camera
 * (`BrumeEyePosition`) at render time (a camera moved without its view
 * proxy) give the reconstruction the view's camera (its SetCamera) and
 * update it; only the images that changed are uploaded again. Directional
 * media (spherical harmonics) need no update at all. Two views of one
 * reconstruction each get their own view, at the cost of an update
 * whenever the other one rendered last.
 *
 * Shown with anything but a Brume texture collection, it draws nothing and
 * says why once.
 *
 * @sa vtkBrumeSceneActors vtkBrumeRadianceReconstruction
 */
#ifndef vtkBrumeRadianceRepresentation_h
#define vtkBrumeRadianceRepresentation_h

#include "vtkBrumeParaViewRepresentationModule.h" // For export macro
#include "vtkCommand.h"                           // For TexturesShownEvent
#include "vtkPVDataRepresentation.h"
#include "vtkSmartPointer.h" // For members
#include "vtkWeakPointer.h"  // For members

#include <string> // For members

class vtkBrumeSceneActors;
class vtkPartitionedDataSetCollection;
class vtkPVRenderView;
class vtkRenderer;

class VTKBRUMEPARAVIEWREPRESENTATION_EXPORT vtkBrumeRadianceRepresentation
  : public vtkPVDataRepresentation
{
public:
  static vtkBrumeRadianceRepresentation* New();
  vtkTypeMacro(vtkBrumeRadianceRepresentation, vtkPVDataRepresentation);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  void SetVisibility(bool visible) override;
  int ProcessViewRequest(
    vtkInformationRequestKey* request, vtkInformation* inInfo, vtkInformation* outInfo) override;

  ///@{
  /// Show the surfaces, the media (default on).
  void SetShowSurfaces(bool show);
  vtkGetMacro(ShowSurfaces, bool);
  void SetShowMedia(bool show);
  vtkGetMacro(ShowMedia, bool);
  ///@}

  ///@{
  /// Slice spacing of the media, in world units (default 0: half the smallest voxel).
  void SetSliceSpacing(double spacing);
  vtkGetMacro(SliceSpacing, double);
  ///@}

  ///@{
  /// The optical depth a float extinction grid's 16-bit copy on the GPU
  /// may be off by (vtkBrumeSceneActors::SetExtinctionDepthTolerance;
  /// default 10^-3, 0 keeps floats exactly).
  void SetExtinctionDepthTolerance(double tolerance);
  double GetExtinctionDepthTolerance();
  ///@}

  ///@{
  /**
   * The media's image sample distance in interactive renders that use
   * ParaView's level of detail (default 2, 1 to 16; see
   * vtkBrumeSliceVolumeMapper::SetImageSampleDistance): drawn that much
   * coarser while the camera moves, at full resolution in still renders.
   * ParaView uses its level of detail when the data shown exceed the render
   * view's LOD threshold (Settings, Render View, "LOD Threshold": 0 always).
   */
  vtkSetClampMacro(InteractiveImageSampleDistance, double, 1.0, 16.0);
  vtkGetMacro(InteractiveImageSampleDistance, double);
  ///@}

  ///@{
  /// Multiplies the radiance shown (default 1): see vtkBrumeSceneActors::SetExposure.
  void SetExposure(double exposure);
  vtkGetMacro(Exposure, double);
  ///@}

  ///@{
  /// Interpolate textures and voxels linearly (default on) or show them as they are.
  void SetTextureInterpolation(bool interpolate);
  vtkGetMacro(TextureInterpolation, bool);
  ///@}

  ///@{
  /// Cull the back of surfaces (default on; see vtkBrumeSceneActors).
  void SetBackfaceCulling(bool cull);
  vtkGetMacro(BackfaceCulling, bool);
  ///@}

  ///@{
  /// Update view-dependent textures toward the view's camera (default on).
  void SetFollowCamera(bool follow);
  vtkGetMacro(FollowCamera, bool);
  ///@}

  ///@{
  /**
   * What the last render showed: the number of props, the viewpoint the
   * textures radiate toward, and the media's image sample distance (for
   * tests and the curious).
   */
  int GetNumberOfProps();
  void GetShownEyePosition(double eye[3]);
  double GetLastImageSampleDistance();
  ///@}

  /**
   * Fired by a render that shows new textures in the props already made,
   * with the number of data sets they changed (an int, call data:
   * vtkBrumeSceneActors::GetNumberOfChangedDataSets): only those are
   * uploaded again. Textures delivered from a server are new objects each
   * time; those equal to what is shown keep the shown ones.
   */
  static constexpr unsigned long TexturesShownEvent = vtkCommand::UserEvent + 1;

protected:
  vtkBrumeRadianceRepresentation();
  ~vtkBrumeRadianceRepresentation() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  bool AddToView(vtkView* view) override;
  bool RemoveFromView(vtkView* view) override;

private:
  vtkBrumeRadianceRepresentation(const vtkBrumeRadianceRepresentation&) = delete;
  void operator=(const vtkBrumeRadianceRepresentation&) = delete;

  // The textures to show this frame: the delivered ones, or the
  // reconstruction's output updated toward the view's camera.
  vtkPartitionedDataSetCollection* Follow(
    vtkPVRenderView* view, vtkPartitionedDataSetCollection* textures);
  // Points the props at `textures`, made anew when the objects changed.
  void Show(vtkPartitionedDataSetCollection* textures);
  void Hide();
  void Warn(const std::string& message);
  void ApplyVisibility();

  vtkSmartPointer<vtkPartitionedDataSetCollection> Cache;
  std::string InputProblem; // why the input cannot be shown, "" if it can
  double Bounds[6];
  vtkSmartPointer<vtkBrumeSceneActors> Actors;
  vtkWeakPointer<vtkRenderer> Renderer;
  vtkWeakPointer<vtkPartitionedDataSetCollection> Shown;
  std::string ShownLayout;                          // the objects' kinds of Shown, in order
  vtkWeakPointer<vtkObject> FollowedReconstruction; // given the view's camera
  std::string LastWarning;
  bool ShowSurfaces = true;
  bool ShowMedia = true;
  double SliceSpacing = 0.0;
  double InteractiveImageSampleDistance = 2.0;
  bool BackfaceCulling = true;
  bool TextureInterpolation = true;
  double Exposure = 1.0;
  bool FollowCamera = true;
};

#endif
