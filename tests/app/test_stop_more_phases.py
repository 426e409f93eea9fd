"""SIGTERM and SIGINT end `validate` on a large sweep, compare's plotting
step and `sweep --mpi` within a second (issue 47; test_stop_phases.py has
the other phases and says what is checked).

- validate of a sweep of 60,000 points (seconds of planning and building
  points): stopped once it has spent a CPU fifth of a second; one line, and
  nothing written anywhere.
- compare, while its Python child draws the CDFs: stopped once the child has
  written its first plot; the child takes back its plots, latsim the tables
  and the directory it made; the child does not outlive it.
- sweep --mpi under mpiexec (two ranks), stopped while both ranks run, the
  signal sent to every rank (as a batch scheduler sends it) or to mpiexec
  (as a terminal does; Open MPI passes it on a second later): every rank is
  gone within the second of getting it, one line in all (signalled through
  mpiexec: that line, or none when mpiexec's teardown drops it), no
  temporary left.
  Skipped, with the reason, when latsim was built without MPI or mpiexec is
  missing.

Usage: test_stop_more_phases.py LATSIM SOURCE_DIR SCRATCH_DIR [MPIEXEC|none] [--repeat N]
(--repeat: every case N times, to show that none is flaky.)
"""

import glob
import json
import os
import shutil
import signal
import subprocess
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "sweep"))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from sweep_checks import check, finish  # noqa: E402
from stop_checks import BOUND_S, children_of, cpu_seconds, expect_stopped, gone_within, leftovers, stop, wait_until  # noqa: E402,E501

args = [a for a in sys.argv[1:] if not a.startswith("--repeat")]
REPEAT = int(sys.argv[sys.argv.index("--repeat") + 1]) if "--repeat" in sys.argv else 1
if "--repeat" in sys.argv:
    args.remove(str(REPEAT))
LATSIM, SOURCE_DIR, SCRATCH = args[:3]
MPIEXEC = args[3] if len(args) > 3 else shutil.which("mpiexec")
BASE = os.path.abspath(os.path.join(SOURCE_DIR, "scenarios", "hmd_60hz_direct.json"))
SIGNALS = (signal.SIGTERM, signal.SIGINT)


def start(*command, env=None):
    return subprocess.Popen(list(command), stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, env=env)


def tree(directory):
    return sorted(os.path.relpath(os.path.join(r, n), directory) for r, ds, fs in os.walk(directory) for n in ds + fs)


shutil.rmtree(SCRATCH, ignore_errors=True)
os.makedirs(SCRATCH)

# 1. validate on a large sweep: 100 x 600 points.
large = os.path.join(SCRATCH, "large_sweep.json")
with open(large, "w") as f:
    json.dump({"base": BASE, "axes": [{"pointer": "/tracker/rate_hz", "values": list(range(30, 1030, 10))},
                                      {"pointer": "/pipeline/render/fixed_ms",
                                       "values": [round(0.01 * i, 2) for i in range(1, 601)]}]}, f)
listing = tree(SCRATCH)
for sig in SIGNALS * REPEAT:
    what = f"validate of 60,000 points ({sig.name})"
    child = start(LATSIM, "validate", large)
    if wait_until(child, lambda: cpu_seconds(child.pid) > 0.2, what):
        # Its own line once its plan or point loop sees the flag; the watchdog's (at 800 ms) where that comes
        # too late: 19 of 50 stops at load 8-10, the cause not yet found (see the stop line's wording).
        expect_stopped(what, sig, stop(child, sig), None, "nothing written")
        check(tree(SCRATCH) == listing, f"{what}: something was written")

# 2. compare's plotting step: a PresentMon capture beside the run of its replay (docs/measured.md).
capture = os.path.join(SOURCE_DIR, "scenarios", "measured", "captures", "test_case_0.csv")
run_dir = os.path.join(SCRATCH, "replay")
done = subprocess.run([LATSIM, "run", os.path.join(SOURCE_DIR, "scenarios", "measured", "current_cpu_gpu.json"),
                       "--out", run_dir, "-q"], capture_output=True, text=True)
check(done.returncode == 0, f"compare's run: {done.stderr.strip()}")
for sig in SIGNALS * REPEAT:
    what = f"compare while drawing ({sig.name})"
    out = os.path.join(SCRATCH, "compare")
    child = start(LATSIM, "compare", capture, run_dir, "--out", out, "--application", "dwm.exe")
    drawing = []

    def first_plot_written():
        drawing[:] = children_of(child.pid)
        return bool(drawing) and bool(glob.glob(os.path.join(out, "compare_*.png")))
    if wait_until(child, first_plot_written, what):
        expect_stopped(what, sig, stop(child, sig), out, f"compare: stopped by {sig.name}; nothing written")
        check(gone_within(drawing), f"{what}: its Python child outlived it")

