"""Bad input costs little: every malformed scene of Testing/Data/BadScenes
(cases.txt), the 2 GiB files that once cost time and memory before their
error (sparse, made here), a scene of a million lights and a .vti whose
image VTK would allocate at 27 TB each end in exit 1 with one message
line, leave no output, and peak within 1 GB of memory (each process's own
peak, from os.wait4). Their times are printed (the slowest with its case);
a case over 60 s fails as a hang, not as a benchmark.

usage: python3 TestBadInputBounds.py BRUME BAD_SCENE_DIR OUTPUT_DIR
"""
import json
import os
import subprocess
import sys
import time

brume, bad_dir, output_dir = sys.argv[1:4]
work = os.path.join(output_dir, "bad-input-bounds")
os.makedirs(work, exist_ok=True)
failures = []
LIMIT_KB = 1024 * 1024


def run_measured(name, scene):
    # Reaped by os.wait4, for the process's own peak memory.
    png = os.path.join(work, name + ".png")
    if os.path.exists(png):
        os.remove(png)
    start = time.monotonic()
    err_path = os.path.join(work, name + ".err")
    with open(err_path, "w") as err:
        process = subprocess.Popen([brume, "render", scene, "-o", png, "--particles", "2000",
                                    "--size", "16x16"], stdout=subprocess.DEVNULL, stderr=err)
        deadline = start + 60
        while True:
            waited, status, usage = os.wait4(process.pid, os.WNOHANG)
            if waited:
                break
            if time.monotonic() > deadline:
                process.kill()
                os.wait4(process.pid, 0)
                failures.append(name + ": over 60 s (a hang)")
                return None, None
            time.sleep(0.005)
        process.returncode = os.waitstatus_to_exitcode(status)
    seconds = time.monotonic() - start
    with open(err_path) as f:
        stderr = f.read()
    lines = [line for line in stderr.splitlines() if line.strip()]
    # One line naming file and field, then brume's "cannot load the scene".
    ok = process.returncode == 1 and not os.path.exists(png) and 1 <= len(lines) <= 2
    if not ok:
        failures.append("%s: exit %s, %d stderr line(s), output %s: %s"
                        % (name, process.returncode, len(lines),
                           "left" if os.path.exists(png) else "none", stderr[:300]))
    if usage.ru_maxrss > LIMIT_KB:
        failures.append("%s: peak memory %.0f MB, over 1 GB" % (name, usage.ru_maxrss / 1024.0))
    return seconds, usage.ru_maxrss


cases = []
with open(os.path.join(bad_dir, "cases.txt")) as f:
    for line in f:
        if "|" in line:
            cases.append((line.split("|")[0], os.path.join(bad_dir, line.split("|")[0] + ".json")))

# The files whose size alone once cost seconds and gigabytes (sparse).
for mesh in ("zeros.obj", "zeros.ply", "zeros.stl"):
    path = os.path.join(work, mesh)
    with open(path, "wb") as f:
        f.truncate(2 ** 31)
    scene = os.path.join(work, mesh + ".json")
    with open(scene, "w") as f:
        json.dump({"brume_scene": 1,
                   "surfaces": [{"name": "s", "file": mesh,
                                 "material": {"reflectance": [0.5, 0.5, 0.5]}}],
                   "lights": [{"type": "point", "position": [0, 2, 0],
                               "intensity": [1, 1, 1]}]}, f)
    cases.append(("2 GiB " + mesh, scene))

# A million lights: refused as the file is read, at the 65,536th, naming 'lights'.
scene = os.path.join(work, "million-lights.json")
with open(scene, "w") as f:
    f.write('{"brume_scene": 1, "surfaces": [{"name": "floor", "quad": [[-1, 0, -1], [-1, 0, 1], '
            '[1, 0, 1], [1, 0, -1]], "material": {"reflectance": [0.5, 0.5, 0.5]}}], "lights": [')
    f.write(", ".join('{"type": "point", "position": [0, 1, 0], "intensity": [1, 1, 1]}'
                      for _ in range(10 ** 6)))
    f.write("]}\n")
cases.append(("a million lights", scene))

slowest = (0.0, "")
largest = (0, "")
for name, scene in cases:
    seconds, peak = run_measured(name.replace(" ", "-").replace("/", "-"), scene)
    if seconds is None:
        continue
    slowest = max(slowest, (seconds, name))
    largest = max(largest, (peak, name))
    if seconds > 5.0:
        print("note: %s took %.2f s" % (name, seconds))

print("%d cases; slowest %.2f s (%s); largest peak %.0f MB (%s)"
      % (len(cases), slowest[0], slowest[1], largest[0] / 1024.0, largest[1]))
for failure in failures:
    print("FAILED: " + failure)
print("%d check(s) failed" % len(failures) if failures else "all checks passed")
sys.exit(1 if failures else 0)
