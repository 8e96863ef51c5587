"""pvbatch: the "Brume Render View", a render view lit by Brume.

A user's own pipeline, with no Brume filter: VTK's Wavelet shown as a
Volume, a Contour of it and a ground plane coloured by its height through
a colour map, in a Brume Render View. The first render traces once and
gives a lit image (the ground's colours on it, the contour's shadow); a
camera move traces nothing again and updates the view; a colour-map edit
traces once more and changes the ground's colours; a settings change
(Particles) traces again. Progressive, an edit of the volume's opacity is
previewed first (BrumePreviewEdits), its slices as far apart as
BrumePreviewSliceSpacing says. Nothing is written to the error output.

usage: pvbatch TestBrumeRenderView.py PLUGIN OUTPUT_DIR
"""
import os
import sys

from paraview.simple import *  # noqa: F401,F403
from vtkmodules.vtkIOImage import vtkPNGReader
from vtkmodules.util.numpy_support import vtk_to_numpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from brume_testing import black_view, check, finish  # noqa: E402

plugin, output_dir = sys.argv[1:3]
LoadPlugin(plugin, ns=globals())
size = 160


def counters(view):
    view.SMProxy.UpdatePropertyInformation()
    return [view.SMProxy.GetProperty(name).GetElement(0)
            for name in ("BrumeNumberOfTraces", "BrumeNumberOfViewUpdates")]


def screenshot(view, name):
    path = os.path.join(output_dir, name)
    SaveScreenshot(path, view, ImageResolution=[size, size])
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    return vtk_to_numpy(image.GetPointData().GetScalars()).reshape(size, size, -1)[:, :, :3]


view = black_view(size, CreateView("BrumeRenderView"))
check(view.GetXMLName() == "BrumeRenderView", "a Brume Render View is created")
view.BrumeParticles = 200000

wavelet = Wavelet()
volume = Show(wavelet, view)
volume.SetRepresentationType("Volume")
ColorBy(volume, ("POINTS", "RTData"))
contour = Contour(Input=wavelet, ContourBy=["POINTS", "RTData"], Isosurfaces=[230.0])
Show(contour, view)
plane = Plane(Origin=[-20, -12, -20], Point1=[20, -12, -20], Point2=[-20, -12, 20],
              XResolution=40, YResolution=40)
height = Elevation(Input=plane, LowPoint=[-20, 0, 0], HighPoint=[20, 0, 0])
ground = Show(height, view)
ColorBy(ground, ("POINTS", "Elevation"))
lut = GetColorTransferFunction("Elevation")
lut.ApplyPreset("Rainbow Uniform", True)

