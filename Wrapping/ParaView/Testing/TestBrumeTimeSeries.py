"""pvbatch: scenes that change over time, stepped by ParaView's time controls.

1. A Brume scene file whose medium lists a .vti file per time step: the
   scene reader's TimestepValues are the file's times, the animation scene
   takes them, and the reconstruction shown with "Brume Radiance" follows
   the animation time: the blob of fog moves from left to right in the
   screenshots, which equal vtkBrumeSceneActors' images of the textures.
2. ParaView's own time series (the XML image reader given the same files,
   its steps 0, 1, 2) made a medium by "Brume Medium From Field": the
   medium's textures follow the animation time the same way (grouped with
   a ground, the medium first: VTK takes a filter's time steps from its
   first input).
3. The same series shown as a Volume in a Brume Render View, no Brume
   filter: a new animation time traces once more, and the fog moves.

usage: pvbatch TestBrumeTimeSeries.py PLUGIN OUTPUT_DIR
"""
import json
import math
import os
import sys

from paraview.simple import *  # noqa: F401,F403
from vtkmodules.vtkCommonCore import vtkFloatArray
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkIOXML import vtkXMLImageDataWriter

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from brume_testing import (at_scene_camera, black_view, check, finish,  # noqa: E402
                           png_pixels, screenshot_like_actors)

plugin, output_dir = sys.argv[1:3]
LoadPlugin(plugin, ns=globals())
work = os.path.join(output_dir, "TestBrumeTimeSeries")
os.makedirs(work, exist_ok=True)

