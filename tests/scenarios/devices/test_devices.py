"""The device profiles of scenarios/devices/ (docs/devices.md): every device
file runs and reports what a headset measurement sees (the head's and the
controller's apparent latency, the camera's measurement of the controller
flick); a higher refresh rate of one headset gives a lower motion-to-photon
latency, by the part of the latency that scales with the refresh period,
derived here from the profile; the devices sweep holds exactly the device
files, and is what scripts/devices_sweep.py writes.

Usage: test_devices.py LATSIM SOURCE_DIR SCRATCH_DIR
"""

import json
import os
import shutil
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from fractions import Fraction

LATSIM, SOURCE_DIR, SCRATCH = sys.argv[1], sys.argv[2], sys.argv[3]
DEVICES = os.path.join(SOURCE_DIR, "scenarios", "devices")
OUT = os.path.join(SCRATCH, "device_profiles")  # not tests/scenarios/devices: that is this directory's build directory

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAILED:", message)


# The device files as the scenario reader merges their includes (one definition, the sweep writer's).
sys.path.insert(0, os.path.join(SOURCE_DIR, "scripts"))
from devices_sweep import load  # noqa: E402


FAMILIES = {
    "index": ["index_80hz.json", "index_90hz.json", "index_120hz.json", "index_144hz.json"],
    "vive_pro2": ["vive_pro2_90hz.json", "vive_pro2_120hz.json"],
    "beyond": ["beyond_75hz.json", "beyond_90hz.json"],
    "quest2": ["quest2_72hz.json", "quest2_90hz.json", "quest2_120hz.json"],
    "quest3": ["quest3_72hz.json", "quest3_90hz.json", "quest3_120hz.json"],
}
OTHERS = ["vive_90hz.json", "index_144hz_monado.json", "psvr2_120hz.json", "rift_cv1_90hz.json", "rift_s_80hz.json"]
FILES = [f for fam in FAMILIES.values() for f in fam] + OTHERS

shutil.rmtree(OUT, ignore_errors=True)
os.makedirs(OUT)


def check_rate(name, f):
    """Whether the application holds the refresh rate, derived from its game thread's cost.

    The game thread asks for its next frame the cost after it was let go; it makes the
    next running start (SteamVR) or the next frame Monado paces when the cost is at most
    a refresh period T. Then no refresh is missed. VRChat's 9.5 ms (engine/vrchat/base.json)
    fits 80, 90 and 75 Hz (12.5, 11.1, 13.3 ms) and not 120 or 144 Hz (8.33, 6.94 ms),
    where it fits two periods: SteamVR counts its first frames late until `late_frames`
    (5) of them raise the throttle level, after which the application runs at half rate
    and the compositor synthesises every other refresh, N/2 of the N refreshes of the run
    less the few before the throttle rose; Monado does not throttle, and the compositor
    warps the old frame on every other refresh, which it counts as missed (N/2 less the
    first)."""
    s = load(os.path.join(DEVICES, name))
    t = period_ms(s)
    cost = s["pipeline"]["stages"][0]["cost"]["fixed_ms"]
    n = round(float(Fraction(str(s["duration_s"])) * Fraction(str(s["display"]["refresh_hz"]))))
    missed, synthesised = f.get("frames_missed", 0), f.get("frames_synthesised", 0)
    if cost <= t:
        check(missed == 0, f"{name}: the application ({cost} ms) makes every refresh ({t:.2f} ms): {missed} missed")
        return
    check(cost <= 2 * t, f"{name}: the test derives half rate only ({cost} ms within two periods of {t:.2f} ms)")
    if s["pipeline"]["pacing"]["application"] == "steamvr":
        check(missed <= 5 and f.get("throttle_raised", 0) == 1,
              f"{name}: throttled once, after at most 5 late frames ({missed} missed, raised {f.get('throttle_raised')})")
        check(n / 2 - 10 <= synthesised <= n / 2,
              f"{name}: half rate, {synthesised} of {n} refreshes synthesised (expected {n / 2 - 10:.0f} to {n / 2:.0f})")
    else:
        check(n / 2 - 10 <= missed <= n / 2, f"{name}: every other of {n} refreshes re-warps the old frame ({missed})")


# The sample's age when the application reads it (the tracker's report interval, the
# USB poll, the phase of the read) depends on the drawn clock phases, not on the
# refresh period. The ideal-tracker runs make it vanish (a 20 kHz tracker on a direct
# link: under 0.05 ms), so that their motion-to-photon is the read-to-photon time the
# refresh period changes, exactly.
# They run the engine's light workload (game thread 2 ms: every rate held), so that the
# fall is the pipeline's and the display's, not the application's throttling (below).
IDEAL_TRACKER = ["--set", "/tracker/rate_hz=20000", "--set", '/transport={"type":"direct"}',
                 "--set", "/pipeline/stages/0/cost/fixed_ms=2"]


