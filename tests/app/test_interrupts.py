"""Interrupted and starved runs and sweeps leave nothing behind and resume intact.

SIGINT and SIGTERM stop `run` and `sweep` at the next event: one line, exit
130/143, no output directory of an unfinished run and no temporary file.
SIGKILL cannot be caught: the next call cleans up and finishes. A disk that
is full (a file-size limit, RLIMIT_FSIZE, which works the same unprivileged
and as root) fails in one line naming the file and the reason, with the
counts of runs; no partial or empty file is left, and after room is made the
same command finishes with exactly the results of an undisturbed sweep.
Every wait is on a file the program writes, never on the clock.

Usage: test_interrupts.py LATSIM SOURCE_DIR SCRATCH_DIR
"""

import glob
import json
import os
import resource
import shutil
import signal
import subprocess
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "sweep"))
from sweep_checks import check, finish, table  # noqa: E402

LATSIM, SOURCE_DIR, SCRATCH = sys.argv[1:4]
BASE = os.path.join(SOURCE_DIR, "scenarios", "hmd_60hz_direct.json")
# Long enough that no run or sweep below can end before its signal arrives.
LONG = ["--set", "/duration_s=100000"]


def latsim(*args, limit_bytes=None):
    def starve():
        # The kernel's answer to a write past the limit is SIGXFSZ; ignored, it is EFBIG.
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit_bytes, limit_bytes))
    return subprocess.run([LATSIM, *args], capture_output=True, text=True,
                          preexec_fn=starve if limit_bytes is not None else None)


def leftovers(directory):
    """Temporary files and staging directories under or beside `directory`."""
    parent, name = os.path.split(directory.rstrip("/"))
    found = [p for p in glob.glob(os.path.join(directory, "**", "*"), recursive=True) if ".tmp" in os.path.basename(p)]
    return found + glob.glob(os.path.join(parent, name + ".tmp*"))


def wait_for(child, ready, what):
    """Waits (bounded) until ready() holds while the child still runs."""
    deadline = time.monotonic() + 300
    while time.monotonic() < deadline and child.poll() is None and not ready():
        time.sleep(0.01)
    check(child.poll() is None, f"{what}: the process ended before the signal (exit {child.returncode})")


def progress_shown(log):
    return lambda: os.path.exists(log) and "run: simulated" in open(log, errors="replace").read()


shutil.rmtree(SCRATCH, ignore_errors=True)
os.makedirs(SCRATCH)

# 1. run: SIGINT and SIGTERM once it is simulating (its progress line says so).
for sig, code in ((signal.SIGINT, 130), (signal.SIGTERM, 143)):
    out, log = os.path.join(SCRATCH, f"run_{sig.name}"), os.path.join(SCRATCH, f"run_{sig.name}.log")
    with open(log, "w") as err:
        child = subprocess.Popen([LATSIM, "run", BASE, "--out", out, "--progress", *LONG], stdout=subprocess.DEVNULL,
                                 stderr=err)
        wait_for(child, progress_shown(log), f"run {sig.name}")
        sent = time.monotonic()
        child.send_signal(sig)
        child.wait()
        took = time.monotonic() - sent
    lines = [l for l in open(log).read().splitlines() if not l.startswith("run: simulated")]
    check(child.returncode == code, f"run {sig.name}: exit {child.returncode}, want {code}")
    # The stop flag is read at every event: the bound the contract states (a
    # second) is met with orders of magnitude to spare (milliseconds here).
    check(took < 1.0, f"run {sig.name}: took {took:.3f} s to stop")
    check(len(lines) == 1 and f"stopped by {sig.name}" in lines[0], f"run {sig.name}: stderr {lines}")
    check(not os.path.exists(out), f"run {sig.name}: output directory left")
    check(not leftovers(out), f"run {sig.name}: temporaries left: {leftovers(out)}")

# 2. run: SIGKILL leaves a staging directory at most; the next run removes it and writes whole results.
out, log = os.path.join(SCRATCH, "run_kill"), os.path.join(SCRATCH, "run_kill.log")
with open(log, "w") as err:
    child = subprocess.Popen([LATSIM, "run", BASE, "--out", out, "--progress", *LONG], stdout=subprocess.DEVNULL,
                             stderr=err)
    wait_for(child, progress_shown(log), "run SIGKILL")
    child.send_signal(signal.SIGKILL)
    child.wait()
check(not os.path.exists(out), "run SIGKILL: a run directory appeared for an unfinished run")
proc = latsim("run", BASE, "--out", out, "--set", "/duration_s=1", "-q")
check(proc.returncode == 0, f"run after SIGKILL: exit {proc.returncode} {proc.stderr}")
check(not leftovers(out), f"run after SIGKILL: leftovers {leftovers(out)}")
reference = os.path.join(SCRATCH, "run_reference")
latsim("run", BASE, "--out", reference, "--set", "/duration_s=1", "-q")
check(open(os.path.join(out, "figures.json")).read() == open(os.path.join(reference, "figures.json")).read(),
      "run after SIGKILL: figures differ from an undisturbed run")

