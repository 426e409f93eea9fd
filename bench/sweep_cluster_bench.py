#!/usr/bin/env python3
"""Throughput of `latsim sweep` on 2,000 short runs through every backend, and
where the time of a short run goes.

    bench/sweep_cluster_bench.py [LATSIM] [WORK_DIR]
      (environment: MPIEXEC=mpiexec, SAMPLE=200, REPEATS=1)

The sweep: scenarios/hmd_60hz_direct.json cut to 1 simulated second, tracker
internal delay 0..24 ms x tracker rate 30/60/120/240 Hz x 20 replications =
2,000 runs. Each backend runs it into a fresh directory:

  -j1, -j2                 one process, one or two run threads
  --mpi, 2 ranks           mpiexec -n 2 (one run thread per rank)
  2 shards                 two --shard processes at once (-j1 each), then --collect
  a process per run        what a job array of one run per task would do:
                           `latsim run` per run, two at a time (a SAMPLE of the runs)

and every table must equal -j1's apart from wall_s. Reported per backend: wall
time, runs/s, CPU time (user + sys, children included). Then the per-run
overhead apart from simulation: process start (`latsim --version`), scenario
resolution (building a point's models without running it, and reading the
scenario), writing the results, claiming, and the tables, from the -j1 sweep's
--timings; and the CPU cost of one `latsim run` process against one run inside
a sweep. The load average is printed before and after each step: the machine
may be shared.
"""

import csv
import json
import os
import re
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
LATSIM = os.path.abspath(sys.argv[1]) if len(sys.argv) > 1 else os.path.join(ROOT, "build", "latsim")
WORK = sys.argv[2] if len(sys.argv) > 2 else "/tmp/latsim_sweep_cluster_bench"
MPIEXEC = os.environ.get("MPIEXEC", "mpiexec")
SAMPLE = int(os.environ.get("SAMPLE", "200"))
RUNS = 2000
MPI_ENV = {**os.environ, "OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1",
           "OMPI_MCA_btl_vader_single_copy_mechanism": "none"}


def load():
    with open("/proc/loadavg") as f:
        return " ".join(f.read().split()[:3])


def cpu_of_children():
    t = os.times()
    return t.children_user + t.children_system


def timed(commands, env=None):
    """Starts every command at once, waits for all; returns (wall s, CPU s of them, their stdout)."""
    cpu0, t0 = cpu_of_children(), time.monotonic()
    procs = [subprocess.Popen(c, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env) for c in commands]
    outs = []
    for p in procs:
        out, err = p.communicate()
        if p.returncode != 0:
            sys.exit(f"failed ({p.returncode}): {' '.join(p.args)}\n{out}{err}")
        outs.append(out)
    return time.monotonic() - t0, cpu_of_children() - cpu0, "".join(outs)


def table(directory):
    with open(os.path.join(directory, "results.csv"), newline="") as f:
        rows = list(csv.reader(f))
    drop = rows[0].index("wall_s")
    return [[c for i, c in enumerate(r) if i != drop] for r in rows]


def sweep_cmd(out, *extra):
    return [LATSIM, "sweep", SWEEP, "--out", os.path.join(WORK, out), *extra]


shutil.rmtree(WORK, ignore_errors=True)
os.makedirs(WORK)
SWEEP = os.path.join(WORK, "short_2000.json")
with open(SWEEP, "w") as f:
    json.dump({"description": "2,000 runs of 1 simulated second, double-buffered, no frames",
               "base": os.path.join(ROOT, "scenarios", "hmd_60hz_direct.json"), "overrides": {"/duration_s": 1},
               "axes": [{"pointer": "/tracker/internal_delay_ms", "range": {"from": 0, "to": 24, "step": 1}},
                        {"pointer": "/tracker/rate_hz", "values": [30, 60, 120, 240]}],
               "replications": 20, "seed": 1}, f)

print(f"machine: {os.cpu_count()} cores; latsim {subprocess.run([LATSIM, '--version'], capture_output=True, text=True).stdout.strip()}")
rows = []


def backend(label, commands, out, env=None, then=None):
    before = load()
    wall, cpu, stdout = timed(commands, env)
    if then:
        w2, c2, s2 = timed([then], env)
        wall, cpu, stdout = wall + w2, cpu + c2, stdout + s2
    rows.append((label, wall, cpu, before, load()))
    if out != "j1" and table(os.path.join(WORK, out)) != table(os.path.join(WORK, "j1")):
        sys.exit(f"{label}: results.csv differs from -j1's")
    return stdout


