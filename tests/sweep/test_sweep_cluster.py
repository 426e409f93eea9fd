"""Program-level checks of latsim sweep on a cluster's two engines, run here:

  shards  three `--shard` processes at once on one directory (one of them
          reading its slice from Slurm's variables), one killed with SIGKILL in
          the middle of a run, --collect naming what is missing, the killed
          shard run again (retaking the dead claim with a warning), --collect:
          tables identical to a -j1 sweep's, and no run started twice except
          the one killed (counted from the journals' start records);
  mpi     `mpirun -n 3 ... --mpi` (oversubscribed; as root where that is who
          we are): results.csv equal to the -j1 sweep's but for wall_s, every
          run started once; bad input under MPI exits 2 and writes nothing.

  scripts scripts/cluster/slurm_array.sh and htcondor.sub, run through
          stand-ins for sbatch and condor_submit that start the jobs here.

Every wait is on a file the sweep writes or a process, never on a time.

Usage: test_sweep_cluster.py shards|mpi|scripts LATSIM SOURCE_DIR SCRATCH_DIR [MPIEXEC]
"""

import collections
import fractions
import glob
import json
import os
import shutil
import signal
import subprocess
import sys
import time

from sweep_checks import check, finish, table

MODE, LATSIM, SOURCE_DIR, SCRATCH = sys.argv[1:5]
MPIEXEC = sys.argv[5] if len(sys.argv) > 5 else "mpiexec"
BASE = os.path.join(SOURCE_DIR, "scenarios", "hmd_60hz_direct.json")


def latsim(*args, env=None):
    return subprocess.run([LATSIM, *args], capture_output=True, text=True, env=env)


def journal_lines(directory, pid="*"):
    """(pid, event, run id) of every journal line, per file in the order written."""
    lines = []
    for path in sorted(glob.glob(os.path.join(directory, "journal", f"*.{pid}.log"))):
        owner = int(os.path.basename(path).rsplit(".", 2)[-2])
        with open(path) as f:
            lines += [(owner, *line.split()[1:3]) for line in f if line.strip()]
    return lines


def starts_per_run(directory):
    return collections.Counter(run for _, event, run in journal_lines(directory) if event == "start")


def write_sweep(name, sweep):
    path = os.path.join(SCRATCH, name)
    with open(path, "w") as f:
        json.dump(sweep, f)
    return path


shutil.rmtree(SCRATCH, ignore_errors=True)
os.makedirs(SCRATCH)

# A run's expected cost is its event estimate (docs/event-budget.md): per
# simulated second the tracker's samples, the display's retraces, one render
# per refresh (this 7.7 ms render fits a refresh: 2 ms + 10,000 x 0.5 us +
# 640 x 480 x 0.8 x 3 ns), and at line level one event per active line.
# Line-level runs are expected longest and start first.
sweep = write_sweep("cluster.json", {
    "base": BASE, "overrides": {"/duration_s": 2}, "replications": 2, "seed": 5,
    "axes": [{"pointer": "/display/refresh_hz", "values": [60, "60000/1001", 72]},
             {"pointer": "/tracker/rate_hz", "values": [60, 120, 240]},
             {"pointer": "/display/scanout", "values": ["field", "line"]}]})
RUNS = 3 * 3 * 2 * 2
reference_dir = os.path.join(SCRATCH, "j1")
proc = latsim("sweep", sweep, "--out", reference_dir, "-j", "1")
check(proc.returncode == 0, f"sweep -j1: exit {proc.returncode} {proc.stderr}")
reference = table(reference_dir)
check(len(reference) == 1 + RUNS, f"-j1 results.csv has {len(reference) - 1} rows, expected {RUNS}")
with open(os.path.join(reference_dir, "plan.json")) as f:
    plan = json.load(f)["runs"]


def expected_events(values):
    """Events of a run: 2 s x (tracker samples + fields x (a retrace, a render, and 480 active lines at line
    level))."""
    refresh = fractions.Fraction(values[0]) if isinstance(values[0], str) else values[0]
    tracker_hz = values[1]
    return 2 * (tracker_hz + refresh * (2 + (480 if values[2] == "line" else 0)))


