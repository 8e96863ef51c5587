"""What the plugin's test scripts share: named checks and the exit status
they give, a black render view looking at the default scene as `brume
render` does, the GUI's window given a Brume Render View of a Wavelet, vtkBrumeSceneActors' image of textures as a VTK user would
draw them, vtkImageDifference's error between two PNG files, and what a
saved state (.pvsm) holds."""
import os
import socket
import subprocess
import sys
import threading

from paraview.simple import CreateView, Render, SaveScreenshot, Show
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkImagingCore import vtkImageDifference
from vtkmodules.vtkIOImage import vtkPNGReader, vtkPNGWriter
from vtkmodules.vtkRenderingCore import vtkRenderer, vtkRenderWindow, vtkWindowToImageFilter

failures = []


def check(ok, what):
    """Prints one named check; a failed one makes finish() exit 1."""
    print(("ok: " if ok else "FAILED: ") + what)
    if not ok:
        failures.append(what)


def finish():
    """Exits 1 when a check failed; otherwise the script ends normally (a
    sys.exit(0) can leave pvbatch to tear down live proxies after OpenVDB's
    and TBB's own exit handlers, and abort)."""
    print("%d check(s) failed" % len(failures) if failures else "all checks passed")
    if failures:
        sys.exit(1)


def saved_proxies(state):
    """The proxies (XML elements) of a state file the GUI saved."""
    import xml.etree.ElementTree as ET
    return ET.parse(state).getroot().find("ServerManagerState").findall("Proxy")


def saved_values(proxy, name):
    """A saved proxy's property `name`: its elements' values, or the ids of
    the proxies it names (inputs, lookup tables)."""
    for prop in proxy.findall("Property"):
        if prop.get("name") == name:
            return [e.get("value") for e in prop if e.tag in ("Element", "Proxy")]
    return []


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


def gui_wavelet_view(particles):
    """In the GUI's start script: the window's view replaced, in its layout,
    by a Brume Render View of `particles` showing a Wavelet as a Volume
    coloured by RTData. Returns the view, the Wavelet and its display."""
    from paraview.simple import AssignViewToLayout, ColorBy, Delete, GetActiveView, GetLayout
    from paraview.simple import Wavelet

    stock = GetActiveView()
    layout = GetLayout(stock)
    Delete(stock)
    view = CreateView("BrumeRenderView")
    AssignViewToLayout(view=view, layout=layout, hint=0)
    view.BrumeParticles = particles
    wavelet = Wavelet()
    volume = Show(wavelet, view)
    volume.SetRepresentationType("Volume")
    ColorBy(volume, ("POINTS", "RTData"))
    return view, wavelet, volume


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


def png_pixels(png):
    """A PNG's RGB values, rows from the bottom, as a (height, width, 3) array."""
    reader = vtkPNGReader()
    reader.SetFileName(png)
    reader.Update()
    image = reader.GetOutput()
    width, height, _ = image.GetDimensions()
    return vtk_to_numpy(image.GetPointData().GetScalars()).reshape(height, width, -1)[:, :, :3]


def actors_image(view, size, textures, camera, png, interpolate=True, extra=None, exposure=1.0):
    """The textures drawn by vtkBrumeSceneActors alone, as a VTK user would,
    at `camera` and size x size pixels, with `view`'s anti-aliasing options
    (with `extra`, a translucent actor, through depth peeling as ParaView)."""
    import brume  # the same modules as the plugin
    renderer = vtkRenderer()
    renderer.SetBackground(0, 0, 0)
    if extra:
        renderer.AddActor(extra)
        renderer.SetUseDepthPeeling(True)
        renderer.SetUseDepthPeelingForVolumes(False)
    renderer.SetUseFXAA(bool(view.UseFXAA))  # as the view, with its options
    options = renderer.GetFXAAOptions()
    options.SetRelativeContrastThreshold(view.FXAARelativeContrastThreshold)
    options.SetHardContrastThreshold(view.FXAAHardContrastThreshold)
    options.SetSubpixelBlendLimit(view.FXAASubpixelBlendLimit)
    options.SetSubpixelContrastThreshold(view.FXAASubpixelContrastThreshold)
    options.SetUseHighQualityEndpoints(bool(view.FXAAUseHighQualityEndpoints))
    options.SetEndpointSearchIterations(view.FXAAEndpointSearchIterations)
    actors = brume.vtkBrumeSceneActors()
    actors.SetInputData(textures)
    actors.SetInterpolate(interpolate)
    actors.SetExposure(exposure)
    assert actors.AddToRenderer(renderer)
    window = vtkRenderWindow()
    window.SetMultiSamples(0)  # as ParaView's windows
    window.SetSize(size, size)
    window.AddRenderer(renderer)
    own = renderer.GetActiveCamera()
    own.SetPosition(camera.GetPosition())
    own.SetFocalPoint(camera.GetFocalPoint())
    own.SetViewUp(camera.GetViewUp())
    own.SetViewAngle(camera.GetViewAngle())
    own.SetClippingRange(camera.GetClippingRange())
    window.Render()
    capture = vtkWindowToImageFilter()
    capture.SetInput(window)
    capture.ReadFrontBufferOff()
    writer = vtkPNGWriter()
    writer.SetFileName(png)
    writer.SetInputConnection(capture.GetOutputPort())
    writer.Write()
    window.Finalize()


