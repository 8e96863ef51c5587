"""pvbatch: the default scene's reconstruction shown in a Brume Render View
looks as `brume render` draws it.

The same scene, particles, seed, size and camera: `brume render`'s PNG
against the view's screenshot, within one grey level on average (the
view's display transform is brume render's: exposure, clamp, sRGB). In a
stock render view the same textures are drawn without that transform, and
darker: printed for the record.

usage: pvbatch TestBrumeRenderViewLook.py PLUGIN BRUME OUTPUT_DIR
"""
import os
import subprocess
import sys

from paraview.simple import *  # noqa: F401,F403
from vtkmodules.vtkIOImage import vtkPNGReader
from vtkmodules.util.numpy_support import vtk_to_numpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from brume_testing import black_view, check, default_camera, finish  # noqa: E402

plugin, brume_exe, output_dir = sys.argv[1:4]
size = 256
LoadPlugin(plugin, ns=globals())


def pixels(path):
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    scalars = reader.GetOutput().GetPointData().GetScalars()
    return vtk_to_numpy(scalars)[:, :3].astype(float)


rendered = os.path.join(output_dir, "TestBrumeRenderViewLook-brume-render.png")
subprocess.run([brume_exe, "render", "--size", "%dx%d" % (size, size), "-o", rendered],
               check=True, stdout=subprocess.DEVNULL)
scene = BrumeDefaultScene()
tracer = BrumeLightTracer(Input=scene, NumberOfParticles=1000000, Seed=0)
textures = BrumeRadianceReconstruction(Scene=scene, Hits=tracer)
means = {}
for kind in ("BrumeRenderView", "RenderView"):
    view = black_view(size, CreateView(kind))
    display = Show(textures, view)
    check(display.Representation == "Brume Radiance",
          "%s: Show() gives 'Brume Radiance' (got '%s')" % (kind, display.Representation))
    Render(view)  # the first render frames the scene: the camera is set after it
    default_camera(view)
    Render(view)
    shown = os.path.join(output_dir, "TestBrumeRenderViewLook-%s.png" % kind)
    SaveScreenshot(shown, view, ImageResolution=[size, size])
    means[kind] = pixels(shown)
    Delete(view)
reference = pixels(rendered)
difference = abs(means["BrumeRenderView"] - reference).mean()
print("mean grey: brume render %.1f, Brume Render View %.1f, render view %.1f; "
      "mean difference %.3f grey levels" % (reference.mean(), means["BrumeRenderView"].mean(),
                                            means["RenderView"].mean(), difference))
check(difference <= 1.0, "the Brume Render View shows brume render's image (within 1 grey level)")
finish()
