"""pvpython: "Brume Radiance" through a pvserver on this machine (client and
server over the loopback) and in the built-in session: the same image, with
the textures following the camera in both.

The textures travel from the server to the client, which renders them
(ParaView 5.11 renders small data on the client). Before each render the
plugin's client side sets the reconstruction's EyePosition to the camera's
position, so that the server updates the view-dependent textures toward it.

With a launcher (for example `mpirun --oversubscribe -np 2`), the server
runs in parallel: every server process holds the same textures, and the
client gets process 0's copy alone (the server's processes run without a
display).

usage: pvpython TestBrumeRadianceClientServer.py PVSERVER PLUGIN OUTPUT_DIR PORT [LAUNCHER...]
(PORT 0: a free one)
"""
import os
import sys

from paraview.simple import *  # noqa: F401,F403
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_INT
from vtkmodules.vtkCommonCore import vtkCommand

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from brume_testing import PVServer, black_view, image_error  # noqa: E402

pvserver, plugin, output_dir, port = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
launcher = sys.argv[5:]
name = "TestBrumeRadianceClientServer" + ("-parallel" if launcher else "")


def render(png):
    """The default scene's textures at a fixed camera, in the active session."""
    LoadPlugin(plugin, remote=False, ns=globals())
    if servermanager.ActiveConnection.IsRemote():
        LoadPlugin(plugin, remote=True, ns=globals())
    scene = BrumeDefaultScene()
    tracer = BrumeLightTracer(Input=scene, NumberOfParticles=100000, Seed=1)
    reconstruction = BrumeRadianceReconstruction(Scene=scene, Hits=tracer)
    view = black_view(160)
    display = Show(reconstruction, view)
    assert display.Representation == "Brume Radiance", display.Representation
    assert display.FollowCamera == 1, "FollowCamera is on by default"
    Render(view)  # the first render frames the scene; then the camera is set
    changed = []

    @calldata_type(VTK_INT)
    def on_update(obj, event, count):
        changed.append(count)

    # The client's representation (it draws) fires its TexturesShownEvent
    # (vtkCommand.UserEvent + 1) with the number of data sets the new
    # textures changed.
    display.GetClientSideObject().GetActiveRepresentation().AddObserver(
        vtkCommand.UserEvent + 1, on_update)
    for position in ([0.4, 0.3, 3.8], [-0.5, 0.2, 3.9]):
        view.CameraPosition = position
        view.CameraFocalPoint = [0, 0, 0]
        view.CameraViewUp = [0, 1, 0]
        view.CameraViewAngle = 40
        Render(view)
        eye = list(reconstruction.EyePosition)
        if any(abs(a - b) > 1e-6 for a, b in zip(eye, position)):
            raise RuntimeError("EyePosition %s did not follow the camera to %s" % (eye, position))
        # Only the fog's texture radiates toward the eye: the walls' and the
        # box's textures and geometry keep what was uploaded.
        print("data sets changed by the move: %s" % changed[-1:])
        if changed[-1:] != [1]:
            raise RuntimeError("data sets changed by the camera's move: %s (expected 1)" % changed)
    SaveScreenshot(png, view, ImageResolution=[160, 160])
    Delete(view)


server = PVServer(pvserver, port, launcher)
try:
    # The server stays connected to the end: it exits when this client does.
    if not Connect("127.0.0.1", server.port) or not servermanager.ActiveConnection.IsRemote():
        raise RuntimeError("no connection to pvserver on port %d" % server.port)
    remote = os.path.join(output_dir, name + "-remote.png")
    render(remote)
    Connect()  # a built-in session, now the active one
    local = os.path.join(output_dir, name + "-builtin.png")
    render(local)
except BaseException:
    server.kill()
    raise

error = image_error(remote, local)
print("%s against built-in: error %g (limit 0.5)"
      % ("parallel server" if launcher else "client-server", error))
sys.exit(0 if error <= 0.5 else 1)
