"""Which files the runs of a sweep keep (--keep and the sweep file's "keep"):
by default none (every run's summary is its record in the results store);
figures.json, summary.json and the traces (timeline, ledger) only for the runs
chosen; the figures are the same whatever is kept; a bad value is one line,
exit 2, nothing written; the report samples its Gantt charts.

Usage: test_sweep_keep.py LATSIM SOURCE_DIR SCRATCH_DIR
"""

import glob
import json
import os
import shutil
import subprocess
import sys

from sweep_checks import check, finish, table

LATSIM, SOURCE_DIR, SCRATCH = sys.argv[1:4]
sys.path.insert(0, os.path.join(SOURCE_DIR, "analysis"))
import latsim_store  # noqa: E402

BASE = os.path.join(SOURCE_DIR, "scenarios", "hmd_60hz_direct.json")
FIGURES_ONLY = ["figures.json", "summary.json"]
# What figures.json holds of a summary: what the scenario and seed determine.
DETERMINED = ["latsim", "seed", "replication", "scenario", "figures", "headline", "warnings", "events",
              "events_per_model", "fingerprint"]


def latsim(*args):
    return subprocess.run([LATSIM, *args], capture_output=True, text=True)


def write_sweep(name, extra=None):
    """8 points (refresh 2 x tracker rate 4) x 2 replications of 1 s: 16 runs."""
    sweep = {"base": BASE, "overrides": {"/duration_s": 1}, "replications": 2, "seed": 5,
             "axes": [{"pointer": "/display/refresh_hz", "values": [60, "60000/1001"]},
                      {"pointer": "/tracker/rate_hz", "values": [60, 120, 180, 240]}]}
    sweep.update(extra or {})
    path = os.path.join(SCRATCH, name)
    with open(path, "w") as f:
        json.dump(sweep, f)
    return path


def run_files(directory):
    """{plan position: sorted file names of that run (none without a run directory)}, from plan.json."""
    with open(os.path.join(directory, "plan.json")) as f:
        runs = json.load(f)["runs"]
    files = {}
    for i, r in enumerate(runs):
        run_dir = os.path.join(directory, "runs", r["run_id"])
        files[i] = sorted(os.listdir(run_dir)) if os.path.isdir(run_dir) else []
    return files, runs


def sweep_ok(name, sweep, *args):
    out = os.path.join(SCRATCH, name)
    proc = latsim("sweep", sweep, "--out", out, "-j", "2", *args)
    check(proc.returncode == 0, f"{name}: exit {proc.returncode} {proc.stderr}")
    return out, proc


shutil.rmtree(SCRATCH, ignore_errors=True)
os.makedirs(SCRATCH)
sweep = write_sweep("keep.json")

# 1. Default: no run keeps a file of its own; each has its record in the store.
default, _ = sweep_ok("default", sweep)
files, runs = run_files(default)
check(len(files) == 16, f"default: {len(files)} runs")
check(all(names == [] for names in files.values()), f"default keeps files: {files[0]}")
check(os.listdir(os.path.join(default, "runs")) == [], "default: run directories made")
store = latsim_store.SweepStore(default)
check(all(r["run_id"] in store for r in runs), "default: a run has no record in the store")

# 2. first: replication 0 of each point keeps its summary and timeline; the others nothing.
first, _ = sweep_ok("first", sweep, "--keep", "first")
files, runs = run_files(first)
for i, r in enumerate(runs):
    expected = sorted(FIGURES_ONLY + ["timeline.csv", "timeline.json"]) if r["replication"] == 0 else []
    check(files[i] == expected, f"first: run {i} (replication {r['replication']}) has {files[i]}")

# 3. all with the ledger: every run keeps its traces, and each figures.json
# holds what the default's record holds (keeping files changes no figure) and
# equals its summary.json but for the bookkeeping.
every, _ = sweep_ok("all", sweep, "--keep", "all", "--ledger")
files, runs = run_files(every)
check(all({"timeline.csv", "frames.csv"} <= set(names) for names in files.values()), f"all: {files[0]}")
every_store = latsim_store.SweepStore(every)
for r in runs:
    with open(os.path.join(every, "runs", r["run_id"], "figures.json"), "rb") as f:
        kept = json.load(f)
    recorded = store.summary(r["run_id"])
    check(kept == {k: recorded[k] for k in DETERMINED if k in recorded},
          f"figures.json of {r['run_id']} differs from the record of --keep figures")
    with open(os.path.join(every, "runs", r["run_id"], "summary.json"), "rb") as f:
        kept_summary = json.load(f)
    check(kept_summary == every_store.summary(r["run_id"]), f"{r['run_id']}: its record and summary.json differ")
