#!/usr/bin/env bash
# Regenerates the figure tables of the documentation (Documentation/*.md)
# from the files Brume's own commands write, so that no figure in those
# tables is typed by hand. A page marks each table with
#   <!-- figures:NAME begin -->  ...  <!-- figures:NAME end -->
# and this script replaces what lies between with a Markdown table built from
#   NAME = bench          Documentation/figures/bench.json (brume bench --json)
#   NAME = chart-SCENE    Data/doc/chart-SCENE.csv         (brume chart --csv)
#   NAME = sweep-SCENE    Data/doc/sweep-SCENE.csv         (brume chart --sweep --csv),
#                         with Data/doc/sweep-SCENE-PARAMETER-Nspp.csv, when
#                         present, as a column against N-spp references
# followed by the commit and the machine the figures were measured on, which
# the script keeps beside them in Documentation/figures/*.meta: recorded when
# a bench JSON is taken (--run, --bench) and when a CSV's content changes
# (this machine, and the CSV's commit, or HEAD when it is not committed).
#
# Usage: scripts/docs.sh [--run | --bench FILE] [--check]
#   (none)        refill the tables from the stored JSON and the CSVs
#   --run         run build/bin/brume bench --json first (minutes; $BRUME
#                 names another brume), keep its JSON, then refill
#   --bench FILE  keep FILE (brume bench --json, measured on this machine at
#                 this commit) as the stored JSON, then refill
#   --check       change nothing; exit 1 if refilling would change a page or
#                 record a new provenance (a test can run this)
# Needs python3 (standard library only) and git.
set -euo pipefail
caller="$PWD"
cd "$(dirname "$0")/.."

usage() {
  sed -n '/^# Usage:/,/^# Needs/p' "$0" | sed 's/^# \{0,1\}//'
}

mode="write"
bench=""
run=0
while [ $# -gt 0 ]; do
  case "$1" in
    --check) mode=check ;;
    --run) run=1 ;;
    --bench)
      [ $# -ge 2 ] || { echo "docs.sh: --bench needs a file" >&2; exit 2; }
      bench="$2"
      shift
      ;;
    --bench=*) bench="${1#--bench=}" ;;
    -h | --help) usage; exit 0 ;;
    *) echo "docs.sh: unknown option $1" >&2; usage >&2; exit 2 ;;
  esac
  shift
done
if [ "$mode" = check ] && { [ "$run" = 1 ] || [ -n "$bench" ]; }; then
  echo "docs.sh: --check takes no new figures (--run, --bench)" >&2
  exit 2
fi
if [ "$run" = 1 ] && [ -n "$bench" ]; then
  echo "docs.sh: --run or --bench FILE, not both" >&2
  exit 2
fi

figures=Documentation/figures
mkdir -p "$figures"
scratch=""
trap '[ -z "$scratch" ] || rm -f "$scratch"' EXIT

