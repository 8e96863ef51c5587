// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeSceneConversion
 * @brief   converts between VTK data and the Brume physics core's types
 *
 * A Brume scene is a vtkPartitionedDataSetCollection with one partitioned
 * dataset per object, named through its vtkCompositeDataSet::NAME() metadata:
 *
 * - a **surface** is a vtkPolyData (polygons and triangle strips are
 *   triangulated). Its material comes from field data (the whole object) and
 *   cell data of the same names (per cell, overriding):
 *   - `BrumeMaterial`: "lambertian" (default), "phong" or "mirror" (a string
 *     in field data; 0, 1, 2 in cell data);
 *   - `BrumeReflectance` (3 components): diffuse reflectance rho_d, default 0.75;
 *   - `BrumeSpecular` (3 components): rho_s of the Phong lobe or the mirror,
 *     default 0; rho_d + rho_s <= 1 per channel;
 *   - `BrumeExponent` (1 component): Phong exponent, default 32 (see
 *     brume/Material.h for the energy-conserving normalized Phong BRDF);
 *   - `BrumeEmission` (3 components): emitted radiance in W m^-2 sr^-1 on the
 *     side the polygon winding's normal points to, default 0.
 * - a **medium** is a vtkImageData whose bounds are the medium's box and whose
 *   field data holds `BrumeSigmaA` and `BrumeSigmaS` (3 components, m^-1),
 *   `BrumeG` (Henyey-Greenstein asymmetry, -1 < g < 1, default 0) and
 *   optionally `BrumeDensityScale` (scales both coefficients). Without a
 *   density it is homogeneous. The density is, in this order: the OpenVDB
 *   float grid `BrumeVDBGrid` (default: the first float grid) of the file
 *   `BrumeVDBFile` (strings), used sparsely in place; the point or cell array
 *   named by the string `BrumeDensityArray`; the active point or cell
 *   scalars. sigma(x) = density(x) * sigma; point densities are interpolated
 *   trilinearly, cell densities are constant per cell. With the field arrays
 *   `BrumeScalarOpacity` ((scalar, opacity) tuples, scalars not decreasing,
 *   opacities in [0, 1]), `BrumeScalarOpacityUnitDistance` (default 1),
 *   `BrumeScalarComponent` (default 0) and `BrumeInterpolation` ("linear",
 *   "nearest"), the array or the OpenVDB grid holds scalars, any finite
 *   values, classified after interpolation: the density is
 *   -ln(1 - opacity) / unit distance (brume::ClassifiedDensity;
 *   vtkBrumeVolumePropertyMedium writes them from a vtkVolumeProperty).
 *
 * Object ids number the surfaces first, then the media, each in collection
 * order. The scene's camera may be given in the collection's field data:
 * `BrumeCameraPosition`, `BrumeCameraFocalPoint`, `BrumeCameraViewUp` (3
 * components) and `BrumeCameraViewAngle` (degrees).
 *
 * Particle hits: vtkBrumeHitConversion. Radiance textures:
 * vtkBrumeRadianceConversion. The camera: vtkBrumeSceneCamera.
 *
 * @sa vtkBrumeHitConversion vtkBrumeRadianceConversion vtkBrumeSceneCamera
 */
#ifndef vtkBrumeSceneConversion_h
#define vtkBrumeSceneConversion_h

#include "vtkBrumeConversionModule.h" // For export macro
#include "vtkSmartPointer.h"          // For return values

#include "brume/RayCaster.h" // For brume::RayCaster
#include "brume/Scene.h"     // For brume::Scene

#include <memory> // For std::shared_ptr
#include <string>
#include <vector>

class vtkDataObject;
class vtkFieldData;
class vtkAlgorithm;
class vtkLightCollection;
class vtkPartitionedDataSetCollection;

class VTKBRUMECONVERSION_EXPORT vtkBrumeSceneConversion
{
public:
  /// Where each core object came from in the collection.
  struct ObjectSource
  {
    unsigned int CollectionIndex;
    std::string Name;
  };

  /**
   * The scene as a collection: a vtkPartitionedDataSetCollection as is, a
   * vtkMultiBlockDataSet converted (block names kept), a single dataset as a
   * one-object collection. Null for anything else.
   */
  static vtkSmartPointer<vtkPartitionedDataSetCollection> AsCollection(vtkDataObject* input);

