"""The Python example (vtkOBJReader, a vtkImageData medium, the three phases)
runs from /usr/bin/python3 and its image matches a baseline.

usage: TestPythonExample.py EXAMPLE_DIR BASELINE OUTPUT_DIR
"""
import os
import sys

from vtkmodules.vtkImagingCore import vtkImageDifference  # noqa: F401 (module check)
from vtkmodules.vtkIOImage import vtkPNGReader
from vtkmodules.vtkImagingCore import vtkImageDifference as _Difference

example_dir, baseline, output_dir = sys.argv[1:4]
sys.path.insert(0, example_dir)
import obj_fog  # noqa: E402

output = os.path.join(output_dir, "TestPythonExample.png")
scene = obj_fog.build_scene(os.path.join(example_dir, "..", "..", "Data", "models", "room.obj"))
image = obj_fog.render(scene, output, particles=100000, size=128)
if not os.path.exists(baseline):
    print("no baseline", baseline, "- the image is", output)
    sys.exit(1)
reader = vtkPNGReader()
reader.SetFileName(baseline)
difference = _Difference()
difference.SetInputData(image)
difference.SetImageConnection(reader.GetOutputPort())
# The same strict settings as the C++ image test (see TestDefaultScene.cxx).
difference.SetThreshold(16)
difference.AllowShiftOff()
difference.AveragingOff()
difference.Update()
error = difference.GetThresholdedError()
print("strict image error", error, "(limit 10)")
sys.exit(0 if error <= 10.0 else 1)
