"""pvbatch: load the Brume plugin, build the default scene's pipeline from
proxies, render the particle hits and compare with a baseline image. The
plugin leaves VTK's Sequential default backend for STDThread (every core),
unless VTK_SMP_BACKEND_IN_USE chose one.

usage: pvbatch TestBrumePlugin.py PLUGIN BASELINE OUTPUT_DIR
"""
import os
import sys
import time

from paraview.simple import *  # noqa: F401,F403

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from brume_testing import black_view, default_camera, image_error  # noqa: E402

plugin, baseline, output_dir = sys.argv[1:4]
start = time.time()
LoadPlugin(plugin, ns=globals())
print("plugin loaded in %.3f s" % (time.time() - start))
from vtkmodules.vtkCommonCore import vtkSMPTools  # noqa: E402

backend = vtkSMPTools.GetBackend()
print("vtkSMPTools backend", backend, "threads", vtkSMPTools.GetEstimatedNumberOfThreads())
assert backend != "Sequential" or os.environ.get("VTK_SMP_BACKEND_IN_USE"), backend

scene = BrumeDefaultScene()
tracer = BrumeLightTracer(Input=scene)
tracer.NumberOfParticles = 20000
tracer.Seed = 1
reconstruction = BrumeRadianceReconstruction(Scene=scene, Hits=tracer)
reconstruction.RadiosityThreshold = 64
reconstruction.UpdatePipeline()
hits = tracer.GetDataInformation().DataInformation.GetNumberOfPoints()
textures = reconstruction.GetDataInformation().DataInformation.GetNumberOfDataSets()
print("hits", hits, "texture datasets", textures)
assert hits > 20000, hits
assert textures >= 7, textures

# The hits are bare points: give them vertices to be drawn.
points = MaskPoints(Input=tracer)
points.OnRatio = 1
points.MaximumNumberofPoints = 10000000
points.GenerateVertices = 1
points.SingleVertexPerCell = 1
view = black_view(300)
display = Show(points, view)
display.SetRepresentationType("Points")
ColorBy(display, ("POINTS", "ObjectId"))
display.LookupTable.RescaleTransferFunction(0, 6)
default_camera(view)
Render(view)
output = os.path.join(output_dir, "TestBrumePlugin.png")
SaveScreenshot(output, view)
# Release the view's OpenGL context before the interpreter tears down.
Delete(view)
del view
if not os.path.exists(baseline):
    print("no baseline", baseline, "- the image is", output)
    sys.exit(1)
error = image_error(output, baseline, threshold=16)
print("strict image error", error, "(limit 10)")
sys.exit(0 if error <= 10.0 else 1)
