"""Messages quote at most about 80 characters of an input: scene files with
a 1 MB unknown key, material type, surface name and unterminated string
(written by this test) each exit 1 with a short message that names the
file and the field, and leave no image.

usage: python3 TestBoundedMessages.py BRUME OUTPUT_DIR
"""
import copy
import json
import os
import subprocess
import sys

brume, output_dir = sys.argv[1:3]
big = "k" * 1000000
base = {"brume_scene": 1,
        "surfaces": [{"name": "ground", "quad": [[-1, 0, -1], [-1, 0, 1], [1, 0, 1], [1, 0, -1]]}],
        "lights": [{"type": "point", "position": [0, 1, 0], "intensity": [1, 1, 1]}]}
cases = {}
scene = copy.deepcopy(base)
scene[big] = 1
cases["key"] = (json.dumps(scene), "(top): unknown key '")
scene = copy.deepcopy(base)
scene["surfaces"][0]["material"] = {"type": big}
cases["type"] = (json.dumps(scene), "surfaces[0].material.type: expected")
scene = copy.deepcopy(base)
scene["surfaces"][0]["name"] = big
scene["surfaces"][0]["quad"] = [[0, 0, 0]] * 4
cases["name"] = (json.dumps(scene), "surfaces[0]: surface '")
cases["string"] = ('{"brume_scene": 1, "name": "' + big, "not valid JSON")
failures = []
for name, (text, field) in cases.items():
    path = os.path.join(output_dir, "bounded-%s.json" % name)
    png = os.path.join(output_dir, "bounded-%s.png" % name)
    with open(path, "w") as f:
        f.write(text)
    if os.path.exists(png):
        os.remove(png)
    run = subprocess.run([brume, "render", path, "-o", png], capture_output=True, text=True)
    longest = max((len(line) for line in run.stderr.splitlines()), default=0)
    ok = (run.returncode == 1 and longest <= 400 and (path + ": " + field) in run.stderr
          and not os.path.exists(png))
    print("%s %s: exit %d, %d bytes on stderr, longest line %d" % (
        "ok:" if ok else "FAILED:", name, run.returncode, len(run.stderr), longest))
    if not ok:
        print(run.stderr[:1000])
        failures.append(name)
sys.exit(1 if failures else 0)
