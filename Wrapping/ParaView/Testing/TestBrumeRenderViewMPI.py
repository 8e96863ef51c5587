"""pvbatch, one process then two (mpirun -np 2): the "Brume Render View"
over processes that each hold a part of the data. A sphere over a ground
in a thin Wavelet medium, each cut by ParaView into pieces, lit by a light
above them: the processes gather the pieces (one surface per source: the
sphere's pieces make it closed again, and it casts its shadow on the
ground's other piece; the medium's pieces one image), share the particles
(each traces its share, the histograms are summed), and each draws the
whole, which ParaView composites by depth.

One process writes its images; two compare theirs with them: the first
render, and a render after a camera move (the view update, collective over
the processes). Both trace the same particles, but the gathered sphere's
points come in another order, so its texels are laid out differently and
single pixels differ by their noise: the images must agree in their means
(within 0.5 level) and in every lit 8 x 8 block's mean (within 10 %, 1 %
on average; lighting each piece alone loses the shadow the sphere casts
on the other piece of the ground: 56 % in a block, measured without the
medium). One trace
per process, no progressive step (a distributed scene traces its whole
budget at once).

Before: the processes summed histograms of different scenes and MPI
aborted. On the way: with each process lighting its own piece, the pieces
of a closed surface were each turned toward the camera on their own; a
camera move summed the histograms a second time (a view update asked the
tracer for the whole instead of this process's share); ParaView's FXAA,
applied after compositing, smeared the silhouettes; and with process 0
alone drawing, ParaView's compositing cut its image to its own piece's
region (the medium 6 % darker).

usage: [mpirun -np 2] pvbatch TestBrumeRenderViewMPI.py PLUGIN OUTPUT_DIR
"""
import os
import sys

from paraview.simple import *  # noqa: F401,F403
from vtkmodules.vtkParallelCore import vtkMultiProcessController

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from brume_testing import black_view, check, finish, png_pixels  # noqa: E402

plugin, output_dir = sys.argv[1:3]
if not os.environ.get("DISPLAY"):
    # Without X, Debian's ParaView 5.11 renders on process 0 alone and its
    # compositing waits for the others.
    print("skipped: mpirun pvbatch renders through an X display")
    sys.exit(0)
controller = vtkMultiProcessController.GetGlobalController()
processes = controller.GetNumberOfProcesses() if controller else 1
LoadPlugin(plugin, ns=globals())
size = 120
view = black_view(size, CreateView("BrumeRenderView"))
view.BrumeParticles = 100000
Show(Sphere(Radius=1.0, ThetaResolution=32, PhiResolution=32), view)
Show(Plane(Origin=[-3, -1, -3], Point1=[3, -1, -3], Point2=[-3, -1, 3],
           XResolution=8, YResolution=8), view)
# A Wavelet around them as a thin medium, cut into pieces too.
medium = Show(Wavelet(WholeExtent=[-8, 8, -8, 8, -8, 8]), view)
medium.SetRepresentationType("Volume")
ColorBy(medium, ("POINTS", "RTData"))
GetOpacityTransferFunction("RTData").Points = [37.35, 0.0, 0.5, 0.0, 276.83, 0.2, 0.5, 0.0]
light = AddLight(view=view)
light.Coords = "Scene"
light.Position = [1.5, 4, 2]
light.FocalPoint = [0, -1, 0]
light.Intensity = 1.0
view.UseLight = 0  # the light kit off: the light above casts the shadow


def shot(name):
    png = os.path.join(output_dir, "TestBrumeRenderViewMPI-%s-%d.png" % (name, processes))
    SaveScreenshot(png, view, ImageResolution=[size, size])
    if processes == 1:
        return
    one = png_pixels(os.path.join(output_dir, "TestBrumeRenderViewMPI-%s-1.png" % name))
    two = png_pixels(png)
    # 8 x 8 blocks' means, of the blocks lit in one process's image.
    blocks = [image.astype(float).mean(axis=2).reshape(size // 8, 8, size // 8, 8).mean(axis=(1, 3))
              for image in (one, two)]
    lit = blocks[0] > 10
    relative = abs(blocks[1][lit] - blocks[0][lit]) / blocks[0][lit]
    print("%s: means %.2f (one process) and %.2f (%d); %d lit blocks differ by %.2f %% on "
          "average, %.2f %% at most" % (name, one.mean(), two.mean(), processes, lit.sum(),
                                        100 * relative.mean(), 100 * relative.max()))
    check(two.mean() > 10, "%s: the image is lit (mean %.1f)" % (name, two.mean()))
    check(abs(one.mean() - two.mean()) <= 0.5 and relative.mean() <= 0.01 and relative.max() <= 0.1,
          "%s: the image of one process (means %.2f and %.2f; blocks %.2f %% on average, "
          "%.2f %% at most)" % (name, one.mean(), two.mean(), 100 * relative.mean(),
                                100 * relative.max()))


Render(view)
shot("first")
GetActiveCamera().Azimuth(30)
Render(view)
shot("moved")
view.SMProxy.UpdatePropertyInformation()
traces = view.SMProxy.GetProperty("BrumeNumberOfTraces").GetElement(0)
steps = view.SMProxy.GetProperty("BrumeNumberOfSteps").GetElement(0)
print("%d process(es): traces %d, steps %d" % (processes, traces, steps))
check(traces == 1 and steps == 0, "one trace, no progressive step (%d, %d)" % (traces, steps))
Delete(view)
finish()
