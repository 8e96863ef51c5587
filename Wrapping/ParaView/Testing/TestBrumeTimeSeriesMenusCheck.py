"""pvbatch, after TestBrumeTimeSeriesMenus.xml: the state the GUI saved once
a user opened puff-series.json (a scene of eight time steps), built the
pipeline from the Filters menu and pressed the VCR toolbar's Next Frame
twice. The state's animation stands at the third step (t = 1) of the
scene's eight; loaded here, its reconstruction at that time shows the puff
higher than at t = 0 (the puff rises), each image what vtkBrumeSceneActors
draws of that time's textures.

usage: pvbatch TestBrumeTimeSeriesMenusCheck.py PLUGIN STATE_DIR SCENE_FILE
"""
import json
import os
import sys

from paraview.simple import *  # noqa: F401,F403

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from brume_testing import (at_scene_camera, black_view, check, finish,  # noqa: E402
                           png_pixels, screenshot_like_actors)

plugin, directory, scene_file = sys.argv[1:4]
state = os.path.join(directory, "puff-series.pvsm")
check(os.path.exists(state), "the GUI saved its state")
LoadPlugin(plugin, ns=globals())
LoadState(state)
reader = FindSource("puff-series.json")
reconstruction = FindSource("BrumeRadianceReconstruction1")
check(reader is not None and reconstruction is not None, "the state's pipeline loads")
times = list(reader.TimestepValues) if reader is not None else []
check(times == [0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 3.5],
      "the scene's eight times reach the GUI: %s" % times)
animation = GetAnimationScene()
check(abs(animation.AnimationTime - 1.0) < 1e-9,
      "Next Frame twice: the animation at t = 1 (%g)" % animation.AnimationTime)

with open(scene_file) as f:
    camera = json.load(f)["camera"]
size = 96


def top_row(png):
    """The highest row (from the bottom) of the image's middle columns that
    is brighter than the black sky: the top of the ground or of the puff."""
    pixels = png_pixels(png).astype(float).sum(axis=2)[:, size // 4:3 * size // 4]
    lit = [i for i in range(size) if pixels[i].max() > 24]
    return max(lit) if lit else -1


if reader is not None and reconstruction is not None:
    FindSource("BrumeLightTracer1").NumberOfParticles = 100000
    view = black_view(size)
    Show(reconstruction, view)
    Render(view)  # the first render frames the scene; then the scene's camera
    at_scene_camera(view, camera)
    heights = []
    for t in (animation.AnimationTime, 0.0):
        animation.AnimationTime = t
        png = screenshot_like_actors(view, reconstruction, size, directory, "puff-t%g" % t,
                                     "at t = %g the view" % t)
        heights.append(top_row(png))
    print("the puff's top (rows from the bottom) at t = 1 and 0:", heights)
    check(heights[0] >= heights[1] + 4, "the puff stands higher at t = 1 than at t = 0: %s"
          % heights)
    Delete(view)  # before the interpreter's exit, as pvbatch expects
    del view
finish()
