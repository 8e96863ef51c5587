"""Checks what Brume.ParaView.GUIPreviewEdits logged (TestBrumeGUIPreviewEditsSetup.py):
in the GUI's own window, an opacity edit and then a colour edit made in the
Color Map Editor are each shown at once by a preview (nothing traced, the
frame changed), after which the GUI renders again by itself, traces the
particles and refines to the whole budget.

usage: python3 TestBrumeGUIPreviewEditsCheck.py LOG
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from brume_testing import check, finish  # noqa: E402

lines = open(sys.argv[1]).read().split("\n") if os.path.exists(sys.argv[1]) else []
print("the view's renders:\n" + "\n".join(lines))
check("script done" in lines, "the start script ran")
renders = []
for line in lines:
    if "=" in line:
        renders.append(dict((k, float(v)) for k, v in (item.split("=") for item in line.split())))


def edited(previews, what, changed, minimum_change):
    """Checks the render that previewed the edit bringing NumberOfPreviews
    to `previews`; `changed(before, at)` says whether the edit is the
    expected one. Returns the index after the edit's trace converged."""
    at = next((i for i, r in enumerate(renders) if r["NumberOfPreviews"] == previews), None)
    check(at is not None and at > 0, "the %s was previewed" % what)
    if at is None or at == 0:
        return len(renders)
    before, preview = renders[at - 1], renders[at]
    check(before["IsConverged"] == 1 and before["NumberOfPreviews"] == previews - 1,
          "the view had converged before the %s" % what)
    check(changed(before, preview), "the %s is the one the events made" % what)
    check(preview["NumberOfTraces"] == before["NumberOfTraces"]
          and preview["NumberOfSteps"] == before["NumberOfSteps"],
          "the %s's preview traced nothing" % what)
    check(preview["Width"] == before["Width"] and preview["Change"] >= minimum_change,
          "the %s's preview shows it (mean change %.2f grey levels, at least %.2f)"
          % (what, preview["Change"], minimum_change))
    check(preview["IsRefining"] == 1 and preview["IsConverged"] == 0,
          "after the %s's preview the view refines" % what)
    following = renders[at + 1] if at + 1 < len(renders) else {}
    check(following.get("NumberOfTraces") == preview["NumberOfTraces"] + 1,
          "the GUI rendered again by itself and traced the %s" % what)
    done = next((i for i in range(at + 1, len(renders)) if renders[i]["IsConverged"] == 1), None)
    check(done is not None and renders[done]["NumberOfPreviews"] == previews
          and renders[done]["IsRefining"] == 0,
          "the %s's trace refined to the whole budget" % what)
    print("%s: the preview took %.3f s to render, the first traced render %.3f s" %
          (what, preview["Seconds"], following.get("Seconds", -1)))
    return len(renders) if done is None else done + 1


edited(1, "opacity edit", lambda b, a: a["OpacityPoints"] == b["OpacityPoints"] + 1, 1.0)
edited(2, "colour edit", lambda b, a: a["ColourPoints"] == b["ColourPoints"]
       and a["OpacityPoints"] == b["OpacityPoints"], 0.5)
last = renders[-1] if renders else {}
check(last.get("IsConverged") == 1 and last.get("IsRefining") == 0
      and last.get("NumberOfPreviews") == 2,
      "the view ends converged, two edits previewed (%s)" % last)
finish()
