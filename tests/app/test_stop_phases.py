"""SIGTERM and SIGINT end every command in every phase within a second.

Each case starts a command, waits until it is in the phase named (a file it
writes, its CPU time, or its child process: never a fixed sleep), sends the
signal and then checks what the contract (issue 47) states: the exit status
128 + the signal's number, one line on stderr naming the signal, no
temporary ("*.tmp*") and no output directory of unfinished work left, and no
child process outliving its parent. The second is the contract's bound; the
flag is looked at every event or every few thousand steps of a
post-processing loop, and a watchdog ends a phase that cannot look at it at
StopSignals' deadline (800 ms), so every case has room to spare.

Usage: test_stop_phases.py LATSIM SOURCE_DIR SCRATCH_DIR
"""

import glob
import os
import shutil
import signal
import subprocess
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "sweep"))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from sweep_checks import check, finish  # noqa: E402
from stop_checks import BOUND_S, alive, children_of, cpu_seconds, expect_stopped, leftovers, stop, wait_until  # noqa: E402

LATSIM, SOURCE_DIR, SCRATCH = sys.argv[1:4]
BASE = os.path.abspath(os.path.join(SOURCE_DIR, "scenarios", "hmd_60hz_direct.json"))
RIG = os.path.join(SOURCE_DIR, "scenarios", "measurement", "min_jerk_rig.json")
# Long enough that nothing below ends before its signal arrives.
LONG = ["--set", "/duration_s=100000"]


def start(*args, env=None):
    return subprocess.Popen([LATSIM, *args], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, env=env)


shutil.rmtree(SCRATCH, ignore_errors=True)
os.makedirs(SCRATCH)

# 1. run, after the simulation: apparent latency's windows a microsecond
# apart over 2 s of simulated time (2e6 windows, each a fit over its
# samples: minutes), which the event budget refuses unless --max-events 0.
# Simulating 2 s of this scenario costs milliseconds: CPU time past 1.5 s
# is spent in post-processing, which the stop line names.
for sig in (signal.SIGTERM, signal.SIGINT):
    out = os.path.join(SCRATCH, f"post_{sig.name}")
    child = start("run", RIG, "--out", out, "--set", "/duration_s=2", "--set", "/apparent_latency/step_ms=0.001",
                  "--max-events", "0", "-q")
    if wait_until(child, lambda: cpu_seconds(child.pid) > 1.5, f"run in post-processing ({sig.name})"):
        expect_stopped(f"run in post-processing ({sig.name})", sig, stop(child, sig), out,
                       "while computing and writing its figures")

# 2. optimise, in its runs (in-process; no signal handling once made it exit
# silently): CPU time past what loading and validating cost.
out = os.path.join(SCRATCH, "optimise")
child = start("optimise", BASE, "--vary", "/pipeline/render/fixed_ms=1:10", "--minimise", "motion_to_photon_ms.mean",
              "--out", out, *LONG)
if wait_until(child, lambda: cpu_seconds(child.pid) > 0.5, "optimise"):
    expect_stopped("optimise", signal.SIGTERM, stop(child, signal.SIGTERM), out, "after 0 setting(s)")

# 3. capacity, likewise.
out = os.path.join(SCRATCH, "capacity")
child = start("capacity", BASE, "--out", out, *LONG)
if wait_until(child, lambda: cpu_seconds(child.pid) > 0.5, "capacity"):
    expect_stopped("capacity", signal.SIGTERM, stop(child, signal.SIGTERM), out, "after 0 count(s)")

# 4. fidelity, while a level runs in its child: the child ends with its
# parent (no orphan still writing levels/), and the unfinished table leaves
# no directory. The level's child is seen by its staging directory. The one
# line is the child's (the run it stopped, and nothing written); the
# parent, whose child spoke for it, adds none, and removes the directory
# it made with the level that had finished.
# The levels are durations: the first (1 s, also run in memory to check the
# metric) ends at once, the second (1e5 s) runs until the signal; it is the
# one waited for.
FIDELITY = ["--vary", "/duration_s=1,100000", "--metric", "motion_to_photon_ms.mean"]
out = os.path.join(SCRATCH, "fidelity")
child = start("fidelity", BASE, *FIDELITY, "--out", out)
levels = os.path.join(out, "levels")
kids = []
def level_running():
    kids[:] = children_of(child.pid)
    return bool(kids) and bool(glob.glob(os.path.join(levels, "*100000.tmp.*")))
