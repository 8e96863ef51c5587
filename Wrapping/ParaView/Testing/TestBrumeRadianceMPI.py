"""pvbatch, alone or under mpirun: the "Brume Radiance" representation of the
project's own cloud over an empty sky, the same image on one process and on
several. Under mpirun every process holds the textures and draws them, and
IceT composites the processes' images by depth: the slices write theirs, or
the cloud, drawn over pixels at the far plane, would be dropped as
background. The textures follow the camera: before each render the
plugin's client side (process 0) sets the reconstruction's EyePosition,
which reaches every process, and the update runs on all of them in step.

usage: pvbatch TestBrumeRadianceMPI.py PLUGIN SCENE_DIR OUTPUT_DIR
(one process writes TestBrumeRadianceMPI-one.png; several compare theirs with it)
"""
import os
import sys

from paraview import servermanager as sm
from paraview.simple import *  # noqa: F401,F403

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from brume_testing import black_view, check, finish, image_error  # noqa: E402

plugin, scene_dir, output_dir = sys.argv[1:4]
if not os.environ.get("DISPLAY"):
    # ParaView 5.11 (Debian's) renders in parallel through X only: without a
    # display it deems remote rendering unavailable, renders on process 0
    # alone, and its IceT pass waits for the others (a Sphere hangs too).
    print("skipped: mpirun pvbatch renders through an X display")
    sys.exit(0)
LoadPlugin(plugin, ns=globals())
processes = sm.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
size = 160
eye, focus = [60.0, 45.0, 170.0], [-5.0, 62.0, 0.0]

scene = OpenDataFile(os.path.join(scene_dir, "cumulus.json"))
tracer = BrumeLightTracer(Input=scene, NumberOfParticles=100000, Seed=1)
reconstruction = BrumeRadianceReconstruction(Scene=scene, Hits=tracer)
view = black_view(size)
display = Show(reconstruction, view)
check(display.Representation == "Brume Radiance", "Show() gives 'Brume Radiance'")
for _ in range(2):  # paraview.simple's first render frames the scene
    view.CameraPosition = eye
    view.CameraFocalPoint = focus
    view.CameraViewUp = [0, 1, 0]
    view.CameraViewAngle = 45
    Render(view)
check(all(abs(a - b) < 1e-6 for a, b in zip(reconstruction.EyePosition, eye)),
      "EyePosition follows the camera (%s)" % list(reconstruction.EyePosition))
one = os.path.join(output_dir, "TestBrumeRadianceMPI-one.png")
if processes == 1:
    SaveScreenshot(one, view, ImageResolution=[size, size])
    check(os.path.exists(one), "one process's image written")
else:
    many = os.path.join(output_dir, "TestBrumeRadianceMPI-%d.png" % processes)
    SaveScreenshot(many, view, ImageResolution=[size, size])
    if os.path.exists(one):
        # IceT's composite rounds a few pixels by a few levels of 255.
        error = image_error(many, one, threshold=16)
        check(error <= 0.5, "%d processes draw one process's image (error %g)" % (processes, error))
    else:
        check(False, "no image of one process (%s): run Brume.ParaView.MPIRenderOne" % one)
finish()
