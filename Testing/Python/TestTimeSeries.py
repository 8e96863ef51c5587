"""A scene that changes over time: a medium given as a list of .vti files
(its time steps) beside a mesh and a medium that do not change.

- vtkBrumeSceneReader announces the steps' times (TIME_STEPS, TIME_RANGE)
  and reads, at each time asked for, the last step at or before it;
- the mesh and the constant medium are read once: their arrays are the same
  objects at every step, and only the steps' files are read again;
- `brume render` renders every step (out.0000.png, ...) and prints each
  step's time; each image is bitwise the one of a scene naming that step's
  file alone, and --time-step K renders step K alone;
- the pipeline's time (vtkBrumePipeline.SetTime) gives the same images;
- lists that are wrong are refused naming the field.

- an OpenVDB medium given as a list (the project's cumulus, its box from
  its grid) renders each step as the file alone does.

usage: TestTimeSeries.py BRUME OUTPUT_DIR [CUMULUS_SCENE]
"""
import json
import math
import os
import subprocess
import sys

from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkDataObject, vtkImageData
from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkIOXML import vtkXMLImageDataReader, vtkXMLImageDataWriter, vtkXMLPolyDataWriter
import numpy as np

import brume

program, output_dir = sys.argv[1:3]
cumulus = sys.argv[3] if len(sys.argv) > 3 else None
work = os.path.join(output_dir, "time-series")
os.makedirs(work, exist_ok=True)
failures = []


def check(ok, what):
    print(("ok: " if ok else "FAILED: ") + what)
    if not ok:
        failures.append(what)


def write_blob(name, centre, n=20):
    """A Gaussian blob of density at `centre` on n^3 points over [-0.5, 0.5]^3."""
    axis = np.linspace(-0.5, 0.5, n)
    z, y, x = np.meshgrid(axis, axis, axis, indexing="ij")
    values = 8.0 * np.exp(-((x - centre) ** 2 + y ** 2 + z ** 2) / 0.04)
    image = vtkImageData()
    image.SetDimensions(n, n, n)
    image.SetOrigin(-0.5, -0.5, -0.5)
    image.SetSpacing(1.0 / (n - 1), 1.0 / (n - 1), 1.0 / (n - 1))
    array = numpy_to_vtk(values.astype(np.float32).ravel(), deep=True)
    array.SetName("density")
    image.GetPointData().AddArray(array)
    writer = vtkXMLImageDataWriter()
    writer.SetFileName(os.path.join(work, name))
    writer.SetInputData(image)
    writer.SetDataModeToBinary()
    if not writer.Write():
        sys.exit("cannot write " + name)


centres = [-0.25, 0.0, 0.25]
for k, c in enumerate(centres):
    write_blob("blob%d.vti" % k, c)
write_blob("haze.vti", 0.0)  # the medium that does not change
ball = vtkSphereSource()
ball.SetRadius(0.15)
ball.SetCenter(0.0, -0.3, 0.3)
ball.Update()
writer = vtkXMLPolyDataWriter()
writer.SetFileName(os.path.join(work, "ball.vtp"))
writer.SetInputData(ball.GetOutput())
writer.Write()

times = [0.0, 0.5, 2.0]
scene = {
    "brume_scene": 1,
    "camera": {"position": [0, 0, 3], "focal_point": [0, 0, 0], "view_up": [0, 1, 0],
               "view_angle": 35},
    "render": {"particles": 20000, "size": [40, 32]},
    "surfaces": [
        {"name": "ground", "quad": [[-2, -0.6, 2], [2, -0.6, 2], [2, -0.6, -2], [-2, -0.6, -2]],
         "material": {"type": "lambertian", "reflectance": [0.6, 0.6, 0.6]}},
        {"name": "ball", "file": "ball.vtp",
         "material": {"type": "lambertian", "reflectance": [0.8, 0.3, 0.2]}}],
    "media": [
        {"name": "blob", "sigma_a": [0.1, 0.1, 0.1], "sigma_s": [0.9, 0.9, 0.9], "g": 0.3,
         "density": {"vti": ["blob0.vti", "blob1.vti", "blob2.vti"], "array": "density",
                     "times": times}},
        {"name": "haze", "sigma_a": [0.01, 0.01, 0.01], "sigma_s": [0.05, 0.05, 0.05],
         "density": {"vti": "haze.vti", "array": "density"}}],
    "lights": [{"type": "point", "position": [0, 1.5, 1.5], "intensity": [3, 3, 3]}],
}


def write_scene(name, document):
    path = os.path.join(work, name)
    with open(path, "w") as f:
        json.dump(document, f)
    return path


series = write_scene("series.json", scene)
steps = []
for k in range(3):
    one = json.loads(json.dumps(scene))
    one["media"][0]["density"] = {"vti": "blob%d.vti" % k, "array": "density"}
    steps.append(write_scene("step%d.json" % k, one))