started = [run for _, event, run in journal_lines(reference_dir) if event == "start"]
longest_first = sorted(plan, key=lambda r: -expected_events(r["values"]))  # stable: ties in plan order
check(started == [r["run_id"] for r in longest_first], "-j1 did not start the runs longest expected first")


def kill_in_a_run(victim, out):
    """Once it has finished two runs, catch the victim between a run's start and
    finish records: freeze it, confirm from its journal that it is still inside
    that run, then kill it. Returns that run's id, or None if the victim ended
    first (a machine so loaded that this process never looked in time)."""
    while victim.poll() is None:
        lines = journal_lines(out, victim.pid)
        if sum(event == "finish" for _, event, _ in lines) >= 2 and lines[-1][1] == "start":
            victim.send_signal(signal.SIGSTOP)
            lines = journal_lines(out, victim.pid)
            if lines[-1][1] == "start":
                victim.send_signal(signal.SIGKILL)
                victim.wait()
                return lines[-1][2]
            victim.send_signal(signal.SIGCONT)
        time.sleep(0.001)
    return None


def shards():
    out = os.path.join(SCRATCH, "shards")
    # Bad slices are bad input: exit 2, nothing written.
    proc = latsim("sweep", sweep, "--out", out, "--shard", "3/3")
    check(proc.returncode == 2 and "--shard" in proc.stderr and not os.path.exists(out), f"--shard 3/3: {proc.stderr}")
    proc = latsim("sweep", sweep, "--out", out, "--shard", "env", env={**os.environ, "SLURM_ARRAY_TASK_ID": "x"})
    check(proc.returncode == 2 and not os.path.exists(out), f"--shard env with a bad task id: {proc.stderr}")
    proc = latsim("sweep", sweep, "--out", out, "--collect")
    check(proc.returncode == 2 and "not a sweep directory" in proc.stderr and not os.path.exists(out),
          f"--collect of nothing: {proc.stderr}")
    proc = latsim("sweep", sweep, "--out", out, "--shard", "0/3", "--mpi")
    check(proc.returncode == 2 and not os.path.exists(out), f"--shard with --mpi: {proc.stderr}")

    def start_shard(index, extra_env=None):
        spec = "env" if extra_env else f"{index}/3"
        return subprocess.Popen([LATSIM, "sweep", sweep, "--out", out, "--shard", spec, "-j", "1"],
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                env={**os.environ, **(extra_env or {})})

    # Shard 2 as the third task of `sbatch --array=1-3` sees it.
    slurm = {"SLURM_ARRAY_TASK_ID": "3", "SLURM_ARRAY_TASK_MIN": "1", "SLURM_ARRAY_TASK_MAX": "3",
             "SLURM_ARRAY_TASK_COUNT": "3"}
    for attempt in range(3):  # again in a fresh directory if the victim ended before it was caught
        shutil.rmtree(out, ignore_errors=True)
        shards = [start_shard(0), start_shard(1), start_shard(2, slurm)]
        victim = shards[1]
        killed_run = kill_in_a_run(victim, out)
        if killed_run is not None:
            break
        for shard in shards:
            shard.communicate()
    check(killed_run is not None and victim.returncode == -signal.SIGKILL,
          f"shard 1 ended (exit {victim.returncode}) before it could be killed in a run, three times")
    killed_finished = killed_run is not None and os.path.exists(os.path.join(out, "done", killed_run))
    print(f"killed shard 1 (pid {victim.pid}) in run {killed_run}; its summary was {'' if killed_finished else 'not '}"
          "written")
    for shard, name in ((shards[0], "shard 0/3:"), (shards[2], "shard 2/3 (SLURM_ARRAY_TASK_ID=3 of 3):")):
        stdout, stderr = shard.communicate()
        check(shard.returncode == 0, f"shard: exit {shard.returncode} {stderr}")
        check(name in stdout and "latsim sweep --collect writes the tables" in stdout, f"shard summary line: {stdout}")

    # Collecting now names what the killed shard left undone.
    proc = latsim("sweep", sweep, "--out", out, "--collect")
    missing = [line.split()[1] for line in proc.stderr.splitlines() if line.strip().startswith("missing ")]
    check(proc.returncode == 1 and "not finished" in proc.stderr, f"early collect: exit {proc.returncode} {proc.stderr}")
    check(killed_finished or killed_run in missing, f"early collect does not name the killed run {killed_run}: {missing}")
    plan_index = {r["run_id"]: i for i, r in enumerate(plan)}
    check(missing and all(plan_index[run] % 3 == 1 for run in missing), f"missing runs not all of shard 1: {missing}")

    # Run the killed shard again: the dead process's claim is retaken with a warning.
    proc = latsim("sweep", sweep, "--out", out, "--shard", "1/3", "-j", "1")
    check(proc.returncode == 0, f"rerun of shard 1: exit {proc.returncode} {proc.stderr}")
    resumed = sum(event == "finish" for _, event, _ in journal_lines(out, victim.pid)) + (1 if killed_finished else 0)
    check(f"shard 1/3: 12 of {RUNS} runs ({resumed} resumed, {12 - resumed} run now, 0 failed)" in proc.stdout,
          f"rerun of shard 1: {proc.stdout}")
    if not killed_finished:
        check(f"run {killed_run}: took over the claim of" in proc.stderr and f":{victim.pid}: process {victim.pid}"
              in proc.stderr and "is gone" in proc.stderr, f"no warning about the dead claim: {proc.stderr}")
    proc = latsim("sweep", sweep, "--out", out, "--collect")
    check(proc.returncode == 0 and f"collected {RUNS} of {RUNS} runs" in proc.stdout,
          f"collect: exit {proc.returncode} {proc.stdout} {proc.stderr}")
    check(table(out) == reference, "sharded, interrupted and resumed results.csv differs from the -j1 sweep's")
    check(os.path.getsize(os.path.join(out, "results.sqlite")) > 0, "results.sqlite missing")
    # Only per-process files (clocks, holder files) may remain, of the killed process: no claim of a run.
    check(all(name.startswith(".") for name in os.listdir(os.path.join(out, "claims"))),
          f"claims left after a complete collect: {os.listdir(os.path.join(out, 'claims'))}")

    # No run done twice: one start per run, but the killed run's, which started
    # again only if it had not finished when it was killed.
    starts = starts_per_run(out)
    by_victim = [run for pid, event, run in journal_lines(out) if pid == victim.pid and event == "start"]
    finished_by_victim = {run for pid, event, run in journal_lines(out) if pid == victim.pid and event == "finish"}
    check([run for run in by_victim if run not in finished_by_victim] == [killed_run],
          f"the killed shard left {by_victim} started, {finished_by_victim} finished")
    expected = {r["run_id"]: 1 for r in plan}
    if killed_run and not killed_finished:
        expected[killed_run] = 2
    check(dict(starts) == expected, f"start records per run differ: {sorted(set(starts.items()) ^ set(expected.items()))}")
    finishes = collections.Counter(run for _, event, run in journal_lines(out) if event == "finish")
    check(all(finishes[r["run_id"]] == 1 for r in plan if r["run_id"] != killed_run or not killed_finished),
          f"finish records per run: {finishes}")