  /// Appends `data` to a scene collection as a one-partition object named `name`.
  static void AddObject(
    vtkPartitionedDataSetCollection* scene, vtkDataObject* data, const std::string& name);

  /**
   * Appends an n-component tuple to the double array `name` of `fieldData`,
   * creating it on first use: how scene properties (BrumeSigmaA, BrumeLight*,
   * ...) are written.
   */
  static void AppendTuple(vtkFieldData* fieldData, const char* name, const double* values, int n);

  /**
   * Builds the core scene from a scene collection. Returns an empty string on
   * success, otherwise a message saying what is wrong with the input. The
   * lights are the collection's field-data lights, then those of
   * `tracedLights` (a tracer's output field data: the lights it was given
   * besides the scene's, see AppendFieldLights), then `lights`: the order in
   * which the hits' EmitterId counts them.
   */
  static std::string ToScene(vtkDataObject* input, brume::Scene& scene,
    std::vector<ObjectSource>* sources = nullptr, vtkLightCollection* lights = nullptr,
    vtkFieldData* tracedLights = nullptr);

  /**
   * What both tracers check before tracing: a non-negative seed and a valid
   * scene (with `lights` added). False, with an error reported on
   * `algorithm`, otherwise.
   */
  static bool ToTracedScene(vtkAlgorithm* algorithm, vtkDataObject* input, vtkIdType seed,
    vtkLightCollection* lights, brume::Scene& scene);

  /**
   * Adds the switched-on lights to the scene. Intensity x DiffuseColor is the
   * radiant intensity (W/sr) of a positional light: a point light when its
   * ConeAngle is 90 degrees or more, otherwise a spot light of that half-angle
   * emitting uniformly in its cone; it is the irradiance (W/m^2) of a
   * directional light, whose collimated beam covers the scene's bounds.
   */
  static std::string ConvertLights(vtkLightCollection* lights, brume::Scene& scene);

  /**
   * Adds the lights listed in a scene collection's field data: the string
   * array `BrumeLightType` ("point", "spot", "directional") and, one tuple
   * per light, `BrumeLightPosition`, `BrumeLightDirection`,
   * `BrumeLightIntensity` (3 components; the same units as vtkLight's) and
   * `BrumeLightConeAngle` (spot half-angle, degrees).
   */
  static std::string ConvertFieldLights(vtkFieldData* fieldData, brume::Scene& scene);

  /**
   * Appends `lights` to `fieldData` in the schema ConvertFieldLights reads:
   * how a tracer's output tells the reconstruction about the vtkLights it
   * was given (a directional light's beam is made again to cover the scene).
   */
  static void AppendFieldLights(const std::vector<brume::Light>& lights, vtkFieldData* fieldData);

  /**
   * The arrays whose converted fields ToScene() keeps (until the array is
   * deleted or modified), so that the tracer, the reconstruction and the
   * renderer convert a field once. A float array of one component is not
   * copied: its field reads the array's memory, and each medium made from
   * it holds a reference to the array.
   */
  static std::size_t GetNumberOfCachedArrays();

  /**
   * The ray caster (Embree's BVH) of `scene`'s surfaces: one built before
   * for the same geometry (every surface's vertex and triangle counts, and
   * a 64-bit hash of their bytes, in order) while anyone still holds it,
   * else a new one. The reconstruction keeps its shadow rays' one, so that
   * the tracer and the reconstruction of the next time step, batch or
   * refinement find it: unchanged surfaces' BVH is built once, not twice
   * per step and batch (a high-quality build of 2*10^6 triangles takes
   * 1.5 s on 2 cores). One cache for the process (here, not in the core,
   * which every module links). Thread safe.
   */
  static std::shared_ptr<const brume::RayCaster> SharedRayCaster(const brume::Scene& scene);

  /// BVHs SharedRayCaster() built (not found) since the process started.
  static std::size_t GetNumberOfRayCasterBuilds();

  /**
   * OpenVDB grids read from their files since the process started: a
   * grid is found again, not read, while anyone holds it (the scene
   * reader's check of its scene, the tracer until its next run, the
   * reconstruction's textures), so that one run reads each file once.
   */
  static std::size_t GetNumberOfOpenVDBLoads();
};

#endif
