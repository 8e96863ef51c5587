"""Surface atlases (vtkBrumeSceneActors::SurfaceAtlasMinimum): many surfaces
drawn through one textured actor give the image their own actors give, up
to the rounding of texture coordinates; an edited texture reaches its slot
in the atlas; the default threshold leaves a scene of few surfaces with an
actor each, and gives a scene of many surfaces a few actors.

usage: python3 TestSurfaceAtlas.py BRUME OUTPUT_DIR
"""
import json
import os
import random
import subprocess
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkPartitionedDataSetCollection
from vtkmodules.vtkRenderingCore import vtkRenderer

import brume

program, output_dir = sys.argv[1:3]
failures = []


def check(ok, what):
    print(("ok: " if ok else "FAILED: ") + what)
    if not ok:
        failures.append(what)


def render(minimum, interpolate=True):
    source = brume.vtkBrumeDefaultSceneSource()
    pipeline = brume.vtkBrumePipeline()
    pipeline.SetInputConnection(source.GetOutputPort())
    pipeline.GetTracer().SetNumberOfParticles(50000)
    pipeline.SetSize(160, 120)
    pipeline.GetReconstruction().FixedViewOn()
    pipeline.GetActors().SetSurfaceAtlasMinimum(minimum)
    pipeline.GetActors().SetInterpolate(interpolate)
    if not pipeline.Update():
        sys.exit("the pipeline failed at " + pipeline.GetFailedPhase())
    image = pipeline.RenderImage()
    actors = pipeline.GetActors()
    return (vtk_to_numpy(image.GetPointData().GetArray("Radiance")).copy(),
            actors.GetNumberOfSurfaceAtlases(), actors.GetProps().GetNumberOfItems())


own, own_atlases, own_props = render(2**31 - 1)
shared, atlases, props = render(0)
surfaces = own_props - props + atlases
print("own actors: %d props; shared: %d props, %d atlas(es), %d surfaces in them"
      % (own_props, props, atlases, surfaces))
check(own_atlases == 0, "VTK_INT_MAX: no atlas")
check(atlases == 1 and surfaces >= 4, "0: the default scene's surfaces share one atlas")
check(render(64)[1] == 0, "the default threshold leaves the default scene's %d surfaces alone"
      % surfaces)
scale = float(own.mean())
difference = np.abs(shared - own)
print("mean radiance %.6g; largest difference %.3g, mean %.3g; pixels differing by over 1e-4 "
      "of the mean: %d of %d" % (scale, difference.max(), difference.mean(),
                                 int((difference > 1e-4 * scale).sum()), own.shape[0]))
check(scale > 0.0, "the image is not black")
# Texture coordinates in an atlas are rounded to float at another scale:
# the filtering weights move by about 1e-7, and a texel's neighbour
# differs by at most the texture's range.
check(difference.max() <= 1e-4 * float(own.max()), "linear filtering: the same image")
own_nearest = render(2**31 - 1, False)[0]
shared_nearest = render(0, False)[0]
differing = int((own_nearest != shared_nearest).any(axis=-1).sum()) if own_nearest.ndim > 1 \
    else int((own_nearest != shared_nearest).sum())
print("nearest texels: %d of %d pixels differ" % (differing, own_nearest.shape[0]))
check(differing <= own_nearest.shape[0] // 1000,
      "nearest texels: the same image (a texel boundary may fall on a pixel)")

# An edited texture reaches its slot.
scene = brume.vtkBrumeDefaultSceneSource()
tracer = brume.vtkBrumeLightTracer()
tracer.SetInputConnection(scene.GetOutputPort())
tracer.SetNumberOfParticles(20000)
reconstruction = brume.vtkBrumeRadianceReconstruction()
reconstruction.SetInputConnection(0, scene.GetOutputPort())
reconstruction.SetInputConnection(1, tracer.GetOutputPort())
reconstruction.Update()
first = vtkPartitionedDataSetCollection()
first.ShallowCopy(reconstruction.GetOutput())
actors = brume.vtkBrumeSceneActors()
actors.SetSurfaceAtlasMinimum(0)
actors.SetInputData(first)
renderer = vtkRenderer()
check(actors.AddToRenderer(renderer), "the props are made")
atlas = actors.GetSurfaceAtlas(0)
texels = vtk_to_numpy(atlas.GetPointData().GetScalars())
edited = vtkPartitionedDataSetCollection()
edited.DeepCopy(first)
radiance = edited.GetPartitionedDataSet(0).GetPartition(0).GetPointData().GetArray("Radiance")
marker = 12345.0
before = int((texels[:, 0] == marker).sum())
radiance.SetComponent(0, 0, marker)
check(actors.UpdateInputs(edited), "an edited copy is accepted")
check(actors.GetNumberOfChangedDataSets() == 1, "one data set changed (%d)"
      % actors.GetNumberOfChangedDataSets())
texels = vtk_to_numpy(actors.GetSurfaceAtlas(0).GetPointData().GetScalars())
# The corner texel and the three border texels around it.
check(before == 0 and int((texels[:, 0] == marker).sum()) == 4,
      "the edited corner texel is in the atlas with its border (%d)"
      % int((texels[:, 0] == marker).sum()))
check(actors.GetSurfaceAtlas(0) is atlas, "the same atlas, its texels copied in place")

# Many objects: a ground with 2,000 tiles draws through a few actors.
rng = random.Random(3)
tiles = {"brume_scene": 1, "name": "tiles",
         "camera": {"position": [0, 3, 8], "focal_point": [0, 0, 0], "view_up": [0, 1, 0],
                    "view_angle": 40},
         "surfaces": [{"name": "ground", "quad": [[-4, 0, -4], [-4, 0, 4], [4, 0, 4], [4, 0, -4]],
                       "material": {"reflectance": [0.6, 0.6, 0.6]}}],
         "lights": [{"type": "point", "position": [0, 3, 0], "intensity": [5, 5, 5]}]}
for k in range(2000):
    x, z = rng.uniform(-4, 4), rng.uniform(-4, 4)
    tiles["surfaces"].append({"name": "tile %d" % k,
                              "quad": [[x, 0.01, z], [x, 0.01, z + 0.05],
                                       [x + 0.05, 0.01, z + 0.05], [x + 0.05, 0.01, z]],
                              "material": {"reflectance": [0.8, 0.2, 0.2]}})
path = os.path.join(output_dir, "atlas-tiles.json")
with open(path, "w") as f:
    json.dump(tiles, f)
source = brume.vtkBrumeSceneReader()
source.SetFileName(path)
pipeline = brume.vtkBrumePipeline()
pipeline.SetInputConnection(source.GetOutputPort())
pipeline.ApplySceneSettings()
pipeline.GetTracer().SetNumberOfParticles(20000)
pipeline.SetSize(64, 48)
check(pipeline.Update(), "2,001 surfaces reconstruct")
image = pipeline.RenderImage()
props = pipeline.GetActors().GetProps().GetNumberOfItems()
print("2,001 surfaces: %d props, %d atlas(es)" % (props, pipeline.GetActors().GetNumberOfSurfaceAtlases()))
check(image is not None and props <= 4, "2,001 surfaces are drawn by at most 4 actors")
print("%d check(s) failed" % len(failures) if failures else "all checks passed")
sys.exit(1 if failures else 0)
