"""pvbatch: "Brume Medium From Field" as a GUI user creates it, with nothing
set. It takes the input's active scalars and their own colour map and
opacity function (those GetColorTransferFunction / GetOpacityTransferFunction
and the Color Map Editor give), a new function fitted to the array's range,
a function whose range is set (or locked) left as it is,
and a unit distance of about a cell, as a Volume display's: one Apply makes
a medium, with no error. With "missing", an input with no scalars gets one
message that names the property to set.

usage: pvbatch TestBrumeFieldMediumDefaults.py PLUGIN [missing]
"""
import math
import os
import sys

from paraview.simple import *  # noqa: F401,F403

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from brume_testing import check, finish  # noqa: E402

plugin = sys.argv[1]
LoadPlugin(plugin, ns=globals())

if len(sys.argv) > 2 and sys.argv[2] == "missing":
    # A sphere has normals but no scalars: nothing to classify.
    medium = BrumeMediumFromField(Input=Sphere())
    check(medium.LookupTable is None and medium.ScalarOpacityFunction is None,
          "no array, no functions")
    medium.UpdatePipeline()
    finish()
    sys.exit(0)

wavelet = Wavelet()
medium = BrumeMediumFromField(Input=wavelet)
check(list(medium.Scalars) == ["POINTS", "RTData"], "the input's active point scalars")
check(medium.LookupTable == GetColorTransferFunction("RTData"), "the array's own colour map")
check(medium.ScalarOpacityFunction == GetOpacityTransferFunction("RTData"),
      "the array's own opacity function")
low, high = wavelet.PointData["RTData"].GetRange()
points = list(medium.ScalarOpacityFunction.Points)
rgb = list(medium.LookupTable.RGBPoints)
check(abs(points[0] - low) < 1e-9 and abs(points[-4] - high) < 1e-9
      and abs(rgb[0] - low) < 1e-9 and abs(rgb[-4] - high) < 1e-9,
      "new functions fitted to the array's range [%g, %g]" % (low, high))
# The Wavelet's 20^3 cells of side 1: a cell's length, as a Volume display's.
check(abs(medium.ScalarOpacityUnitDistance - math.sqrt(3.0)) < 1e-9,
      "a unit distance of about a cell (%g)" % medium.ScalarOpacityUnitDistance)
medium.UpdatePipeline()
fd = medium.GetClientSideObject().GetOutput().GetFieldData()
opacity = fd.GetArray("BrumeScalarOpacity")
check(opacity is not None and opacity.GetNumberOfTuples() == len(points) // 4
      and abs(opacity.GetTuple2(1)[0] - high) < 1e-9,
      "one Apply makes a medium of the array's opacity function")

# An array a display already colours, with the user's own colour map (its
# range set, as colouring a display leaves it): the medium takes that map
# as it is, not refitted.
elevation = Elevation(Input=wavelet, LowPoint=[-10, -10, -10], HighPoint=[10, 10, 10])
edited = GetColorTransferFunction("Elevation")
edited.RGBPoints = [0.2, 0.1, 0.2, 0.9, 0.7, 1.0, 0.8, 0.4]
edited.ScalarRangeInitialized = 1
GetOpacityTransferFunction("Elevation").Points = [0.2, 0.0, 0.5, 0.0, 0.7, 0.3, 0.5, 0.0]
used = BrumeMediumFromField(Input=elevation, Scalars=["POINTS", "Elevation"])
check(used.LookupTable == edited and list(used.LookupTable.RGBPoints)[0] == 0.2
      and list(used.ScalarOpacityFunction.Points)[4] == 0.7,
      "a colour map whose range is set keeps the user's points")

# A locked range is not refitted either.
scaled = Calculator(Input=wavelet, ResultArrayName="Scaled", Function="RTData*2")
locked = GetColorTransferFunction("Scaled")
locked.AutomaticRescaleRangeMode = "Never"
locked.RGBPoints = [0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0]
lockedMedium = BrumeMediumFromField(Input=scaled, Scalars=["POINTS", "Scaled"])
check(list(lockedMedium.LookupTable.RGBPoints)[4] == 1.0, "a locked range stays as it is")
finish()
