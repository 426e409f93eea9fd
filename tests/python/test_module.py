"""The Python module against the command line it stands beside.

Every expected value comes from the other method: `latsim run` / `latsim
sweep` / `latsim schema` on the same input, or the error line the command
line prints. Checked: figures.json and the ledger, sample and timeline files
byte for byte; the in-memory tables against those files; a dict against its
file; bad input as latsim.ScenarioError with the pointer and nothing
written; the GIL released while simulating; Ctrl-C ends a long run with
KeyboardInterrupt and nothing written; a sweep's table against latsim
sweep's results.csv; the schema.

Usage: test_module.py LATSIM SOURCE_DIR SCRATCH_DIR   (PYTHONPATH=build/python)
"""
import json
import os
import shutil
import signal
import subprocess
import sys
import threading
import time

import pandas

import latsim

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import module_checks  # noqa: E402
from module_checks import check  # noqa: E402

LATSIM, SOURCE_DIR, SCRATCH = sys.argv[1:4]
BASE = os.path.join(SOURCE_DIR, "scenarios", "hmd_60hz_direct.json")


def cli(*args):
    return module_checks.cli(LATSIM, *args)


def read(path, mode="rb"):
    with open(path, mode) as f:
        return f.read()


shutil.rmtree(SCRATCH, ignore_errors=True)
os.makedirs(SCRATCH)

# 1. The same run both ways: every deterministic file byte for byte.
cli_out, py_out = os.path.join(SCRATCH, "cli"), os.path.join(SCRATCH, "py")
proc = cli("run", BASE, "--set", "/duration_s=1", "--out", cli_out, "--ledger", "--samples")
check(proc.returncode == 0, f"latsim run: exit {proc.returncode}: {proc.stderr.strip()}")
r = latsim.run(BASE, set={"/duration_s": 1}, out=py_out, ledger=True, samples=True, timeline=True)
for name in ("figures.json", "frames.csv", "fields.csv", "tracker.csv", "samples.csv", "timeline.csv",
             "timeline.json"):
    check(read(os.path.join(cli_out, name)) == read(os.path.join(py_out, name)), f"{name} differs from latsim run's")
figures_file = json.loads(read(os.path.join(cli_out, "figures.json")))
check(r.figures == figures_file["figures"], "Result.figures differs from figures.json")
check(r.fingerprint == figures_file["fingerprint"], "Result.fingerprint differs from figures.json")
# The command line prints the mean to three decimals.
printed = [line for line in proc.stdout.splitlines() if "motion_to_photon_ms: mean" in line]
check(printed and f"mean {r.figures['motion_to_photon_ms']['mean']:.3f} " in printed[0],
      f"mean: {printed} against {r.figures['motion_to_photon_ms']['mean']}")

# 2. The tables in memory are the files' contents.
for name in ("frames", "fields", "tracker"):
    from_file = pandas.read_csv(os.path.join(cli_out, f"{name}.csv"))
    from_file = from_file.mask(from_file < 0)  # -1 marks no value (no time, no sample): missing in the tables
    table = getattr(r, name)
    check(list(table.columns) == list(from_file.columns) and table.equals(from_file.astype(table.dtypes.to_dict())),
          f"Result.{name} differs from {name}.csv")
check(len(r.frames) > 0, "no frames in the ledger")
samples_file = pandas.read_csv(os.path.join(cli_out, "samples.csv"))
# samples.csv prints t_ms to six decimals and values to nine significant digits.
check(len(r.samples) == len(samples_file) and (r.samples["name"].astype(str) == samples_file["name"]).all()
      and ((r.samples["t_ms"] - samples_file["t_ms"]).abs() <= 5e-7).all()
      and ((r.samples["value"] - samples_file["value"]).abs() <= 1e-8 * samples_file["value"].abs() + 1e-300).all(),
      "Result.samples differs from samples.csv")
memory = latsim.run(BASE, set={"/duration_s": 1}, timeline=True)
timeline_file = pandas.read_csv(os.path.join(cli_out, "timeline.csv"))
check(len(memory.timeline) == len(timeline_file) > 0
      and (memory.timeline[["stage", "frame", "eye", "unit"]] == timeline_file[["stage", "frame", "eye", "unit"]]).all().all()
      # timeline.csv cuts times to whole nanoseconds (six decimals of a ms).
      and ((memory.timeline[["start_ms", "end_ms"]] - timeline_file[["start_ms", "end_ms"]]).abs() <= 1.001e-6).all().all(),
      "Result.timeline in memory differs from timeline.csv")
check(memory.figures == r.figures, "a run without files has other figures")
try:
    memory.frames
    check(False, "Result.frames without ledger=True")
