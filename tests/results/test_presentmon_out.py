"""presentmon.csv and latsim compare, end to end.

1. (The two-sample Kolmogorov-Smirnov distance and the percentiles are
   checked by hand in tests/models/capture/test_comparison.cpp, where they live.)
2. A frame_stages run whose stage costs vary (uniform) writes presentmon.csv
   whose every value agrees with the run's other records, read independently:
   timeline.csv (each stage's start and end, in ms with six decimals) and
   frames.csv (the ledger: each image's scanout start, in ps). timeline.csv
   truncates each instant to the nanosecond, so a duration from it is within
   1 ns of the exact one; presentmon.csv is exact to the picosecond.
3. latsim compare of the run against itself gives KS distance 0 on the
   quantities both sides define alike; against a capture's process it reads
   what a hand count gives.
4. A run whose CPU and GPU stages are driven by that presentmon.csv
   (cost.trace, in order) repeats its values frame by frame, and compare
   says those columns are replayed (left out of the verdict), their KS
   distance within the bound a prefix allows.
5. Bad input (missing capture, several processes and none chosen, a malformed
   cell): exit 2, one line on stderr, nothing written.
6. A runtime's own statistics (an OVR Metrics export) against the Quest 2
   scenario driven by it: one verdict line per quantity, the replayed GPU
   times left out, early frames said to have no counterpart; a broken row of
   an export is bad input naming its file and line.

Usage: test_presentmon_out.py LATSIM SOURCE_DIR SCRATCH_DIR
"""

import csv
import json
import os
import shutil
import subprocess
import sys

LATSIM, SOURCE, SCRATCH = sys.argv[1], sys.argv[2], sys.argv[3]

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAILED:", message)


# --- 2. presentmon.csv against timeline.csv and frames.csv -----------------
shutil.rmtree(SCRATCH, ignore_errors=True)
os.makedirs(SCRATCH)
scenario = {
    "description": "CPU and GPU a frame apart, stage costs varying uniformly",
    "duration_s": 1, "seed": 7,
    "motion": {"type": "constant", "axis": [0, 1, 0], "rate_deg_s": 60, "position_m": [0, 1.6, 0]},
    "tracker": {"rate_hz": 1000, "internal_delay_ms": 0},
    "transport": {"type": "direct"},
    "display": {"refresh_hz": 62.5, "width_px": 640, "height_px": 480, "vblank_lines": 0, "hblank_px": 0,
                "hfov_deg": 90, "scanout": "line"},
    "pipeline": {
        "type": "frame_stages",
        "processors": [{"name": "cpu"}, {"name": "gpu"}],
        "stages": [
            {"name": "I", "on": "cpu", "start": "retrace", "samples_pose": True, "cost": {"fixed_ms": 1}},
            {"name": "S", "on": "cpu", "cost": {"fixed_ms": 5, "variation": "uniform", "variation_fraction": 0.4}},
            {"name": "R", "on": "cpu", "cost": {"fixed_ms": 3}},
            {"name": "G", "on": "gpu", "cost": {"fixed_ms": 9, "variation": "uniform", "variation_fraction": 0.3}},
        ],
    },
}
scenario_file = os.path.join(SCRATCH, "varying.json")
with open(scenario_file, "w") as f:
    json.dump(scenario, f)
run_dir = os.path.join(SCRATCH, "run")
r = subprocess.run([LATSIM, "run", scenario_file, "--out", run_dir, "--ledger", "--quiet"],
                   capture_output=True, text=True)
check(r.returncode == 0, f"latsim run exits 0 ({r.stderr.strip()})")


def read_csv(name):
    with open(os.path.join(run_dir, name), newline="") as f:
        return list(csv.DictReader(f))


pm = read_csv("presentmon.csv")
timeline = read_csv("timeline.csv")
ledger = read_csv("frames.csv")
stage = {(row["stage"], int(row["frame"])): (float(row["start_ms"]), float(row["end_ms"])) for row in timeline}
first_scanout_ps = {}
for row in ledger:
    frame = int(row["frame"])
    first_scanout_ps[frame] = min(first_scanout_ps.get(frame, 1 << 62), int(row["scanout_start_ps"]))

# About 62 frames in a second at 62.5 Hz; the last one or two are still on their way.
check(55 <= len(pm) <= 62, f"presentmon.csv has a row per frame shown ({len(pm)})")
check(list(pm[0].keys())[:10] == ["Application", "ProcessID", "SwapChainAddress", "PresentRuntime", "SyncInterval",
                                   "AllowsTearing", "FrameType", "TimeInSeconds", "MsBetweenPresents",
                                   "MsBetweenDisplayChange"], "the PresentMon columns come first, in its order")
