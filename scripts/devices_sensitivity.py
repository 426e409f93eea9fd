#!/usr/bin/env python3
"""The sensitivity table of docs/validation.md: how far the simulated camera
measurement of each validated profile moves when one assumption moves across
its plausible range, the others held at the profile's values.

For every profile and assumption it runs the profile at the assumption's low
and high value (and the profile as it is), each over the replications of the
devices sweep, and prints a Markdown table of the camera figure's mean
(measured_latency_ms, frame counting) at both ends and the change from the
profile's own figure. Runs go two at a time; a run whose results are already in OUT_DIR is not run again;
--only TEXT keeps the rows whose label holds TEXT:

    python3 scripts/devices_sensitivity.py build/latsim [OUT_DIR] [--only TEXT]
"""

import json
import os
import statistics
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEVICES = os.path.join(ROOT, "scenarios", "devices")
REPLICATIONS = 8

PROFILES = [
    ("index_144hz.json", "Index 144 Hz"),
    ("vive_90hz.json", "Vive 90 Hz"),
    ("vive_pro2_90hz.json", "Vive Pro 2 90 Hz"),
    ("vive_pro2_120hz.json", "Vive Pro 2 120 Hz"),
]

VARY = ["/pipeline/stages/0/cost/variation=normal"]
FRACTION = "/pipeline/stages/0/cost/variation_fraction="
MEAN = "/pipeline/stages/0/cost/fixed_ms="
CORRELATION = "/pipeline/stages/0/cost/variation_correlation_frames="

# (label, [--set values at the low end], [at the high end]); each a plausible range docs/devices.md gives.
ASSUMPTIONS = [
    ("running start 2 / 4 ms (3)", ["/pipeline/pacing/steamvr/running_start_ms=2"],
     ["/pipeline/pacing/steamvr/running_start_ms=4"]),
    ("render thread: no hand-over / a frame behind (a frame behind)", ["/pipeline/stages/1/start=after"],
     ["/pipeline/stages/1/start=next_frame"]),
    ("workload: the engine's light one / heavy, both held at every rate (VRChat's)",
     ["/pipeline/stages/0/cost/fixed_ms=2", "/pipeline/stages/1/cost/fixed_ms=1.5", "/pipeline/stages/2/cost/fixed_ms=3"],
     ["/pipeline/stages/0/cost/fixed_ms=@0.7T", "/pipeline/stages/1/cost/fixed_ms=@0.5T",
      "/pipeline/stages/2/cost/fixed_ms=@0.8T"]),
    ("VRChat's game thread 8 / 12 ms (9.5): holds 120 Hz, not 144 / holds 80 Hz, not 90",
     ["/pipeline/stages/0/cost/fixed_ms=8"], ["/pipeline/stages/0/cost/fixed_ms=12"]),
    # Frame-to-frame variability of the game thread (normal, sd as a fraction of the mean;
    # docs/devices.md: 5 to 25 % from the captures in shared/data), at the profile's mean,
    # then means near the 120 Hz budget (8.33 ms) with the captures' central spread (10 %).
    ("game thread varying by 5 % / 25 % (none)", VARY + [FRACTION + "0.05"], VARY + [FRACTION + "0.25"]),
    ("game thread 7 / 7.5 ms varying by 10 % (9.5, none)", VARY + [FRACTION + "0.1", MEAN + "7"],
     VARY + [FRACTION + "0.1", MEAN + "7.5"]),
    ("game thread 7.2 / 7.35 ms varying by 10 % (9.5, none)", VARY + [FRACTION + "0.1", MEAN + "7.2"],
     VARY + [FRACTION + "0.1", MEAN + "7.35"]),
    ("game thread 7.35 ms varying by 5 % / 20 % (9.5, none)", VARY + [FRACTION + "0.05", MEAN + "7.35"],
     VARY + [FRACTION + "0.2", MEAN + "7.35"]),
    # The same load varying slowly: a first-order autoregression over N frames (docs/devices.md:
    # the captures' per-second averages spread as much as their frames; 90, about a second, assumed).
    ("game thread varying by 10 % over 30 / 300 frames (none)",
     VARY + [FRACTION + "0.1", CORRELATION + "30"], VARY + [FRACTION + "0.1", CORRELATION + "300"]),
    ("game thread 8 / 9 ms varying by 10 % over 90 frames (9.5, none)",
     VARY + [FRACTION + "0.1", CORRELATION + "90", MEAN + "8"], VARY + [FRACTION + "0.1", CORRELATION + "90", MEAN + "9"]),
    ("game thread 8.5 / 9.5 ms varying by 10 % over 90 frames (9.5, none)",
     VARY + [FRACTION + "0.1", CORRELATION + "90", MEAN + "8.5"],
     VARY + [FRACTION + "0.1", CORRELATION + "90", MEAN + "9.5"]),
    ("host: none / the Vive recording's delay on every USB link and its lost reports",
     ["/transport/os_jitter_ms=0", "/tracker/imu/report_loss_probability=0"],
     ["/transport/os_jitter_ms=1.83", "/transport/os_jitter=exponential", "/tracker/imu/report_loss_probability=0.472",
      "/controller/transport/os_jitter_ms=1.83", "/controller/transport/os_jitter=exponential"]),
    ("controller reports 1000 / 125 Hz (250)", ["/controller/tracker/rate_hz=1000"], ["/controller/tracker/rate_hz=125"]),
    ("controller radio 1 / 4 ms (2)", ["/controller/transport/os_delay_ms=1"], ["/controller/transport/os_delay_ms=4"]),
    # The flick keeps its place in the head's rests: the rest makes up the head's period, the delay its start.
    ("flick 0.1 / 0.3 s (0.15)",
     ["/controller/motion/duration_s=0.1", "/controller/motion/rest_s=0.9137", "/controller/motion/delay_s=0.3"],
     ["/controller/motion/duration_s=0.3", "/controller/motion/rest_s=0.7137", "/controller/motion/delay_s=0.5"]),
    ("flick 20 / 60 deg (40)", ["/controller/motion/amplitude_deg=20"], ["/controller/motion/amplitude_deg=60"]),
    ("object seen moving at 0.2 / 2 deg (0.5)", ["/measurement/threshold_deg=0.2"], ["/measurement/threshold_deg=2"]),
    ("camera 240 / 120 fps", ["/measurement/fps=240", "/measurement/readout_ms=3.5"],
     ["/measurement/fps=120", "/measurement/readout_ms=6"]),
    ("shutter global / rolling, display 5 ms before the object", ["/measurement/shutter=global"],
     ["/measurement/shutter=rolling", "/measurement/object_row=1", "/measurement/display_row=0"]),
    ("LCD / OLED response 0.5 / 3 ms", ["/display/persistence/response_ms=0.5"], ["/display/persistence/response_ms=3"]),
    ("prediction from the fusion / none (fusion)", ["/host/prediction/type=fusion"], ["/host/prediction/type=none"]),
]