def mpi():
    env = {**os.environ, "OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1",
           "OMPI_MCA_rmaps_base_oversubscribe": "1",
           # Containers often forbid the cross-memory attach Open MPI's shared memory tries first.
           "OMPI_MCA_btl_vader_single_copy_mechanism": "none",
           "ASAN_OPTIONS": "detect_leaks=0"}
    mpirun = [MPIEXEC, "--oversubscribe", "-n", "3"]
    if os.geteuid() == 0:
        mpirun.insert(1, "--allow-run-as-root")
    out = os.path.join(SCRATCH, "mpi")
    bad = write_sweep("bad.json", {"base": BASE, "axes": [{"pointer": "/tracker/rate_hz", "values": [60, -5]}]})
    proc = subprocess.run([*mpirun, LATSIM, "sweep", bad, "--out", out, "--mpi"], capture_output=True, text=True,
                          env=env, timeout=300)
    check(proc.returncode == 2 and "/axes/0/values/1: /tracker/rate_hz" in proc.stderr,
          f"MPI bad input: exit {proc.returncode} {proc.stderr}")
    check(not os.path.exists(out), "MPI bad input: output directory was created")

    proc = subprocess.run([*mpirun, LATSIM, "sweep", sweep, "--out", out, "--mpi"], capture_output=True, text=True,
                          env=env, timeout=600)
    check(proc.returncode == 0, f"mpirun sweep: exit {proc.returncode} {proc.stdout} {proc.stderr}")
    check(f"{RUNS} runs (0 resumed, {RUNS} run now, 0 failed) on 3 MPI rank(s)" in proc.stdout, f"summary: {proc.stdout}")
    check(table(out) == reference, "MPI results.csv differs from the -j1 sweep's")
    check(dict(starts_per_run(out)) == {r["run_id"]: 1 for r in plan}, "a run was started more than once, or never")
    ranks = {pid for pid, _, _ in journal_lines(out)}
    check(len(ranks) >= 2, f"runs were done by {len(ranks)} process(es) only")

    # Again on the finished directory: every run resumed, nothing run.
    proc = subprocess.run([*mpirun, LATSIM, "sweep", sweep, "--out", out, "--mpi"], capture_output=True, text=True,
                          env=env, timeout=300)
    check(proc.returncode == 0 and f"({RUNS} resumed, 0 run now" in proc.stdout, f"MPI rerun: {proc.stdout} {proc.stderr}")
    check(table(out) == reference, "MPI rerun changed results.csv")


