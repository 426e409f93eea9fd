"""latency_over_time reads every shipped pipeline's fields.csv without taking a
sentinel for a time, and plots first light as its label says.

For each pipeline the figure registry names (results/figure_registry.json), a shipped
scenario with that pipeline runs for one simulated second with --ledger. Each
refresh's first-light latency is the latency of one lit span the recorder
counted (its field's first line shown), so it must lie within that run's
motion_to_photon_ms (and rotation_latency_ms) [min, max]; an
orientation_measured_ps of -1 (address recalculation looks the orientation up
per line at scanout) read as a time would put it at the scanout instant
itself, hundreds of milliseconds and growing. Then a hand derivation of first
light on a global-flash display, and the percentile windows of a dense series.

Usage: test_latency_over_time.py LATSIM SOURCE_DIR SCRATCH_DIR
"""

import csv
import glob
import json
import os
import shutil
import struct
import subprocess
import sys

LATSIM, SOURCE_DIR, SCRATCH = sys.argv[1], os.path.abspath(sys.argv[2]), os.path.abspath(sys.argv[3])
sys.path.insert(0, os.path.join(SOURCE_DIR, "analysis"))

import latency_over_time  # noqa: E402
import latsim_results  # noqa: E402

failures = []
checked = []
# A picosecond floored differently in a float sum: far below any sentinel's error (hundreds of ms).
EPS_MS = 1e-6
# Pipelines that show no whole images: no fields.csv rows to plot (the registry's headline frameless: "no whole images").
NO_FIELDS = {"frameless"}


def check(condition, message):
    checked.append(message)
    if not condition:
        failures.append(message)
        print("FAILED:", message)


def pipelines_in_registry():
    """The pipelines the figure registry names: every figure's producers but "all"."""
    names = set()
    for figure in latsim_results.read_registry(os.path.join(SOURCE_DIR, "results", "figure_registry.json"))["figures"]:
        if isinstance(figure["pipelines"], list):
            names.update(figure["pipelines"])
    return names


def scenarios_by_pipeline():
    """{pipeline type: shipped scenario files that name it at their top level}, sorted."""
    found = {}
    for path in sorted(glob.glob(os.path.join(SOURCE_DIR, "scenarios", "**", "*.json"), recursive=True)):
        try:
            with open(path, encoding="utf-8") as f:
                data = json.load(f)
        except ValueError:
            continue
        pipeline = data.get("pipeline") if isinstance(data, dict) and "axes" not in data else None
        if isinstance(pipeline, dict) and "type" in pipeline:
            found.setdefault(pipeline["type"], []).append(path)
    return found


def run(scenario, out):
    shutil.rmtree(out, ignore_errors=True)
    proc = subprocess.run([LATSIM, "run", scenario, "--ledger", "-q", "-o", out, "--set", "/duration_s=1"],
                          capture_output=True, text=True)
    return proc.returncode == 0 and os.path.isfile(os.path.join(out, "fields.csv"))


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def within(value, dist):
    return dist["min"] - EPS_MS <= value <= dist["max"] + EPS_MS