view.CameraPosition = [0, 25, 60]
view.CameraFocalPoint = [0, -4, 0]
view.CameraViewUp = [0, 1, 0]
view.CameraViewAngle = 40
Render(view)
first = screenshot(view, "TestBrumeRenderView.png")
traces, updates = counters(view)
print("traces %d, view updates %d, mean %.1f" % (traces, updates, first.mean()))
check(traces == 1, "the first render traces once (got %d)" % traces)
check(first.mean() > 10, "the image is lit (mean %.1f)" % first.mean())
# The ground's colours: its left (low) end and right (high) end differ in hue.
row = size // 4  # the ground's near half (rows from the bottom), its left and right ends
left, right = first[row, size // 5].astype(int), first[row, size * 4 // 5].astype(int)
check(abs(int(left[0]) - int(right[0])) + abs(int(left[2]) - int(right[2])) > 40,
      "the ground shows its colour map (%s against %s)" % (left, right))

camera = GetActiveCamera()
camera.Azimuth(10)
Render(view)
traces, updates = counters(view)
check(traces == 1 and updates >= 1,
      "a camera move traces nothing again (traces %d, view updates %d)" % (traces, updates))

lut.ApplyPreset("Cool to Warm", True)
Render(view)
edited = screenshot(view, "TestBrumeRenderView-edited.png")
traces, _ = counters(view)
check(traces == 2, "a colour-map edit traces once more (traces %d)" % traces)
check(abs(edited.astype(float) - first.astype(float)).mean() > 1,
      "the edited colour map changes the image")

view.BrumeParticles = 100000
Render(view)
traces, _ = counters(view)
check(traces == 3, "a new particle count traces again (traces %d)" % traces)


def flag(name):
    view.SMProxy.UpdatePropertyInformation()
    return view.SMProxy.GetProperty(name).GetElement(0)


# Progressive (as in the GUI, where the view renders again while it
# refines): each render adds particles until the budget is traced, and then
# nothing is left to refine.
check(flag("BrumeIsRefining") == 0, "a script's view traces its whole budget at once")
view.BrumeProgressive = 1
view.BrumeParticles = 400000
Render(view)
steps = 1
while flag("BrumeIsRefining") and steps < 10:
    Render(view)
    steps += 1
check(steps > 1 and flag("BrumeIsConverged") == 1 and flag("BrumeIsRefining") == 0,
      "a progressive view refines step by step until converged (%d renders)" % steps)

# Previews (on by default, while progressive): an edit of the volume's
# opacity is drawn at once from the last light, and traced at the next
# render, which the GUI makes by itself (the view is refining).
opacity = GetOpacityTransferFunction("RTData")
low, high = opacity.Points[0], opacity.Points[-4]
traces, _ = counters(view)
previews = flag("BrumeNumberOfPreviews")
opacity.Points = [low, 0.0, 0.5, 0.0, 160.0, 0.6, 0.5, 0.0, high, 1.0, 0.5, 0.0]
Render(view)
check(flag("BrumeNumberOfPreviews") == previews + 1 and counters(view)[0] == traces,
      "an opacity edit is previewed, nothing traced (previews %d, traces %d)"
      % (flag("BrumeNumberOfPreviews"), counters(view)[0]))
check(flag("BrumeIsRefining") == 1, "the view refines after a preview")
Render(view)  # (a screenshot would render again too: the preview is one frame)
check(counters(view)[0] == traces + 1, "the render after a preview traces")
# A preview's slice spacing (a drawing setting, traced frames keep theirs)
# reaches the view's pass; its effect on the slices is Brume.Pass's to check.
def spacing(view):
    view.SMProxy.UpdatePropertyInformation()
    return view.GetProperty("BrumePreviewSliceSpacingInfo").GetElement(0)


check(spacing(view) == 2.0, "previews draw slices twice as far apart by default (%g)"
      % spacing(view))
view.BrumePreviewSliceSpacing = 3.0
check(spacing(view) == 3.0, "BrumePreviewSliceSpacing reaches the pass (%g)" % spacing(view))
# So does the 16-bit tolerance of volumes on the GPU, to the pass's props.
def tolerance(view):
    view.SMProxy.UpdatePropertyInformation()
    return view.GetProperty("BrumeExtinctionDepthToleranceInfo").GetElement(0)


check(abs(tolerance(view) - 1e-3) < 1e-12, "volumes go up within 10^-3 by default (%g)"
      % tolerance(view))
view.BrumeExtinctionDepthTolerance = 0.0
check(tolerance(view) == 0.0, "BrumeExtinctionDepthTolerance reaches the pass's props (%g)"
      % tolerance(view))
view.BrumeExtinctionDepthTolerance = 1e-3
view.BrumePreviewEdits = 0
opacity.Points = [low, 0.0, 0.5, 0.0, 160.0, 0.3, 0.5, 0.0, high, 1.0, 0.5, 0.0]
Render(view)
check(flag("BrumeNumberOfPreviews") == previews + 1 and counters(view)[0] == traces + 2,
      "with previews off, an edit is traced at once")
Delete(view)  # before the interpreter's exit, as pvbatch expects
finish()
