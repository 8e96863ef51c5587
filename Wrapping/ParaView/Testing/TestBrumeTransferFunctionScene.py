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
from brume_testing import actors_image, black_view, check, finish, image_error  # noqa: E402

plugin, scene_file, output_dir = sys.argv[1:4]
LoadPlugin(plugin, ns=globals())

reader = OpenDataFile(scene_file)
check(reader is not None and reader.GetXMLName() == "BrumeSceneReader",
      "OpenDataFile uses the Brume scene reader")
tracer = BrumeLightTracer(Input=reader, NumberOfParticles=100000, Seed=1)
reconstruction = BrumeRadianceReconstruction(Scene=reader, Hits=tracer)
reconstruction.UpdatePipeline()
textures = reconstruction.GetClientSideObject().GetOutput()
tables = 0
for i in range(textures.GetNumberOfPartitionedDataSets()):
    pds = textures.GetPartitionedDataSet(i)
    for k in range(pds.GetNumberOfPartitions()):
        fd = pds.GetPartition(k).GetFieldData()
        tables += 1 if fd.GetArray("ExtinctionTransferFunction") is not None else 0
check(tables == 1, "the plume's scalars travel with the function's table (%d tables)" % tables)

with open(scene_file) as f:
    camera_settings = json.load(f)["camera"]
size = 128
view = black_view(size)
display = Show(reconstruction, view)
check(display.Representation == "Brume Radiance",
      "Show() gives 'Brume Radiance' (got '%s')" % display.Representation)
Render(view)
view.CameraPosition = camera_settings["position"]
view.CameraFocalPoint = camera_settings["focal_point"]
view.CameraViewUp = camera_settings["view_up"]
view.CameraViewAngle = camera_settings["view_angle"]
Render(view)
shown = os.path.join(output_dir, "TestBrumeTransferFunctionScene.png")
SaveScreenshot(shown, view, ImageResolution=[size, size])
expected = os.path.join(output_dir, "TestBrumeTransferFunctionScene-actors.png")
actors_image(view, size, reconstruction.GetClientSideObject().GetOutput(),
             view.GetActiveCamera(), expected)
error = image_error(shown, expected)
check(error <= 0.5, "the render view shows what vtkBrumeSceneActors draws (error %g)" % error)
display.ShowMedia = 0
Render(view)
bare = os.path.join(output_dir, "TestBrumeTransferFunctionScene-bare.png")
SaveScreenshot(bare, view, ImageResolution=[size, size])
error = image_error(shown, bare)
check(error > 10, "the classified plume is drawn (error %g against the room alone)" % error)

Delete(view)  # before the interpreter's exit, as pvbatch expects
del view
finish()
