"""The ParaView GUI (paraview --script=THIS --exit, under an X display):
load the plugin, show the default scene's reconstruction (the "Brume
Radiance" representation), save the view and compare it with a baseline.
ParaView's exit code does not carry a script's failure: the verdict goes
to BRUME_GUI_RESULT ("ok" or why not), which the test reads.

environment: BRUME_PLUGIN, BRUME_GUI_BASELINE, BRUME_GUI_OUTPUT (a folder),
BRUME_GUI_RESULT (a file)
"""
import os
import traceback

verdict = "the script did not finish"
try:
    from paraview.simple import *  # noqa: F401,F403
    from vtkmodules.vtkImagingCore import vtkImageDifference
    from vtkmodules.vtkIOImage import vtkPNGReader

    LoadPlugin(os.environ["BRUME_PLUGIN"], ns=globals())
    scene = BrumeDefaultScene()
    tracer = BrumeLightTracer(Input=scene, NumberOfParticles=200000, Seed=1)
    reconstruction = BrumeRadianceReconstruction(Scene=scene, Hits=tracer)
    view = GetActiveViewOrCreate("RenderView")
    view.UseColorPaletteForBackground = 0
    view.Background = [0, 0, 0]
    view.OrientationAxesVisibility = 0
    display = Show(reconstruction, view)
    Render(view)  # the first render frames the scene
    view.CameraPosition = [0, 0, 4]
    view.CameraFocalPoint = [0, 0, 0]
    view.CameraViewUp = [0, 1, 0]
    view.CameraViewAngle = 40
    Render(view)
    shown = os.path.join(os.environ["BRUME_GUI_OUTPUT"], "TestBrumeGUI.png")
    SaveScreenshot(shown, view, ImageResolution=[300, 300])
    baseline = os.environ["BRUME_GUI_BASELINE"]
    if display.Representation != "Brume Radiance":
        verdict = "the representation is %s" % display.Representation
    elif not os.path.exists(baseline):
        verdict = "no baseline %s; the image is %s" % (baseline, shown)
    else:
        readers = []
        for name in (shown, baseline):
            reader = vtkPNGReader()
            reader.SetFileName(name)
            readers.append(reader)
        difference = vtkImageDifference()
        difference.SetInputConnection(readers[0].GetOutputPort())
        difference.SetImageConnection(readers[1].GetOutputPort())
        difference.SetThreshold(16)
        difference.AllowShiftOff()
        difference.AveragingOff()
        difference.Update()
        error = difference.GetThresholdedError()
        verdict = "ok" if error <= 10 else "image error %g (limit 10): %s" % (error, shown)
except Exception:
    verdict = traceback.format_exc()
with open(os.environ["BRUME_GUI_RESULT"], "w") as result:
    result.write(verdict + "\n")
