"""pvbatch: a scene whose medium is a scalar field classified by a transfer
function (Data/scenes/plume-transfer-function.json), opened, traced,
reconstructed and shown with "Brume Radiance" as a ParaView user would.
The medium's extinction reaches the view as scalars and the function's
table; the screenshot equals vtkBrumeSceneActors' image of the same
textures, and the medium changes it.

usage: pvbatch TestBrumeTransferFunctionScene.py PLUGIN SCENE OUTPUT_DIR
"""
import json
import os
import sys

from paraview.simple import *  # noqa: F401,F403

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from brume_testing import (check, check_media_drawn, finish, partitions_with,  # noqa: E402
                           shown_at_scene_camera)

plugin, scene_file, output_dir = sys.argv[1:4]
LoadPlugin(plugin, ns=globals())

reader = OpenDataFile(scene_file)
check(reader is not None and reader.GetXMLName() == "BrumeSceneReader",
      "OpenDataFile uses the Brume scene reader")
tracer = BrumeLightTracer(Input=reader, NumberOfParticles=100000, Seed=1)
reconstruction = BrumeRadianceReconstruction(Scene=reader, Hits=tracer)
reconstruction.UpdatePipeline()
textures = reconstruction.GetClientSideObject().GetOutput()
tables = partitions_with(textures, "ExtinctionTransferFunction")
check(tables == 1, "the plume's scalars travel with the function's table (%d tables)" % tables)

with open(scene_file) as f:
    camera_settings = json.load(f)["camera"]
size = 128
view, display, shown = shown_at_scene_camera(reconstruction, camera_settings, size, output_dir,
                                            "TestBrumeTransferFunctionScene")
check_media_drawn(view, display, shown, size, output_dir, "TestBrumeTransferFunctionScene",
                  "the classified plume")

Delete(view)  # before the interpreter's exit, as pvbatch expects
del view
finish()