shutil.rmtree(SCRATCH, ignore_errors=True)
os.makedirs(SCRATCH)
documented = pipelines_in_registry()
check(len(documented) >= 9, f"pipelines read from results/figure_registry.json: {sorted(documented)}")
candidates = scenarios_by_pipeline()
sentinel_rows = 0
for pipeline in sorted(documented):
    out = os.path.join(SCRATCH, pipeline)
    scenario = next((s for s in candidates.get(pipeline, []) if run(s, out)), None)
    check(scenario is not None, f"{pipeline}: no shipped scenario runs with --ledger")
    if scenario is None:
        continue
    fields = read_csv(os.path.join(out, "fields.csv"))
    sentinel_rows += sum(1 for r in fields if r["orientation_measured_ps"] == "-1")
    points = latency_over_time.read_fields(out)
    if not fields:
        check(pipeline in NO_FIELDS, f"{pipeline}: {os.path.basename(scenario)} shows no image in fields.csv")
        continue
    check(bool(points), f"{pipeline}: fields.csv has rows but nothing was read")
    with open(os.path.join(out, "summary.json")) as f:
        figures = json.load(f)["figures"]
    # Spans lit after the run's end are not in the figures (docs/figures.md, "A lit span").
    points = [p for p in points if p[0] <= 1.0]
    mtp = figures["motion_to_photon_ms"]
    bad = [p for p in points if not within(p[1], mtp)]
    check(not bad, f"{pipeline}: first-light MTP outside [{mtp['min']}, {mtp['max']}] ms: {bad[:3]}")
    rotation = figures.get("rotation_latency_ms")
    if rotation:
        rotated = [p for p in points if p[2] is not None]
        check(rotated, f"{pipeline}: no rotation latency read")
        bad = [p for p in rotated if not within(p[2], rotation)]
        check(not bad, f"{pipeline}: first-light rotation outside [{rotation['min']}, {rotation['max']}] ms: {bad[:3]}")
check(sentinel_rows > 0, "no pipeline wrote orientation_measured_ps = -1: the sentinel case went untested")

# Hand derivation: Valve Index at 90 Hz, global flash (lit 0.48 ms, response 1 ms), 1600 active lines
# and 50 blank ones. The panel flashes at the next retrace, one period T = 1000/90 ms after this one,
# whose first active line is written 50/1650 T after it: first light - scanout start
# = T (1 - 50/1650) + 1 + 0.48 / 2 = 11.1111 x 0.969697 + 1.24 = 12.01444 ms.
index = os.path.join(SCRATCH, "index_90hz")
check(run(os.path.join(SOURCE_DIR, "scenarios", "devices", "index_90hz.json"), index), "index_90hz runs")
want_ms = 1000 / 90 * (1 - 50 / 1650) + 1 + 0.24
starts = {}
for r in read_csv(os.path.join(index, "fields.csv")):
    if r["eye"] == "0" and r["first_line"] == "0":
        starts.setdefault(int(r["retrace_ps"]), int(r["scanout_start_ps"]))
points = latency_over_time.read_fields(index)
offsets = [p[0] * 1e3 - start * 1e-9 for p, start in zip(points, [starts[k] for k in sorted(starts)])]
check(len(points) == len(starts) and all(abs(o - want_ms) < 1e-5 for o in offsets),
      f"first light after scanout start: {offsets[:3]} ms, want {want_ms:.5f}")

# A dense series alternating between 57 and 140 ms (an address recalculation pipeline's renders):
# 400 refreshes in 10 windows of 40, each 20 at 57 and 20 at 140. The 10th percentile is 57, the 90th
# 140, the median halfway between the 20th and 21st values: 98.5.
xs = [i * 0.01 for i in range(400)]
ys = [57.0 if i % 2 == 0 else 140.0 for i in range(400)]
bands = latency_over_time.windows(xs, ys)
check(len(bands) == 10 and all(b[2:] == (57.0, 98.5, 140.0) for b in bands), f"windows {bands[:2]}")
# Windows of 3.99 s / 10 = 0.399 s: the first from 0, the last ending at the last refresh.
check(bands[0][0] == 0.0 and abs(bands[-1][1] - 3.99) < 1e-12, f"window span {bands[0][:2]} .. {bands[-1][:2]}")

# The plot of these runs: drawn, at most 2,000 px wide.
coll = latsim_results.load(SCRATCH)
base = latency_over_time.plot(coll)
png = os.path.join(SCRATCH, f"{base}.png") if base else ""
if os.path.isfile(png):
    with open(png, "rb") as f:
        width, height = struct.unpack(">II", f.read(24)[16:24])
    check(width <= 2000, f"{png}: {width} px wide")
else:
    check(False, "latency_over_time.png not drawn")

print(f"latency over time: {len(checked) - len(failures)} checks passed, {len(failures)} failed")
sys.exit(1 if failures else 0)
