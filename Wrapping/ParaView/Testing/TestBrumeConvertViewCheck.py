"""pvbatch, after TestBrumeConvertView.xml: the state the GUI saved once a
user's render view (TestBrumeConvertViewSetup.py) was switched to the
Brume Render View by two GUI actions (the view's title-bar menu, Convert
To ..., Brume Render View). The new view shows what the old one showed,
as it showed it: the Wavelet as a Volume coloured by RTData through the
session's RTData colour map and opacity function, the Contour coloured by
RTData, the camera's direction. Loaded here, the state renders a lit image
(the medium and the contour drawn over the background) with no error.

usage: pvbatch TestBrumeConvertViewCheck.py PLUGIN STATE_DIR
"""
import math
import os
import sys
import xml.etree.ElementTree as ET

from paraview.simple import *  # noqa: F401,F403
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from brume_testing import check, finish, saved_proxies, saved_values  # noqa: E402

plugin, directory = sys.argv[1:3]
state = os.path.join(directory, "converted.pvsm")
check(os.path.exists(state), "the GUI saved its state")
proxies = saved_proxies(state)
by_id = {p.get("id"): p for p in proxies}
values = saved_values


views = [p for p in proxies if p.get("group") == "views"]
check(len(views) == 1 and views[0].get("type") == "BrumeRenderView",
      "the view is a Brume Render View (got %s)" % [v.get("type") for v in views])
view = views[0]
shown = {}
for rid in values(view, "Representations"):
    rep = by_id[rid]
    source = values(rep, "Input")
    if values(rep, "Visibility") == ["1"] and source:
        shown[source[0]] = rep
names = {}
for collection in ET.parse(state).getroot().find("ServerManagerState").findall("ProxyCollection"):
    for item in collection.findall("Item"):
        names[(collection.get("name"), item.get("id"))] = item.get("name")
by_name = {names.get(("sources", sid)): rep for sid, rep in shown.items()}
check(set(by_name) == {"Wavelet1", "Contour1"}, "both sources are shown (got %s)" % sorted(by_name))
lut = [i for (c, i), n in names.items() if c == "lookup_tables" and n == "RTData.PVLookupTable"]
opacity = [i for (c, i), n in names.items()
           if c == "piecewise_functions" and n == "RTData.PiecewiseFunction"]
wavelet, contour = by_name.get("Wavelet1"), by_name.get("Contour1")
if wavelet is not None and contour is not None:
    check(values(wavelet, "Representation") == ["Volume"], "the Wavelet is still a Volume")
    check(values(wavelet, "ColorArrayName")[-1:] == ["RTData"]
          and values(contour, "ColorArrayName")[-1:] == ["RTData"],
          "both are coloured by RTData")
    check(values(wavelet, "LookupTable") == lut and values(contour, "LookupTable") == lut,
          "through the session's RTData colour map")
    check(values(wavelet, "ScalarOpacityFunction") == opacity,
          "and its opacity function")
position = [float(x) for x in values(view, "CameraPosition")]
focal = [float(x) for x in values(view, "CameraFocalPoint")]
direction = [p - f for p, f in zip(position, focal)]
norm = math.sqrt(sum(d * d for d in direction)) or 1.0
expected = [30 / math.sqrt(4900.0), 20 / math.sqrt(4900.0), 60 / math.sqrt(4900.0)]
check(max(abs(d / norm - e) for d, e in zip(direction, expected)) < 1e-6,
      "the camera looks from where it looked (%s)" % position)

# The saved state renders a lit image in pvbatch.
LoadPlugin(plugin, ns=globals())
LoadState(state)
view = GetActiveView() or FindViewOrCreate("BrumeRenderView1", "BrumeRenderView")
view.BrumeParticles = 200000
png = os.path.join(directory, "converted.png")
SaveScreenshot(png, view, ImageResolution=[160, 120])
reader = vtkPNGReader()
reader.SetFileName(png)
reader.Update()
pixels = vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars())[:, :3].astype(float)
background = pixels[0]
drawn = (abs(pixels - background).sum(axis=1) > 6).mean()
check(view.GetXMLName() == "BrumeRenderView" and 0.05 < drawn < 0.9,
      "the state renders the medium and the contour over the background (%.0f %% of pixels)"
      % (100 * drawn))
Delete(view)
finish()
