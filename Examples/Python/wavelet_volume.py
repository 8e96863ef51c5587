#!/usr/bin/env python3
"""A VTK volume pipeline switched to Brume: VTK's Wavelet
(vtkRTAnalyticSource) and one vtkVolumeProperty, rendered by
vtkGPUVolumeRayCastMapper with its volumetric scattering and by Brume's
global illumination (vtkBrumeVolumePropertyMedium), side by side, under the
same point light and directional light, over a ground.

    PYTHONPATH=build/lib/python3.11/site-packages \\
        python3 Examples/Python/wavelet_volume.py -o wavelet.png
"""
import argparse
import time

from vtkmodules.vtkCommonCore import vtkDoubleArray
from vtkmodules.vtkCommonDataModel import (vtkCompositeDataSet, vtkPartitionedDataSet,
                                           vtkPartitionedDataSetCollection,
                                           vtkPiecewiseFunction)
from vtkmodules.vtkFiltersCore import vtkImageAppend, vtkTriangleFilter
from vtkmodules.vtkFiltersSources import vtkPlaneSource
from vtkmodules.vtkImagingCore import vtkRTAnalyticSource
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import (vtkActor, vtkColorTransferFunction, vtkLight,
                                         vtkPolyDataMapper, vtkRenderer, vtkRenderWindow,
                                         vtkVolume, vtkVolumeProperty, vtkWindowToImageFilter)
from vtkmodules.vtkRenderingVolume import vtkGPUVolumeRayCastMapper
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (the OpenGL factories)
import vtkmodules.vtkRenderingVolumeOpenGL2  # noqa: F401

import brume


def volume_property():
    """How the field looks, as a VTK user would write it."""
    opacity = vtkPiecewiseFunction()
    opacity.AddPoint(90, 0.0)
    opacity.AddPoint(170, 0.12)
    opacity.AddPoint(280, 0.6)
    colour = vtkColorTransferFunction()
    colour.AddRGBPoint(90, 0.2, 0.4, 0.9)
    colour.AddRGBPoint(280, 1.0, 0.8, 0.6)
    prop = vtkVolumeProperty()
    prop.SetScalarOpacity(opacity)
    prop.SetColor(colour)
    prop.SetScalarOpacityUnitDistance(1.0)
    prop.SetInterpolationTypeToLinear()
    prop.SetScatteringAnisotropy(0.3)
    prop.ShadeOn()
    return prop


def lights(physical):
    """A point light above one corner and a low sun (both vtkLights). Brume
    reads a light's Intensity x DiffuseColor as W/sr (positional) or W/m^2
    (directional); VTK's shading as a unitless factor."""
    point = vtkLight()
    point.SetLightTypeToSceneLight()
    point.SetPositional(True)
    point.SetConeAngle(180)
    point.SetPosition(14, 20, 18)
    point.SetFocalPoint(0, 0, 0)
    point.SetIntensity(1500.0 if physical else 0.7)
    point.SetDiffuseColor(1.0, 0.9, 0.8)
    sun = vtkLight()
    sun.SetLightTypeToSceneLight()
    sun.SetPositional(False)
    sun.SetPosition(-1, 2, 0.5)
    sun.SetFocalPoint(0, 0, 0)
    sun.SetIntensity(1.0 if physical else 0.5)
    sun.SetDiffuseColor(0.8, 0.9, 1.0)
    return [point, sun]


def ground():
    plane = vtkPlaneSource()
    plane.SetOrigin(-40, -11, 40)
    plane.SetPoint1(40, -11, 40)
    plane.SetPoint2(-40, -11, -40)
    triangles = vtkTriangleFilter()
    triangles.SetInputConnection(plane.GetOutputPort())
    triangles.Update()
    return triangles.GetOutput()


def set_camera(renderer):
    camera = renderer.GetActiveCamera()
    camera.SetPosition(0, 12, 52)
    camera.SetFocalPoint(0, -2, 0)
    camera.SetViewUp(0, 1, 0)
    camera.SetViewAngle(35)
    renderer.ResetCameraClippingRange()
    return camera


def window(size):
    renderer = vtkRenderer()
    win = vtkRenderWindow()
    win.SetOffScreenRendering(1)
    win.SetMultiSamples(0)
    win.SetSize(size, size)
    win.AddRenderer(renderer)
    return renderer, win