# The reader: times announced, the step at or before the time asked for.
reader = brume.vtkBrumeSceneReader()
reader.SetFileName(series)
reader.UpdateInformation()
info = reader.GetOutputInformation(0)
sddp = vtkStreamingDemandDrivenPipeline
announced = [info.Get(sddp.TIME_STEPS(), k) for k in range(info.Length(sddp.TIME_STEPS()))]
check(announced == times, "TIME_STEPS %s" % announced)
check([info.Get(sddp.TIME_RANGE(), k) for k in range(2)] == [0.0, 2.0], "TIME_RANGE")


def medium_array(collection, name):
    for i in range(collection.GetNumberOfPartitionedDataSets()):
        meta = collection.GetMetaData(i)
        if meta.Get(collection.NAME()) == name:
            return collection.GetPartitionedDataSet(i).GetPartition(0)
    return None


def peak_x(image):
    values = vtk_to_numpy(image.GetPointData().GetArray("density"))
    n = image.GetDimensions()[0]
    return -0.5 + (int(np.argmax(values)) % n) / (n - 1.0)


kept = None
for time, expected in [(0.0, 0), (0.4, 0), (0.5, 1), (1.9, 1), (2.0, 2), (7.0, 2), (-1.0, 0)]:
    reader.UpdateTimeStep(time)
    out = reader.GetOutput()
    blob = medium_array(out, "blob")
    check(abs(peak_x(blob) - centres[expected]) < 0.03,
          "time %g reads step %d (peak at x = %.3f)" % (time, expected, peak_x(blob)))
    arrays = (medium_array(out, "ball").GetPoints().GetData(),
              medium_array(out, "haze").GetPointData().GetArray("density"))
    if kept is None:
        kept = arrays
    check(arrays[0] is kept[0] and arrays[1] is kept[1],
          "time %g: the mesh's points and the constant medium's densities are the same "
          "arrays as at the first step" % time)
# Seven executions, three of them on the step before: the mesh and the
# haze read once, the steps' files once per change of step (0, 1, 2, 0).
check(reader.GetNumberOfFileReads() == 2 + 4,
      "files read: %d (the mesh and the haze once, a step's file at each of its 4 changes)"
      % reader.GetNumberOfFileReads())

# brume render: every step, each the image of its own scene.
result = subprocess.run([program, "render", series, "-o", os.path.join(work, "out.vti")],
                        capture_output=True, text=True)
print(result.stdout, result.stderr)
check(result.returncode == 0, "brume render exits 0")
for k, t in enumerate(times):
    check("time step %d of 3 (t = %g): " % (k, t) in result.stdout,
          "brume render prints step %d and its time" % k)


def radiance(path):
    r = vtkXMLImageDataReader()
    r.SetFileName(path)
    r.Update()
    return vtk_to_numpy(r.GetOutput().GetPointData().GetArray("Radiance"))


def time_value(path):
    r = vtkXMLImageDataReader()
    r.SetFileName(path)
    r.Update()
    value = r.GetOutput().GetFieldData().GetArray("TimeValue")
    return value.GetValue(0) if value is not None else None


images = []
for k in range(3):
    alone = os.path.join(work, "alone%d.vti" % k)
    subprocess.run([program, "render", steps[k], "-o", alone], check=True, capture_output=True)
    check(time_value(os.path.join(work, "out.%04d.vti" % k)) == times[k],
          "step %d's .vti records its time, %g" % (k, times[k]))
    stepped = radiance(os.path.join(work, "out.%04d.vti" % k))
    images.append(stepped)
    check((stepped == radiance(alone)).all() and stepped.mean() > 0,
          "step %d bitwise the image of its file alone (mean %.5f)" % (k, stepped.mean()))
check(not (images[0] == images[2]).all(), "the steps' images differ")
one = os.path.join(work, "one.vti")
result = subprocess.run([program, "render", series, "--time-step", "1", "-o", one],
                        capture_output=True, text=True)
check(result.returncode == 0 and (radiance(one) == images[1]).all(),
      "--time-step 1 renders step 1 alone to OUTPUT")

# The pipeline stepped from Python: the same images.
source = brume.vtkBrumeSceneReader()
source.SetFileName(series)
pipeline = brume.vtkBrumePipeline()
pipeline.SetInputConnection(source.GetOutputPort())
pipeline.ApplySceneSettings()
pipeline.GetReconstruction().FixedViewOn()
check(pipeline.GetNumberOfTimeSteps() == 3 and pipeline.GetTimeStep(2) == 2.0,
      "the pipeline lists the scene's steps")
for k in (2, 0):
    pipeline.SetTime(times[k])
    ok = pipeline.Update()
    image = pipeline.RenderImage() if ok else None
    check(image is not None and
          (vtk_to_numpy(image.GetPointData().GetArray("Radiance")) == images[k]).all(),
          "vtkBrumePipeline.SetTime(%g): brume render's step %d" % (times[k], k))

