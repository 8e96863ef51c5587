// SPDX-License-Identifier: BSD-3-Clause
// The view every evaluation measures (private to Brume::Evaluation).
#ifndef vtkBrumeEvaluationView_h
#define vtkBrumeEvaluationView_h

#include "vtkSmartPointer.h"

#include "brume/PathTracer.h" // For brume::PinholeCamera

class vtkCamera;
class vtkDataObject;

struct vtkBrumeEvaluationView
{
  /**
   * A new camera with the position, focal point, view up and view angle of
   * `camera`; without one, of the scene's camera (its field data, see
   * vtkBrumeSceneConversion::GetCamera); without that, Brume's default view:
   * from (0, 0, 4) toward the origin, +y up, 40 degrees.
   */
  static vtkSmartPointer<vtkCamera> Camera(vtkDataObject* scene, vtkCamera* camera);

  /// The same pinhole camera for the physics core, `width` x `height` pixels.
  static brume::PinholeCamera Pinhole(vtkCamera* camera, int width, int height);
};

#endif