# 3. sweep --mpi: four runs of 1e5 simulated seconds on two ranks.
if MPIEXEC == "none":
    print("stop phases: sweep --mpi skipped: this latsim was built without MPI (LATSIM_MPI=OFF)")
elif not MPIEXEC or not shutil.which(MPIEXEC):
    print("stop phases: sweep --mpi skipped: no mpiexec (Debian's openmpi-bin)")
else:
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OMPI_MCA_rmaps_base_oversubscribe="1", OMPI_MCA_btl_vader_single_copy_mechanism="none")
    # A stopped rank leaves without MPI_Finalize (finalising waits on the job mpiexec is ending), so Open MPI's
    # own allocations are still held at exit: under LeakSanitizer they are not latsim's leaks
    # (tests/sweep/test_sweep_cluster.py runs its MPI sweeps the same way).
    env["ASAN_OPTIONS"] = ":".join(filter(None, [env.get("ASAN_OPTIONS", ""), "detect_leaks=0"]))
    sweep_file = os.path.join(SCRATCH, "mpi_sweep.json")
    with open(sweep_file, "w") as f:
        json.dump({"base": BASE, "overrides": {"/duration_s": 100000},
                   "axes": [{"pointer": "/tracker/rate_hz", "values": [60, 90, 120, 240]}]}, f)
    # Each way a stop reaches the ranks: (how, signal every rank, the bound on the ranks' end). A batch
    # scheduler signals every task of the job (Slurm's scancel does); a terminal or a kill signals mpiexec,
    # which passes the stop on as SIGTERM only after its odls_base_sigkill_timeout (Open MPI 4.1: 1 s,
    # SIGCONT first): the ranks then have the contract's second. mpiexec's own exit, after its own cleanup
    # (about a second), is bounded loosely.
    for how, to_ranks, bound_s in (("every rank", True, BOUND_S), ("mpiexec", False, 1.0 + BOUND_S)):
        for sig in SIGNALS * REPEAT:
            what = f"sweep --mpi, {sig.name} to {how}"
            out = os.path.join(SCRATCH, "mpi")
            shutil.rmtree(out, ignore_errors=True)
            child = subprocess.Popen([MPIEXEC, "--quiet", "--oversubscribe", "-n", "2", LATSIM, "sweep", sweep_file,
                                      "--out", out, "--mpi"], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                                     text=True, env=env)
            ranks = []

            def both_ranks_run():
                ranks[:] = children_of(child.pid)
                return len(ranks) == 2 and len(glob.glob(os.path.join(out, "claims", "*"))) == 2
            if not wait_until(child, both_ranks_run, what):
                continue
            sent = time.monotonic()
            for pid in ranks if to_ranks else [child.pid]:
                os.kill(pid, sig)
            check(gone_within(ranks, bound_s), f"{what}: a rank ran on past {bound_s} s")
            ranks_s = time.monotonic() - sent
            try:
                _, err = child.communicate(timeout=10)
            except subprocess.TimeoutExpired:
                child.kill()
                _, err = child.communicate()
            lines = [line for line in err.splitlines() if line.strip()]
            # mpiexec passes the stop on as SIGTERM whichever it got; a scheduler's signal reaches the ranks as sent.
            said = sig if to_ranks else signal.SIGTERM
            said_it = all(f"sweep: stopped by {said.name}" in line for line in lines)
            if to_ranks:
                check(len(lines) == 1 and said_it, f"{what}: stderr {lines}")
            else:
                # mpiexec, ending the job of its own accord, may stop forwarding the ranks' output before rank 0's
                # line reaches it (Open MPI's teardown, seen once in a loaded CI run): that line or nothing.
                check(len(lines) <= 1 and said_it, f"{what}: stderr {lines}")
            if to_ranks:
                check(child.returncode == 128 + sig, f"{what}: mpiexec's exit {child.returncode}, want {128 + sig}")
            check(not leftovers(out) and not glob.glob(os.path.join(out, "runs", "*.tmp*")),
                  f"{what}: temporaries left: {leftovers(out)}")
            if REPEAT > 1:
                print(f"{what}: the ranks ended {ranks_s:.3f} s after the signal")

finish(f"stop in more phases ({REPEAT} time(s) each)")
