"""vtkBrumeImageError from Python: errors of synthetic radiance images with
known values (a 10 % offset, a checkerboard finer than the blocks, a mask),
and a clear failure on images of different sizes.

usage: TestImageError.py
"""
import math
import sys

from vtkmodules.vtkCommonCore import vtkCommand, vtkFloatArray, vtkUnsignedCharArray
from vtkmodules.vtkCommonDataModel import vtkImageData

import brume

failures = []


def expect(ok, what):
    if not ok:
        failures.append(what)
        print("FAILED:", what)


def image(width, height, value):
    """A Brume float image whose pixel (x, y) is value(x, y) in every channel."""
    radiance = vtkFloatArray()
    radiance.SetName("Radiance")
    radiance.SetNumberOfComponents(3)
    radiance.SetNumberOfTuples(width * height)
    for y in range(height):
        for x in range(width):
            v = value(x, y)
            radiance.SetTuple3(y * width + x, v, v, v)
    result = vtkImageData()
    result.SetDimensions(width, height, 1)
    result.GetPointData().AddArray(radiance)
    return result


def mask(width, height, inside):
    values = vtkUnsignedCharArray()
    values.SetName("MediumMask")
    values.SetNumberOfTuples(width * height)
    for y in range(height):
        for x in range(width):
            values.SetValue(y * width + x, 1 if inside(x, y) else 0)
    result = vtkImageData()
    result.SetDimensions(width, height, 1)
    result.GetPointData().SetScalars(values)
    return result


reference = image(16, 16, lambda x, y: 2.0)
error = brume.vtkBrumeImageError()

expect(error.Compare(image(16, 16, lambda x, y: 2.2), reference), "an offset image compares")
for name, value in (("MAE", error.GetRelativeMAE()), ("RMSE", error.GetRelativeRMSE()),
                    ("block error", error.GetBlockError())):
    expect(math.isclose(value, 0.1, abs_tol=1e-6), f"{name} of a 10 % offset is {value}")

checkerboard = image(16, 16, lambda x, y: 2.5 if (x + y) % 2 else 1.5)
expect(error.Compare(checkerboard, reference), "a checkerboard compares")
expect(error.GetBlockError() == 0.0, "no block error under the blocks' size")
expect(math.isclose(error.GetRelativeMAE(), 0.25), "a per-pixel error of 25 %")

left_off = image(16, 16, lambda x, y: 2.4 if x < 8 else 2.0)
expect(error.Compare(left_off, reference, mask(16, 16, lambda x, y: x < 8)), "masked")
expect(math.isclose(error.GetRelativeMAE(), 0.2, abs_tol=1e-6), "20 % on the masked half")
expect(error.GetNumberOfPixels() == 128, "half the pixels compared")

reported = []
error.AddObserver(vtkCommand.ErrorEvent, lambda caller, event: reported.append(event))
expect(not error.Compare(image(16, 8, lambda x, y: 2.0), reference), "different sizes fail")
expect(len(reported) == 1, "and say so")
expect(math.isnan(error.GetRelativeMAE()), "with NaN errors")

expect(brume.vtkBrumeImageError.IsFinite(reference), "a finite image")
expect(not brume.vtkBrumeImageError.IsFinite(image(4, 4, lambda x, y: math.inf)), "infinity")

sys.exit(1 if failures else 0)
