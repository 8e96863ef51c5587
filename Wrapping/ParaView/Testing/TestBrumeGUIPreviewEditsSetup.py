"""The ParaView GUI's start (--script) for Brume.ParaView.GUIPreviewEdits:
a Brume Render View in the window's layout, showing a Wavelet as a Volume
coloured by RTData, with Progressive and Preview Edits left at their
defaults. After every render of the view it appends to BRUME_GUI_LOG the
view's counters, the render's seconds, the opacity and colour functions'
point counts, and the frame's size, mean and mean difference from the last
frame of the same size (read from the window, not rendered again); the
events file then edits the functions through the Color Map Editor."""
import os
import sys
import time

import numpy
from paraview.simple import *  # noqa: F401,F403
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkRenderingCore import vtkWindowToImageFilter

sys.path.insert(0, os.environ["BRUME_TESTING_DIR"])
from brume_testing import gui_wavelet_view  # noqa: E402

view, wavelet, volume = gui_wavelet_view(600000)  # 131,072, then 524,288, then 600,000
SetActiveSource(wavelet)
view.CameraPosition = [30, 20, 60]
view.CameraFocalPoint = [0, 0, 0]
view.CameraViewUp = [0, 1, 0]
opacity = GetOpacityTransferFunction("RTData")
colour = GetColorTransferFunction("RTData")
log = open(os.environ["BRUME_GUI_LOG"], "w")
names = ("NumberOfTraces", "NumberOfSteps", "NumberOfPreviews", "IsRefining", "IsConverged")
last = {"frame": None, "start": 0.0}


def frame():
    grab = vtkWindowToImageFilter()
    grab.SetInput(view.GetRenderWindow())
    grab.ShouldRerenderOff()
    grab.ReadFrontBufferOff()
    grab.Update()
    image = grab.GetOutput()
    width, height = image.GetDimensions()[:2]
    return vtk_to_numpy(image.GetPointData().GetScalars()).reshape(height, width, -1).astype(float)


def started(proxy, event):
    last["start"] = time.perf_counter()


def rendered(proxy, event):
    seconds = time.perf_counter() - last["start"]
    proxy.UpdatePropertyInformation()
    pixels = frame()
    before = last["frame"]
    change = numpy.abs(pixels - before).mean() if before is not None and \
        before.shape == pixels.shape else -1.0
    last["frame"] = pixels
    values = ["%s=%d" % (name, proxy.GetProperty("Brume" + name).GetElement(0)) for name in names]
    values += ["OpacityPoints=%d" % (len(opacity.Points) // 4),
               "ColourPoints=%d" % (len(colour.RGBPoints) // 4),
               "Width=%d" % pixels.shape[1], "Seconds=%.4f" % seconds,
               "Mean=%.3f" % pixels.mean(), "Change=%.3f" % change]
    log.write(" ".join(values) + "\n")
    log.flush()


view.SMProxy.AddObserver("StartEvent", started)
view.SMProxy.AddObserver("EndEvent", rendered)
Render(view)
log.write("script done\n")
log.flush()
