"""The ParaView GUI's start (--script): a user's own pipeline in the stock
render view, with no Brume filter. VTK's Wavelet shown as a Volume coloured
by RTData (its colour map and a light opacity function), and a Contour of
it coloured by RTData; the camera moved off its default.
TestBrumeConvertView.xml then switches the view to Brume."""
from paraview.simple import *  # noqa: F401,F403

wavelet = Wavelet()
view = GetActiveViewOrCreate("RenderView")
volume = Show(wavelet, view)
contour = Contour(Input=wavelet, ContourBy=["POINTS", "RTData"], Isosurfaces=[200.0])
surface = Show(contour, view)
ColorBy(volume, ("POINTS", "RTData"))
volume.SetRepresentationType("Volume")
ColorBy(surface, ("POINTS", "RTData"))
GetColorTransferFunction("RTData").RescaleTransferFunction(37.35, 276.83)
GetOpacityTransferFunction("RTData").Points = [37.35, 0.0, 0.5, 0.0, 276.83, 0.3, 0.5, 0.0]
view.CameraPosition = [30, 20, 60]
view.CameraFocalPoint = [0, 0, 0]
view.CameraViewUp = [0, 1, 0]
Render(view)
