"""The ParaView GUI connected to a pvserver on this machine, with remote
rendering: a Brume Render View refines on the server by itself, as in the
built-in session. (pvpython drives it: it starts the server and the GUI,
and reads what the GUI logged.)

The GUI (paraview --server-url=... --script=SETUP --test-script=EVENTS
--exit, the plugin loaded on both sides through PV_PLUGIN_PATH) renders a
Wavelet volume and a contour once from its start script, then lets its
event loop run. Checks: every render was drawn on the server; the view
went on rendering after the script, each render adding particles, until
the whole budget was traced (one trace, two steps); the GUI printed no
error or warning. Needs an X display (skipped without one).

With a launcher (`mpirun --oversubscribe -np 2`) the server runs in
parallel, each process holding a piece of the data: the view traces its
whole budget at once there (a distributed scene has no progressive
steps), so the checks are that every render was drawn on the server, the
budget traced in one trace with no step, and nothing printed.

usage: pvpython TestBrumeGUIClientServer.py PVSERVER PARAVIEW PLUGIN_DIR OUTPUT_DIR [LAUNCHER...]
"""
import os
import subprocess
import sys

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
from brume_testing import PVServer, check, finish  # noqa: E402

pvserver, paraview, plugin_dir, output_dir = sys.argv[1:5]
launcher = sys.argv[5:]
if not os.environ.get("DISPLAY"):
    print("skipped: the ParaView GUI needs an X display")
    sys.exit(0)
os.environ["PV_PLUGIN_PATH"] = plugin_dir
log = os.path.join(output_dir, "TestBrumeGUIClientServer%s.log" % ("-parallel" if launcher else ""))
if os.path.exists(log):
    os.remove(log)
server = PVServer(pvserver, launcher=launcher, display=True)
try:
    gui = subprocess.run(
        [paraview, "--server-url=" + server.url(), "--dr",
         "--script=" + os.path.join(here, "TestBrumeGUIClientServerSetup.py"),
         "--test-script=" + os.path.join(here, "TestBrumeGUIClientServer.xml"), "--exit"],
        env=dict(os.environ, BRUME_GUI_LOG=log, BRUME_TESTING_DIR=here), capture_output=True,
        text=True, timeout=150)
    server.process.wait(timeout=30)  # it exits when its client does
except BaseException:
    server.kill()
    raise
output = gui.stdout + gui.stderr
check(gui.returncode == 0, "the GUI played its events (exit code %d)" % gui.returncode)
# (Named, not quoted: the retrying wrapper reads an error in a quoted one.)
for forbidden, what in (("ERR|", "error"), ("WARN|", "warning"), ("Warning:", "VTK warning")):
    check(forbidden not in output, "the GUI printed no %s" % what)
lines = open(log).read().split("\n") if os.path.exists(log) else []
print("the view's renders, as the client reported them:\n" + "\n".join(lines))
check("script done" in lines, "the start script ran")
done = lines.index("script done") if "script done" in lines else len(lines)


def parsed(part):
    return [dict((k, int(v)) for k, v in (item.split("=") for item in line.split()))
            for line in part if "=" in line]


by_script, by_gui = parsed(lines[:done]), parsed(lines[done + 1:])
renders = by_script + by_gui
check(renders and all(r["LastRenderOnServer"] == 1 for r in renders),
      "every render was drawn on the server")
last = renders[-1] if renders else {}
if launcher:
    check(last.get("NumberOfTraces") == 1 and last.get("NumberOfSteps") == 0
          and last.get("IsConverged") == 1 and last.get("IsRefining") == 0,
          "the view traced its whole budget at once (%s)" % last)
else:
    steps_by_script = max([0] + [r["NumberOfSteps"] for r in by_script])
    check(any(r["NumberOfSteps"] > steps_by_script for r in by_gui),
          "the GUI rendered again by itself, adding particles")
    check(last.get("NumberOfTraces") == 1 and last.get("NumberOfSteps") == 2
          and last.get("IsConverged") == 1 and last.get("IsRefining") == 0,
          "the view ends with its whole budget traced, in one trace and two steps (%s)" % last)
if not renders or last.get("IsConverged") != 1:
    print("the GUI's output:\n" + output[-5000:])
    print("the server's output:\n" + "".join(server.output[-300:]))
finish()