def expand(values, refresh_hz):
    """@0.7T: that fraction of the refresh period, in ms."""
    t = 1000.0 / refresh_hz
    out = []
    for v in values:
        pointer, value = v.split("=", 1)
        if value.startswith("@") and value.endswith("T"):
            value = f"{float(value[1:-1]) * t:.4f}"
        out.append(f"{pointer}={value}")
    return out


def refresh_of(name):
    digits = "".join(c if c.isdigit() else " " for c in name).split()
    return float(digits[-1]) if digits else 90.0


def run(job):
    latsim, out_dir, name, tag, sets, rep = job
    out = os.path.join(out_dir, f"{name[:-5]}_{tag}_{rep}")
    args = [latsim, "run", os.path.join(DEVICES, name), "--out", out, "-q", "--replication", str(rep)]
    for s in sets:
        args += ["--set", s]
    # A run already in OUT_DIR is kept (delete it to run it again).
    if not os.path.exists(os.path.join(out, "figures.json")):
        proc = subprocess.run(args, capture_output=True, text=True)
        if proc.returncode != 0:
            return None
    f = json.load(open(os.path.join(out, "figures.json"), encoding="utf-8"))["figures"]
    m = f.get("measured_latency_ms")
    return m["mean"] if isinstance(m, dict) and m.get("count", 0) > 0 else None


def mean_of(results):
    vals = [r for r in results if r is not None]
    return statistics.mean(vals) if vals else float("nan")


def main():
    args = sys.argv[1:]
    only = None
    if "--only" in args:
        i = args.index("--only")
        only = args[i + 1]
        del args[i:i + 2]
    latsim = args[0]
    out_dir = args[1] if len(args) > 1 else "/tmp/latsim_sensitivity"
    rows = [i for i, (label, _, _) in enumerate(ASSUMPTIONS) if only is None or only in label]
    os.makedirs(out_dir, exist_ok=True)
    jobs = []
    for name, _ in PROFILES:
        hz = refresh_of(name)
        jobs += [(latsim, out_dir, name, "base", [], r) for r in range(REPLICATIONS)]
        for i in rows:
            _, low, high = ASSUMPTIONS[i]
            jobs += [(latsim, out_dir, name, f"a{i}lo", expand(low, hz), r) for r in range(REPLICATIONS)]
            jobs += [(latsim, out_dir, name, f"a{i}hi", expand(high, hz), r) for r in range(REPLICATIONS)]
    with ThreadPoolExecutor(max_workers=2) as pool:
        results = list(pool.map(run, jobs))
    by = {}
    for job, value in zip(jobs, results):
        by.setdefault((job[2], job[3]), []).append(value)
    header = "| assumption (profile's value) | " + " | ".join(label for _, label in PROFILES) + " |"
    print(header)
    print("|" + "---|" * (len(PROFILES) + 1))
    print("| the profile as it is | " + " | ".join(f"{mean_of(by[(n, 'base')]):.1f}" for n, _ in PROFILES) + " |")
    for i in rows:
        label = ASSUMPTIONS[i][0]
        cells = []
        for n, _ in PROFILES:
            base = mean_of(by[(n, "base")])
            lo, hi = mean_of(by[(n, f"a{i}lo")]), mean_of(by[(n, f"a{i}hi")])
            cells.append(f"{lo - base:+.1f} / {hi - base:+.1f}")
        print(f"| {label} | " + " | ".join(cells) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