def run(job):
    name, ideal = job
    out = os.path.join(OUT, name[:-5] + ("_ideal" if ideal else ""))
    proc = subprocess.run([LATSIM, "run", os.path.join(DEVICES, name), "--out", out, "-q"] +
                          (IDEAL_TRACKER if ideal else []), capture_output=True, text=True)
    return name, ideal, proc, out


FAMILY_FILES = [f for fam in FAMILIES.values() for f in fam]
with ThreadPoolExecutor(max_workers=2) as pool:
    results = list(pool.map(run, [(f, False) for f in FILES] + [(f, True) for f in FAMILY_FILES]))

figures, ideal = {}, {}
for name, is_ideal, proc, out in results:
    check(proc.returncode == 0, f"{name} runs{' (ideal tracker)' if is_ideal else ''}: {proc.stderr.strip()}")
    if proc.returncode != 0:
        continue
    f = json.load(open(os.path.join(out, "figures.json"), encoding="utf-8"))
    f = f.get("figures", f)
    if is_ideal:
        ideal[name] = f
        continue
    figures[name] = f
    for figure in ["motion_to_photon_ms", "apparent_latency_ms_start", "apparent_latency_ms_onset",
                   "apparent_latency_ms_steady", "controller_apparent_latency_ms_start", "measured_latency_ms",
                   "prediction_catch_up_ms"]:
        check(isinstance(f.get(figure), dict) and f[figure].get("count", 0) > 0, f"{name} reports {figure}")


def period_ms(scenario):
    return float(1000 / Fraction(str(scenario["display"]["refresh_hz"])))


for name, f in figures.items():
    check_rate(name, f)


def periods_of_pacing(scenario):
    """Refresh periods between the pose drawn being read and the retrace its image is shown from.

    Both runtimes wake the game thread a whole number of periods before the retrace
    its frame is shown from: SteamVR's running start reads the pose 3 ms before
    retrace V and shows the frame from V + (1 + h) T, h the stages handed over to the
    next frame (an engine's render thread); Phase Sync wakes it the frame time plus
    margins before the latch, and the frame time holds the h periods of the hand-overs
    besides work shorter than a period, so it is shown from the (1 + h)-th retrace
    after the wake-up. A pose read after hb of the hand-overs (a late-latching GPU)
    is hb periods younger: 1 + h - hb periods, plus constants (the running start,
    or the work after the read and the margins)."""
    stages = scenario["pipeline"]["stages"]
    handovers = [i for i, st in enumerate(stages) if st.get("start") == "next_frame"]
    drawn = max(i for i, st in enumerate(stages) if st.get("samples_pose"))
    return 1 + len(handovers) - sum(1 for i in handovers if i <= drawn)


def periods_of_illumination(scenario):
    """Refresh periods from the retrace to the centre pixel's photon, besides the flash.

    Global illumination lights the panel once every row (the whole field) is written:
    one period; rolling illumination lights the centre row after the blank lines and half
    the active ones."""
    display = scenario["display"]
    if display["persistence"]["type"] == "global":
        return 1
    lines = display["height_px"] + display["vblank_lines"]
    return (display["vblank_lines"] + display["height_px"] / 2) / lines


def scaled_part(scenario):
    """The part of read-to-photon latency that changes with the refresh rate (ms)."""
    t = period_ms(scenario)
    lit = scenario["display"]["persistence"].get("lit_ms", 0)
    return (periods_of_pacing(scenario) + periods_of_illumination(scenario)) * t + lit / 2


TOLERANCE_MS = 0.1  # Phase Sync's estimate before the first measured frame (one period), and the ideal sample's age
for family, files in FAMILIES.items():
    for low, high in zip(files, files[1:]):
        if low not in ideal or high not in ideal or low not in figures or high not in figures:
            continue
        s_low, s_high = load(os.path.join(DEVICES, low)), load(os.path.join(DEVICES, high))
        expected = scaled_part(s_low) - scaled_part(s_high)
        fall = ideal[low]["motion_to_photon_ms"]["mean"] - ideal[high]["motion_to_photon_ms"]["mean"]
        check(abs(fall - expected) <= TOLERANCE_MS,
              f"{low} -> {high}: read-to-photon falls by {fall:.3f} ms, expected {expected:.3f} ms (+- {TOLERANCE_MS})")
        check(ideal[high]["motion_to_photon_ms"]["mean"] < ideal[low]["motion_to_photon_ms"]["mean"],
              f"{family}: {high} has a lower motion-to-photon than {low} when the application holds both rates")

