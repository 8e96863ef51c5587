"""pvbatch: a Brume scene file and an OpenVDB grid opened as a ParaView user
opens files.

OpenDataFile() picks the plugin's scene reader for a Brume scene and not for
another JSON file, and its OpenVDB reader for a .vdb grid. The project's own
cloud (cumulus.json: an OpenVDB medium in sunlight over a plain, whose
extinction at the grid's own resolution travels in bricks) is traced,
reconstructed and shown with "Brume Radiance" at the scene file's camera;
the screenshot equals vtkBrumeSceneActors' image of the same textures.

usage: pvbatch TestBrumeSceneFile.py PLUGIN SCENE_DIR OUTPUT_DIR
(SCENE_DIR: the build's Data/scenes, with cumulus.json and cumulus.vdb)
"""
import json
import os
import sys

from paraview.simple import *  # noqa: F401,F403

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from brume_testing import (check, check_media_drawn, finish, partitions_with,  # noqa: E402
                           shown_at_scene_camera)

plugin, scene_dir, output_dir = sys.argv[1:4]
LoadPlugin(plugin, ns=globals())


scene_file = os.path.join(scene_dir, "cumulus.json")
reader = OpenDataFile(scene_file)
check(reader is not None and reader.GetXMLName() == "BrumeSceneReader",
      "OpenDataFile(cumulus.json) uses the Brume scene reader (%s)"
      % (reader.GetXMLName() if reader else None))

# A JSON file that is not a Brume scene is not offered to it.
other = os.path.join(output_dir, "TestBrumeSceneFile-other.json")
with open(other, "w") as f:
    json.dump({"not": "a scene"}, f)
factory = servermanager.vtkSMProxyManager.GetProxyManager().GetReaderFactory()
session = servermanager.ActiveConnection.Session
check(factory.CanReadFile(scene_file, "sources", "BrumeSceneReader", session),
      "the scene reader can read cumulus.json")
check(not factory.CanReadFile(other, "sources", "BrumeSceneReader", session),
      "a JSON file without 'brume_scene' is not offered to the scene reader")

grid = OpenDataFile(os.path.join(scene_dir, "cumulus.vdb"))
check(grid is not None and grid.GetXMLName() == "BrumeOpenVDBReader",
      "OpenDataFile(cumulus.vdb) uses the Brume OpenVDB reader")
if grid is not None:
    grid.UpdatePipeline()
    density = grid.PointData["density"] if "density" in grid.PointData.keys() else None
    check(density is not None and density.GetRange()[1] > 0.0,
          "the grid's density reaches the image (%s)" % (density.GetRange() if density else None,))

with open(scene_file) as f:
    camera_settings = json.load(f)["camera"]
size = 160
tracer = BrumeLightTracer(Input=reader, NumberOfParticles=100000, Seed=1)
reconstruction = BrumeRadianceReconstruction(Scene=reader, Hits=tracer)
reconstruction.UpdatePipeline()
textures = reconstruction.GetClientSideObject().GetOutput()
bricked = partitions_with(textures, "ExtinctionBrickSamples")
check(bricked == 1, "the cloud's extinction travels in bricks (%d sparse grids)" % bricked)

view, display, shown = shown_at_scene_camera(reconstruction, camera_settings, size, output_dir,
                                            "TestBrumeSceneFile")

# Without the medium's bricks drawn, the image would be the plain's alone:
# the cloud must change it.
check_media_drawn(view, display, shown, size, output_dir, "TestBrumeSceneFile", "the cloud")

Delete(view)  # before the interpreter's exit, as pvbatch expects
del view
finish()
