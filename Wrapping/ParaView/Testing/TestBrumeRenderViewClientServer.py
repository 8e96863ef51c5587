"""pvpython: the "Brume Render View" through a pvserver on this machine,
rendered on the server (a volume asks ParaView for remote rendering), and
the same in the built-in session.

A Wavelet shown as a Volume and a Contour of it, on a black background:
- with Progressive "In the GUI" (the default) a script's view traces its
  whole budget once: one trace, no step, converged;
- with Progressive "On" each render adds particles until the budget is
  traced. The server traces; the client reports the server's counters
  (BrumeNumberOfTraces, BrumeNumberOfSteps, BrumeIsRefining,
  BrumeIsConverged), which is what the GUI reads to render again;
- the server's image, which travels to the client, is the built-in
  session's, and lit, except on the volume's partly transparent silhouette,
  where ParaView composites a server's image over the client's background
  its own way (the stock render view differs there as much: thresholded
  errors 13.5 / 1.6 / 0.04 at 0 / 8 / 16 levels on this scene);
- with the colour palette's background (grey), the server's image shows it
  as the built-in session does (the server draws on a transparent black
  that the client composites over its background).

With a launcher (`mpirun --oversubscribe -np 2`), the server runs in
parallel, each process holding a piece of the Wavelet: the processes
gather the pieces and share the particles, with no progressive step (a
distributed scene traces its whole budget at once), and the image is
still the built-in session's.

usage: pvpython TestBrumeRenderViewClientServer.py PVSERVER PLUGIN OUTPUT_DIR [LAUNCHER...]
"""
import os
import sys

from paraview.simple import *  # noqa: F401,F403

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from brume_testing import PVServer, black_view, check, finish, image_error, png_pixels  # noqa: E402,E501

pvserver, plugin, output_dir = sys.argv[1:4]
launcher = sys.argv[4:]
size = 160
if not os.environ.get("DISPLAY") or os.environ.get("BRUME_RENDER_WINDOW") in ("egl", "osmesa"):
    # Without X, Debian's ParaView 5.11 finds its OpenGL probe failing on the
    # server and calls remote rendering unavailable: the client would draw
    # alone, without the volume's data.
    print("skipped: a server renders for its client only through an X display here")
    sys.exit(0)


def state(view):
    view.SMProxy.UpdatePropertyInformation()
    return {name: view.SMProxy.GetProperty("Brume" + name).GetElement(0)
            for name in ("NumberOfTraces", "NumberOfSteps", "IsRefining", "IsConverged")}


def render(where):
    LoadPlugin(plugin, remote=False, ns=globals())
    if servermanager.ActiveConnection.IsRemote():
        LoadPlugin(plugin, remote=True, ns=globals())
    view = black_view(size, CreateView("BrumeRenderView"))
    view.BrumeParticles = 300000
    wavelet = Wavelet()
    volume = Show(wavelet, view)
    volume.SetRepresentationType("Volume")
    ColorBy(volume, ("POINTS", "RTData"))
    Show(Contour(Input=wavelet, ContourBy=["POINTS", "RTData"], Isosurfaces=[230.0]), view)
    Render(view)  # the first render frames the scene; then the camera is set
    view.CameraPosition = [0, 25, 60]
    view.CameraFocalPoint = [0, -4, 0]
    view.CameraViewUp = [0, 1, 0]
    view.CameraViewAngle = 40
    Render(view)
    first = state(view)
    print("%s, In the GUI: %s" % (where, first))
    check(first == {"NumberOfTraces": 1, "NumberOfSteps": 0, "IsRefining": 0, "IsConverged": 1},
          "%s: a script's view traces its whole budget once (%s)" % (where, first))

    view.BrumeProgressive = 1
    view.BrumeParticles = 600000  # 131,072, then 524,288, then 600,000
    renders = []
    for _ in range(10):
        Render(view)
        renders.append(state(view))
        if not renders[-1]["IsRefining"]:
            break
    print("%s, On: %s" % (where, renders))
    steps = [r["NumberOfSteps"] for r in renders]
    if where == "parallel server":
        check(renders == [{"NumberOfTraces": 2, "NumberOfSteps": 0, "IsRefining": 0,
                           "IsConverged": 1}],
              "%s: a distributed scene traces its whole budget at once (%s)" % (where, renders))
    else:
        check(len(renders) == 3 and steps == [0, 1, 2] and renders[-1]["IsConverged"] == 1
              and all(r["NumberOfTraces"] == 2 for r in renders)
              and [r["IsRefining"] for r in renders] == [1, 1, 0],
              "%s: a progressive view traces once and refines in two steps to its budget (%s)"
              % (where, renders))
    pngs = []
    for background in ("black", "palette"):
        view.UseColorPaletteForBackground = int(background == "palette")
        png = os.path.join(output_dir, "TestBrumeRenderViewClientServer-%s-%s.png"
                           % (where, background))
        SaveScreenshot(png, view, ImageResolution=[size, size])
        pngs.append(png)
    Delete(view)
    return pngs


server = PVServer(pvserver, launcher=launcher, display=True)
try:
    check(Connect("127.0.0.1", server.port) is not None
          and servermanager.ActiveConnection.IsRemote(), "connected to the pvserver")
    GetSettingsProxy("RenderViewSettings").RemoteRenderThreshold = 0
    remote = render("parallel server" if launcher else "client-server")
    Connect()  # a built-in session, now the active one
    local = render("built-in")
except BaseException:
    server.kill()
    raise

error = image_error(remote[0], local[0], threshold=16)
means = [png_pixels(png).mean() for png in (remote[0], local[0])]
print("the server's image against the built-in session's: error %g at 16 levels (limit 1), "
      "mean %.2f against %.2f" % (error, means[0], means[1]))
check(means[1] > 10, "the built-in image is lit (mean %.1f)" % means[1])
check(error <= 1 and abs(means[0] - means[1]) <= 0.5,
      "the server draws the built-in session's image (error %g, mean %.2f against %.2f)"
      % (error, means[0], means[1]))
corners = [png_pixels(png)[2, 2].tolist() for png in (remote[1], local[1])]
check(corners[0] == corners[1] and sum(corners[1]) > 100,
      "the server's image shows the view's grey background (%s against %s)" % tuple(corners))
finish()