if wait_until(child, level_running, "fidelity level"):
    expect_stopped("fidelity", signal.SIGTERM, stop(child, signal.SIGTERM), out, "interrupted at simulated t")
    check(not os.path.exists(out), "fidelity: the finished first level was left")
    gone_by = time.monotonic() + BOUND_S
    while time.monotonic() < gone_by and any(alive(k) for k in kids):
        time.sleep(0.01)
    check(not any(alive(k) for k in kids), f"fidelity: its level child {kids} outlived it")

# 5. fidelity killed outright (SIGKILL): the level child still ends (it is
# told when its parent dies) and removes its staging directory.
out = os.path.join(SCRATCH, "fidelity_kill")
child = start("fidelity", BASE, *FIDELITY, "--out", out)
levels = os.path.join(out, "levels")
if wait_until(child, level_running, "fidelity level (SIGKILL)"):
    child.kill()
    child.communicate()
    gone_by = time.monotonic() + BOUND_S
    while time.monotonic() < gone_by and any(alive(k) for k in kids):
        time.sleep(0.01)
    check(not any(alive(k) for k in kids), f"fidelity SIGKILL: its level child {kids} outlived it")
    check(not glob.glob(os.path.join(levels, "*.tmp.*")), "fidelity SIGKILL: the level's staging directory was left")

# 5b. report, while its Python child draws: the child is passed the signal,
# takes back what it wrote and says so in the one line; the directory is as
# it was. A sweep of 12 points, each kept whole, takes seconds to draw;
# ready once the child has spent a CPU second (past importing matplotlib).
import json  # noqa: E402
sweep_file = os.path.join(SCRATCH, "report_sweep.json")
with open(sweep_file, "w") as f:
    json.dump({"base": BASE, "overrides": {"/duration_s": 1}, "keep": "all",
               "axes": [{"pointer": "/tracker/rate_hz", "values": [60, 90, 120, 180, 240, 360]},
                        {"pointer": "/display/refresh_hz", "values": [60, 120]}]}, f)
report_dir = os.path.join(SCRATCH, "report_sweep")
done = subprocess.run([LATSIM, "sweep", sweep_file, "--out", report_dir, "-j", "2"], capture_output=True, text=True)
check(done.returncode == 0, f"report's sweep: {done.stderr.strip()}")
before = sorted(os.listdir(report_dir))
child = start("report", report_dir)
drawing = []
def report_drawing():
    drawing[:] = children_of(child.pid)
    return bool(drawing) and cpu_seconds(drawing[0]) > 1.0
if wait_until(child, report_drawing, "report"):
    result = stop(child, signal.SIGTERM)
    expect_stopped("report", signal.SIGTERM, result, None, "report: stopped by SIGTERM; nothing written")
    check(sorted(os.listdir(report_dir)) == before, "report: files were left in the directory")
    check(not leftovers(report_dir), f"report: temporaries left: {leftovers(report_dir)}")
    gone_by = time.monotonic() + BOUND_S
    while time.monotonic() < gone_by and any(alive(k) for k in drawing):
        time.sleep(0.01)
    check(not any(alive(k) for k in drawing), "report: its Python child outlived it")

# 6. A deadline of 1 ms (the variable run_child sets for its children): the
# watchdog and the run's own stop race, and whichever ends the run, it ends
# with one line, exit 143 and nothing left (the watchdog removes the
# registered staging directory itself).
env = dict(os.environ, LATSIM_STOP_DEADLINE_MS="1")
out = os.path.join(SCRATCH, "watchdog")
child = start("run", BASE, "--out", out, *LONG, env=env)
staging = lambda: bool(glob.glob(out + ".tmp.*"))  # noqa: E731
if wait_until(child, staging, "run under the watchdog"):
    expect_stopped("run under the watchdog", signal.SIGTERM, stop(child, signal.SIGTERM), out)

finish("stop in every phase")
