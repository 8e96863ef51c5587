// SPDX-License-Identifier: BSD-3-Clause
// vtkBrumeRendererScene's parts (private to the module): what becomes of an
// actor's data and of the renderer's point lights.
#ifndef vtkBrumeRendererSceneParts_h
#define vtkBrumeRendererSceneParts_h

#include "vtkSmartPointer.h"

#include "brume/Light.h"

#include <vector>

class vtkActor;
class vtkCamera;
class vtkMultiProcessController;
class vtkDataSet;
class vtkPartitionedDataSetCollection;
class vtkPolyData;

namespace vtkBrumeRendererSceneParts
{
/**
 * The polygons of `data` (one dataset the actor's mapper draws) as a Brume
 * surface: in world coordinates, with the actor's property as material and
 * its mapper's colours as reflectance (point colours per vertex, cell
 * colours per cell), turned to show its side to the camera (closed
 * surfaces outward, open ones toward `camera`; not turned with a null
 * camera). Null without polygons.
 */
vtkSmartPointer<vtkPolyData> ActorSurface(vtkActor* actor, vtkDataSet* data, vtkCamera* camera);

/**
 * Collective: the whole scene of which `part` is this process's share, on
 * every process alike. Surfaces of the same name (one prop's pieces on
 * several processes, made by ActorSurface unturned) become one, turned as
 * ActorSurface turns a surface (the pieces of a closed surface are open);
 * the other processes' volumes are kept as their own media, named
 * "<name> (process r)". The scene's field data are `part`'s.
 */
vtkSmartPointer<vtkPartitionedDataSetCollection> Gathered(
  vtkMultiProcessController* controller, vtkPartitionedDataSetCollection* part, vtkCamera* camera);

/// Point lights outside the sphere bounding `scene` become spots of the
/// same intensity whose cone just holds it.
void AimPointLights(vtkPartitionedDataSetCollection* scene, std::vector<brume::Light>& lights);
}

#endif
