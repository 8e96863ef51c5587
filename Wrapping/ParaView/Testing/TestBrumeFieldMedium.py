"""pvbatch: a ParaView user's volume switched to Brume. VTK's Wavelet made a
medium by "Brume Medium From Field" with the array's own colour map and
opacity function (GetColorTransferFunction / GetOpacityTransferFunction),
grouped with a ground, lit by a light of the view's kind (AddLight), traced,
reconstructed and shown with "Brume Radiance". The functions' points reach
the medium; editing the colour map or the opacity function, as their
editors do, traces and reconstructs anew and changes the view; the
screenshot equals vtkBrumeSceneActors' image of the same textures.

usage: pvbatch TestBrumeFieldMedium.py PLUGIN OUTPUT_DIR
"""
import os
import sys

from paraview.simple import *  # noqa: F401,F403

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from brume_testing import (check, check_media_drawn, finish, image_error,  # noqa: E402
                           partitions_with, shown_at_scene_camera)

plugin, output_dir = sys.argv[1:3]
LoadPlugin(plugin, ns=globals())
# Brume's Python classes (on PYTHONPATH), so that the reconstruction's
# client-side object answers with its own methods.
import brume  # noqa: E402,F401

wavelet = Wavelet()
lut = GetColorTransferFunction("RTData")
lut.ColorSpace = "RGB"
lut.RGBPoints = [90, 0.2, 0.4, 0.9, 280, 1.0, 0.8, 0.6]
opacity = GetOpacityTransferFunction("RTData")
opacity.Points = [90, 0.0, 0.5, 0.0, 170, 0.12, 0.5, 0.0, 280, 0.6, 0.5, 0.0]
# Ranges set, as a display coloured by the array leaves them: the medium
# takes the functions as they are (a function whose range was never set is
# fitted to the array's, as ColorBy does; TestBrumeFieldMediumDefaults.py).
lut.ScalarRangeInitialized = 1
opacity.ScalarRangeInitialized = 1

medium = BrumeMediumFromField(Input=wavelet)
medium.Scalars = ["POINTS", "RTData"]
medium.ScalarOpacityFunction = opacity
medium.LookupTable = lut
medium.ScalarOpacityUnitDistance = 1.0
medium.ScatteringAnisotropy = 0.3
medium.Albedo = [0.9, 0.9, 0.9]
medium.UpdatePipeline()
fd = medium.GetClientSideObject().GetOutput().GetFieldData()
points = fd.GetArray("BrumeScalarOpacity")
check(points is not None and points.GetNumberOfTuples() == 3
      and points.GetTuple2(1) == (170.0, 0.12),
      "the opacity function's points reach the medium")
colours = fd.GetArray("BrumeScalarColor")
check(colours is not None and colours.GetNumberOfTuples() == 2
      and colours.GetTuple4(1) == (280.0, 1.0, 0.8, 0.6),
      "the colour map's points reach the medium")
check(abs(fd.GetArray("BrumeG").GetTuple1(0) - 0.3) < 1e-6, "g from ScatteringAnisotropy")

ground = Triangulate(Input=Plane(Origin=[-40, -11, 40], Point1=[40, -11, 40],
                                 Point2=[-40, -11, -40]))
scene = GroupDatasets(Input=[ground, medium])
light = CreateLight()  # what AddLight(view) adds to a view
light.Coords = "Scene"
light.Type = "Directional"
light.Position = [-1, 2, 0.5]
light.FocalPoint = [0, 0, 0]
light.Intensity = 1.0
light.DiffuseColor = [1.0, 0.95, 0.9]
camera = {"position": [0, 12, 52], "focal_point": [0, -2, 0], "view_up": [0, 1, 0],
          "view_angle": 35}
tracer = BrumeLightTracer(Input=scene, NumberOfParticles=100000, Seed=1, Lights=[light])
reconstruction = BrumeRadianceReconstruction(Scene=scene, Hits=tracer,
                                             EyePosition=camera["position"])
reconstruction.UpdatePipeline()
textures = reconstruction.GetClientSideObject().GetOutput()
check(partitions_with(textures, "AlbedoTransferFunction") == 1,
      "the wavelet's albedo table reaches the view")

size = 96
name = "TestBrumeFieldMedium"
view, display, shown = shown_at_scene_camera(reconstruction, camera, size, output_dir, name)


def screenshot(suffix):
    Render(view)
    png = os.path.join(output_dir, "%s-%s.png" % (name, suffix))
    SaveScreenshot(png, view, ImageResolution=[size, size])
    return png


# The editors change the functions' proxies: the medium follows.
filter = reconstruction.GetClientSideObject()
sampled = filter.GetNumberOfNativeBricksSampled()
reused = filter.GetNumberOfNativeBricksReused()
kept = filter.GetNumberOfDirectLightsKept()
lut.RGBPoints = [90, 0.9, 0.3, 0.1, 280, 0.9, 0.3, 0.1]
recoloured = screenshot("recoloured")
# A colour edit keeps the medium's extinction and the shadow rays through it.
check(sampled > 0 and filter.GetNumberOfNativeBricksSampled() == sampled
      and filter.GetNumberOfNativeBricksReused() == reused + sampled
      and filter.GetNumberOfDirectLightsKept() > kept,
      "a colour edit keeps every brick of extinction and the shadow rays (sampled %d -> %d, "
      "kept %d -> %d, rays kept %d -> %d)"
      % (sampled, filter.GetNumberOfNativeBricksSampled(), reused,
         filter.GetNumberOfNativeBricksReused(), kept, filter.GetNumberOfDirectLightsKept()))
check(image_error(recoloured, shown) > 10, "a new colour map changes the view (error %g)"
      % image_error(recoloured, shown))
colours = medium.GetClientSideObject().GetOutput().GetFieldData().GetArray("BrumeScalarColor")
check(colours.GetTuple4(0) == (90.0, 0.9, 0.3, 0.1), "the medium has the new colours")


def albedo_table(textures):
    for i in range(textures.GetNumberOfPartitionedDataSets()):
        pds = textures.GetPartitionedDataSet(i)
        for k in range(pds.GetNumberOfPartitions()):
            table = pds.GetPartition(k).GetFieldData().GetArray("AlbedoTransferFunction")
            if table is not None:
                return table
    return None


table = albedo_table(reconstruction.GetClientSideObject().GetOutput())
check(table is not None and all(abs(a - b) < 1e-6 for a, b in
                                zip(table.GetTuple3(0), (0.81, 0.27, 0.09))),
      "the view's albedo table is the new colour times Albedo: %s"
      % (table.GetTuple3(0) if table else None,))
kept = filter.GetNumberOfDirectLightsKept()
opacity.Points = [90, 0.0, 0.5, 0.0, 280, 0.05, 0.5, 0.0]
thinner = screenshot("thinner")
check(filter.GetNumberOfNativeBricksSampled() > sampled
      and filter.GetNumberOfDirectLightsKept() == kept,
      "an opacity edit samples the extinction and casts the shadow rays again")
check(image_error(thinner, recoloured) > 10, "a new opacity function changes the view (error %g)"
      % image_error(thinner, recoloured))
check_media_drawn(view, display, thinner, size, output_dir, name, "the wavelet")

Delete(view)  # before the interpreter's exit, as pvbatch expects
del view
finish()
