// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkBrumeSceneCamera
 * @brief   the camera a Brume scene names, or the default view
 *
 * A scene collection may name its camera in its field data:
 * `BrumeCameraPosition`, `BrumeCameraFocalPoint`, `BrumeCameraViewUp` (3
 * components) and `BrumeCameraViewAngle` (degrees). Where it names none,
 * every Brume tool uses the default view, defined once in the physics core
 * (brume::PinholeCamera): from (0, 0, 4) toward the origin, +y up, a 40
 * degree vertical view angle.
 *
 * From Python:
 * @code{.py}
 * camera = vtkCamera()
 * brume.vtkBrumeSceneCamera.SetFromScene(scene.GetOutputDataObject(0), camera)
 * @endcode
 */
#ifndef vtkBrumeSceneCamera_h
#define vtkBrumeSceneCamera_h

#include "vtkBrumeDataModelModule.h" // For export macro
#include "vtkObject.h"

class vtkCamera;
class vtkDataObject;
class vtkFieldData;

class VTKBRUMEDATAMODEL_EXPORT vtkBrumeSceneCamera : public vtkObject
{
public:
  static vtkBrumeSceneCamera* New();
  vtkTypeMacro(vtkBrumeSceneCamera, vtkObject);

  /// Sets `camera` to the default view.
  static void SetToDefault(vtkCamera* camera);

  /// The default view as numbers.
  static void GetDefault(
    double position[3], double focalPoint[3], double viewUp[3], double& viewAngle);

  /**
   * Sets `camera` to the scene's camera and returns true when the scene's
   * field data names one (every array present), else to the default view
   * and returns false.
   */
  static bool SetFromScene(vtkDataObject* scene, vtkCamera* camera);

  /**
   * The scene's camera as numbers: the default view, overridden by each of
   * the scene's camera arrays that is present. True when all are.
   */
  static bool GetSceneCamera(vtkDataObject* scene, double position[3], double focalPoint[3],
    double viewUp[3], double& viewAngle);

  /// Writes `camera` into a scene's field data (replacing the arrays there).
  static void WriteToScene(vtkCamera* camera, vtkFieldData* fieldData);

protected:
  vtkBrumeSceneCamera() = default;
  ~vtkBrumeSceneCamera() override = default;

private:
  vtkBrumeSceneCamera(const vtkBrumeSceneCamera&) = delete;
  void operator=(const vtkBrumeSceneCamera&) = delete;
};

#endif