centres = [-0.3, 0.0, 0.3]
files = []
for k, c in enumerate(centres):
    n = 16
    image = vtkImageData()
    image.SetDimensions(n, n, n)
    image.SetOrigin(-0.5, -0.5, -0.5)
    image.SetSpacing(1.0 / (n - 1), 1.0 / (n - 1), 1.0 / (n - 1))
    density = vtkFloatArray()
    density.SetName("density")
    density.SetNumberOfTuples(n ** 3)
    for i in range(n ** 3):
        x, y, z = (-0.5 + (i % n) / (n - 1.0), -0.5 + (i // n % n) / (n - 1.0),
                   -0.5 + (i // (n * n)) / (n - 1.0))
        density.SetValue(i, 12.0 * math.exp(-((x - c) ** 2 + y ** 2 + z ** 2) / 0.02))
    image.GetPointData().AddArray(density)
    files.append(os.path.join(work, "blob%d.vti" % k))
    writer = vtkXMLImageDataWriter()
    writer.SetFileName(files[-1])
    writer.SetInputData(image)
    writer.SetDataModeToBinary()
    writer.Write()

times = [0.0, 0.5, 2.0]
camera = {"position": [0, 0, 3], "focal_point": [0, 0, 0], "view_up": [0, 1, 0],
          "view_angle": 35}
scene_file = os.path.join(work, "series.json")
with open(scene_file, "w") as f:
    json.dump({
        "brume_scene": 1, "camera": camera,
        "surfaces": [{"name": "ground",
                      "quad": [[-2, -0.6, 2], [2, -0.6, 2], [2, -0.6, -2], [-2, -0.6, -2]],
                      "material": {"type": "lambertian", "reflectance": [0.5, 0.5, 0.5]}}],
        "media": [{"name": "blob", "sigma_a": [0.05, 0.05, 0.05], "sigma_s": [0.95, 0.95, 0.95],
                   "density": {"vti": [os.path.basename(p) for p in files], "array": "density",
                               "times": times}}],
        "lights": [{"type": "point", "position": [0, 1.2, 1.2], "intensity": [40, 40, 40]}]}, f)

size = 96


def centroid_x(png):
    """The brightness-weighted column of a screenshot's rows above the
    ground (the upper 55 %), from -1 (left) to 1."""
    pixels = png_pixels(png).astype(float).sum(axis=2)
    columns = pixels[int(0.45 * pixels.shape[0]):, :].sum(axis=0)
    xs = [(2.0 * (i + 0.5) / len(columns)) - 1.0 for i in range(len(columns))]
    return sum(x * w for x, w in zip(xs, columns)) / max(columns.sum(), 1e-9)


# 1. The scene file's own steps.
reader = OpenDataFile(scene_file)
check(list(reader.TimestepValues) == times,
      "the scene reader's TimestepValues: %s" % list(reader.TimestepValues))
animation = GetAnimationScene()
animation.UpdateAnimationUsingDataTimeSteps()
check(list(GetTimeKeeper().TimestepValues) == times,
      "the animation takes the scene's times: %s" % list(GetTimeKeeper().TimestepValues))
tracer = BrumeLightTracer(Input=reader, NumberOfParticles=60000, Seed=1)
reconstruction = BrumeRadianceReconstruction(Scene=reader, Hits=tracer,
                                             EyePosition=camera["position"])
view = black_view(size)
Show(reconstruction, view)
at_scene_camera(view, camera)


def screenshot_at(t, name):
    """The view's screenshot at animation time t."""
    animation.AnimationTime = t
    Render(view)
    png = os.path.join(work, name)
    SaveScreenshot(png, view, ImageResolution=[size, size])
    return png


shots = []
for k, t in enumerate(times):
    animation.AnimationTime = t
    png = screenshot_like_actors(view, reconstruction, size, work, "scene-step%d" % k,
                                 "at t = %g the view" % t)
    shots.append(centroid_x(png))
print("brightness centroids (x, -1 to 1) at the three times:", shots)
check(shots[0] < shots[1] < shots[2] and shots[2] - shots[0] > 0.1,
      "the fog moves left to right as the animation time goes on: %s" % shots)
Delete(view)
del view

# 2. ParaView's own time series made a medium.
series = XMLImageDataReader(FileName=files)
series.PointArrayStatus = ["density"]
check(list(series.TimestepValues) == [0.0, 1.0, 2.0],
      "ParaView's reader of the three files has steps %s" % list(series.TimestepValues))
medium = BrumeMediumFromField(Input=series)
medium.Scalars = ["POINTS", "density"]
opacity = GetOpacityTransferFunction("density")
opacity.Points = [0.0, 0.0, 0.5, 0.0, 12.0, 0.9, 0.5, 0.0]
opacity.ScalarRangeInitialized = 1
medium.ScalarOpacityFunction = opacity
medium.ScalarOpacityUnitDistance = 0.1
ground = Triangulate(Input=Plane(Origin=[-2, -0.6, 2], Point1=[2, -0.6, 2],
                                 Point2=[-2, -0.6, -2]))
# The medium first: VTK's pipeline takes a filter's time steps from its
# first input, and a group whose first input does not change over time is
# not brought up to date at a new time.
grouped = GroupDatasets(Input=[medium, ground])
light = CreateLight()
light.Coords = "Scene"
light.Type = "Positional"
light.Position = [0, 1.2, 1.2]
light.FocalPoint = [0, 0, 0]
light.Intensity = 40.0
field_tracer = BrumeLightTracer(Input=grouped, NumberOfParticles=60000, Seed=1, Lights=[light])
field_reconstruction = BrumeRadianceReconstruction(Scene=grouped, Hits=field_tracer,
                                                   EyePosition=camera["position"])
view = black_view(size)
Show(field_reconstruction, view)
at_scene_camera(view, camera)
animation.UpdateAnimationUsingDataTimeSteps()
field_shots = [centroid_x(screenshot_at(t, "field-t%g.png" % t)) for t in (0.0, 2.0)]
print("brightness centroids of the field's medium at t = 0 and 2:", field_shots)
check(field_shots[1] - field_shots[0] > 0.1,
      "the field's medium follows ParaView's time: %s" % field_shots)
Delete(view)
del view

# 3. The Brume Render View: ParaView's own representations, lit by Brume.
view = black_view(size, CreateView("BrumeRenderView"))
view.BrumeParticles = 60000
volume = Show(series, view)
volume.SetRepresentationType("Volume")
ColorBy(volume, ("POINTS", "density"))
Show(ground, view)
at_scene_camera(view, camera)


def traces():
    view.SMProxy.UpdatePropertyInformation()
    return view.SMProxy.GetProperty("BrumeNumberOfTraces").GetElement(0)


view_shots, counts = [], []
for t in (0.0, 2.0):
    view_shots.append(centroid_x(screenshot_at(t, "render-view-t%g.png" % t)))
    counts.append(traces())
print("Brume Render View: centroids %s, traces %s" % (view_shots, counts))
check(counts[1] == counts[0] + 1, "a new time traces once more (%s)" % counts)
check(view_shots[1] - view_shots[0] > 0.1,
      "the Brume Render View's fog follows the time: %s" % view_shots)
Delete(view)
del view
finish()
