"""The volume-property example (Examples/Python/wavelet_volume.py) from
/usr/bin/python3: vtkBrumeVolumePropertyMedium carries the property's scalar
opacity, colour, unit distance, interpolation and g into the medium's field
data;
vtkLights given to the tracer light the reconstruction; both renderers draw
the field.

usage: TestWaveletVolume.py EXAMPLE_DIR
"""
import math
import sys

from vtkmodules.vtkImagingCore import vtkRTAnalyticSource

sys.path.insert(0, sys.argv[1])
import wavelet_volume  # noqa: E402

import brume  # noqa: E402

failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
        print("FAILED:", what)


wavelet = vtkRTAnalyticSource()
wavelet.Update()
prop = wavelet_volume.volume_property()

medium = brume.vtkBrumeVolumePropertyMedium()
medium.SetInputConnection(wavelet.GetOutputPort())
medium.SetVolumeProperty(prop)
medium.Update()
fd = medium.GetOutput().GetFieldData()
points = fd.GetArray("BrumeScalarOpacity")
opacity = prop.GetScalarOpacity()
check(points is not None and points.GetNumberOfTuples() == opacity.GetSize(),
      "one (scalar, opacity) point per node of the property's function")
for i in range(opacity.GetSize()):
    node = [0.0] * 4
    opacity.GetNodeValue(i, node)
    check(points.GetTuple2(i) == (node[0], node[1]), f"node {i} carried over")
colours = fd.GetArray("BrumeScalarColor")
colour = prop.GetRGBTransferFunction()
check(colours is not None and colours.GetNumberOfTuples() == colour.GetSize(),
      "one (scalar, red, green, blue) point per node of the property's colour")
for i in range(colour.GetSize()):
    node = [0.0] * 6
    colour.GetNodeValue(i, node)
    check(colours.GetTuple4(i) == tuple(node[:4]), f"colour node {i} carried over")
check(fd.GetArray("BrumeScalarOpacityUnitDistance").GetTuple1(0) == 1.0, "unit distance")
check(abs(fd.GetArray("BrumeG").GetTuple1(0) - 0.3) < 1e-6, "g from ScatteringAnisotropy")
check(fd.GetAbstractArray("BrumeInterpolation").GetValue(0) == "linear", "interpolation")
check(fd.GetAbstractArray("BrumeDensityArray").GetValue(0) == "RTData", "the wavelet's array")

_, radiance, seconds = wavelet_volume.render_brume(wavelet, prop, 48, 40000)
values = radiance.GetPointData().GetScalars()
n = values.GetNumberOfTuples()
check(all(math.isfinite(values.GetComponent(i, c)) for i in range(n) for c in range(3)),
      "Brume's radiance is finite")
centre = values.GetTuple3(24 * 48 + 24)
check(min(centre) > 0.0, f"the field is lit in Brume's image: {centre}")
image, vtk_seconds = wavelet_volume.render_vtk(wavelet, prop, 48)
scalars = image.GetPointData().GetScalars()
check(scalars.GetRange(0)[1] > 0, "VTK's ray caster draws something")
print(f"Brume {seconds:.3f} s, vtkGPUVolumeRayCastMapper {vtk_seconds:.3f} s")
sys.exit(1 if failures else 0)
