#!/usr/bin/env python3
"""A VTK program lit by Brume: a sphere and VTK's Wavelet volume over a
ground under one positional light, written as any VTK program is, drawn
once by VTK and once with Brume's render pass (the three lines marked
"Brume": import it, make the pass, set it on the renderer), side by side.

    PYTHONPATH=build/lib/python3.11/site-packages \\
        python3 Examples/Python/vtk_scene_pass.py -o vtk-scene-pass.png
"""
import argparse

from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
from vtkmodules.vtkFiltersCore import vtkImageAppend
from vtkmodules.vtkFiltersSources import vtkPlaneSource, vtkSphereSource
from vtkmodules.vtkImagingCore import vtkRTAnalyticSource
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import (vtkActor, vtkColorTransferFunction, vtkLight,
                                         vtkPolyDataMapper, vtkRenderer, vtkRenderWindow,
                                         vtkVolume, vtkVolumeProperty, vtkWindowToImageFilter)
from vtkmodules.vtkRenderingVolume import vtkGPUVolumeRayCastMapper
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (the OpenGL factories)
import vtkmodules.vtkRenderingVolumeOpenGL2  # noqa: F401

import brume  # Brume (also picks X, EGL or OSMesa render windows, as brume does)


def scene(size):
    """The VTK program: actors, a volume, a light, a camera."""
    renderer = vtkRenderer()
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetMultiSamples(0)
    window.SetSize(size, size)
    window.AddRenderer(renderer)

    ground = vtkPlaneSource()
    ground.SetOrigin(-4, -1, 4)
    ground.SetPoint1(4, -1, 4)
    ground.SetPoint2(-4, -1, -4)
    sphere = vtkSphereSource()
    sphere.SetCenter(1.3, -0.35, 0.3)
    sphere.SetRadius(0.65)
    sphere.SetThetaResolution(64)
    sphere.SetPhiResolution(48)
    for source, colour, specular in ((ground, (0.7, 0.7, 0.7), 0.0),
                                     (sphere, (0.9, 0.35, 0.2), 0.2)):
        mapper = vtkPolyDataMapper()
        mapper.SetInputConnection(source.GetOutputPort())
        actor = vtkActor()
        actor.SetMapper(mapper)
        actor.GetProperty().SetColor(*colour)
        actor.GetProperty().SetSpecular(specular)
        actor.GetProperty().SetSpecularPower(40)
        renderer.AddActor(actor)

    wavelet = vtkRTAnalyticSource()  # 21^3 points, scalars 37 ... 277
    opacity = vtkPiecewiseFunction()
    opacity.AddPoint(90, 0.0)
    opacity.AddPoint(170, 0.15)
    opacity.AddPoint(280, 0.7)
    colours = vtkColorTransferFunction()
    colours.AddRGBPoint(90, 0.4, 0.6, 1.0)
    colours.AddRGBPoint(280, 1.0, 0.85, 0.7)
    prop = vtkVolumeProperty()
    prop.SetScalarOpacity(opacity)
    prop.SetColor(colours)
    prop.SetScalarOpacityUnitDistance(1.0)
    prop.SetInterpolationTypeToLinear()
    mapper = vtkGPUVolumeRayCastMapper()
    mapper.SetInputConnection(wavelet.GetOutputPort())
    volume = vtkVolume()
    volume.SetMapper(mapper)
    volume.SetProperty(prop)
    volume.SetScale(0.08)
    volume.SetPosition(-1.0, -0.1, 0.0)
    renderer.AddVolume(volume)

    light = vtkLight()
    light.SetLightTypeToSceneLight()
    light.SetPositional(True)
    light.SetConeAngle(180)
    light.SetPosition(1.5, 4, 3)
    light.SetFocalPoint(0, 0, 0)
    light.SetIntensity(1.0)  # a factor of VTK's shading; the pass maps it (PhysicalLights)
    renderer.AddLight(light)

    camera = renderer.GetActiveCamera()
    camera.SetPosition(0, 2.2, 8)
    camera.SetFocalPoint(0, -0.3, 0)
    camera.SetViewAngle(35)
    renderer.ResetCameraClippingRange()
    return renderer, window


def grab(window):
    window.Render()
    image = vtkWindowToImageFilter()
    image.SetInput(window)
    image.ReadFrontBufferOff()
    image.Update()
    return image.GetOutput()


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("-o", "--output", default="vtk-scene-pass.png")
    parser.add_argument("--size", type=int, default=384)
    parser.add_argument("--particles", type=int, default=1000000)
    args = parser.parse_args()

    renderer, window = scene(args.size)
    vtk_image = grab(window)  # VTK's own rendering

    brume_pass = brume.vtkBrumePass()  # Brume
    renderer.SetPass(brume_pass)  # Brume
    brume_pass.SetNumberOfParticles(args.particles)
    window.Render()  # the first frame: a first progressive step
    while not brume_pass.IsConverged():  # each frame: 4 times the particles
        window.Render()
    brume_image = grab(window)
    print("Brume traced", brume_pass.GetNumberOfTraces(), "time(s), in",
          brume_pass.GetNumberOfReconstructions(), "progressive steps")

    side = vtkImageAppend()
    side.SetAppendAxis(0)
    side.AddInputData(vtk_image)
    side.AddInputData(brume_image)
    writer = vtkPNGWriter()
    writer.SetFileName(args.output)
    writer.SetInputConnection(side.GetOutputPort())
    writer.Write()
    print("wrote", args.output)
    return brume_image


if __name__ == "__main__":
    main()
