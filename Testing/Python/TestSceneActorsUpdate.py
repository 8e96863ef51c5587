"""vtkBrumeSceneActors.UpdateInputs: a prop keeps the data set it shows when
the new one holds the same geometry and bytes, and takes any that differ.
A view update's new medium texture keeps its unchanged extinction array.
CanUpdateInputs says quietly which collections UpdateInputs would take.

usage: python3 TestSceneActorsUpdate.py
"""
import sys

import brume
from vtkmodules.vtkCommonDataModel import vtkPartitionedDataSetCollection
from vtkmodules.vtkRenderingCore import vtkCamera, vtkRenderer

failures = []


def check(ok, what):
    print(("ok: " if ok else "FAILED: ") + what)
    if not ok:
        failures.append(what)


scene = brume.vtkBrumeDefaultSceneSource()
tracer = brume.vtkBrumeLightTracer()
tracer.SetInputConnection(scene.GetOutputPort())
tracer.SetNumberOfParticles(20000)
reconstruction = brume.vtkBrumeRadianceReconstruction()
reconstruction.SetInputConnection(0, scene.GetOutputPort())
reconstruction.SetInputConnection(1, tracer.GetOutputPort())
camera = vtkCamera()
brume.vtkBrumeSceneCamera.SetToDefault(camera)
reconstruction.SetCamera(camera)
reconstruction.Update()
first = vtkPartitionedDataSetCollection()
first.ShallowCopy(reconstruction.GetOutput())

actors = brume.vtkBrumeSceneActors()
actors.SetInputData(first)
check(not actors.CanUpdateInputs(first), "no props to update before AddToRenderer")
renderer = vtkRenderer()
check(actors.AddToRenderer(renderer), "the props are made")
check(actors.CanUpdateInputs(first), "the props can take their own input")

# Other objects: one fewer, or two swapped (a surface where the fog was).
fewer = vtkPartitionedDataSetCollection()
fewer.SetNumberOfPartitionedDataSets(first.GetNumberOfPartitionedDataSets() - 1)
for i in range(fewer.GetNumberOfPartitionedDataSets()):
    fewer.SetPartitionedDataSet(i, first.GetPartitionedDataSet(i))
check(not actors.CanUpdateInputs(fewer), "one object fewer is not taken")
swapped = vtkPartitionedDataSetCollection()
swapped.ShallowCopy(first)
fog = [i for i in range(first.GetNumberOfPartitionedDataSets())
       if first.GetPartitionedDataSet(i).GetPartition(0).GetCellData().GetArray("SourceRadiance")][0]
other = 0 if fog != 0 else 1
swapped.SetPartitionedDataSet(fog, first.GetPartitionedDataSet(other))
swapped.SetPartitionedDataSet(other, first.GetPartitionedDataSet(fog))
check(not actors.CanUpdateInputs(swapped), "a surface where the fog was is not taken")
check(actors.GetNumberOfChangedDataSets() == -1, "no update yet")

# The same textures as new objects (as a ParaView server sends them again).
copy = vtkPartitionedDataSetCollection()
copy.DeepCopy(first)
check(actors.UpdateInputs(copy), "a copy is accepted")
check(actors.GetNumberOfChangedDataSets() == 0,
      "a copy changes nothing (%d)" % actors.GetNumberOfChangedDataSets())

# One texel of one surface's texture differs: that image alone is taken.
edited = vtkPartitionedDataSetCollection()
edited.DeepCopy(first)
radiance = edited.GetPartitionedDataSet(0).GetPartition(0).GetPointData().GetArray("Radiance")
radiance.SetComponent(0, 0, radiance.GetComponent(0, 0) + 1.0)
check(actors.UpdateInputs(edited), "an edited copy is accepted")
check(actors.GetNumberOfChangedDataSets() == 1,
      "one edited texel changes one data set (%d)" % actors.GetNumberOfChangedDataSets())

# The camera turns: the fog's texture (per view) alone changes.
def fog_image(textures):
    for i in range(textures.GetNumberOfPartitionedDataSets()):
        image = textures.GetPartitionedDataSet(i).GetPartition(0)
        if image.GetCellData().GetArray("SourceRadiance"):
            return image


before = fog_image(reconstruction.GetOutput())
camera.Azimuth(10.0)
reconstruction.Update()
after = fog_image(reconstruction.GetOutput())
check(after is not before, "the turn makes a new fog texture")
check(after.GetCellData().GetArray("Extinction") is before.GetCellData().GetArray("Extinction"),
      "it keeps the extinction array, which the turn does not change (renderers skip it)")
turned = vtkPartitionedDataSetCollection()
turned.DeepCopy(reconstruction.GetOutput())
check(actors.UpdateInputs(turned), "the turned textures are accepted")
check(actors.GetNumberOfChangedDataSets() == 2,
      "the turn changes the edited surface back and the fog (%d)"
      % actors.GetNumberOfChangedDataSets())
print("%d check(s) failed" % len(failures) if failures else "all checks passed")
sys.exit(1 if failures else 0)
