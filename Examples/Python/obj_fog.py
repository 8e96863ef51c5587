#!/usr/bin/env python3
"""Brume from Python: a room read with vtkOBJReader, a smoke blob given as a
vtkImageData, the three phases (particle tracing, reconstruction, slice
rendering), a PNG.

    PYTHONPATH=build/lib/python3.11/site-packages \
        python3 Examples/Python/obj_fog.py -o obj_fog.png
"""
import argparse
import math
import os

from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkFloatArray
from vtkmodules.vtkCommonDataModel import (vtkCompositeDataSet, vtkImageData,
                                           vtkPartitionedDataSet,
                                           vtkPartitionedDataSetCollection)
from vtkmodules.vtkFiltersSources import vtkPlaneSource
from vtkmodules.vtkIOGeometry import vtkOBJReader
from vtkmodules.vtkIOImage import vtkPNGWriter

import brume

HERE = os.path.dirname(os.path.abspath(__file__))


def field(data, name, *values):
    """Sets a field array (a Brume material or medium parameter)."""
    array = vtkDoubleArray()
    array.SetName(name)
    array.SetNumberOfComponents(len(values))
    array.InsertNextTuple(values)
    data.GetFieldData().AddArray(array)


def build_scene(obj_file):
    """The scene collection: the room, a square light, a smoke blob."""
    scene = vtkPartitionedDataSetCollection()

    def add(data, name):
        index = scene.GetNumberOfPartitionedDataSets()
        pds = vtkPartitionedDataSet()
        pds.SetNumberOfPartitions(1)
        pds.SetPartition(0, data)
        scene.SetPartitionedDataSet(index, pds)
        scene.GetMetaData(index).Set(vtkCompositeDataSet.NAME(), name)

    reader = vtkOBJReader()
    reader.SetFileName(obj_file)
    reader.Update()
    room = reader.GetOutput()
    field(room, "BrumeReflectance", 0.7, 0.7, 0.7)
    add(room, "room")

    light = vtkPlaneSource()  # a square facing -y just under the ceiling
    light.SetOrigin(-0.3, 0.99, -0.3)
    light.SetPoint1(0.3, 0.99, -0.3)  # (Point1 - Origin) x (Point2 - Origin) is -y
    light.SetPoint2(-0.3, 0.99, 0.3)
    light.Update()
    emitter = light.GetOutput()
    field(emitter, "BrumeReflectance", 0, 0, 0)
    field(emitter, "BrumeEmission", 12, 11, 10)
    add(emitter, "light")

    n = 24  # a Gaussian blob of smoke, density on the points
    smoke = vtkImageData()
    smoke.SetDimensions(n, n, n)
    smoke.SetOrigin(-0.6, -0.8, -0.6)
    smoke.SetSpacing(1.2 / (n - 1), 1.2 / (n - 1), 1.2 / (n - 1))
    density = vtkFloatArray()
    density.SetName("density")
    for k in range(n):
        for j in range(n):
            for i in range(n):
                x, y, z = smoke.GetPoint(smoke.ComputePointId((i, j, k)))
                r2 = x * x + (y + 0.2) ** 2 + z * z
                density.InsertNextValue(3.0 * math.exp(-r2 / 0.08))
    smoke.GetPointData().SetScalars(density)
    field(smoke, "BrumeSigmaA", 1.2, 1.2, 1.2)  # a sooty smoke: albedo 0.4
    field(smoke, "BrumeSigmaS", 0.8, 0.8, 0.8)
    field(smoke, "BrumeG", 0.5)
    add(smoke, "smoke")
    return scene


def render(scene, output, particles=300000, size=256):
    """The three phases through one object, then the image tone-mapped to a PNG."""
    pipeline = brume.vtkBrumePipeline()
    pipeline.SetInputData(scene)
    pipeline.GetTracer().SetNumberOfParticles(particles)
    pipeline.SetSize(size, size)
    camera = pipeline.GetCamera()
    camera.SetPosition(0, 0, 4)
    camera.SetFocalPoint(0, 0, 0)
    camera.SetViewUp(0, 1, 0)
    camera.SetViewAngle(40)
    if not pipeline.Update():
        raise RuntimeError("brume: " + pipeline.GetFailedPhase() + " failed")
    image = pipeline.ToneMap(pipeline.RenderImage())
    writer = vtkPNGWriter()
    writer.SetFileName(output)
    writer.SetInputData(image)
    writer.Write()
    return image


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("-o", "--output", default="obj_fog.png")
    parser.add_argument("--obj", default=os.path.join(HERE, "..", "..", "Data", "models", "room.obj"))
    parser.add_argument("--particles", type=int, default=300000)
    parser.add_argument("--size", type=int, default=256)
    args = parser.parse_args()
    render(build_scene(args.obj), args.output, args.particles, args.size)
    print("wrote", args.output)


if __name__ == "__main__":
    main()
