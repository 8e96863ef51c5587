"""pvbatch: the "Brume Radiance" representation.

Show(reconstruction) in a render view gives the representation by default;
its screenshot equals vtkBrumeSceneActors' render of the same textures,
camera and size, and the baseline. Moving the camera updates the
view-dependent textures once (the reconstruction's eye follows the camera)
and the image equals the one made from scratch at that camera. Shown with a
dataset that is not Brume's, it draws nothing and says why. Interactive
renders with ParaView's level of detail draw the media coarser
(InteractiveImageSampleDistance), still renders at full resolution. Prints the
frame time of the representation (camera moves included) at the view size.

usage: pvbatch TestBrumeRadianceRepresentation.py PLUGIN BASELINE OUTPUT_DIR [SIZE]
"""
import os
import sys
import time

from paraview.simple import *  # noqa: F401,F403
from vtkmodules.vtkIOImage import vtkPNGReader
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_STRING

import brume  # noqa: F401  the Brume classes' wrappers (GetClientSideObject())

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from brume_testing import actors_image, black_view, check, default_camera, finish, image_error  # noqa: E402,E501

plugin, baseline, output_dir = sys.argv[1:4]
size = int(sys.argv[4]) if len(sys.argv) > 4 else 200
LoadPlugin(plugin, ns=globals())


def reference(textures, camera, png, interpolate=True, extra=None, exposure=1.0):
    """vtkBrumeSceneActors alone, with this test's view and size."""
    actors_image(view, size, textures, camera, png, interpolate, extra, exposure)


scene = BrumeDefaultScene()
tracer = BrumeLightTracer(Input=scene, NumberOfParticles=200000, Seed=1)
reconstruction = BrumeRadianceReconstruction(Scene=scene, Hits=tracer)
reconstruction.UpdatePipeline()

view = black_view(size)
display = Show(reconstruction, view)
check(display.Representation == "Brume Radiance",
      "Show() gives 'Brume Radiance' (got '%s')" % display.Representation)
default_camera(view)
Render(view)  # paraview.simple's first render frames the scene: the camera moves
shown = os.path.join(output_dir, "TestBrumeRadianceRepresentation.png")
SaveScreenshot(shown, view, ImageResolution=[size, size])

algorithm = reconstruction.GetClientSideObject()
camera = view.GetActiveCamera()
first = os.path.join(output_dir, "TestBrumeRadianceRepresentation-actors.png")
reference(algorithm.GetOutput(), camera, first)
error = image_error(shown, first)
check(error <= 0.5, "the render view shows what vtkBrumeSceneActors draws (error %g)" % error)
if os.path.exists(baseline):
    error = image_error(shown, baseline, threshold=16)
    check(error <= 10, "the baseline (error %g, limit 10)" % error)
else:
    check(False, "no baseline %s; the image is %s" % (baseline, shown))

# The camera moves: the fog (forward scattering, per view) follows it.
updates = algorithm.GetNumberOfViewUpdates()
view.CameraPosition = [1.2, 0.6, 3.6]
Render(view)
moved = os.path.join(output_dir, "TestBrumeRadianceRepresentation-moved.png")
SaveScreenshot(moved, view, ImageResolution=[size, size])
eye = algorithm.GetOutput().GetFieldData().GetArray("BrumeEyePosition").GetTuple3(0)
check(max(abs(a - b) for a, b in zip(eye, camera.GetPosition())) < 1e-6,  # single precision
      "the textures radiate toward the camera (%s, camera %s)" % (eye, camera.GetPosition()))
check(algorithm.GetNumberOfViewUpdates() == updates + 1,
      "one view update (%d)" % (algorithm.GetNumberOfViewUpdates() - updates))
scratch = BrumeRadianceReconstruction(Scene=scene, Hits=tracer)
scratch.EyePosition = list(camera.GetPosition())
scratch.UpdatePipeline()
again = os.path.join(output_dir, "TestBrumeRadianceRepresentation-scratch.png")
reference(scratch.GetClientSideObject().GetOutput(), camera, again)
error = image_error(moved, again)
check(error <= 0.5, "after the move, the image made from scratch at the camera (error %g)" % error)