FAKE_SBATCH = r"""#!/usr/bin/python3
# Stands in for Slurm's sbatch: runs the job at once (array tasks at the same
# time) with the variables Slurm sets, #SBATCH lines as defaults; the jobs'
# output goes to stderr, stdout is the job id.
import os, subprocess, sys
args, opts = sys.argv[1:], {}
while args and args[0].startswith("--"):
    key, _, value = args.pop(0)[2:].partition("=")
    opts.setdefault(key, value)
script, *script_args = args
with open(script) as f:
    for line in f:
        if line.startswith("#SBATCH --"):
            key, _, value = line[len("#SBATCH --"):].strip().partition("=")
            opts.setdefault(key, value)
counter = os.path.join(os.path.dirname(os.path.abspath(sys.argv[0])), "jobs")
job = (int(open(counter).read()) if os.path.exists(counter) else 100) + 1
open(counter, "w").write(str(job))
env = dict(os.environ, SLURM_JOB_ID=str(job), SLURM_CPUS_PER_TASK=opts.get("cpus-per-task", "1"))
for item in opts.get("export", "ALL").split(",")[1:]:
    key, _, value = item.partition("=")
    env[key] = value
if "array" in opts:
    first, last = map(int, opts["array"].split("-"))
    tasks = [subprocess.Popen(["bash", script, *script_args], stdout=sys.stderr, env=dict(env,
             SLURM_ARRAY_JOB_ID=str(job), SLURM_ARRAY_TASK_ID=str(i), SLURM_ARRAY_TASK_MIN=str(first),
             SLURM_ARRAY_TASK_MAX=str(last), SLURM_ARRAY_TASK_STEP="1", SLURM_ARRAY_TASK_COUNT=str(last - first + 1)))
             for i in range(first, last + 1)]
    for task in tasks:
        task.wait()
else:
    subprocess.run(["bash", script, *script_args], env=env, stdout=sys.stderr)
print(job)
"""

