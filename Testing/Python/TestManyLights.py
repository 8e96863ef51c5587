"""Thousands of small lights (street lamps, instrument LEDs): a ground under
5,000 and under 20,000 point lights renders, exit 0, within 1 GB of peak
memory. The direct light's grid is coarsened so that texels x lights stay
within 2^23; under 20,000 lights the grid would be too coarse to be worth
computing, and the particles carry the direct light (a warning says so).
A thousand objects share one budget of direct-light texels. Above 65,535
objects and lights together, the file is refused at parse time, naming the
lights. The scenes are written by this test, not
committed.

usage: python3 TestManyLights.py BRUME OUTPUT_DIR
"""
import json
import os
import random
import resource
import subprocess
import sys

brume, output_dir = sys.argv[1:3]
failures = []


def check(ok, what):
    print(("ok: " if ok else "FAILED: ") + what)
    if not ok:
        failures.append(what)


def scene(lights):
    rng = random.Random(lights)
    return {
        "brume_scene": 1,
        "name": "%d lamps over a ground" % lights,
        "camera": {"position": [0, 3, 8], "focal_point": [0, 0, 0], "view_up": [0, 1, 0],
                   "view_angle": 40},
        "surfaces": [{"name": "ground", "quad": [[-4, 0, -4], [-4, 0, 4], [4, 0, 4], [4, 0, -4]],
                      "material": {"reflectance": [0.6, 0.6, 0.6]}}],
        "lights": [{"type": "point",
                    "position": [rng.uniform(-4, 4), 0.5, rng.uniform(-4, 4)],
                    "intensity": [0.01, 0.01, 0.01]} for _ in range(lights)],
    }


for lights in (5000, 20000):
    path = os.path.join(output_dir, "many-lights-%d.json" % lights)
    png = os.path.join(output_dir, "many-lights-%d.png" % lights)
    with open(path, "w") as f:
        json.dump(scene(lights), f)
    if os.path.exists(png):
        os.remove(png)
    before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    run = subprocess.run([brume, "render", path, "--particles", "200000", "--size", "128x128",
                          "-o", png], capture_output=True, text=True)
    peak_kb = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    print("%d lights: exit %d, peak memory %.0f MB (children's maximum so far: %d KB before)"
          % (lights, run.returncode, peak_kb / 1024.0, before))
    check(run.returncode == 0 and os.path.exists(png),
          "%d lights render (stderr: %s)" % (lights, run.stderr.strip()[:300]))
    check(peak_kb <= 1024 * 1024, "%d lights within 1 GB (%.0f MB)" % (lights, peak_kb / 1024.0))
    if lights == 20000:
        check("estimated from the particles" in run.stderr,
              "under 20,000 lights the particles carry the direct light, and a warning says so")

# Many objects: 1,000 small tiles over the ground. Each planar object's
# direct-light grid would hold 256^2 texels (65.5 million in all, 5 GB with
# their arrivals); the scene's take one texel size, the finest within 2^23
# texels x lights, a warning says so, and the run stays within 1 GB. The
# ground (8 m) keeps its own 256^2 texels: a 5 cm tile needs fewer of a size.
tiles = scene(1)
rng = random.Random(7)
for k in range(1000):
    x, z = rng.uniform(-4, 4), rng.uniform(-4, 4)
    tiles["surfaces"].append({"name": "tile %d" % k,
                              "quad": [[x, 0.01, z], [x, 0.01, z + 0.05], [x + 0.05, 0.01, z + 0.05],
                                       [x + 0.05, 0.01, z]],
                              "material": {"reflectance": [0.8, 0.2, 0.2]}})
path = os.path.join(output_dir, "many-objects.json")
png = os.path.join(output_dir, "many-objects.png")
with open(path, "w") as f:
    json.dump(tiles, f)
if os.path.exists(png):
    os.remove(png)
run = subprocess.run([brume, "render", path, "--particles", "200000", "--size", "128x128",
                      "--timings", "-o", png], capture_output=True, text=True)
peak_kb = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
check(run.returncode == 0 and os.path.exists(png),
      "1,001 objects render (stderr: %s)" % run.stderr.strip()[:300])
check("grids are coarsened to one texel size for the whole scene" in run.stderr,
      "the scene's direct-light grids are coarsened, and a warning says so")
ground = [line for line in run.stdout.splitlines() if line.split()[:1] == ["ground"]]
check(len(ground) == 1 and "256 x   256" in ground[0],
      "the ground keeps its 256^2 texels (%s)" % (ground[0].strip() if ground else "no row"))
check(run.stdout.count("\n  tile ") <= 31 and "more textures" in run.stdout,
      "--timings lists 32 textures and sums the rest in a line")
check(peak_kb <= 1024 * 1024, "1,001 objects within 1 GB (%.0f MB, the children's peak so far)"
      % (peak_kb / 1024.0))

# At the limit: a floor and 65,534 lights render (the particles carry the
# direct light).
path = os.path.join(output_dir, "many-lights-65534.json")
png = os.path.join(output_dir, "many-lights-65534.png")
with open(path, "w") as f:
    json.dump(scene(65534), f)
run = subprocess.run([brume, "render", path, "--particles", "2000", "--size", "16x16", "-o", png],
                     capture_output=True, text=True)
check(run.returncode == 0 and os.path.exists(png),
      "65,535 objects and lights, the most a scene holds, render (stderr: %s)"
      % run.stderr.strip()[:300])

# Above the limit of 65,535 objects and lights together: refused while the
# file is read, at the 65,536th, naming the array that overflows, before
# its document is built or a light is made.
path = os.path.join(output_dir, "many-lights-70000.json")
png = os.path.join(output_dir, "many-lights-70000.png")
with open(path, "w") as f:
    json.dump(scene(70000), f)
run = subprocess.run([brume, "render", path, "-o", png], capture_output=True, text=True)
check(run.returncode == 1 and not os.path.exists(png)
      and "many-lights-70000.json: lights: the scene has 65536 objects and lights so far: "
          "a scene holds at most 65,535 together" in run.stderr,
      "70,000 lights are refused at parse time, naming 'lights' (stderr: %s)"
      % run.stderr.strip()[:300])
sys.exit(1 if failures else 0)
