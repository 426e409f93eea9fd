"""Program-level checks of latsim sweep, fidelity and report on short scenarios:
bad input writes nothing, -j1 and -j2 give identical tables, a sweep killed
with SIGKILL resumes with no run lost or duplicated and no temporary file
left, the fidelity error is zero at the finest level, and the report renders.

Usage: test_sweep_program.py LATSIM SOURCE_DIR SCRATCH_DIR
"""

import csv
import glob
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import time

from sweep_checks import check, finish, table

LATSIM, SOURCE_DIR, SCRATCH = sys.argv[1:4]
BASE = os.path.join(SOURCE_DIR, "scenarios", "hmd_60hz_direct.json")


def latsim(*args):
    return subprocess.run([LATSIM, *args], capture_output=True, text=True)


def write_sweep(name, sweep):
    path = os.path.join(SCRATCH, name)
    with open(path, "w") as f:
        json.dump(sweep, f)
    return path


def temporaries(directory):
    return [p for p in glob.glob(os.path.join(directory, "**", "*"), recursive=True) if ".tmp" in os.path.basename(p)]


shutil.rmtree(SCRATCH, ignore_errors=True)
os.makedirs(SCRATCH)

# 1. Bad input: named with its JSON pointer, exit 2, nothing written.
bad = write_sweep("bad_pointer.json", {"base": BASE, "axes": [{"pointer": "/display/no_such_key", "values": [1, 2]}]})
out = os.path.join(SCRATCH, "bad_out")
proc = latsim("sweep", bad, "--out", out)
check(proc.returncode == 2, f"bad pointer: exit {proc.returncode}")
check("bad_pointer.json: /axes/0/pointer:" in proc.stderr and "/display/no_such_key" in proc.stderr,
      f"bad pointer message: {proc.stderr.strip()}")
check(not os.path.exists(out), "bad pointer: output directory was created")
bad = write_sweep("bad_value.json", {"base": BASE, "axes": [{"pointer": "/tracker/rate_hz", "values": [60, -5]}]})
proc = latsim("sweep", bad, "--out", out)
check(proc.returncode == 2 and "/axes/0/values/1: /tracker/rate_hz" in proc.stderr, f"bad value: {proc.stderr.strip()}")
check(not os.path.exists(out), "bad value: output directory was created")

# 2. Identical results for -j1 and -j2.
sweep = write_sweep("small.json", {
    "base": BASE, "overrides": {"/duration_s": 2}, "replications": 2, "seed": 3,
    "axes": [{"pointer": "/display/refresh_hz", "values": [60, "60000/1001"]},
             {"pointer": "/tracker/rate_hz", "range": {"from": 60, "to": 240, "step": 60}},
             {"pointer": "/display/interlaced", "values": [False, True]}]})
j1, j2 = os.path.join(SCRATCH, "j1"), os.path.join(SCRATCH, "j2")
proc = latsim("sweep", sweep, "--out", j1, "-j", "1")
check(proc.returncode == 0, f"sweep -j1: exit {proc.returncode} {proc.stderr}")
proc = latsim("sweep", sweep, "--out", j2, "-j", "2")
check(proc.returncode == 0, f"sweep -j2: exit {proc.returncode} {proc.stderr}")
reference = table(j1)
check(len(reference) == 1 + 32, f"results.csv has {len(reference) - 1} rows, expected 32")
check(reference == table(j2), "results.csv differs between -j1 and -j2")
check(os.path.getsize(os.path.join(j2, "results.sqlite")) > 0, "results.sqlite missing")
with open(os.path.join(j1, "plan.json")) as f:
    plan_ids = [r["run_id"] for r in json.load(f)["runs"]]
check([r[0] for r in reference[1:]] == plan_ids, "results.csv rows are not in plan order")

# 3. Kill -9 in the middle, damage the directory as a crash would, resume.
killed = os.path.join(SCRATCH, "killed")