def render_vtk(wavelet, prop, size):
    """vtkGPUVolumeRayCastMapper with volumetric scattering (VTK >= 9.2)."""
    renderer, win = window(size)
    mapper = vtkGPUVolumeRayCastMapper()
    mapper.SetInputConnection(wavelet.GetOutputPort())
    mapper.SetVolumetricScatteringBlending(1.0)
    mapper.SetGlobalIlluminationReach(0.5)
    volume = vtkVolume()
    volume.SetMapper(mapper)
    volume.SetProperty(prop)
    renderer.AddVolume(volume)
    ground_mapper = vtkPolyDataMapper()
    ground_mapper.SetInputData(ground())
    actor = vtkActor()
    actor.SetMapper(ground_mapper)
    actor.GetProperty().SetColor(0.6, 0.6, 0.6)
    renderer.AddActor(actor)
    renderer.AutomaticLightCreationOff()
    for light in lights(physical=False):
        renderer.AddLight(light)
    set_camera(renderer)
    start = time.perf_counter()
    win.Render()
    seconds = time.perf_counter() - start
    renderer.GetActiveCamera().Azimuth(0.5)  # a next frame, after upload and compilation
    start = time.perf_counter()
    win.Render()
    render_vtk.next_frame = time.perf_counter() - start
    renderer.GetActiveCamera().Azimuth(-0.5)
    win.Render()
    grab = vtkWindowToImageFilter()
    grab.SetInput(win)
    grab.Update()
    return grab.GetOutput(), seconds


def render_brume(wavelet, prop, size, particles):
    """The same property and lights through Brume's three phases."""
    medium = brume.vtkBrumeVolumePropertyMedium()
    medium.SetInputConnection(wavelet.GetOutputPort())
    medium.SetVolumeProperty(prop)
    medium.SetAlbedo(0.9, 0.9, 0.9)
    medium.Update()

    scene = vtkPartitionedDataSetCollection()
    for index, (data, name) in enumerate([(ground(), "ground"), (medium.GetOutput(), "wavelet")]):
        pds = vtkPartitionedDataSet()
        pds.SetNumberOfPartitions(1)
        pds.SetPartition(0, data)
        scene.SetPartitionedDataSet(index, pds)
        scene.GetMetaData(index).Set(vtkCompositeDataSet.NAME(), name)
    reflectance = vtkDoubleArray()
    reflectance.SetName("BrumeReflectance")
    reflectance.SetNumberOfComponents(3)
    reflectance.InsertNextTuple((0.6, 0.6, 0.6))
    scene.GetPartitionedDataSet(0).GetPartition(0).GetFieldData().AddArray(reflectance)

    start = time.perf_counter()
    pipeline = brume.vtkBrumePipeline()
    pipeline.SetInputData(scene)
    pipeline.GetTracer().SetNumberOfParticles(particles)
    for light in lights(physical=True):
        pipeline.GetTracer().AddLight(light)
    pipeline.SetSize(size, size)
    pipeline.SetCamera(set_camera(vtkRenderer()))
    if not pipeline.Update():
        raise RuntimeError("brume: " + pipeline.GetFailedPhase() + " failed")
    # One image: what a rebuild would reuse is freed before the GPU's copy.
    pipeline.ReleaseBuildState()
    radiance = pipeline.RenderImage()
    seconds = time.perf_counter() - start
    return pipeline.ToneMap(radiance), radiance, seconds


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("-o", "--output", default="wavelet.png")
    parser.add_argument("--particles", type=int, default=1000000)
    parser.add_argument("--size", type=int, default=384)
    args = parser.parse_args()

    wavelet = vtkRTAnalyticSource()  # 21^3 points over [-10, 10]^3, scalars 37 ... 277
    wavelet.Update()
    prop = volume_property()
    vtk_image, vtk_seconds = render_vtk(wavelet, prop, args.size)
    brume_image, _, brume_seconds = render_brume(wavelet, prop, args.size, args.particles)
    side = vtkImageAppend()
    side.SetAppendAxis(0)
    side.AddInputData(vtk_image)
    side.AddInputData(brume_image)
    writer = vtkPNGWriter()
    writer.SetFileName(args.output)
    writer.SetInputConnection(side.GetOutputPort())
    writer.Write()
    print(f"vtkGPUVolumeRayCastMapper: {vtk_seconds:.3f} s (first frame), "
          f"{render_vtk.next_frame:.3f} s (next frame)")
    print(f"Brume ({args.particles} particles, tracing to first frame): {brume_seconds:.3f} s")
    print("wrote", args.output)


if __name__ == "__main__":
    main()
