"""vtkBrumePipeline from Python gives what `brume render` gives: a scene file
read by vtkBrumeSceneReader, its render settings and camera taken, the
particle count and size set over them, one fixed view; the radiance is
bitwise that of `brume render SCENE --particles N --size WxH -o x.vti`.
Then another scene, with other objects, through the same pipeline: its
image is a fresh pipeline's.

usage: TestPipelineLikeRender.py BRUME SCENE OUTPUT_DIR
"""
import os
import subprocess
import sys

from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLImageDataReader

import brume

program, scene, output_dir = sys.argv[1:4]
particles, width, height = 30000, 48, 40
output = os.path.join(output_dir, "pipeline-like-render.vti")
subprocess.run([program, "render", scene, "--particles", str(particles),
                "--size", f"{width}x{height}", "-o", output], check=True)
reader = vtkXMLImageDataReader()
reader.SetFileName(output)
reader.Update()
expected = vtk_to_numpy(reader.GetOutput().GetPointData().GetArray("Radiance"))

source = brume.vtkBrumeSceneReader()
source.SetFileName(scene)
pipeline = brume.vtkBrumePipeline()
pipeline.SetInputConnection(source.GetOutputPort())
if not pipeline.ApplySceneSettings():
    sys.exit("the scene did not load")
pipeline.GetTracer().SetNumberOfParticles(particles)
pipeline.SetSize(width, height)
pipeline.GetReconstruction().FixedViewOn()
if not pipeline.Update():
    sys.exit("the pipeline failed at " + pipeline.GetFailedPhase())
image = pipeline.RenderImage()
radiance = vtk_to_numpy(image.GetPointData().GetArray("Radiance"))

print("pixels", radiance.shape[0], "mean radiance", float(radiance.mean()),
      "brume render's", float(expected.mean()))
if radiance.shape != expected.shape or not (radiance == expected).all():
    sys.exit("the pipeline's image differs from brume render's")
if not expected.mean() > 0.0:
    sys.exit("brume render's image is black: nothing was compared")
print("bitwise equal to brume render's")

# Another scene through the same pipeline, whose objects differ: its props
# are made again, and its image is that of a fresh pipeline given the
# same settings (the first scene's) and then that scene.
other = brume.vtkBrumeDefaultSceneSource()
pipeline.SetInputConnection(other.GetOutputPort())
if not pipeline.Update():
    sys.exit("the pipeline failed on the default scene at " + pipeline.GetFailedPhase())
second = pipeline.RenderImage()
if second is None:
    sys.exit("the props could not show the default scene's objects")
fresh = brume.vtkBrumePipeline()  # with the first scene's settings, as the pipeline has them
fresh.SetInputConnection(source.GetOutputPort())
fresh.ApplySceneSettings()
fresh.SetInputConnection(other.GetOutputPort())
fresh.GetTracer().SetNumberOfParticles(particles)
fresh.SetSize(width, height)
fresh.GetReconstruction().FixedViewOn()
if not fresh.Update():
    sys.exit("a fresh pipeline failed at " + fresh.GetFailedPhase())
a = vtk_to_numpy(second.GetPointData().GetArray("Radiance"))
b = vtk_to_numpy(fresh.RenderImage().GetPointData().GetArray("Radiance"))
print("another scene: mean radiance", float(a.mean()), "a fresh pipeline's", float(b.mean()))
if a.shape != b.shape or not (a == b).all() or not b.mean() > 0.0:
    sys.exit("another scene's image differs from a fresh pipeline's")
print("another scene: bitwise equal to a fresh pipeline's")
