"""The ParaView GUI (paraview --script=THIS --exit, under an X display):
load the plugin, show the default scene's reconstruction (the "Brume
Radiance" representation), save the view and compare it with a baseline.
ParaView's exit code does not carry a script's failure: the verdict goes
to BRUME_GUI_RESULT ("ok" or why not), which the test reads.

environment: BRUME_PLUGIN, BRUME_GUI_BASELINE, BRUME_GUI_OUTPUT (a folder),
BRUME_GUI_RESULT (a file), BRUME_TESTING_DIR (this folder)
"""
import os
import traceback

verdict = "the script did not finish"
try:
    import sys

    from paraview.simple import *  # noqa: F401,F403

    sys.path.insert(0, os.environ["BRUME_TESTING_DIR"])
    from brume_testing import black_view, frame_then_default_camera, image_error

    LoadPlugin(os.environ["BRUME_PLUGIN"], ns=globals())
    scene = BrumeDefaultScene()
    tracer = BrumeLightTracer(Input=scene, NumberOfParticles=200000, Seed=1)
    reconstruction = BrumeRadianceReconstruction(Scene=scene, Hits=tracer)
    view = black_view(None, GetActiveViewOrCreate("RenderView"))
    display = Show(reconstruction, view)
    frame_then_default_camera(view)
    shown = os.path.join(os.environ["BRUME_GUI_OUTPUT"], "TestBrumeGUI.png")
    SaveScreenshot(shown, view, ImageResolution=[300, 300])
    baseline = os.environ["BRUME_GUI_BASELINE"]
    if display.Representation != "Brume Radiance":
        verdict = "the representation is %s" % display.Representation
    elif not os.path.exists(baseline):
        verdict = "no baseline %s; the image is %s" % (baseline, shown)
    else:
        error = image_error(shown, baseline, threshold=16)
        verdict = "ok" if error <= 10 else "image error %g (limit 10): %s" % (error, shown)
except Exception:
    verdict = traceback.format_exc()
with open(os.environ["BRUME_GUI_RESULT"], "w") as result:
    result.write(verdict + "\n")