timings = backend("`-j1`", [sweep_cmd("j1", "-j", "1", "--timings")], "j1")
backend("`-j2`", [sweep_cmd("j2", "-j", "2")], "j2")
backend("`--mpi`, 2 ranks", [[MPIEXEC, "--oversubscribe", *(["--allow-run-as-root"] if os.geteuid() == 0 else []),
                              "-n", "2", *sweep_cmd("mpi", "--mpi")]], "mpi", env=MPI_ENV)
backend("2 shards + `--collect`", [sweep_cmd("shards", "--shard", f"{i}/2", "-j", "1") for i in range(2)], "shards",
        then=sweep_cmd("shards", "--collect"))

# A process per run, as a job array of one run per task would start them: the
# first SAMPLE runs of the plan, two processes at a time.
with open(os.path.join(WORK, "j1", "plan.json")) as f:
    plan = json.load(f)
base = os.path.join(ROOT, "scenarios", "hmd_60hz_direct.json")
per_run = []
for r in plan["runs"][:SAMPLE]:
    sets = ["--set", "/duration_s=1", "--set", f"/seed={r['seed']}"]
    for axis, value in zip(plan["axes"], r["values"]):
        sets += ["--set", f"{axis['pointer']}={json.dumps(value)}"]
    per_run.append([LATSIM, "run", base, *sets, "--replication", str(r["replication"]), "-q",
                    "--out", os.path.join(WORK, "per_run", r["run_id"])])
before = load()
cpu0, t0 = cpu_of_children(), time.monotonic()
pending, running = list(per_run), []
while pending or running:
    while pending and len(running) < 2:
        running.append(subprocess.Popen(pending.pop(0)))
    running[0].wait()
    if running[0].returncode != 0:
        sys.exit("latsim run failed")
    running.pop(0)
wall, cpu = time.monotonic() - t0, cpu_of_children() - cpu0
rows.append((f"a process per run, 2 at a time ({SAMPLE} runs)", wall * RUNS / SAMPLE, cpu * RUNS / SAMPLE, before, load()))
# The same run, the same figures: the sweep runs exactly what `latsim run` runs.
first = plan["runs"][0]["run_id"]
with open(os.path.join(WORK, "per_run", first, "figures.json")) as a, \
        open(os.path.join(WORK, "j1", "runs", first, "figures.json")) as b:
    if json.load(a) != json.load(b):
        sys.exit("latsim run and the sweep disagree on the first run's figures")

print()
print("| backend | wall (s) | runs/s | CPU (s) | CPU per run (ms) | load before → after |")
print("|---|---:|---:|---:|---:|---|")
for label, wall, cpu, before, after in rows:
    note = " (scaled from the sample)" if "process per run" in label else ""
    print(f"| {label}{note} | {wall:.1f} | {RUNS / wall:.0f} | {cpu:.1f} | {1e3 * cpu / RUNS:.2f} | {before} → {after} |")

# Where a run's time goes, from the -j1 sweep's own accounting.
print()
print(timings.strip())
phase = re.search(r"checking (\d+) point\(s\) [\d.]+ s \(([\d.]+) ms each.*runs ([\d.]+) s, tables ([\d.]+) s", timings)
per = re.search(r"per run: ([\d.]+) ms simulating, ([\d.]+) ms building models and figures \(and a kept run's files\), "
                r"([\d.]+) ms recording, ([\d.]+) ms reading and binding the scenario, ([\d.]+) ms claiming", timings)
build_ms = float(phase[2])
simulate, build_figures, record, read, claim = (float(x) for x in per.groups())
starts = []
for _ in range(50):
    t0 = time.monotonic()
    subprocess.run([LATSIM, "--version"], stdout=subprocess.DEVNULL, check=True)
    starts.append(time.monotonic() - t0)
starts.sort()
start_ms = 1e3 * starts[len(starts) // 2]
print()
print("| per run | ms | share of a run in a sweep |")
print("|---|---:|---:|")
total = simulate + build_figures + record + read + claim + 1e3 * float(phase[4]) / RUNS
for label, ms in (("simulating (the run's own wall_s)", simulate),
                  ("resolving the scenario: reading it and building the models", read + build_ms),
                  ("the figures (and a kept run's files)", build_figures - build_ms),
                  ("writing the run's record into the store, and its mark", record),
                  ("claiming, journal, temporaries", claim),
                  ("the tables (results.csv, results.sqlite), per run", 1e3 * float(phase[4]) / RUNS)):
    print(f"| {label} | {ms:.2f} | {100 * ms / total:.0f} % |")
print(f"| process start (`latsim --version`, median of 50), once per process | {start_ms:.1f} | |")
print(f"\nload at the end: {load()}")