if [ "$run" = 1 ]; then
  brume="${BRUME:-build/bin/brume}"
  case "$brume" in /* | build/bin/brume) ;; *) brume="$caller/$brume" ;; esac
  if [ ! -x "$brume" ]; then
    echo "docs.sh: no $brume: build first (scripts/build.sh)" >&2
    exit 1
  fi
  scratch="$(mktemp --suffix=.json)"
  # A whole command that fails makes brume bench exit 1 but still write the
  # other figures: those are kept, and the failure said.
  if ! "$brume" bench --json "$scratch"; then
    echo "docs.sh: brume bench exited with an error (see above); keeping the figures it wrote" >&2
  fi
  bench="$scratch"
fi

new_bench=0
if [ -n "$bench" ]; then
  case "$bench" in /*) ;; *) bench="$caller/$bench" ;; esac
  if [ ! -s "$bench" ]; then
    echo "docs.sh: no bench JSON in $bench" >&2
    exit 1
  fi
  /usr/bin/python3 -c 'import json, sys; d = json.load(open(sys.argv[1])); assert isinstance(d.get("figures"), list)' "$bench" ||
    { echo "docs.sh: $bench is not brume bench --json output" >&2; exit 1; }
  # The commit the figures were measured at: the tree as it stands before
  # the copy below changes it.
  BENCH_COMMIT="$(git rev-parse --short HEAD 2>/dev/null || echo unknown)"
  if [ -n "$(git status --porcelain --untracked-files=no 2>/dev/null)" ]; then
    BENCH_COMMIT="$BENCH_COMMIT with uncommitted changes"
  fi
  export BENCH_COMMIT
  cp "$bench" "$figures/bench.json"
  new_bench=1
fi

/usr/bin/python3 - "$mode" "$new_bench" <<'PYTHON'
"""The tables: JSON and CSV to Markdown, between the pages' markers."""
import csv
import datetime
import glob
import hashlib
import json
import os
import re
import subprocess
import sys

MODE, NEW_BENCH = sys.argv[1], sys.argv[2] == "1"
FIGURES = "Documentation/figures"
MARKER = re.compile(r"^(<!-- figures:([\w.-]+) begin -->\n)(.*?)^(<!-- figures:\2 end -->)$", re.S | re.M)
ANY_MARKER = re.compile(r"^<!-- figures:[\w.-]+ (?:begin|end) -->$", re.M)
PLACEHOLDER = "*No bench figures stored yet: run `scripts/docs.sh --run` to fill (after building).*\n"
stale = []


def git(*args):
    try:
        return subprocess.run(["git", *args], check=True, capture_output=True, text=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return ""


def this_machine():
    cpu = ""
    try:
        with open("/proc/cpuinfo") as info:
            for line in info:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    cpus = len(os.sched_getaffinity(0))
    return "%s, %d CPUs%s" % (os.uname().machine, cpus, " (%s)" % cpu if cpu else "")


def head_commit():
    commit = git("rev-parse", "--short", "HEAD") or "unknown"
    if git("status", "--porcelain", "--untracked-files=no"):
        commit += " with uncommitted changes"
    return commit


def read_meta(path):
    meta = {}
    if os.path.exists(path):
        with open(path, encoding="utf-8") as f:
            for line in f:
                if "=" in line and not line.startswith("#"):
                    key, value = line.rstrip("\n").split("=", 1)
                    meta[key.strip()] = value.strip()
    return meta


def write_meta(path, meta, comment):
    with open(path, "w", encoding="utf-8") as f:
        f.write("# %s\n" % comment)
        for key, value in meta.items():
            f.write("%s=%s\n" % (key, value))


def csv_provenance(path):
    """The stored provenance of a CSV, recorded anew when its content changed."""
    stem = os.path.splitext(os.path.basename(path))[0]
    meta_path = os.path.join(FIGURES, stem + ".meta")
    meta = read_meta(meta_path)
    with open(path, "rb") as f:
        digest = hashlib.sha256(f.read()).hexdigest()
    if meta.get("sha256") == digest:
        return meta
    committed = git("ls-files", "--error-unmatch", path) and not git("status", "--porcelain", "--", path)
    logged = git("log", "-1", "--format=%h %ad", "--date=short", "--", path).split() if committed else []
    if len(logged) == 2:
        commit, date = logged
    else:
        commit, date = head_commit() + " (the CSV not committed)", datetime.date.today().isoformat()
    meta = {"source": path, "sha256": digest, "commit": commit, "date": date, "machine": this_machine()}
    if MODE == "check":
        stale.append("%s: %s changed since its provenance was recorded" % (meta_path, path))
    else:
        write_meta(meta_path, meta, "Where %s was measured (scripts/docs.sh; edit machine= if it was elsewhere)" % path)
        print("docs.sh: recorded %s as measured at %s on %s" % (path, commit, meta["machine"]))
    return meta


def provenance_line(command, path, meta):
    return "Measured by `%s` (`%s`) at commit `%s` (%s) on %s." % (
        command, path, meta.get("commit", "unknown"), meta.get("date", "date unknown"),
        meta.get("machine", "an unrecorded machine"))


def table(header, align, rows):
    out = ["| " + " | ".join(header) + " |", "|" + "|".join(align) + "|"]
    out += ["| " + " | ".join(row) + " |" for row in rows]
    return "\n".join(out) + "\n"


SUPERSCRIPT = str.maketrans("0123456789-", "⁰¹²³⁴⁵⁶⁷⁸⁹⁻")


def count(value):
    """1000000 as 10⁶, 2000000 as 2·10⁶, 300 as 300."""
    v = float(value)
    if v < 10000 or v != int(v):
        return "%g" % v
    exponent = len(str(int(v))) - 1
    mantissa = v / 10 ** exponent
    if mantissa != int(mantissa):
        return "{:,}".format(int(v))
    power = "10" + str(exponent).translate(SUPERSCRIPT)
    return power if mantissa == 1 else "%d·%s" % (mantissa, power)


def significant(value, digits=3):
    text = "%#.*g" % (digits, value)
    if "e" in text:
        return "%g" % value
    return text.rstrip(".")


def percent(value, decimals=1):
    return "%.*f %%" % (decimals, 100.0 * float(value))


def number(text):
    """A sweep's value: -0.990000 as −0.99, 1000000 as 10⁶, words as they are."""
    try:
        v = float(text)
    except ValueError:
        return text
    if v == int(v) and abs(v) >= 10000:
        return count(v)
    return ("%g" % v).replace("-", "−")


# ------------------------------------------------------------------ bench
def bench_block():
    path = os.path.join(FIGURES, "bench.json")
    meta_path = os.path.join(FIGURES, "bench.meta")
    if NEW_BENCH:
        meta = {"date": datetime.date.today().isoformat(),
                "commit": os.environ.get("BENCH_COMMIT") or head_commit(), "machine": this_machine(),
                "window": os.environ.get("BRUME_RENDER_WINDOW", "auto") + (
                    " (DISPLAY set)" if os.environ.get("DISPLAY") else " (no DISPLAY)")}
        write_meta(meta_path, meta, "Where Documentation/figures/bench.json was measured (scripts/docs.sh)")
    if not os.path.exists(path):
        return PLACEHOLDER
    with open(path, encoding="utf-8") as f:
        doc = json.load(f)
    meta = read_meta(meta_path)
    rows = []
    for fig in doc["figures"]:
        value = float(fig["value"])
        shown = "{:,.0f}".format(value) if abs(value) >= 1e5 else significant(value, 4)
        target = fig.get("target", "").replace("<=", "≤").replace(">=", "≥")
        verdict = {True: "met", False: "**missed**"}.get(fig.get("met"), "")
        rows.append(["`%s`" % fig["key"], shown, fig.get("unit", ""), target, verdict, fig.get("note", "")])
    out = table(["figure", "value", "unit", "target", "verdict", "what"],
                ["---", "---:", "---", "---", "---", "---"], rows)
    particles = doc.get("particles")
    run = "%s particles, seed %s, %s threads (vtkSMPTools %s)" % (
        count(particles) if particles is not None else "?", doc.get("seed", "?"),
        doc.get("threads", "?"), doc.get("smp_backend", "?"))
    line = "Measured by `brume bench --json` at commit `%s` (%s) on %s: %s, window %s." % (
        meta.get("commit", "unknown"), meta.get("date", "date unknown"),
        meta.get("machine", "an unrecorded machine"), run, meta.get("window", "unrecorded"))
    if any("target" in f for f in doc["figures"]) and not any("met" in f for f in doc["figures"]):
        line += " The targets hold at the default particle count only: no verdicts at this one."
    return out + "\n" + line + "\n"


# ------------------------------------------------------------------ charts
METHODS = {
    "pipeline": "pipeline, full",
    "pipeline-new-view": "pipeline, new view",
    "pipeline-sh": "pipeline, SH media, full",
    "pipeline-sh-new-view": "pipeline, SH media, new view",
    "path-tracer": "path tracer",
}


def read_csv(path):
    with open(path, newline="", encoding="utf-8") as f:
        return list(csv.DictReader(f))


def chart_block(name):
    path = "Data/doc/%s.csv" % name
    if not os.path.exists(path):
        raise SystemExit("docs.sh: no %s for the marker figures:%s" % (path, name))
    rows = []
    for r in read_csv(path):
        method = r["method"]
        budget = ("%s spp" % count(r["budget"])) if method == "path-tracer" else "%s particles" % count(r["budget"])
        rows.append([METHODS.get(method, method), budget, significant(float(r["seconds"])),
                     percent(r["block_error"], 2), percent(r["rel_mae"]), percent(r["rel_rmse"]),
                     percent(r["rel_mae_medium"]), percent(r["rel_rmse_medium"])])
    out = table(["method", "budget", "time (s)", "block error", "rel. MAE", "rel. RMSE",
                 "rel. MAE, medium pixels", "rel. RMSE, medium pixels"],
                ["---", "---:", "---:", "---:", "---:", "---:", "---:", "---:"], rows)
    return out + "\n" + provenance_line("brume chart --csv", path, csv_provenance(path)) + "\n"


def sweep_block(name):
    path = "Data/doc/%s.csv" % name
    if not os.path.exists(path):
        raise SystemExit("docs.sh: no %s for the marker figures:%s" % (path, name))
    # Cases measured again against references of more samples.
    again = {}
    spp = None
    companions = []
    for extra in sorted(glob.glob("Data/doc/%s-*spp.csv" % name)):
        m = re.search(r"-(\d+)spp\.csv$", extra)
        if not m:
            continue
        spp = int(m.group(1))
        companions.append(extra)
        for r in read_csv(extra):
            again[(r["parameter"], r["value"])] = r
    header = ["parameter", "value", "pipeline rel. MAE", "SH media rel. MAE", "path tracer, same time",
              "pipeline time (s)", "block error: pipeline / SH / path tracer"]
    if again:
        header.append("pipeline (SH) against %s spp" % "{:,}".format(spp))
    header.append("reference's own noise")
    rows = []
    for r in read_csv(path):
        row = [r["parameter"], number(r["value"]), percent(r["pipeline_rel_mae"]),
               percent(r["pipeline_sh_rel_mae"]),
               "%s (%s spp)" % (percent(r["pathtracer_rel_mae"]), r["pathtracer_spp"]),
               significant(float(r["pipeline_seconds"])),
               " / ".join(percent(r[k], 2) for k in
                          ("pipeline_block_error", "pipeline_sh_block_error", "pathtracer_block_error"))]
        if again:
            a = again.get((r["parameter"], r["value"]))
            row.append("%s (%s)" % (percent(a["pipeline_rel_mae"]), percent(a["pipeline_sh_rel_mae"])) if a else "")
        row.append(percent(r["reference_noise"]))
        if r.get("finite", "1") != "1":
            row[1] += " (**not finite**)"
        rows.append(row)
    out = table(header, ["---", "---"] + ["---:"] * (len(header) - 2), rows)
    lines = [provenance_line("brume chart --sweep --csv", path, csv_provenance(path))]
    for extra in companions:
        lines.append(provenance_line("brume chart --sweep --csv", extra, csv_provenance(extra)))
    return out + "\n" + "\n\n".join(lines) + "\n"


def block(name):
    if name == "bench":
        return bench_block()
    if name.startswith("chart-"):
        return chart_block(name)
    if name.startswith("sweep-"):
        return sweep_block(name)
    raise SystemExit("docs.sh: unknown figures marker '%s'" % name)


cache = {}


def fill(match):
    name = match.group(2)
    if name not in cache:
        try:
            cache[name] = block(name)
        except (KeyError, ValueError, TypeError, json.JSONDecodeError) as error:
            raise SystemExit("docs.sh: figures:%s: its source is not what brume writes (%s: %s)"
                             % (name, type(error).__name__, error))
    note = "<!-- generated by scripts/docs.sh: edit its sources, not this table -->\n\n"
    content = cache[name] if name == "bench" and cache[name] == PLACEHOLDER else note + cache[name]
    return match.group(1) + content + match.group(4)


out_of_date = {}
for page in sorted(glob.glob("Documentation/*.md")):
    with open(page, encoding="utf-8") as f:
        text = f.read()
    if len(ANY_MARKER.findall(text)) != 2 * len(MARKER.findall(text)):
        raise SystemExit("docs.sh: %s: a figures marker without its pair" % page)
    new = MARKER.sub(fill, text)
    if new != text:
        out_of_date[page] = new
if MODE != "check":
    for page, new in out_of_date.items():
        with open(page, "w", encoding="utf-8") as f:
            f.write(new)
        print("docs.sh: refilled %s" % page)

if MODE == "check":
    for page in out_of_date:
        print("docs.sh --check: %s is out of date: run scripts/docs.sh" % page, file=sys.stderr)
    for entry in stale:
        print("docs.sh --check: %s: run scripts/docs.sh" % entry, file=sys.stderr)
    sys.exit(1 if out_of_date or stale else 0)
PYTHON