def finished_runs(directory):
    """Runs marked finished: DIR/done/<run id> (the .mark.* files are what the marks link to)."""
    return [n for n in os.listdir(os.path.join(directory, "done")) if not n.startswith(".")] \
        if os.path.isdir(os.path.join(directory, "done")) else []


# It keeps the traces of replication 0 (for the report's Gantt charts below);
# the tables must still equal those of -j1 and -j2, which kept none.
child = subprocess.Popen([LATSIM, "sweep", sweep, "--out", killed, "-j", "2", "--keep", "first"], stdout=subprocess.DEVNULL,
                         stderr=subprocess.DEVNULL)
deadline = time.monotonic() + 60
while time.monotonic() < deadline and child.poll() is None:
    if len(finished_runs(killed)) >= 4:
        break
    time.sleep(0.005)
if child.poll() is None:
    child.send_signal(signal.SIGKILL)
child.wait()
check(child.returncode == -signal.SIGKILL, f"the sweep ended before it could be killed (exit {child.returncode})")
check(len(finished_runs(killed)) >= 1, "no run finished before the kill")
# A run killed while its record was being appended: the frame is cut short and
# the run is not marked finished. The last frame of the largest segment plays it.
sys.path.insert(0, os.path.join(SOURCE_DIR, "analysis"))
import latsim_store  # noqa: E402
segments = sorted(glob.glob(os.path.join(killed, "store", "*.seg")), key=os.path.getsize)
with open(segments[-1], "rb") as f:
    data = f.read()
at, last = len(latsim_store.SEGMENT_MAGIC), None
while at + latsim_store.HEADER <= len(data):
    length, _, run = latsim_store.struct.unpack_from("<IIQ", data, at + 4)
    last, at = (f"{run:016x}", at), at + latsim_store.HEADER + length
victim, victim_at = last
with open(segments[-1], "r+b") as f:
    f.truncate(victim_at + latsim_store.HEADER + 10)
if os.path.exists(os.path.join(killed, "done", victim)):
    os.remove(os.path.join(killed, "done", victim))
check(victim not in latsim_store.SweepStore(killed), "the frame cut short is still read")
# A kept run's files half staged, and a table half written.
os.makedirs(os.path.join(killed, "runs", victim + ".tmp"), exist_ok=True)
with open(os.path.join(killed, "runs", victim + ".tmp", "summary.json"), "w") as f:
    f.write('{"events": 12')
with open(os.path.join(killed, "results.csv.tmp.99999"), "w") as f:
    f.write("run_id,po")
proc = latsim("sweep", sweep, "--out", killed, "-j", "2", "--keep", "first")
check(proc.returncode == 0, f"resumed sweep: exit {proc.returncode} {proc.stderr}")
# At least the two planted: a kill during a write legitimately leaves another,
# and the staging directory of each run the kill caught midway (every one
# must be gone afterwards, checked below).
removed = re.search(r"removed (\d+) unfinished temporary file", proc.stderr)
check(removed is not None and int(removed.group(1)) >= 2, f"resume did not report the stray files: {proc.stderr}")
check(" resumed," in proc.stdout and "(0 resumed" not in proc.stdout, f"nothing was resumed: {proc.stdout}")
resumed = table(killed)
ids = [r[0] for r in resumed[1:]]
check(len(ids) == len(set(ids)) == 32, f"resumed sweep has {len(ids)} rows, {len(set(ids))} distinct")
check(resumed == reference, "resumed results.csv differs from the uninterrupted one")
check(not temporaries(killed), f"temporary files left: {temporaries(killed)}")
check(len(finished_runs(killed)) == 32, "not every run is marked finished")
check(victim in latsim_store.SweepStore(killed), "the run cut short has no record after the resume")
with open(os.path.join(killed, "plan.json")) as f:
    plan_runs = json.load(f)["runs"]
kept = sorted(d for d in os.listdir(os.path.join(killed, "runs")))
check(kept == sorted(r["run_id"] for r in plan_runs if r["replication"] == 0),
      f"--keep first: {len(kept)} run directories, expected replication 0 of each of the 16 points")
check(all(os.path.isfile(os.path.join(killed, "runs", d, "summary.json")) for d in kept), "a kept run has no summary.json")