FAKE_CONDOR_SUBMIT = r"""#!/usr/bin/python3
# Stands in for condor_submit: expands the submit file's macros, $(Process)
# and $(Cluster), and runs every job of its queue at once (no file transfer).
# Command-line name=value pairs replace the file's values.
import re, subprocess, sys
overrides = dict(a.split("=", 1) for a in sys.argv[1:] if "=" in a)
file = [a for a in sys.argv[1:] if "=" not in a][0]
macros, count = {}, 0
for line in open(file):
    line = line.strip()
    if not line or line.startswith("#"):
        continue
    if line.startswith("queue"):
        count = line.split()[1]
        continue
    key, _, value = line.partition("=")
    macros[key.strip()] = value.strip()
macros.update(overrides)
def expand(text, process):
    for _ in range(10):
        text = re.sub(r"\$\((\w+)\)", lambda m: str(process) if m[1] == "Process" else "1" if m[1] == "Cluster"
                      else macros[m[1]], text)
    return text
jobs = [subprocess.Popen([expand(macros["executable"], p), *expand(macros["arguments"], p).strip('"').split()])
        for p in range(int(expand(count, 0)))]
for job in jobs:
    job.wait()
"""


def scripts():
    """The example batch scripts, run through stand-ins for sbatch and condor_submit."""
    bin_dir = os.path.join(SCRATCH, "bin")
    os.makedirs(bin_dir)
    for name, text in (("sbatch", FAKE_SBATCH), ("condor_submit", FAKE_CONDOR_SUBMIT)):
        with open(os.path.join(bin_dir, name), "w") as f:
            f.write(text)
        os.chmod(os.path.join(bin_dir, name), 0o755)
    env = {**os.environ, "PATH": bin_dir + os.pathsep + os.environ["PATH"], "LATSIM": LATSIM}
    cluster_dir = os.path.join(SOURCE_DIR, "scripts", "cluster")

    bad = write_sweep("bad.json", {"base": BASE, "axes": [{"pointer": "/tracker/rate_hz", "values": [60, -5]}]})
    out = os.path.join(SCRATCH, "slurm")
    proc = subprocess.run([os.path.join(cluster_dir, "slurm_array.sh"), bad, out, "3"], capture_output=True,
                          text=True, env=env, cwd=SCRATCH)
    check(proc.returncode == 2 and "/axes/0/values/1" in proc.stderr and not os.path.exists(out),
          f"slurm_array.sh with a bad sweep: exit {proc.returncode} {proc.stderr}")
    proc = subprocess.run([os.path.join(cluster_dir, "slurm_array.sh"), sweep, out, "3"], capture_output=True,
                          text=True, env=env, cwd=SCRATCH)
    check(proc.returncode == 0, f"slurm_array.sh: exit {proc.returncode} {proc.stderr}")
    check("every point valid; 0 finished" in proc.stdout, f"slurm_array.sh did not check the sweep: {proc.stdout}")
    check(all(f"sweep: shard {i}/3 (SLURM_ARRAY_TASK_ID={i} of 3)" in proc.stderr for i in range(3)) and
          f"collected {RUNS} of {RUNS} runs" in proc.stderr,
          f"slurm_array.sh: three shards and a collect expected: {proc.stderr}")
    check(table(out) == reference, "results.csv from slurm_array.sh differs from the -j1 sweep's")

    out = os.path.join(SCRATCH, "condor")
    proc = subprocess.run(["condor_submit", os.path.join(cluster_dir, "htcondor.sub"), f"latsim={LATSIM}",
                           f"sweep={sweep}", f"out={out}", "shards=4"], capture_output=True, text=True, env=env,
                          cwd=SCRATCH)
    check(proc.returncode == 0 and proc.stdout.count("sweep: shard ") == 4, f"htcondor.sub: {proc.stdout} {proc.stderr}")
    proc = latsim("sweep", sweep, "--out", out, "--collect")
    check(proc.returncode == 0 and table(out) == reference, f"collect after htcondor.sub: {proc.stderr}")


{"shards": shards, "mpi": mpi, "scripts": scripts}[MODE]()
finish(f"sweep {MODE}")
