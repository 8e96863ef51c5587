"""What the plugin's test scripts share: a black render view looking at the
default scene as `brume render` does, and vtkImageDifference's error
between two PNG files."""
from paraview.simple import CreateView, Render
from vtkmodules.vtkImagingCore import vtkImageDifference
from vtkmodules.vtkIOImage import vtkPNGReader


def default_camera(view):
    """The default scene's camera: from (0, 0, 4), 40 degrees."""
    view.CameraPosition = [0, 0, 4]
    view.CameraFocalPoint = [0, 0, 0]
    view.CameraViewUp = [0, 1, 0]
    view.CameraViewAngle = 40


def black_view(size, view=None):
    """A render view of size x size pixels (or `view`), black, no axes."""
    view = view or CreateView("RenderView")
    if size:
        view.ViewSize = [size, size]
    view.UseColorPaletteForBackground = 0
    view.Background = [0, 0, 0]
    view.OrientationAxesVisibility = 0
    return view


def frame_then_default_camera(view):
    """paraview.simple's first render frames the scene: render once, then
    set the default camera and render again."""
    Render(view)
    default_camera(view)
    Render(view)


def image_error(test_png, reference_png, threshold=0):
    """vtkImageDifference's thresholded error (0: equal images)."""
    readers = []
    for name in (test_png, reference_png):
        reader = vtkPNGReader()
        reader.SetFileName(name)
        readers.append(reader)
    difference = vtkImageDifference()
    difference.SetInputConnection(readers[0].GetOutputPort())
    difference.SetImageConnection(readers[1].GetOutputPort())
    difference.SetThreshold(threshold)
    difference.AllowShiftOff()
    difference.AveragingOff()
    difference.Update()
    return difference.GetThresholdedError()