# Two media of different lists: the scene's steps are both lists' times
# merged; at each, each medium takes its last step at or before it.
two = json.loads(json.dumps(scene))
two["media"][1]["density"] = {"vti": ["blob2.vti", "blob0.vti"], "array": "density",
                              "times": [0.25, 1.0]}
merged = brume.vtkBrumeSceneReader()
merged.SetFileName(write_scene("two-lists.json", two))
merged.UpdateInformation()
minfo = merged.GetOutputInformation(0)
merged_times = [minfo.Get(sddp.TIME_STEPS(), k) for k in range(minfo.Length(sddp.TIME_STEPS()))]
check(merged_times == [0.0, 0.25, 0.5, 1.0, 2.0], "two lists' times merged: %s" % merged_times)
for time, blob_step, haze_step in [(0.0, 0, 0), (0.25, 0, 0), (0.5, 1, 0), (1.0, 1, 1),
                                   (2.0, 2, 1)]:
    merged.UpdateTimeStep(time)
    out = merged.GetOutput()
    got = (peak_x(medium_array(out, "blob")), peak_x(medium_array(out, "haze")))
    want = (centres[blob_step], [0.25, -0.25][haze_step])
    check(abs(got[0] - want[0]) < 0.03 and abs(got[1] - want[1]) < 0.03,
          "at t = %g the media are at their steps %d and %d (peaks %.3f, %.3f)"
          % (time, blob_step, haze_step, got[0], got[1]))

# Times before zero, no time asked for: the first step, and its time.
early = json.loads(json.dumps(scene))
early["media"][0]["density"]["times"] = [-2.0, -1.0, 3.0]
first = brume.vtkBrumeSceneReader()
first.SetFileName(write_scene("early.json", early))
first.Update()
data_time = first.GetOutput().GetInformation().Get(vtkDataObject.DATA_TIME_STEP())
check(data_time == -2.0 and abs(peak_x(medium_array(first.GetOutput(), "blob")) - centres[0]) < 0.03,
      "no time asked for: the first step, at t = %g" % data_time)

# Lists that cannot be read.
bad = [
    ({"vti": [], "array": "density"}, "media[0].density.vti: expected a file, or a list"),
    ({"vti": ["blob0.vti", "blob1.vti"], "times": [0, 1, 2]},
     "media[0].density.times: expected 2 numbers, one time per file"),
    ({"vti": ["blob0.vti", "blob1.vti"], "times": [1, 1]},
     "media[0].density.times[1]: expected finite numbers, each greater"),
    ({"vti": ["blob0.vti", "nowhere.vti"]}, "media[0].density.vti[1]: no file"),
    ({"vti": ["blob0.vti", 3]}, "media[0].density.vti[1]: expected a non-empty string"),
    ({"vti": "blob0.vti", "times": [0]}, "media[0].density.times: needs a list of files"),
]
for k, (density, message) in enumerate(bad):
    wrong = json.loads(json.dumps(scene))
    wrong["media"][0]["density"] = density
    path = write_scene("bad%d.json" % k, wrong)
    result = subprocess.run([program, "render", path, "-o", os.path.join(work, "never.png")],
                            capture_output=True, text=True)
    check(result.returncode == 1 and message in result.stderr,
          "refused naming the field: %s (exit %d: %s)"
          % (message, result.returncode, result.stderr.strip()[-160:]))
check(not os.path.exists(os.path.join(work, "never.png")), "no image of a refused scene")
result = subprocess.run([program, "render", series, "--time-step", "3", "-o",
                         os.path.join(work, "never.png")], capture_output=True, text=True)
check(result.returncode == 2 and "the scene has 3 time steps, 0 to 2" in result.stderr,
      "--time-step past the last step: exit 2")

# An OpenVDB list: its steps' boxes come from their grids, as one file's.
if cumulus:
    with open(cumulus) as f:
        cloud = json.load(f)
    vdb = os.path.join(os.path.dirname(os.path.abspath(cumulus)), "cumulus.vdb")
    cloud["render"] = {"particles": 20000, "size": [32, 24]}
    cloud["media"][0]["density"]["vdb"] = vdb
    alone = write_scene("cloud.json", cloud)
    cloud["media"][0]["density"]["vdb"] = [vdb, vdb]
    cloud["media"][0]["density"]["times"] = [0.0, 10.0]
    listed = write_scene("cloud-series.json", cloud)
    subprocess.run([program, "render", alone, "-o", os.path.join(work, "cloud.vti")],
                   check=True, capture_output=True)
    result = subprocess.run([program, "render", listed, "--time-step", "1", "-o",
                             os.path.join(work, "cloud-step1.vti")], capture_output=True, text=True)
    check(result.returncode == 0 and "time step 1 of 2 (t = 10)" in result.stdout
          and (radiance(os.path.join(work, "cloud-step1.vti"))
               == radiance(os.path.join(work, "cloud.vti"))).all(),
          "an OpenVDB list's step renders as its file alone")

if failures:
    sys.exit("%d checks failed" % len(failures))
