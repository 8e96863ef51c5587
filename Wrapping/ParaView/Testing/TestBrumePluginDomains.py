"""pvpython: properties outside their domains give a clear error, no crash.
(ctest checks that each message appears: Testing/CheckOutput.cmake.)

usage: pvpython TestBrumePluginDomains.py [PLUGIN]   (or the plugin from PV_PLUGIN_PATH)
"""
import sys

from paraview.simple import *  # noqa: F401,F403

if len(sys.argv) > 1:
    LoadPlugin(sys.argv[1], ns=globals())

scene = BrumeDefaultScene()
cases = []
tracer = BrumeLightTracer(Input=scene)
tracer.NumberOfParticles = -5
tracer.UpdatePipeline()
cases.append(("NumberOfParticles", "NumberOfParticles must be in"))

good = BrumeLightTracer(Input=scene)
good.NumberOfParticles = 2000
for name, value, expected in (("RadiosityThreshold", 0.0, "RadiosityThreshold must be positive"),
                              ("MediumResolution", 100000, "MediumResolution in"),
                              ("HistogramRefinement", 99, "HistogramRefinement must be in")):
    reconstruction = BrumeRadianceReconstruction(Scene=scene, Hits=good)
    setattr(reconstruction, name, value)
    reconstruction.UpdatePipeline()
    cases.append((name, expected))

reference = BrumeReferencePathTracer(Input=scene)
reference.SamplesPerPixel = 0
reference.UpdatePipeline()
cases.append(("SamplesPerPixel", "SamplesPerPixel must be in"))

# The messages go to ParaView's log (stderr); ctest checks them
# (Testing/CheckOutput.cmake). Each failed filter produced no data.
for proxy in (tracer, reference):
    assert proxy.GetDataInformation().DataInformation.GetNumberOfPoints() == 0
print("expected messages:", "; ".join(expected for _, expected in cases))
