"""pvbatch, after TestBrumeGodRaysMenus.xml: the state the GUI saved once
a user opened god-rays.json and built the pipeline from the Filters menu
(Brume Light Tracer, then Brume Radiance Reconstruction through its input
dialog). The reconstruction's Scene is the scene file's reader and its
Hits the tracer on that reader; loaded here, the state's reconstruction
shown at the scene file's camera draws what vtkBrumeSceneActors draws of
the same textures, and the haze changes the image.

usage: pvbatch TestBrumeGodRaysMenusCheck.py PLUGIN STATE_DIR SCENE_FILE
"""
import json
import os
import sys

from paraview.simple import *  # noqa: F401,F403

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from brume_testing import (check, check_media_drawn, finish, saved_proxies,  # noqa: E402
                           saved_values, shown_at_scene_camera)

plugin, directory, scene_file = sys.argv[1:4]
state = os.path.join(directory, "god-rays.pvsm")
check(os.path.exists(state), "the GUI saved its state")
proxies = saved_proxies(state)
values = saved_values


def of_type(kind):
    return [p for p in proxies if p.get("group") in ("sources", "filters") and p.get("type") == kind]


readers, tracers, reconstructions = (of_type("BrumeSceneReader"), of_type("BrumeLightTracer"),
                                     of_type("BrumeRadianceReconstruction"))
check(len(readers) == 1 and len(tracers) == 1 and len(reconstructions) == 1,
      "one reader, one tracer, one reconstruction (got %d, %d, %d)"
      % (len(readers), len(tracers), len(reconstructions)))
if readers and tracers and reconstructions:
    reader, tracer, reconstruction = readers[0], tracers[0], reconstructions[0]
    check(os.path.basename((values(reader, "FileName") or [""])[0]) == "god-rays.json",
          "the reader reads god-rays.json (%s)" % values(reader, "FileName"))
    check(values(tracer, "Input") == [reader.get("id")], "the tracer traces the scene file")
    check(values(reconstruction, "Scene") == [reader.get("id")],
          "the input dialog put the scene in Scene (%s)" % values(reconstruction, "Scene"))
    check(values(reconstruction, "Hits") == [tracer.get("id")],
          "and the tracer in Hits (%s)" % values(reconstruction, "Hits"))

# The saved state renders the lit room in pvbatch.
LoadPlugin(plugin, ns=globals())
LoadState(state)
tracer = FindSource("BrumeLightTracer1")
reconstruction = FindSource("BrumeRadianceReconstruction1")
check(tracer is not None and reconstruction is not None, "the state's pipeline loads")
if tracer is not None and reconstruction is not None:
    tracer.NumberOfParticles = 200000
    with open(scene_file) as f:
        camera_settings = json.load(f)["camera"]
    view, display, shown = shown_at_scene_camera(reconstruction, camera_settings, 160, directory,
                                                "TestBrumeGodRaysMenus")
    check_media_drawn(view, display, shown, 160, directory, "TestBrumeGodRaysMenus", "the haze")
    Delete(view)  # before the interpreter's exit, as pvbatch expects
    del view
finish()
