#!/usr/bin/env python3
"""A surface coloured by a scalar through a colour map, lit by Brume: a
terrain warped and coloured by its height beside a white ball, under one
positional light, written as any VTK program is, drawn once by VTK and
once with Brume's render pass (the lines marked "Brume"), side by side.
The colours are the terrain's reflectance: the light they bounce tints
the ball (colour bleeding).

    PYTHONPATH=build/lib/python3.11/site-packages \\
        python3 Examples/Python/vtk_scalar_colouring.py -o vtk-scalar-colouring.png
"""
import argparse

from vtkmodules.vtkFiltersCore import vtkElevationFilter, vtkImageAppend
from vtkmodules.vtkFiltersGeneral import vtkWarpScalar
from vtkmodules.vtkFiltersSources import vtkPlaneSource, vtkSphereSource
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import (vtkActor, vtkColorTransferFunction, vtkLight,
                                         vtkPolyDataMapper, vtkRenderer, vtkRenderWindow,
                                         vtkWindowToImageFilter)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (the OpenGL factories)

import brume  # Brume (also picks X, EGL or OSMesa render windows, as brume does)


def scene(size):
    """The VTK program: a coloured terrain, a ball, a light, a camera."""
    renderer = vtkRenderer()
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetMultiSamples(0)
    window.SetSize(size, size)
    window.AddRenderer(renderer)

    ground = vtkPlaneSource()
    ground.SetOrigin(-3, -1, 3)
    ground.SetPoint1(3, -1, 3)
    ground.SetPoint2(-3, -1, -3)
    ground.SetResolution(96, 96)
    height = vtkElevationFilter()  # a scalar from -x (0) to +x (1)
    height.SetInputConnection(ground.GetOutputPort())
    height.SetLowPoint(-3, 0, 0)
    height.SetHighPoint(3, 0, 0)
    colours = vtkColorTransferFunction()  # red, then yellow, then blue
    colours.AddRGBPoint(0.0, 0.85, 0.1, 0.05)
    colours.AddRGBPoint(0.5, 0.8, 0.75, 0.2)
    colours.AddRGBPoint(1.0, 0.05, 0.15, 0.85)
    terrain = vtkPolyDataMapper()
    terrain.SetInputConnection(height.GetOutputPort())
    terrain.SetLookupTable(colours)
    terrain.SetScalarRange(0.0, 1.0)
    actor = vtkActor()
    actor.SetMapper(terrain)
    renderer.AddActor(actor)

    ball = vtkSphereSource()
    ball.SetCenter(0, -0.2, 0)
    ball.SetRadius(0.8)
    ball.SetThetaResolution(96)
    ball.SetPhiResolution(48)
    mapper = vtkPolyDataMapper()
    mapper.SetInputConnection(ball.GetOutputPort())
    actor = vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().SetColor(0.9, 0.9, 0.9)
    renderer.AddActor(actor)

    light = vtkLight()
    light.SetLightTypeToSceneLight()
    light.SetPositional(True)
    light.SetConeAngle(180)
    light.SetPosition(0, 4, 1)
    light.SetFocalPoint(0, 0, 0)
    light.SetIntensity(0.6)
    renderer.AddLight(light)

    camera = renderer.GetActiveCamera()
    camera.SetPosition(0, 1.2, 6)
    camera.SetFocalPoint(0, -0.5, 0)
    camera.SetViewAngle(35)
    renderer.ResetCameraClippingRange()
    return renderer, window


def grab(window):
    image = vtkWindowToImageFilter()
    image.SetInput(window)
    image.ReadFrontBufferOff()
    image.Update()
    return image.GetOutput()


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("-o", "--output", default="vtk-scalar-colouring.png")
    parser.add_argument("--size", type=int, default=384)
    parser.add_argument("--particles", type=int, default=8000000)
    args = parser.parse_args()

    renderer, window = scene(args.size)
    window.Render()
    vtk_image = grab(window)  # VTK's own rendering

    brume_pass = brume.vtkBrumePass()  # Brume
    brume_pass.SetNumberOfParticles(args.particles)  # Brume
    renderer.SetPass(brume_pass)  # Brume
    window.Render()
    while not brume_pass.IsConverged():  # progressive: each frame, 4 times the particles
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


if __name__ == "__main__":
    main()