NS = 1e-6  # one nanosecond, in ms
gpu_values = set()
previous = None
for row in pm:
    frame = int(row["FrameId"])
    g0, g1 = stage[("G", frame)]
    cpu = sum(stage[(s, frame)][1] - stage[(s, frame)][0] for s in ("I", "S", "R"))
    present_ms = stage[("R", frame)][1]
    check(abs(float(row["MsGPUBusy"]) - (g1 - g0)) < NS, f"frame {frame}: MsGPUBusy is G's duration")
    check(abs(float(row["MsGPUTime"]) - (g1 - g0)) < NS, f"frame {frame}: MsGPUTime is G's span")
    check(abs(float(row["MsCPUBusy"]) - cpu) < 3 * NS, f"frame {frame}: MsCPUBusy is I + S + R")
    check(abs(float(row["TimeInSeconds"]) * 1e3 - present_ms) < NS, f"frame {frame}: the present is R's end")
    check(abs(float(row["MsRenderPresentLatency"]) - (g1 - present_ms)) < NS, f"frame {frame}: G's end - present")
    check(abs(float(row["MsGPULatency"]) - (g0 - stage[("I", frame)][0])) < NS, f"frame {frame}: GPU latency")
    # Line scanout without blanking or pixel latency: the first photon is the scanout start of the field.
    until = first_scanout_ps[frame] / 1e9 - float(row["TimeInSeconds"]) * 1e3
    check(abs(float(row["MsUntilDisplayed"]) - until) < 1e-9, f"frame {frame}: MsUntilDisplayed (ledger)")
    if previous is not None:
        check(int(row["FrameId"]) == int(previous["FrameId"]) + 1, "rows in frame order")
        between = float(row["TimeInSeconds"]) - float(previous["TimeInSeconds"])
        check(abs(float(row["MsBetweenPresents"]) - between * 1e3) < 1e-9, f"frame {frame}: MsBetweenPresents")
    gpu_values.add(row["MsGPUBusy"])
    previous = row