# The sweep's points are the device files (zip mode: the i-th value of every axis).
sweep = json.load(open(os.path.join(DEVICES, "devices_sweep.json"), encoding="utf-8"))
check(sweep.get("mode") == "zip" and sweep.get("replications", 1) >= 8, "the sweep is zipped, 8 replications or more")
stale = subprocess.run([sys.executable, os.path.join(SOURCE_DIR, "scripts", "devices_sweep.py"), "--check"],
                       capture_output=True, text=True)
check(stale.returncode == 0, f"devices_sweep.json is what scripts/devices_sweep.py writes: {stale.stdout.strip()}")
base = load(os.path.join(DEVICES, sweep["base"]))
pointers = [a["pointer"] for a in sweep["axes"]]
n = len(sweep["axes"][0]["values"])
check(n == len(FILES), f"the sweep has one point per device file ({n} of {len(FILES)})")
for i in range(n):
    point = json.loads(json.dumps(base))
    for axis in sweep["axes"]:
        point[axis["pointer"][1:]] = axis["values"][i]
    matches = [f for f in FILES
               if all(load(os.path.join(DEVICES, f)).get(p[1:]) == point.get(p[1:]) for p in pointers if p != "/description")]
    check(len(matches) == 1, f"sweep point {i} ({point['description']}) is exactly one device file: {matches}")


# The report's devices table (analysis/devices_table.py) on hand-made rows: mean and
# sample standard deviation over replications, [1, 3] -> 2 +- sqrt(2).
sys.path.insert(0, os.path.join(SOURCE_DIR, "analysis"))
import latsim_results as lr  # noqa: E402
import devices_table  # noqa: E402


def summary(rate, mtp):
    dist = lambda m: {"mean": m, "count": 4}  # noqa: E731
    return {"scenario": {"display": {"refresh_hz": rate}},
            "figures": {"motion_to_photon_ms": dist(mtp), "apparent_latency_ms_onset": dist(mtp / 10),
                        "apparent_latency_ms_steady": dist(0.5), "measured_latency_ms": dist(mtp / 2)}}


rows = [lr.Row("a", ["a0", "a1"], [summary(90, 1), summary(90, 3)], {"/description": "A 90 Hz"}),
        lr.Row("b", ["b0"], [summary("60000/1001", 20)], {"/description": "B"}),
        lr.Row("v", ["v0"], [summary(90, 80)], {"/description": "HTC Vive 90 Hz"})]
coll = lr.Collection("sweep", SCRATCH, rows, axes=["/description"])
table = "\n".join(devices_table.markdown(coll))
check("| A 90 Hz | 90 | 2.00 ± 1.41 |  | 0.20 ± 0.14 | 0.50 ± 0.00 |  |  | 1.00 ± 0.71 |  | 2 |" in table,
      f"row A: means and standard deviations over two replications:\n{table}")
check("| B | 59.9401 | 20.00 |  | 2.00 | 0.50 |  |  | 10.00 |  | 1 |" in table, "row B: one replication, no spread; 60000/1001 Hz")
# A device with public measurements: each beside the camera figure, with the difference (40 - 43.3 = -3.3).
check("43.3 ± 2.0 (-3.3): controller flick" in table and "30.8 (+9.2): controller movement onset" in table,
      f"the Vive's row sets the published measurements beside its camera figure:\n{table}")
check(devices_table.markdown(lr.Collection("sweep", SCRATCH, rows[:1], axes=["/description"])) == [],
      "one row is no comparison: no section")


# The report of a directory of two device runs has the devices section, one row each.
runs = os.path.join(SCRATCH, "devices_report")
shutil.rmtree(runs, ignore_errors=True)
os.makedirs(runs)
for name in ["index_90hz", "quest2_90hz"]:
    if os.path.isdir(os.path.join(OUT, name)):
        shutil.copytree(os.path.join(OUT, name), os.path.join(runs, name))
rep = subprocess.run([sys.executable, os.path.join(SOURCE_DIR, "analysis", "report.py"), runs, "--gantt-limit", "0"],
                     capture_output=True, text=True)
check(rep.returncode == 0, f"report of two device runs: {rep.stderr.strip()}")
md = open(os.path.join(runs, "report.md"), encoding="utf-8").read() if rep.returncode == 0 else ""
check("## Devices: what a headset measurement sees" in md, "the report has the devices section")
check("| index_90hz | 90 |" in md and "| quest2_90hz | 90 |" in md, "one row per device run, with its refresh rate")

if failures:
    print(f"{len(failures)} failures")
    sys.exit(1)
print("ok: device profiles")
