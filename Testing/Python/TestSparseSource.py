"""A medium image in the sparse form, from Python: the field arrays of
vtkBrumeSliceVolumeMapper's sparse source radiance, validated and expanded
by DenseSourceArray to one tuple per cell (0 in bricks not stored).

usage: python3 TestSparseSource.py
"""
import sys

import brume
from vtkmodules.vtkCommonCore import vtkFloatArray, vtkIntArray
from vtkmodules.vtkCommonDataModel import vtkImageData

failures = []


def check(ok, what):
    print(("ok: " if ok else "FAILED: ") + what)
    if not ok:
        failures.append(what)


Mapper = brume.vtkBrumeSliceVolumeMapper
# 10 x 3 x 2 cells: bricks of 8 x 3 x 2 cells, two along x; the second
# brick stored in slot 0, the first not stored.
cells = (10, 3, 2)
image = vtkImageData()
image.SetDimensions(cells[0] + 1, cells[1] + 1, cells[2] + 1)
edge = [Mapper.SourceBrickEdge(n) for n in cells]
check(edge == [8, 3, 2], "brick edges %s" % edge)
check(Mapper.SourceBricksAlong(cells[0]) == 2, "two bricks along x")
slots = vtkIntArray()
slots.SetName("SourceBrickSlots")
for slot in (-1, 0):
    slots.InsertNextValue(slot)
samples = vtkFloatArray()
samples.SetName("SourceRadianceBrickSamples")
samples.SetNumberOfComponents(3)
brick_cells = edge[0] * edge[1] * edge[2]
for c in range(brick_cells):
    samples.InsertNextTuple3(c + 1.0, 0.5, 0.25)
image.GetFieldData().AddArray(slots)
image.GetFieldData().AddArray(samples)

check(Mapper.IsSparseSource(image), "the image is in the sparse form")
check(Mapper.ValidateInput(image) == "", "valid: '%s'" % Mapper.ValidateInput(image))
dense = Mapper.DenseSourceArray(image, "SourceRadiance")
check(dense is not None and dense.GetNumberOfTuples() == 60, "one tuple per cell")
if dense is not None:
    wrong = 0
    for k in range(cells[2]):
        for j in range(cells[1]):
            for i in range(cells[0]):
                cell = (k * cells[1] + j) * cells[0] + i
                if i < 8:
                    want = 0.0  # the first brick is not stored
                else:
                    want = ((k * edge[1] + j) * edge[0] + (i - 8)) + 1.0
                wrong += dense.GetComponent(cell, 0) != want
    check(wrong == 0, "cells expanded from their brick (%d wrong)" % wrong)

# A slot the samples do not hold is refused, and not expanded.
slots.SetValue(1, 3)
check("slot" in Mapper.ValidateInput(image), "bad slot: '%s'" % Mapper.ValidateInput(image))
check(Mapper.DenseSourceArray(image, "SourceRadiance") is None, "bad slot: nothing expanded")

print("%d check(s) failed" % len(failures) if failures else "all checks passed")
sys.exit(1 if failures else 0)
