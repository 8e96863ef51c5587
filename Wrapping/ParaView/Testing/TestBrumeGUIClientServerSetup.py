"""The ParaView GUI's start (--script), connected to a pvserver: a Brume
Render View in the window's layout, showing a Wavelet as a Volume and a
Contour of it (a volume makes ParaView render on the server), with
Progressive left "In the GUI". Every render of the view appends the view's
state, as the client reports it, to BRUME_GUI_LOG; the script renders
once, and the GUI's own renders follow while the events file lets its
event loop run."""
import os
import sys

from paraview.simple import *  # noqa: F401,F403

GetSettingsProxy("RenderViewSettings").RemoteRenderThreshold = 0
sys.path.insert(0, os.environ["BRUME_TESTING_DIR"])
from brume_testing import gui_wavelet_view  # noqa: E402

view, wavelet, volume = gui_wavelet_view(600000)  # 131,072, then 524,288, then 600,000
Show(Contour(Input=wavelet, ContourBy=["POINTS", "RTData"], Isosurfaces=[200.0]), view)
view.CameraPosition = [30, 20, 60]
view.CameraFocalPoint = [0, 0, 0]
view.CameraViewUp = [0, 1, 0]
log = open(os.environ["BRUME_GUI_LOG"], "w")
names = ("LastRenderOnServer", "NumberOfTraces", "NumberOfSteps", "IsRefining", "IsConverged")


def rendered(proxy, event):
    proxy.UpdatePropertyInformation()
    log.write(" ".join("%s=%d" % (name, proxy.GetProperty("Brume" + name).GetElement(0))
                       for name in names) + "\n")
    log.flush()


view.SMProxy.AddObserver("EndEvent", rendered)
Render(view)
log.write("script done\n")
log.flush()