def at_scene_camera(view, camera_settings):
    """Puts a view at a scene file's camera (its "camera" block)."""
    view.CameraPosition = camera_settings["position"]
    view.CameraFocalPoint = camera_settings["focal_point"]
    view.CameraViewUp = camera_settings["view_up"]
    view.CameraViewAngle = camera_settings["view_angle"]


def screenshot_like_actors(view, reconstruction, size, output_dir, name, what="the render view"):
    """Renders the view, saves its screenshot (NAME.png) and
    vtkBrumeSceneActors' image of the reconstruction's textures
    (NAME-actors.png), and checks that they agree. Returns the screenshot."""
    Render(view)
    shown = os.path.join(output_dir, name + ".png")
    SaveScreenshot(shown, view, ImageResolution=[size, size])
    expected = os.path.join(output_dir, name + "-actors.png")
    actors_image(view, size, reconstruction.GetClientSideObject().GetOutput(),
                 view.GetActiveCamera(), expected)
    error = image_error(shown, expected)
    check(error <= 0.5, "%s shows what vtkBrumeSceneActors draws (error %g)" % (what, error))
    return shown


def shown_at_scene_camera(reconstruction, camera_settings, size, output_dir, name):
    """Shows a reconstruction with "Brume Radiance" in a black view at a
    scene file's camera, saves the screenshot (NAME.png) and
    vtkBrumeSceneActors' image of the same textures (NAME-actors.png), and
    checks that they agree. Returns the view, the display and the screenshot."""
    view = black_view(size)
    display = Show(reconstruction, view)
    check(display.Representation == "Brume Radiance",
          "Show() gives 'Brume Radiance' (got '%s')" % display.Representation)
    Render(view)  # the first render frames the scene; then the scene's camera
    at_scene_camera(view, camera_settings)
    shown = screenshot_like_actors(view, reconstruction, size, output_dir, name)
    return view, display, shown


def partitions_with(textures, array):
    """The partitions of a reconstruction's output whose field data hold `array`."""
    count = 0
    for i in range(textures.GetNumberOfPartitionedDataSets()):
        pds = textures.GetPartitionedDataSet(i)
        for k in range(pds.GetNumberOfPartitions()):
            count += 1 if pds.GetPartition(k).GetFieldData().GetArray(array) is not None else 0
    return count


def check_media_drawn(view, display, shown, size, output_dir, name, what):
    """Draws the view again without its media (NAME-bare.png) and checks
    that the media changed the screenshot `shown`."""
    display.ShowMedia = 0
    Render(view)
    bare = os.path.join(output_dir, name + "-bare.png")
    SaveScreenshot(bare, view, ImageResolution=[size, size])
    error = image_error(shown, bare)
    check(error > 10, "%s is drawn (error %g without the media)" % (what, error))


class PVServer:
    """A pvserver on this machine (loopback), started for a test, with its
    output kept (a full pipe would stop it) for the failure's message.
    With a launcher (for example `mpirun --oversubscribe -np 2`) it runs in
    parallel, its processes without a display (ParaView's probe of their
    rendering goes through the plugin's EGL; Xvfb refused one of several
    processes' windows now and then), unless `display` keeps it (a server
    that renders for its client needs X). PORT 0: a free one."""

    def __init__(self, pvserver, port=0, launcher=(), display=False):
        if port == 0:
            with socket.socket() as probe:
                probe.bind(("127.0.0.1", 0))
                port = probe.getsockname()[1]
        self.port = port
        command = [pvserver, "--server-port=%d" % port]
        environment = dict(os.environ)
        if launcher:
            # Line-buffered through the launcher, so that "Accepting
            # connection" arrives. The client is an MPI process of its own
            # (a singleton): the launcher must not see its variables.
            command = list(launcher) + ["stdbuf", "-oL"] + command
            environment = {k: v for k, v in environment.items()
                           if k.startswith("OMPI_ALLOW")
                           or not k.startswith(("OMPI_", "PMIX_", "OPAL_"))}
            if not display:
                environment.pop("DISPLAY", None)
        self.output = []
        self.process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                        text=True, env=environment)
        for line in self.process.stdout:
            if "Accepting connection" in line:
                break
        else:
            raise RuntimeError("pvserver did not start")
        threading.Thread(target=lambda: self.output.extend(self.process.stdout),
                         daemon=True).start()

    def url(self):
        # 127.0.0.1: a minimal root may not resolve "localhost".
        return "cs://127.0.0.1:%d" % self.port

    def kill(self):
        """No server left behind by a failure; its last output is shown."""
        self.process.kill()
        print("the server's output:\n" + "".join(self.output[-300:]))