# 3. run on a full disk: exit 1, one line naming the file and errno's text, nothing left.
out = os.path.join(SCRATCH, "run_full")
proc = latsim("run", BASE, "--out", out, "--set", "/duration_s=1", limit_bytes=4096)
check(proc.returncode == 1, f"run on a full disk: exit {proc.returncode}")
check(len(proc.stderr.splitlines()) == 1 and "File too large" in proc.stderr and "cannot write" in proc.stderr,
      f"run on a full disk: {proc.stderr.strip()}")
check(not os.path.exists(out) and not leftovers(out), f"run on a full disk left {leftovers(out)}")

# 4. sweep: a reference, then SIGINT / SIGTERM after the first finished run, then resume.
sweep = os.path.join(SCRATCH, "sweep.json")
with open(sweep, "w") as f:
    json.dump({"base": BASE, "overrides": {"/duration_s": 20, "/tracker/jitter_ms": 1}, "replications": 2, "seed": 5,
               "axes": [{"pointer": "/tracker/rate_hz", "values": [60, 120, 240, 480, 1000, 2000]}]}, f)
ref_dir = os.path.join(SCRATCH, "sweep_reference")
proc = latsim("sweep", sweep, "--out", ref_dir, "-j", "2")
check(proc.returncode == 0, f"reference sweep: exit {proc.returncode} {proc.stderr}")
reference = table(ref_dir)


def summaries(directory):
    """The runs marked finished (DIR/done/<run id>; .mark.* files are what the marks link to)."""
    return [p for p in glob.glob(os.path.join(directory, "done", "*")) if not os.path.basename(p).startswith(".")]


for sig, code in ((signal.SIGINT, 130), (signal.SIGTERM, 143)):
    out = os.path.join(SCRATCH, f"sweep_{sig.name}")
    child = subprocess.Popen([LATSIM, "sweep", sweep, "--out", out, "-j", "2"], stdout=subprocess.DEVNULL,
                             stderr=subprocess.PIPE, text=True)
    wait_for(child, lambda: len(summaries(out)) >= 1, f"sweep {sig.name}")
    child.send_signal(sig)
    stderr = child.communicate()[1]
    check(child.returncode == code, f"sweep {sig.name}: exit {child.returncode}, want {code}")
    lines = stderr.splitlines()
    check(len(lines) == 1 and f"stopped by {sig.name}" in lines[0], f"sweep {sig.name}: stderr {lines}")
    check(not leftovers(out), f"sweep {sig.name}: temporaries left: {leftovers(out)}")
    done_before = len(summaries(out))
    check(0 < done_before < 12, f"sweep {sig.name}: {done_before} runs finished before the stop")
    proc = latsim("sweep", sweep, "--out", out, "-j", "2")
    check(proc.returncode == 0, f"sweep resumed after {sig.name}: exit {proc.returncode} {proc.stderr}")
    check(f"({done_before} resumed" in proc.stdout, f"sweep after {sig.name} did not resume: {proc.stdout.strip()}")
    check(table(out) == reference, f"sweep after {sig.name}: results differ from the undisturbed sweep")
    check(not leftovers(out), f"sweep after {sig.name}: temporaries left")

# 5. sweep on a full disk: one line with the file, the reason and the counts; resumes intact.
# A run's record is about 1.5 KB (its segment's first, 2.5 KB): a file may
# take two or three of them before the limit, and the plan fits.
out = os.path.join(SCRATCH, "sweep_full")
proc = latsim("sweep", sweep, "--out", out, "-j", "2", limit_bytes=4096)
check(proc.returncode == 1, f"sweep on a full disk: exit {proc.returncode} {proc.stderr}")
lines = [l for l in proc.stderr.splitlines() if not l.startswith("sweep: ") or "stopped" in l or "failed" in l]
check(len(lines) == 1 and "File too large" in lines[0] and "finished" in lines[0] and "failed" in lines[0],
      f"sweep on a full disk: {proc.stderr.strip()}")
check(not leftovers(out), f"sweep on a full disk: temporaries left: {leftovers(out)}")
check(len(summaries(out)) < 12, "sweep on a full disk: every run finished")
sys.path.insert(0, os.path.join(SOURCE_DIR, "analysis"))
import latsim_store  # noqa: E402
finished_store = latsim_store.SweepStore(out)
check(all(os.path.basename(p) in finished_store for p in summaries(out)),
      "sweep on a full disk: a run marked finished has no record")
proc = latsim("sweep", sweep, "--out", out, "-j", "2")
check(proc.returncode == 0, f"sweep after room was made: exit {proc.returncode} {proc.stderr}")
check(table(out) == reference, "sweep after a full disk: results differ from the undisturbed sweep")

# 6. report on a full disk: one line, no traceback, no partial or empty file.
# matplotlib builds its font cache on first use; on a fresh machine that
# write would also hit the limit and add a warning of matplotlib's own, so
# the cache is built first, without a limit, by the Python that latsim runs.
python = "/usr/bin/python3" if os.path.exists("/usr/bin/python3") else "python3"
subprocess.run([python, "-c", "import matplotlib.font_manager"], capture_output=True, check=False)
proc = latsim("report", ref_dir, limit_bytes=64)
check(proc.returncode == 1, f"report on a full disk: exit {proc.returncode}")
check(len(proc.stderr.strip().splitlines()) == 1 and "Traceback" not in proc.stderr, f"report: {proc.stderr.strip()}")
check(not leftovers(ref_dir), f"report on a full disk: temporaries left: {leftovers(ref_dir)}")

finish("interrupts and full disks")