# Nearest texels and voxels: vtkBrumeSceneActors' image with Interpolate off.
display.TextureInterpolation = 0
Render(view)
nearest = os.path.join(output_dir, "TestBrumeRadianceRepresentation-nearest.png")
SaveScreenshot(nearest, view, ImageResolution=[size, size])
blocky = os.path.join(output_dir, "TestBrumeRadianceRepresentation-nearest-actors.png")
reference(algorithm.GetOutput(), camera, blocky, interpolate=False)
error = image_error(nearest, blocky)
check(error <= 0.5 and image_error(nearest, moved) > 0.5,
      "Interpolation off: nearest texels, as vtkBrumeSceneActors draws them (error %g)" % error)
display.TextureInterpolation = 1

# The 16-bit tolerance of volumes on the GPU reaches the representation's
# props (its effect on the atlas is Brume.Pass's and Brume.SliceVolumeMapper's
# to check).
def tolerance():
    display.SMProxy.UpdatePropertyInformation()
    return display.SMProxy.GetProperty("ExtinctionDepthToleranceInfo").GetElement(0)


check(abs(tolerance() - 1e-3) < 1e-12, "volumes go up within 10^-3 by default (%g)" % tolerance())
display.ExtinctionDepthTolerance = 0.0
Render(view)
check(tolerance() == 0.0, "ExtinctionDepthTolerance reaches the props (%g)" % tolerance())
display.ExtinctionDepthTolerance = 1e-3

# Exposure 2.5: surfaces and media brighter, as vtkBrumeSceneActors draws them.
display.Exposure = 2.5
Render(view)
bright = os.path.join(output_dir, "TestBrumeRadianceRepresentation-exposure.png")
SaveScreenshot(bright, view, ImageResolution=[size, size])
expected = os.path.join(output_dir, "TestBrumeRadianceRepresentation-exposure-actors.png")
reference(algorithm.GetOutput(), camera, expected, exposure=2.5)
error = image_error(bright, expected)
check(error <= 0.5 and image_error(bright, moved) > 0.5,
      "Exposure 2.5: as vtkBrumeSceneActors draws it, brighter (error %g)" % error)
display.Exposure = 1.0

# A translucent sphere in front of the fog: ParaView peels translucent
# geometry; the representation keeps the media out of the peeling passes.
ball = Sphere(Center=[0.25, -0.2, 0.6], Radius=0.3, ThetaResolution=24, PhiResolution=24)
ballDisplay = Show(ball, view)
ballDisplay.Opacity = 0.4
ballDisplay.Ambient = 1.0
ballDisplay.Diffuse = 0.0
ballDisplay.AmbientColor = [0.2, 0.4, 0.8]
ballDisplay.DiffuseColor = [0.2, 0.4, 0.8]
Render(view)
peeled = os.path.join(output_dir, "TestBrumeRadianceRepresentation-translucent.png")
SaveScreenshot(peeled, view, ImageResolution=[size, size])
from vtkmodules.vtkFiltersSources import vtkSphereSource  # noqa: E402
from vtkmodules.vtkRenderingCore import vtkActor, vtkPolyDataMapper  # noqa: E402
source = vtkSphereSource()
source.SetCenter(0.25, -0.2, 0.6)
source.SetRadius(0.3)
source.SetThetaResolution(24)
source.SetPhiResolution(24)
mapper = vtkPolyDataMapper()
mapper.SetInputConnection(source.GetOutputPort())
actor = vtkActor()
actor.SetMapper(mapper)
actor.GetProperty().SetOpacity(0.4)
actor.GetProperty().SetAmbient(1.0)
actor.GetProperty().SetDiffuse(0.0)
actor.GetProperty().SetAmbientColor(0.2, 0.4, 0.8)
actor.GetProperty().SetDiffuseColor(0.2, 0.4, 0.8)
expected = os.path.join(output_dir, "TestBrumeRadianceRepresentation-translucent-actors.png")
reference(algorithm.GetOutput(), camera, expected, extra=actor)
error = image_error(peeled, expected)
check(error <= 0.5, "with translucent geometry, the media once, outside the peeling (error %g)"
      % error)
