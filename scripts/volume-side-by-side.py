#!/usr/bin/env python3
"""Times VTK's vtkGPUVolumeRayCastMapper and Brume's render pass on the same
volume and property: VTK's Wavelet at POINTS^3 points (float scalars over the
same [-10, 10]^3 box whatever POINTS), Examples/Python/wavelet_volume.py's
vtkVolumeProperty and lights, over its ground, SIZE^2 pixels, one window
each: the ray caster with its volumetric scattering (VTK >= 9.2) and with
its plain compositing, and the pass. Prints a Markdown table of medians
over RUNS runs of each (each in its own process, taking turns): the first
frame (upload and shader compilation included; for Brume also tracing and
reconstruction), a frame of the same view, and a new view (a 2 degree
turn, the median of VIEWS), and for Brume the budget's end (progressive
frames until converged).

usage: PYTHONPATH=build/lib/python3.11/site-packages \\
           scripts/volume-side-by-side.py [--points 512] [--size 512]
           [--particles 2000000] [--runs 3] [--views 5]
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
RENDERERS = ("vtk-scattering", "vtk", "brume")


def measure(renderer, points, size, particles, turns):
    """One renderer's figures, in this process."""
    sys.path.insert(0, os.path.join(HERE, "..", "Examples", "Python"))
    from vtkmodules.vtkImagingCore import vtkRTAnalyticSource
    from vtkmodules.vtkRenderingCore import vtkActor, vtkPolyDataMapper, vtkVolume
    from vtkmodules.vtkRenderingVolume import vtkGPUVolumeRayCastMapper
    import vtkmodules.vtkRenderingOpenGL2  # noqa: F401
    import vtkmodules.vtkRenderingVolumeOpenGL2  # noqa: F401
    import wavelet_volume as example

    half = (points - 1) // 2
    wavelet = vtkRTAnalyticSource()
    wavelet.SetWholeExtent(-half, points - 1 - half, -half, points - 1 - half,
                           -half, points - 1 - half)
    wavelet.Update()
    image = wavelet.GetOutput()
    spacing = 20.0 / (points - 1)
    image.SetSpacing(spacing, spacing, spacing)
    image.SetOrigin(-half * spacing, -half * spacing, -half * spacing)

    ren, win = example.window(size)
    physical = renderer == "brume"
    prop = example.volume_property()
    mapper = vtkGPUVolumeRayCastMapper()  # for Brume, replaced by the pass's own
    if renderer == "vtk-scattering":
        mapper.SetVolumetricScatteringBlending(1.0)
        mapper.SetGlobalIlluminationReach(0.5)
    mapper.SetInputData(image)
    volume = vtkVolume()
    volume.SetMapper(mapper)
    volume.SetProperty(prop)
    ren.AddVolume(volume)
    ground_mapper = vtkPolyDataMapper()
    ground_mapper.SetInputData(example.ground())
    actor = vtkActor()
    actor.SetMapper(ground_mapper)
    actor.GetProperty().SetColor(0.6, 0.6, 0.6)
    ren.AddActor(actor)
    ren.AutomaticLightCreationOff()
    for light in example.lights(physical=physical):
        ren.AddLight(light)
    example.set_camera(ren)
    pass_ = None
    if renderer == "brume":
        import brume
        pass_ = brume.vtkBrumePass()
        pass_.SetNumberOfParticles(particles)
        ren.SetPass(pass_)

    def frame():
        start = time.perf_counter()
        win.Render()
        win.WaitForCompletion()
        return time.perf_counter() - start

    figures = {"first": frame()}
    if pass_ is not None:
        budget = figures["first"]
        for _ in range(64):
            if pass_.IsConverged():
                break
            budget += frame()
        figures["budget"] = budget
    figures["same"] = frame()
    views = []
    for _ in range(turns):
        ren.GetActiveCamera().Azimuth(2.0)
        views.append(frame())
    figures["view"] = statistics.median(views)
    return figures


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--points", type=int, default=512)
    parser.add_argument("--size", type=int, default=512)
    parser.add_argument("--particles", type=int, default=2000000)
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--views", type=int, default=5)
    parser.add_argument("--one", choices=RENDERERS, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.one:
        print(json.dumps(measure(args.one, args.points, args.size, args.particles, args.views)))
        return
    results = {renderer: [] for renderer in RENDERERS}
    for _ in range(args.runs):
        for renderer in RENDERERS:
            out = subprocess.run(
                [sys.executable, os.path.abspath(__file__), "--one", renderer, "--points",
                 str(args.points), "--size", str(args.size), "--particles",
                 str(args.particles), "--views", str(args.views)],
                check=True, capture_output=True, text=True).stdout
            results[renderer].append(json.loads(out.strip().splitlines()[-1]))

    def median(renderer, key):
        values = [r[key] for r in results[renderer] if key in r]
        return statistics.median(values) if values else None

    def cell(value):
        return "–" if value is None else f"{value:.3f} s"

    print(f"| renderer ({args.points}³ float Wavelet, {args.size}², medians of {args.runs}) "
          "| first frame | to the budget | same view again | new view (2° turn) |")
    print("|---|---:|---:|---:|---:|")
    for renderer, name in (("vtk-scattering", "volumetric scattering"), ("vtk", "compositing")):
        print(f"| `vtkGPUVolumeRayCastMapper`, {name} | {cell(median(renderer, 'first'))} | – "
              f"| {cell(median(renderer, 'same'))} | {cell(median(renderer, 'view'))} |")
    print(f"| `vtkBrumePass`, {args.particles:,} particles | {cell(median('brume', 'first'))} "
          f"| {cell(median('brume', 'budget'))} | {cell(median('brume', 'same'))} "
          f"| {cell(median('brume', 'view'))} |")


if __name__ == "__main__":
    main()
