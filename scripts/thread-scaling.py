#!/usr/bin/env python3
"""Prints the thread-scaling table of `brume bench`: tracing, transport
alone, reconstruction (full and first call) and the tracer's ray rate over
Embree's, at each thread count, as medians of RUNS runs, with each phase's
speed-up over one thread. Markdown, for Documentation/large-runs.md.

usage: scripts/thread-scaling.py [--brume build/bin/brume] [--particles N]
           [--threads 1,2,4,...] [--runs R]
The default thread counts are the powers of two up to this machine's cores
(and the cores themselves).
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
parser.add_argument("--brume", default=os.path.join(os.path.dirname(__file__), "..", "build",
                                                    "bin", "brume"))
parser.add_argument("--particles", type=int, default=1000000)
parser.add_argument("--threads", default="")
parser.add_argument("--runs", type=int, default=3)
parser.add_argument("--window", default="egl")
args = parser.parse_args()

cores = os.cpu_count() or 1
if args.threads:
    counts = [int(t) for t in args.threads.split(",")]
else:
    counts, t = [], 1
    while t < cores:
        counts.append(t)
        t *= 2
    counts.append(cores)

KEYS = ("particle_tracing", "transport_only", "reconstruction_full", "reconstruction_first_call",
        "tracer_over_embree_throughput")
medians = {}
with tempfile.TemporaryDirectory() as work:
    for threads in counts:
        runs = {key: [] for key in KEYS}
        for r in range(args.runs):
            out = os.path.join(work, "bench-%d-%d.json" % (threads, r))
            done = subprocess.run([args.brume, "bench", "--particles", str(args.particles),
                                   "--threads", str(threads), "--window", args.window,
                                   "--json", out], stdout=subprocess.DEVNULL,
                                  stderr=subprocess.PIPE, text=True)
            if done.returncode != 0 or not os.path.exists(out):
                sys.exit("brume bench --threads %d failed: %s" % (threads, done.stderr[-500:]))
            with open(out) as f:
                figures = {fig["key"]: fig["value"] for fig in json.load(f)["figures"]}
            for key in KEYS:
                runs[key].append(figures[key])
        medians[threads] = {key: statistics.median(values) for key, values in runs.items()}
        print("%d thread(s) done" % threads, file=sys.stderr)

one = medians[counts[0]]
print("`brume bench --particles %d`, medians of %d runs, %d cores here"
      % (args.particles, args.runs, cores))
print()
print("| threads | tracing (s) | speed-up | transport alone (s) | reconstruction (ms) | speed-up "
      "| first call / steady | tracer / Embree rays |")
print("|---:|---:|---:|---:|---:|---:|---:|---:|")
for threads in counts:
    m = medians[threads]
    print("| %d | %.3f | %.2f | %.3f | %.1f | %.2f | %.2f | %.2f |"
          % (threads, m["particle_tracing"], one["particle_tracing"] / m["particle_tracing"],
             m["transport_only"], m["reconstruction_full"],
             one["reconstruction_full"] / m["reconstruction_full"],
             m["reconstruction_first_call"] / m["reconstruction_full"],
             m["tracer_over_embree_throughput"]))