except AttributeError as e:
    check("ledger=True" in str(e), f"Result.frames without the ledger: {e}")

# 3. A dict is its file: the same figures, and includes found from base_dir.
with open(BASE) as f:
    doc = json.load(f)
doc["duration_s"] = 1
check(latsim.run(doc).figures == r.figures, "the scenario as a dict has other figures")
included = {"include": os.path.basename(BASE), "duration_s": 1}
check(latsim.run(included, base_dir=os.path.dirname(BASE)).figures == r.figures, "a dict including its file differs")
check(latsim.run(BASE, set={"/duration_s": 1}, seed=7).figures != r.figures, "seed 7 changes nothing")

# 4. Bad input: the command line's line, its pointer, nothing written.
def scenario_error(*args, **kwargs):
    try:
        latsim.run(*args, **kwargs)
    except latsim.ScenarioError as e:
        return e
    return None


bad_doc = dict(doc, duration_s="long")
bad_file = os.path.join(SCRATCH, "bad.json")
with open(bad_file, "w") as f:
    json.dump(bad_doc, f)
expected = cli("run", bad_file, "--out", os.path.join(SCRATCH, "bad_cli")).stderr.strip()
bad_out = os.path.join(SCRATCH, "bad_py")
e = scenario_error(bad_doc, out=bad_out)
check(e is not None and e.pointer == "/duration_s" and isinstance(e, ValueError), f"bad dict: {e!r}")
check(e is not None and str(e) == expected.replace(bad_file, "<dict>"), f"bad dict: {e} against {expected}")
check(e is not None and e.file == "<dict>" and e.message and e.message in str(e), f"bad dict parts: {e!r}")
check(not os.path.exists(bad_out), "bad input wrote its output directory")
e = scenario_error(bad_file)
check(e is not None and str(e) == expected, f"bad file: {e} against {expected}")
expected = cli("run", BASE, "--set", "/display/no_such_key=1", "--out", os.path.join(SCRATCH, "x")).stderr.strip()
e = scenario_error(BASE, set={"/display/no_such_key": 1})
check(e is not None and str(e) == expected and e.pointer == "/display/no_such_key", f"bad --set: {e} against {expected}")
e = scenario_error(dict(doc, tracker=dict(doc["tracker"], rate_hz=float("nan"))))
check(e is not None and e.pointer == "/tracker/rate_hz", f"NaN in a dict: {e!r}")
for bad_call, error in ((lambda: latsim.run(BASE, seed=-1), ValueError), (lambda: latsim.run(42), TypeError),
                        (lambda: latsim.run(BASE, set={"duration_s": 1}), ValueError)):
    try:
        bad_call()
        check(False, f"no {error.__name__}")
    except error:
        pass

# 5. The GIL is released while simulating: a Python thread keeps running.
ticks, done = [], threading.Event()


def tick():
    while not done.is_set():
        ticks.append(time.monotonic())
        time.sleep(0.002)


ticker = threading.Thread(target=tick)
ticker.start()
time.sleep(0.05)
start = time.monotonic()
latsim.run(BASE, set={"/duration_s": 600, "/output/timeline": False})
end = time.monotonic()
done.set()
ticker.join()
during = [t for t in ticks if start < t < end]
# Holding the GIL, the thread would tick at most once or twice (switch interval 5 ms).
check(end - start < 0.1 or len(during) >= 10, f"GIL held: {len(during)} ticks in a {end - start:.2f} s run")

# 6. Ctrl-C stops a long run with KeyboardInterrupt and writes nothing.
long_out = os.path.join(SCRATCH, "interrupted")
code = ("import sys, latsim\nprint('started', flush=True)\n"
        f"latsim.run({BASE!r}, set={{'/duration_s': 100000}}, out={long_out!r})\n")
child = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
child.stdout.readline()
time.sleep(1.0)
sent = time.monotonic()
child.send_signal(signal.SIGINT)
try:
    _, err = child.communicate(timeout=30)
except subprocess.TimeoutExpired:
    child.kill()
    _, err = child.communicate()
# Python ends on an uncaught KeyboardInterrupt by killing itself with SIGINT.
check(child.returncode == -signal.SIGINT and err.rstrip().endswith("KeyboardInterrupt"),
      f"Ctrl-C: exit {child.returncode}: {err.strip()[-300:]}")
check(time.monotonic() - sent < 10, f"Ctrl-C took {time.monotonic() - sent:.1f} s")
check(not os.path.exists(long_out) and not [n for n in os.listdir(SCRATCH) if n.startswith("interrupted.tmp")],
      "an interrupted run left files")