check(table(default) == table(every), "results.csv differs between --keep figures and all")

# 4. runs=I,J: exactly those plan positions keep traces (ledger with them).
chosen, _ = sweep_ok("chosen", sweep, "--keep", "runs=1,14", "--ledger")
files, _ = run_files(chosen)
with_traces = sorted(i for i, names in files.items() if "timeline.csv" in names)
with_ledger = sorted(i for i, names in files.items() if "frames.csv" in names)
check(with_traces == [1, 14] and with_ledger == [1, 14], f"runs=1,14 kept traces of {with_traces}, ledger {with_ledger}")

# 5. The sweep file's key, and --keep over it.
keyed = write_sweep("keyed.json", {"keep": "runs=3"})
from_file, _ = sweep_ok("from_file", keyed)
files, _ = run_files(from_file)
check(sorted(i for i, n in files.items() if "timeline.csv" in n) == [3], "sweep file keep runs=3 not honoured")
overridden, _ = sweep_ok("overridden", keyed, "--keep", "figures")
files, _ = run_files(overridden)
check(all(n == [] for n in files.values()), "--keep figures did not override the file's keep")

# 6. The ledger without a run kept in full: a warning, and the sweep runs.
_, proc = sweep_ok("ledger_warned", sweep, "--ledger")
check("warning" in proc.stderr and "--keep" in proc.stderr, f"--ledger without --keep: no warning: {proc.stderr}")

# 7. Bad values: one line on stderr, exit 2, nothing written.
for value, says in [("some", "expected figures, first, all or runs="), ("runs=", "is not a run position"),
                    ("runs=1,x", "\"x\" is not a run position"), ("runs=16", "run 16 is not in the plan"),
                    ("runs=-1", "is not a run position"), ("", "expected figures")]:
    out = os.path.join(SCRATCH, "bad_keep")
    proc = latsim("sweep", sweep, "--out", out, "--keep", value)
    lines = proc.stderr.strip().splitlines()
    check(proc.returncode == 2 and len(lines) == 1 and "--keep" in lines[0] and says in lines[0],
          f"--keep {value!r}: exit {proc.returncode} {proc.stderr!r}")
    check(not os.path.exists(out), f"--keep {value!r}: output directory was created")
for value, says in [(3, "expected a string"), ("runs=99", "run 99 is not in the plan"), ("last", "expected figures")]:
    bad = write_sweep("bad_key.json", {"keep": value})
    out = os.path.join(SCRATCH, "bad_key")
    proc = latsim("sweep", bad, "--out", out)
    lines = proc.stderr.strip().splitlines()
    check(proc.returncode == 2 and len(lines) == 1 and "bad_key.json: /keep:" in lines[0] and says in lines[0],
          f"\"keep\": {value!r}: exit {proc.returncode} {proc.stderr!r}")
    check(not os.path.exists(out), f"\"keep\": {value!r}: output directory was created")

# 8. The report of the 'first' sweep: 8 points have a timeline, 6 charts drawn by
# default (the first and the last point among them), and report.md says how to get more.
proc = latsim("report", first)
check(proc.returncode == 0, f"report: exit {proc.returncode} {proc.stderr}")
drawn = sorted(os.path.basename(os.path.dirname(p)) for p in glob.glob(os.path.join(first, "runs", "*", "gantt.png")))
files, runs = run_files(first)
check(len(drawn) == 6, f"report drew {len(drawn)} Gantt charts, expected a sample of 6")
check(runs[0]["run_id"] in drawn and runs[14]["run_id"] in drawn, "the sample should span the first to the last point")
with open(os.path.join(first, "report.md")) as f:
    md = f.read()
check("2 more point(s) have a timeline.csv" in md and "--gantt-limit N" in md, "report.md does not say how to get more")
check(os.path.isfile(os.path.join(first, "heatmap.png")), "report: heat map of a two-axis sweep missing")
# The report of the default sweep, which kept no run's files, reads each point's summary from the store.
proc = latsim("report", default)
check(proc.returncode == 0, f"report of a sweep without run files: exit {proc.returncode} {proc.stderr}")
with open(os.path.join(default, "report.md")) as f:
    md = f.read()
check("MTP mean over phases, analytic (ms)" in md and "double_buffer" in md,
      "report of a sweep without run files: no pipeline or analytic column (summaries not read from the store)")
check(os.path.isfile(os.path.join(default, "mtp_cdf.png")), "report of a sweep without run files: no CDF")
proc = latsim("report", first, "--figure", "no_such_column")
check(proc.returncode == 2 and "--figure no_such_column" in proc.stderr, f"report --figure bad: {proc.returncode} {proc.stderr}")

finish("sweep keep")