# 4. A second call on a finished sweep runs nothing and changes nothing.
proc = latsim("sweep", sweep, "--out", killed, "-j", "2")
check(proc.returncode == 0 and "(32 resumed, 0 run now" in proc.stdout, f"rerun: {proc.stdout}")
check(table(killed) == reference, "rerun changed results.csv")

# 5. Fidelity: the error column is exactly zero at the finest level.
fid = os.path.join(SCRATCH, "fidelity")
proc = latsim("fidelity", BASE, "--vary", "/display/scanout=field,line", "--set", "/duration_s=1",
              "--metric", "motion_to_photon_ms.p99", "--out", fid)
check(proc.returncode == 0, f"fidelity: exit {proc.returncode} {proc.stderr}")
# The cost is said before it is paid: line scanout adds 480 - 1 events per
# field to field scanout's one, 479 x 60 = 28,740 in 1 s (printed to 2 digits).
import re  # noqa: E402
priced = re.search(r"fidelity: 2 levels, expected events field ([0-9.e+]+), line ([0-9.e+]+); .* about [0-9.e+-]+ s",
                   proc.stderr)
check(priced is not None, f"fidelity should print its expected cost first: {proc.stderr}")
if priced:
    field_events, line_events = float(priced.group(1)), float(priced.group(2))
    check(abs(line_events - field_events - 28740) <= 0.05 * line_events, f"expected events {priced.group(0)}")
with open(os.path.join(fid, "fidelity.csv"), newline="") as f:
    levels = list(csv.DictReader(f))
check(len(levels) == 2 and levels[-1]["/display/scanout"] == "line", f"fidelity levels {levels}")
check(levels[-1]["abs_error"] == "0" and levels[-1]["rel_error"] == "0", f"finest level error {levels[-1]}")
check(int(levels[1]["events"]) > int(levels[0]["events"]), "line scanout should cost more events than field")
for name in ("fidelity.md", "fidelity.png", "fidelity.svg"):
    check(os.path.isfile(os.path.join(fid, name)), f"fidelity: {name} missing")
proc = latsim("fidelity", BASE, "--vary", "/display/scanout=field,sideways", "--metric", "x", "--out", fid + "_bad")
check(proc.returncode == 2 and not os.path.exists(fid + "_bad"), f"fidelity bad level: {proc.returncode} {proc.stderr}")
# An unknown metric is found before anything is written (it once ran level 0,
# left levels/0_field behind and printed every figure on an 868-character line).
proc = latsim("fidelity", BASE, "--vary", "/display/scanout=field,line", "--set", "/duration_s=1",
              "--metric", "no_such_figure.mean", "--out", fid + "_metric")
lines = proc.stderr.strip().splitlines()
check(proc.returncode == 2 and not os.path.exists(fid + "_metric"), f"fidelity bad metric: {proc.returncode} {proc.stderr}")
check(len(lines) == 1 and len(lines[0]) <= 300 and "no_such_figure.mean" in lines[0] and "motion_to_photon_ms" in lines[0],
      f"fidelity bad metric message: {proc.stderr}")

# 6. The report renders from the sweep directory.
proc = latsim("report", killed, "--gantt-limit", "1")
check(proc.returncode == 0, f"report: exit {proc.returncode} {proc.stderr}")
with open(os.path.join(killed, "latency_table.csv"), newline="") as f:
    check(len(list(csv.DictReader(f))) == 16, "report: latency table should have one row per sweep point")
for name in ("report.md", "mtp_cdf.png", "mtp_histogram.svg", "sweep_rate_hz.png", "sweep_interlaced.svg"):
    check(os.path.isfile(os.path.join(killed, name)), f"report: {name} missing")
check(len(glob.glob(os.path.join(killed, "runs", "*", "gantt.png"))) == 1, "report: --gantt-limit 1 not honoured")
check(latsim("report", os.path.join(SCRATCH, "nowhere")).returncode == 2, "report on a missing directory")

finish("sweep program")