Hide(ball, view)

# Two views of one reconstruction, each with its own camera: each render
# updates the textures toward its own view (one update per switch), and a
# view's image does not change when the other one renders.
other = black_view(size)
Show(reconstruction, other)
Render(other)  # the first render frames the scene
other.CameraPosition = [-1.0, 0.4, 3.7]
other.CameraFocalPoint = [0, 0, 0]
other.CameraViewUp = [0, 1, 0]
other.CameraViewAngle = 40
updates = algorithm.GetNumberOfViewUpdates()
Render(other)
second = os.path.join(output_dir, "TestBrumeRadianceRepresentation-second.png")
SaveScreenshot(second, other, ImageResolution=[size, size])
expected = os.path.join(output_dir, "TestBrumeRadianceRepresentation-second-actors.png")
reference(algorithm.GetOutput(), other.GetActiveCamera(), expected)
error = image_error(second, expected)
check(error <= 0.5, "a second view shows its own camera's textures (error %g)" % error)
Render(view)
first = os.path.join(output_dir, "TestBrumeRadianceRepresentation-first-again.png")
SaveScreenshot(first, view, ImageResolution=[size, size])
error = image_error(first, moved)
check(error <= 0.5, "the first view, rendered again, is as before (error %g)" % error)
check(algorithm.GetNumberOfViewUpdates() == updates + 2,
      "one view update per switch of view (%d)" % (algorithm.GetNumberOfViewUpdates() - updates))
Delete(other)
del other

# Frame time at this size: a camera step and a render, view updates included.
frames = 10
start = time.time()
for k in range(frames):
    view.CameraPosition = [1.2 - 0.1 * k, 0.6, 3.6]
    Render(view)
print("frame %.1f ms at %dx%d (a camera step each, view updates included)"
      % (1000 * (time.time() - start) / frames, size, size))

# ParaView's level of detail (LOD threshold 0: every interactive render):
# the media drawn coarser while interacting, at full resolution at rest.
def drawn_distance():
    display.SMProxy.UpdatePropertyInformation()
    return display.SMProxy.GetProperty("LastImageSampleDistance").GetElement(0)


view.LODThreshold = 0.0
Render(view)  # the view's next update decides on its level of detail
check(drawn_distance() == 1.0, "a still render: full resolution (%g)" % drawn_distance())
view.CameraPosition = [0.4, 0.5, 3.6]
view.SMProxy.InteractiveRender()
check(drawn_distance() == 2.0,
      "an interactive render draws the media at image sample distance 2 (%g)"
      % drawn_distance())
display.InteractiveImageSampleDistance = 3.0
view.SMProxy.InteractiveRender()
check(drawn_distance() == 3.0,
      "InteractiveImageSampleDistance 3 is followed (%g)" % drawn_distance())
Render(view)
check(drawn_distance() == 1.0,
      "a still render draws the media at full resolution (%g)"
      % drawn_distance())
view.LODThreshold = 20.0

# Not Brume's data: nothing drawn, a message.
Hide(reconstruction, view)
sphere = Sphere()
bad = Show(sphere, view)
bad.SetRepresentationType("Brume Radiance")
warnings = []


@calldata_type(VTK_STRING)
def on_warning(obj, event, message):
    warnings.append(message)


bad.GetClientSideObject().GetActiveRepresentation().AddObserver("WarningEvent", on_warning)
Render(view)
empty = os.path.join(output_dir, "TestBrumeRadianceRepresentation-sphere.png")
SaveScreenshot(empty, view, ImageResolution=[size, size])
reader = vtkPNGReader()
reader.SetFileName(empty)
reader.Update()
drawn = max(reader.GetOutput().GetPointData().GetScalars().GetRange(c)[1] for c in range(3))
check(drawn == 0, "a sphere: nothing drawn (brightest value %g)" % drawn)
check(len(warnings) == 1 and "shows the output of Brume Radiance Reconstruction" in warnings[0],
      "a sphere: one warning saying why (%s)" % warnings)

Delete(view)
del view
finish()