# 6b. SIGTERM while a run is writing into its staging directory ends the
# process by SIGTERM, as Python's default would, but with the staging
# directory removed first (it used to be left). Ready when the staging
# directory exists: the run is under way.
term_out = os.path.join(SCRATCH, "terminated")
code = f"import latsim\nlatsim.run({BASE!r}, set={{'/duration_s': 100000}}, out={term_out!r})\n"
child = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
ready_by = time.monotonic() + 120
while time.monotonic() < ready_by and child.poll() is None and \
        not [n for n in os.listdir(SCRATCH) if n.startswith("terminated.tmp")]:
    time.sleep(0.01)
check(child.poll() is None, f"SIGTERM: the run ended before the signal ({child.returncode})")
sent = time.monotonic()
child.send_signal(signal.SIGTERM)
try:
    _, err = child.communicate(timeout=30)
except subprocess.TimeoutExpired:
    child.kill()
    _, err = child.communicate()
check(child.returncode == -signal.SIGTERM, f"SIGTERM: exit {child.returncode}: {err.strip()[-300:]}")
check(time.monotonic() - sent < 1.0, f"SIGTERM took {time.monotonic() - sent:.2f} s")
check(not os.path.exists(term_out) and not [n for n in os.listdir(SCRATCH) if n.startswith("terminated.tmp")],
      "a run stopped by SIGTERM left files")

# 6c. A NUL in a path is refused, not cut short (it named another directory).
try:
    latsim.run(BASE, set={"/duration_s": 0.1}, out=os.path.join(SCRATCH, "nul\0cut"))
    check(False, "a NUL in out was accepted")
except ValueError as e:
    check("NUL" in str(e), f"a NUL in out: {e}")
check(not os.path.exists(os.path.join(SCRATCH, "nul")), "a NUL in out: the path cut short was written")
# A name of 300 bytes (a file name holds 255 on Linux) was refused only when
# the run's files were written, as an OSError after the run: now before it.
started = time.process_time()
try:
    latsim.run(BASE, set={"/duration_s": 1000}, out=os.path.join(SCRATCH, "n" * 300))
    check(False, "an out name of 300 bytes was accepted")
except ValueError as e:
    check("255 bytes" in str(e), f"an out name of 300 bytes: {e}")
# 1000 s of this scenario costs seconds of CPU; refused before it, it costs none.
check(time.process_time() - started < 0.5, "an out name of 300 bytes: refused after the run")

# 7. A sweep: its table is latsim sweep's (results.csv's runs and figures) but for wall time.
sweep_doc = {"base": BASE, "overrides": {"/duration_s": 1},
             "axes": [{"pointer": "/display/refresh_hz", "values": [60, 120]},
                      {"pointer": "/tracker/rate_hz", "values": [60, 240]}]}
sweep_file = os.path.join(SCRATCH, "sweep.json")
with open(sweep_file, "w") as f:
    json.dump(sweep_doc, f)
proc = cli("sweep", sweep_file, "--out", os.path.join(SCRATCH, "sweep_cli"), "-j2")
check(proc.returncode == 0, f"latsim sweep: {proc.stderr.strip()}")
expected = latsim.load(os.path.join(SCRATCH, "sweep_cli")).drop(columns=["wall_s"])
table = latsim.sweep(sweep_doc, jobs=2)
check(len(table) == 4 and table.drop(columns=["wall_s"]).equals(expected), f"sweep table:\n{table}\n{expected}")
results_csv = pandas.read_csv(os.path.join(SCRATCH, "sweep_cli", "results.csv"), dtype={"run_id": str})
check(table["run_id"].tolist() == results_csv["run_id"].tolist()
      and table["motion_to_photon_ms.p99"].tolist() == results_csv["mtp_p99_ms"].tolist(), "the table is results.csv's")
kept = os.path.join(SCRATCH, "sweep_py")
check(latsim.sweep(sweep_file, jobs=1, out=kept).drop(columns=["wall_s"]).equals(expected), "sweep of the file")
check(os.path.exists(os.path.join(kept, "results.sqlite")), "sweep with out= kept no results.sqlite")
try:
    latsim.sweep(dict(sweep_doc, axes=[{"pointer": "/display/no_such_key", "values": [1, 2]}]))
    check(False, "a bad sweep ran")
except latsim.ScenarioError as e:
    check(e.pointer == "/axes/0/pointer" and str(e).startswith("<dict>: /axes/0/pointer:"), f"bad sweep: {e}")

# 8. The schema is latsim schema's.
check(latsim.schema() == json.loads(cli("schema").stdout), "schema differs from latsim schema")
check(latsim.schema("markdown") == cli("schema", "--format", "markdown").stdout, "markdown differs")

module_checks.finish("ok: the module gives the command line's files, figures, errors, sweep table and schema")