check(len(gpu_values) > len(pm) // 2, "the GPU's costs vary from frame to frame")
check(all(row["MsGPUBusy"].split(".")[1].__len__() == 9 for row in pm), "milliseconds with nine decimals")

# --- 3. latsim compare -----------------------------------------------------
r = subprocess.run([LATSIM, "compare", os.path.join(run_dir, "presentmon.csv"), run_dir], capture_output=True,
                   text=True)
check(r.returncode == 0, f"compare of a run with itself exits 0 ({r.stderr.strip()})")
rows = {x["quantity"]: x for x in csv.DictReader(open(os.path.join(run_dir, "compare", "compare.csv")))}
check(list(rows) == ["frame_interval", "cpu_busy", "cpu_wait", "gpu_busy", "until_displayed", "display_change",
                     "dropped"], f"compare.csv has a row per quantity ({list(rows)})")
for q in ("frame_interval", "cpu_busy", "gpu_busy", "dropped"):
    check(float(rows[q]["ks_distance"]) == 0.0, f"a run against itself: KS distance 0 for {q}")
    check(os.path.exists(os.path.join(run_dir, "compare", f"compare_{q}.png")), f"CDF plot {q}")
# frame_stages reports the work of its CPU stages alone, PresentMon the time between presents: said, not judged.
check(rows["cpu_busy"]["standing"] == "differs", "CPU busy: the definitions differ")
check(rows["cpu_wait"]["standing"] == "no counterpart", "CPU wait: frame_stages's present takes no time")
verdict = open(os.path.join(run_dir, "compare", "compare.md")).read().split("## Verdict")[1]
check(sum(1 for line in verdict.splitlines() if line.startswith("- ")) == len(rows), "one verdict line per quantity")
real = os.path.join(SOURCE, "tests", "results", "data", "two_processes.csv")
# A capture's process beside the run.
r = subprocess.run([LATSIM, "compare", real, run_dir, "--application", "dwm.exe", "--out",
                    os.path.join(SCRATCH, "vs_dwm"), "--no-plots"], capture_output=True, text=True)
check(r.returncode == 0, f"compare of a capture's process with the run exits 0 ({r.stderr.strip()})")
rows = {x["quantity"]: x for x in csv.DictReader(open(os.path.join(SCRATCH, "vs_dwm", "compare.csv")))}
# The capture's dwm.exe rows, by hand: MsGPUBusy 0.6803, 0.6792, NA -> two values, mean 0.67975.
check(rows["gpu_busy"]["capture_count"] == "2", "the capture's NA cell is not counted")
check(abs(float(rows["gpu_busy"]["capture_mean"]) - 0.67975) < 1e-12, "the capture's mean, by hand")
# Its MsUntilDisplayed: 16.2114, 16.2211, NA: p50 of two values is their mean.
check(abs(float(rows["until_displayed"]["capture_p50"]) - 16.21625) < 1e-12, "the capture's p50, by hand")
check(float(rows["gpu_busy"]["ks_distance"]) == 1.0, "a GPU busy of 0.68 ms against one of 9 ms +-30 %: disjoint, KS 1")
check(rows["gpu_busy"]["agrees"] == "0", "so they do not agree")
# Its dropped share: one of three frames has no display time.
check(abs(float(rows["dropped"]["capture_mean"]) - 1 / 3) < 1e-9, "the capture's share never displayed, by hand")

# --- 4. a run driven by the first run's presentmon.csv --------------------
# One CPU stage costing the capture's MsCPUBusy and the GPU stage its
# MsGPUBusy, in order: frame k of the driven run costs row k's values, so its
# own presentmon.csv repeats them exactly (the same nine decimals).
# Stage costs from a capture (cost.trace) come with the capture reader's scenario keys; a latsim without them
# has nothing to drive a run with, and this part says so.
schema = subprocess.run([LATSIM, "schema", "--format", "json-schema"], capture_output=True, text=True).stdout
if '"at_end"' not in schema:
    print("part 4 not run: this latsim has no cost.trace")
else:
    driven = json.loads(json.dumps(scenario))
    driven["duration_s"] = 0.9
    capture_file = os.path.join(run_dir, "presentmon.csv")
    trace = {"file": capture_file, "at_end": "stop"}
    driven["pipeline"]["stages"] = [
        {"name": "C", "on": "cpu", "start": "retrace", "samples_pose": True,
         "cost": {"trace": dict(trace, column="MsCPUBusy")}},
        {"name": "G", "on": "gpu", "cost": {"trace": dict(trace, column="MsGPUBusy")}},
    ]
    driven_file = os.path.join(SCRATCH, "driven.json")
    with open(driven_file, "w") as f:
        json.dump(driven, f)
    driven_dir = os.path.join(SCRATCH, "driven")
    r = subprocess.run([LATSIM, "run", driven_file, "--out", driven_dir, "--quiet"], capture_output=True, text=True)
    check(r.returncode == 0, f"the driven run exits 0 ({r.stderr.strip()})")
    with open(os.path.join(driven_dir, "presentmon.csv"), newline="") as f:
        replayed = list(csv.DictReader(f))
    check(40 <= len(replayed) < len(pm), f"the driven run shows fewer frames than the capture has ({len(replayed)})")
    for k, row in enumerate(replayed):
        check(row["MsGPUBusy"] == pm[k]["MsGPUBusy"], f"driven frame {k}: MsGPUBusy is the capture's row {k}")
        check(row["MsCPUBusy"] == pm[k]["MsCPUBusy"], f"driven frame {k}: MsCPUBusy is the capture's row {k}")
    # The driven values are the first n of the capture's N: for every x, F_capture and F_driven differ by at
    # most (N - n) / N (the n shared values count 1/n against 1/N, the N - n others only on one side).
    bound = (len(pm) - len(replayed)) / len(pm)
    r = subprocess.run([LATSIM, "compare", capture_file, driven_dir], capture_output=True, text=True)
    check(r.returncode == 0, f"compare of a capture and a run driven by it exits 0 ({r.stderr.strip()})")
    rows = {x["quantity"]: x for x in csv.DictReader(open(os.path.join(driven_dir, "compare", "compare.csv")))}
    for q in ("cpu_busy", "gpu_busy"):
        ks = float(rows[q]["ks_distance"])
        check(ks <= bound + 1e-6, f"driven quantity {q}: KS {ks} within {bound:.4f}")
        check(rows[q]["standing"] == "replayed" and rows[q]["agrees"] == "",
              f"driven quantity {q}: replayed, left out of the verdict")

# --- 5. bad input ----------------------------------------------------------
def bad(args, what):
    target = os.path.join(SCRATCH, "bad_out")
    shutil.rmtree(target, ignore_errors=True)
    r = subprocess.run([LATSIM, "compare", *args, "--out", target], capture_output=True, text=True)
    check(r.returncode == 2, f"{what}: exit 2 (got {r.returncode})")
    check(len(r.stderr.strip().splitlines()) == 1, f"{what}: one line on stderr ({r.stderr!r})")
    check(not os.path.exists(target), f"{what}: nothing written")
    return r.stderr


bad([os.path.join(SCRATCH, "missing.csv"), run_dir], "a missing capture")
err = bad([real, run_dir], "several processes, none chosen")
check("dwm.exe 1564" in err and "Presenter.exe 8320" in err, "names the processes the capture holds")
malformed = os.path.join(SCRATCH, "malformed.csv")
with open(malformed, "w") as f:
    f.write("MsBetweenPresents,MsGPUBusy\n16.6,1.0\n16.7,fast\n")
err = bad([malformed, run_dir], "a malformed cell")
check(":3:" in err and "MsGPUBusy" in err and "'fast'" in err, "names line, column and value")
bad([real, os.path.join(SCRATCH, "no_run_here")], "a run directory that does not exist")

# --- 6. a runtime's statistics ---------------------------------------------
ovr = os.path.join(SOURCE, "scenarios", "measured", "captures", "ovr-metrics", "OGMP_1.csv")
quest_dir = os.path.join(SCRATCH, "quest")
r = subprocess.run([LATSIM, "run", os.path.join(SOURCE, "scenarios", "measured", "quest2_ovr_72hz.json"), "--out",
                    quest_dir, "--quiet", "--set", "/duration_s=3"], capture_output=True, text=True)
check(r.returncode == 0, f"the Quest 2 run exits 0 ({r.stderr.strip()})")
r = subprocess.run([LATSIM, "compare", ovr, quest_dir, "--no-plots"], capture_output=True, text=True)
check(r.returncode == 0, f"compare of an OVR Metrics export with a run exits 0 ({r.stderr.strip()})")
rows = {x["quantity"]: x for x in csv.DictReader(open(os.path.join(quest_dir, "compare", "compare.csv")))}
check(list(rows) == ["frame_rate", "refresh", "prediction", "stale", "early", "tears", "app_gpu", "timewarp_gpu"],
      f"the runtime's quantities ({list(rows)})")
check(rows["app_gpu"]["standing"] == "replayed" and rows["timewarp_gpu"]["standing"] == "replayed",
      "the GPU times the run plays from the export are replayed")
check(rows["prediction"]["standing"] == "predicted" and rows["prediction"]["agrees"] in ("0", "1"),
      "the prediction time is judged")
check(rows["early"]["standing"] == "no counterpart" and rows["early"]["agrees"] == "", "early frames: no counterpart")
check(rows["refresh"]["standing"] == "input", "the refresh rate is the scenario's")
check(rows["prediction"]["capture_count"] == "104", "the export's 104 whole seconds")
verdict = open(os.path.join(quest_dir, "compare", "compare.md")).read().split("## Verdict")[1]
check(sum(1 for line in verdict.splitlines() if line.startswith("- ")) == len(rows), "one verdict line per quantity")
# The two VrApi lines and a SteamVR frame timing file (written from openvr.h's fields) against the same run.
for capture, quantities in ((os.path.join(SOURCE, "scenarios", "measured", "captures", "vrapi", "vrapi_stats_lines.txt"),
                             {"frame_rate", "prediction", "stale", "early", "tears"}),
                            (os.path.join(SOURCE, "tests", "models", "capture", "data", "steamvr_frame_timing.csv"),
                             {"frame_interval", "stale", "app_gpu", "timewarp_gpu"})):
    out = os.path.join(SCRATCH, "vs_" + os.path.basename(capture))
    r = subprocess.run([LATSIM, "compare", capture, quest_dir, "--no-plots", "--out", out], capture_output=True,
                       text=True)
    check(r.returncode == 0, f"compare of {os.path.basename(capture)} with a run exits 0 ({r.stderr.strip()})")
    got = {x["quantity"]: x for x in csv.DictReader(open(os.path.join(out, "compare.csv")))}
    check(quantities <= set(got), f"{os.path.basename(capture)}: rows {sorted(got)}")
broken = os.path.join(SCRATCH, "broken_ovr.csv")
with open(ovr) as f:
    lines = f.read().splitlines()
lines[3] = lines[3].replace(",72,", ",7x2,", 1)
with open(broken, "w") as f:
    f.write("\n".join(lines) + "\n")
err = bad([broken, quest_dir], "a broken row of an OVR Metrics export")
check("broken_ovr.csv:4:" in err, f"names the file and line ({err.strip()})")

print(f"{'FAILED' if failures else 'ok'}: {len(failures)} failures")
sys.exit(1 if failures else 0)
