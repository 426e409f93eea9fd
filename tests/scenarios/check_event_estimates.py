#!/usr/bin/env python3
"""Every shipped scenario's event estimate is near the events its run executes.

A run refuses to start when the events it is estimated to execute exceed
--max-events (docs/event-budget.md): the estimate must never be far below the
real count, or a run that cannot finish slips through, nor far above, or a
legal run is refused. Each shipped scenario runs for one simulated second
and its summary.json gives both: "events" (counted by the kernel) and
"events_estimate.events_without_steps" (rates declared by the models and the
pipeline, times the duration; steps of work that are not events are left out).

The band, derived: every declared rate is a unit rate (samples, fields,
lines, frames, chunks, messages, ticks) that the code fixes or bounds
exactly, times the events one unit makes, counted from the processes' waits.
A wait that finds its condition already met makes no event, so a unit's count
is off by at most a factor of 2 either way; a unit rate bounded by the refresh
(a frame that misses its field is shown a field later) is off by at most 2;
and the first second holds start-up transients (the first tracker sample
arriving, pipelines filling), at most a factor of 2 more. 2 × 2 × 2 = 8 < 10:
the estimate must lie within [events / 10, events × 10], for the run and
for every model that executes at least 100 events.

Usage: check_event_estimates.py LATSIM SOURCE_DIR SCRATCH_DIR
"""

import glob
import json
import os
import shutil
import subprocess
import sys

LATSIM, SOURCE_DIR, SCRATCH = sys.argv[1:4]
BAND = 10.0
# Below this many events a model's own count is not judged (its total is).
MODEL_MIN_EVENTS = 100


def shipped_scenarios():
    """The scenarios check_fingerprints.sh runs: not sweeps, not bases."""
    found = []
    for path in sorted(glob.glob(os.path.join(SOURCE_DIR, "scenarios", "**", "*.json"), recursive=True)):
        rel = os.path.relpath(path, SOURCE_DIR)
        if "/sweeps/" in rel or rel.endswith("/base.json") or "/data/" in rel:
            continue
        if '"axes":' in open(path).read():
            continue
        found.append(rel)
    return found


shutil.rmtree(SCRATCH, ignore_errors=True)
os.makedirs(SCRATCH)
failures = []
for rel in shipped_scenarios():
    out = os.path.join(SCRATCH, "run")
    shutil.rmtree(out, ignore_errors=True)
    done = subprocess.run([LATSIM, "run", rel, "--out", out, "--set", "/duration_s=1", "-q"], cwd=SOURCE_DIR,
                          capture_output=True, text=True)
    if done.returncode != 0:
        failures.append(f"{rel}: exit {done.returncode}: {done.stderr.strip()}")
        continue
    summary = json.load(open(os.path.join(out, "summary.json")))
    events = summary["events"]
    estimate = summary["events_estimate"]["events_without_steps"]
    ratio = estimate / events if events else float("inf")
    line = f"{rel}: {events} events, estimate {estimate:.0f} ({ratio:.2f}x, key {summary['events_estimate']['dominant']})"
    print(line)
    if not (events / BAND <= estimate <= events * BAND):
        failures.append(line + f": outside [1/{BAND:g}, {BAND:g}]")
    # Model by model too, where the count is large enough to judge (a serial
    # line that never queues makes none of the line events it may make).
    by_model = {}
    for rate in summary["events_estimate"]["rates"]:
        if not rate["steps"]:
            by_model[rate["model"]] = by_model.get(rate["model"], 0.0) + rate["per_s"] * 1.0
    for model, actual in summary["events_per_model"].items():
        predicted = by_model.get(model, 0.0)
        if actual >= MODEL_MIN_EVENTS and not (actual / BAND <= predicted <= actual * BAND):
            failures.append(f"{rel}: model {model}: {actual} events, estimate {predicted:.0f}")
shutil.rmtree(SCRATCH, ignore_errors=True)
for f in failures:
    print("FAIL " + f)
sys.exit(1 if failures else 0)
