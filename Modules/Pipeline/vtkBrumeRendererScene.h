// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeRendererScene
 * @brief   the scene a vtkRenderer holds, as a Brume scene collection
 *
 * A source whose output is the Brume scene (see vtkBrumeSceneConversion) of
 * a renderer's visible props and lights, so that what VTK draws with
 * mappers, properties and volumes is what Brume lights:
 *
 * @code
 * vtkNew<vtkBrumeRendererScene> scene;
 * scene->SetRenderer(renderer);                 // the renderer you built
 * vtkNew<vtkBrumePipeline> pipeline;
 * pipeline->SetInputConnection(scene->GetOutputPort());
 * pipeline->SetCamera(renderer->GetActiveCamera());
 * pipeline->Update();
 * @endcode
 *
 * - **Actors** (any vtkMapper whose input is a vtkDataSet; other than
 *   polygonal data, its outer surface) become surfaces in world coordinates
 *   (the actor's matrix applied). The vtkProperty gives the material:
 *   Diffuse x DiffuseColor the diffuse reflectance; with Specular > 0 a
 *   normalized Phong lobe of Specular x SpecularColor and SpecularPower
 *   (both scaled down together where their sum would exceed 1). Actors
 *   with Opacity < 1 are left out (Brume's surfaces are opaque), as are
 *   props that are not vtkActors or vtkVolumes.
 * - **Scalar colouring**: where the mapper colours by scalars
 *   (ScalarVisibility, its ScalarMode, array, lookup table and scalar
 *   range, as VTK maps them), Diffuse x the mapped colour is the
 *   reflectance: point colours as the point array BrumeReflectance
 *   (interpolated over the triangles, as VTK interpolates colours), cell
 *   colours as the cell array. It colours the light each bounce carries
 *   on (colour bleeding) as well as what is shown; a planar surface gets
 *   its direct light computed per texel with the reflectance there.
 *   Colouring by a field-data tuple, the mapped alpha and textures are not
 *   read.
 * - **Which side shows**: Brume shows a surface's front side (its
 *   polygons' winding), VTK both: a closed surface (coincident points
 *   merged) is turned outward, an open one toward the camera as it stands
 *   when the scene is built. Only the renderer's own view props that are
 *   vtkActors (not vtkFollowers) or vtkVolumes are lit; the parts of other
 *   props (widgets, assemblies) are drawn by VTK.
 * - **Volumes** become media classified by their vtkVolumeProperty
 *   (vtkBrumeVolumePropertyMedium, its Albedo given here): images
 *   directly, other datasets resampled. The volume's translation and
 *   axis-aligned scale are applied; a rotated volume is refused.
 * - **Lights**: the renderer's switched-on lights. VTK's intensities are
 *   factors of its shading, not radiometric: by default (PhysicalLights
 *   off) a light of Intensity 1 gives an irradiance of pi W/m^2 at its
 *   focal point (a positional light: pi x its distance to the focal point
 *   squared, in W/sr; a directional one: pi W/m^2), so that a white
 *   Lambertian surface facing it there has a radiance of 1, as bright as
 *   VTK shades it. With PhysicalLights on, Intensity x DiffuseColor is read
 *   as W/sr (positional) or W/m^2 (directional), as vtkBrumeLightTracer
 *   reads vtkLights. Both are multiplied by LightScale. Headlights and
 *   camera lights are taken where they stand when the scene is built; they
 *   do not follow the camera afterwards. A renderer without a light gets
 *   what VTK would give it: a directional light along the active camera's
 *   view. A point light outside the sphere that bounds the scene becomes a
 *   spot of the same intensity whose cone just holds that sphere: the same
 *   light wherever there is something to light, without tracing the
 *   particles that would leave the scene at once.
 *
 * The output is rebuilt only when a prop, its mapper's input, a property,
 * a volume property or a scene light changed (camera moves rebuild
 * nothing). The camera is not part of the scene: give the renderer's to
 * vtkBrumePipeline::SetCamera.
 *
 * @sa vtkBrumePipeline vtkBrumeVolumePropertyMedium vtkBrumeSceneConversion
 */
#ifndef vtkBrumeRendererScene_h
#define vtkBrumeRendererScene_h

#include "vtkBrumePipelineModule.h" // For export macro
#include "vtkPartitionedDataSetCollectionAlgorithm.h"

class vtkMultiProcessController;
class vtkProp;
class vtkRenderer;

class VTKBRUMEPIPELINE_EXPORT vtkBrumeRendererScene
  : public vtkPartitionedDataSetCollectionAlgorithm
{
public:
  static vtkBrumeRendererScene* New();
  vtkTypeMacro(vtkBrumeRendererScene, vtkPartitionedDataSetCollectionAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The renderer whose props and lights make the scene (held weakly: the
  /// renderer usually owns what lights it).
  void SetRenderer(vtkRenderer* renderer);
  vtkRenderer* GetRenderer();
  ///@}

  ///@{
  /**
   * A renderer with nothing to light (no opaque actor with polygons, no
   * volume) gives an empty scene (on) or an error (off, the default).
   * vtkBrumePass allows it: an empty view is drawn by VTK alone.
   */
  vtkSetMacro(AllowEmpty, bool);
  vtkGetMacro(AllowEmpty, bool);
  vtkBooleanMacro(AllowEmpty, bool);
  ///@}

  ///@{
  /// Lights in W/sr and W/m^2 rather than VTK's shading factors (default off).
  vtkSetMacro(PhysicalLights, bool);
  vtkGetMacro(PhysicalLights, bool);
  vtkBooleanMacro(PhysicalLights, bool);
  ///@}

  ///@{
  /// Multiplies every light's power (default 1).
  vtkSetClampMacro(LightScale, double, 0.0, 1e12);
  vtkGetMacro(LightScale, double);
  ///@}

  ///@{
  /// Single-scattering albedo of every volume's medium (default 0.8 0.8 0.8).
  vtkSetVector3Macro(Albedo, double);
  vtkGetVector3Macro(Albedo, double);
  ///@}

  ///@{
  /**
   * The processes among which the scene is distributed (default null: the
   * renderer holds all of it). With several, each renderer holds a part
   * (ParaView's parallel views): the update is collective, and every
   * process's output is the whole scene (vtkBrumeRendererSceneParts'
   * Gathered: one prop's pieces one surface, turned as a whole), with the
   * point lights aimed at all of it. Translates() still names this
   * process's own props.
   */
  void SetController(vtkMultiProcessController* controller);
  vtkGetObjectMacro(Controller, vtkMultiProcessController);
  ///@}

  /// Including the renderer's props, their data and the scene's lights.
  vtkMTimeType GetMTime() override;

  /// Whether the last update made `prop` part of the scene (the props it
  /// did not are drawn by VTK as usual, see vtkBrumePass).
  bool Translates(vtkProp* prop);

  /// Whether the last scene built holds headlights or camera lights (placed
  /// where the camera stood when it was built).
  bool HasCameraLights();
  /// Whether it holds such lights and the renderer's camera has changed
  /// since it placed them: vtkBrumePass builds the scene again then before
  /// it traces, so that they stand where the camera does.
  bool AreCameraLightsBehind();

  /**
   * A 64-bit hash of the last scene built: its objects' names, geometry,
   * cell arrays and field data, and its lights (headlights and camera
   * lights without their placement, which follows the camera); a medium's
   * point arrays by identity (the array object and its MTime, not its
   * values: volumes are large; by values in a gathered scene, whose arrays
   * are new at each gathering). Equal for a scene built again from
   * unchanged props (ParaView touches mappers and colour maps it does not
   * change), different, but for hash collisions, after any change that
   * alters the scene.
   */
  vtkTypeUInt64 GetContentSignature();

protected:
  vtkBrumeRendererScene();
  ~vtkBrumeRendererScene() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  bool PhysicalLights = false;
  bool AllowEmpty = false;
  double LightScale = 1.0;
  double Albedo[3] = { 0.8, 0.8, 0.8 };
  vtkMultiProcessController* Controller = nullptr;

private:
  vtkBrumeRendererScene(const vtkBrumeRendererScene&) = delete;
  void operator=(const vtkBrumeRendererScene&) = delete;

  struct vtkInternals;
  vtkInternals* Internals;
};

#endif
