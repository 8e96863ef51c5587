"""mpirun -np 2 pvbatch: the "Brume Render View" over two processes is not
supported, and says so without aborting. Each process holds its part of a
Wavelet's contour and traces it alone (a shared trace needs the same scene
on every process): the render completes on both. (Before, the processes
summed histograms of different scenes and MPI aborted.) The composited
image is not checked: it is black, because ParaView's compositing reads
each process's depth, which Brume's display pass does not write.

usage: mpirun -np 2 pvbatch TestBrumeRenderViewMPI.py PLUGIN OUTPUT_DIR
"""
import os
import sys

from paraview.simple import *  # noqa: F401,F403
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from brume_testing import black_view, check, finish  # noqa: E402

plugin, output_dir = sys.argv[1:3]
if not os.environ.get("DISPLAY"):
    # Without X, Debian's ParaView 5.11 renders on process 0 alone and its
    # compositing waits for the others.
    print("skipped: mpirun pvbatch renders through an X display")
    sys.exit(0)
LoadPlugin(plugin, ns=globals())
size = 120
view = black_view(size, CreateView("BrumeRenderView"))
view.BrumeParticles = 100000
Show(Contour(Input=Wavelet(), ContourBy=["POINTS", "RTData"], Isosurfaces=[200.0]), view)
Render(view)
view.SMProxy.UpdatePropertyInformation()
traces = view.SMProxy.GetProperty("BrumeNumberOfTraces").GetElement(0)
png = os.path.join(output_dir, "TestBrumeRenderViewMPI.png")
SaveScreenshot(png, view, ImageResolution=[size, size])
reader = vtkPNGReader()
reader.SetFileName(png)
reader.Update()
mean = vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars()).mean()
print("traces %d, image mean %.1f" % (traces, mean))
check(traces == 1, "the first process traced its part once (%d)" % traces)
Delete(view)
finish()
