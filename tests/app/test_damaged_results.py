"""`latsim report` on damaged result directories: one line, exit 2, nothing written.

The corpus is built here from what latsim itself writes (a run with its
ledger, a small sweep): each case damages one file the way a crash, a full
disk or a hand edit would (truncated mid-line, junk bytes, emptied, a value
no result holds such as 1e308, a JSON array where an object belongs, a short
table row, a file deleted) and expects what the contract states (issue 47):
exit status 2, exactly one line on stderr that names the damaged file, no
Python traceback, and not one file added to or changed in the directory.
The undamaged copies are reported first, so that every failure below is the
damage's and not the report's.

Usage: test_damaged_results.py LATSIM SOURCE_DIR SCRATCH_DIR
"""

import json
import os
import re
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "sweep"))
from sweep_checks import check, finish  # noqa: E402

LATSIM, SOURCE_DIR, SCRATCH = sys.argv[1:4]
BASE = os.path.abspath(os.path.join(SOURCE_DIR, "scenarios", "hmd_60hz_direct.json"))


def latsim(*args):
    return subprocess.run([LATSIM, *args], capture_output=True, text=True)


def snapshot(directory):
    """Every file under `directory` with its bytes."""
    found = {}
    for root, _, files in os.walk(directory):
        for name in files:
            path = os.path.join(root, name)
            with open(path, "rb") as f:
                found[os.path.relpath(path, directory)] = f.read()
    return found


def truncate_mid_line(path):
    """Cuts the file near its middle, never at a line's end: a half-written last line."""
    with open(path, "rb") as f:
        data = f.read()
    cut = len(data) // 2
    while cut > 1 and data[cut - 1:cut] in (b"\n", b","):
        cut -= 1
    with open(path, "wb") as f:
        f.write(data[:cut])


def replace_text(path, old, new):
    with open(path, encoding="utf-8") as f:
        text = f.read()
    check(old in text, f"corpus: {path} lacks {old!r}")
    with open(path, "w", encoding="utf-8") as f:
        f.write(text.replace(old, new, 1))


def write(path, data):
    with open(path, "wb") as f:
        f.write(data)


def short_row(path):
    """Drops the last field of the table's second line."""
    with open(path, encoding="utf-8") as f:
        lines = f.read().splitlines()
    lines[1] = lines[1].rsplit(",", 1)[0]
    with open(path, "w", encoding="utf-8") as f:
        f.write("\n".join(lines) + "\n")


def big_cell(path, column):
    """Puts 1e308 into `column` of the table's first data row."""
    with open(path, encoding="utf-8") as f:
        lines = f.read().splitlines()
    header = lines[0].split(",")
    cells = lines[1].split(",")
    check(column in header and len(cells) == len(header), f"corpus: {path}: no plain column {column}")
    cells[header.index(column)] = "1e308"
    lines[1] = ",".join(cells)
    with open(path, "w", encoding="utf-8") as f:
        f.write("\n".join(lines) + "\n")


shutil.rmtree(SCRATCH, ignore_errors=True)
os.makedirs(SCRATCH)

# The pristine corpus: a run with its ledger (fields.csv) and timeline, a sweep of two points.
run_dir = os.path.join(SCRATCH, "run")
proc = latsim("run", BASE, "--out", run_dir, "--set", "/duration_s=1", "--ledger", "-q")
check(proc.returncode == 0, f"corpus run: {proc.stderr.strip()}")
sweep_file = os.path.join(SCRATCH, "sweep.json")
with open(sweep_file, "w") as f:
    json.dump({"base": BASE, "overrides": {"/duration_s": 1}, "keep": "first",
               "axes": [{"pointer": "/tracker/rate_hz", "values": [60, 120]}]}, f)
sweep_dir = os.path.join(SCRATCH, "sweep")
proc = latsim("sweep", sweep_file, "--out", sweep_dir, "-j", "2")
check(proc.returncode == 0, f"corpus sweep: {proc.stderr.strip()}")
for name, pristine in (("run", run_dir), ("sweep", sweep_dir)):
    copy = os.path.join(SCRATCH, "pristine_" + name)
    shutil.copytree(pristine, copy)
    proc = latsim("report", copy)
    check(proc.returncode == 0 and "Traceback" not in proc.stderr, f"pristine {name}: {proc.stderr.strip()[-300:]}")
sweep_run = os.path.join("runs", sorted(os.listdir(os.path.join(sweep_dir, "runs")))[0])
for needed in ("summary.json", "timeline.csv", "fields.csv"):
    check(os.path.isfile(os.path.join(run_dir, needed)), f"corpus: the run wrote no {needed}")

# (name, pristine directory, the file damaged, how)
CASES = [
    ("summary truncated", run_dir, "summary.json", truncate_mid_line),
    ("summary junk", run_dir, "summary.json", lambda p: write(p, b"\x00\xff junk {")),
    ("summary empty", run_dir, "summary.json", lambda p: write(p, b"")),
    ("summary an array", run_dir, "summary.json", lambda p: write(p, b"[]")),
    ("summary 1e308", run_dir, "summary.json", lambda p: replace_text(p, '"mean": ', '"mean": 1e308, "was": ')),
    ("summary NaN", run_dir, "summary.json", lambda p: replace_text(p, '"mean": ', '"mean": NaN, "was": ')),
    ("timeline junk", run_dir, "timeline.csv", lambda p: write(p, b"stage,frame,eye,unit,start_ms,end_ms\nx,y,z\n")),
    ("timeline truncated", run_dir, "timeline.csv", truncate_mid_line),
    ("fields truncated", run_dir, "fields.csv", truncate_mid_line),
    ("plan an array", sweep_dir, "plan.json", lambda p: write(p, b"[]")),
    ("plan truncated", sweep_dir, "plan.json", truncate_mid_line),
    ("results short row", sweep_dir, "results.csv", short_row),
    ("results 1e308", sweep_dir, "results.csv", lambda p: big_cell(p, "point")),
    ("results junk", sweep_dir, "results.csv", lambda p: write(p, b"point,replication,run_id\n\x01,\x02,/\n")),
    ("point summary truncated", sweep_dir, os.path.join(sweep_run, "summary.json"), truncate_mid_line),
]

# A run id is 16 hex digits; about one in 1,850 is all decimal digits and then
# reads as a number beyond any figure's bound: it is a name, no damage.
digits_dir = os.path.join(SCRATCH, "run_id_digits")
shutil.copytree(sweep_dir, digits_dir)
old_id = os.path.basename(sweep_run)
os.rename(os.path.join(digits_dir, sweep_run), os.path.join(digits_dir, "runs", "2774305458476704"))
replace_text(os.path.join(digits_dir, "results.csv"), old_id, "2774305458476704")
proc = latsim("report", digits_dir)
check(proc.returncode == 0 and "Traceback" not in proc.stderr,
      f"an all-digit run id: exit {proc.returncode}, want 0: {proc.stderr.strip()[-300:]}")

# A kept run's summary.json deleted is no damage: every run's figures are also
# its record in the sweep's results store (docs/sweeps.md), which the report reads.
deleted_dir = os.path.join(SCRATCH, "point_summary_deleted")
shutil.copytree(sweep_dir, deleted_dir)
os.remove(os.path.join(deleted_dir, sweep_run, "summary.json"))
proc = latsim("report", deleted_dir)
check(proc.returncode == 0 and "Traceback" not in proc.stderr,
      f"point summary deleted: exit {proc.returncode}, want 0 (the store holds it): {proc.stderr.strip()[-300:]}")

PROGRESS_LINE = re.compile(r"^report: .+ \d+/\d+( done)?$")

for number, (name, pristine, damaged, damage) in enumerate(CASES):
    case_dir = os.path.join(SCRATCH, f"case_{number}")
    shutil.copytree(pristine, case_dir)
    damage(os.path.join(case_dir, damaged))
    before = snapshot(case_dir)
    proc = latsim("report", case_dir)
    # Progress lines ("report: <task> i/n", analysis/progress.py) come only
    # when the work before the damaged file takes seconds, as on a loaded
    # machine: they are not the error line, which must be the only other one.
    lines = [x for x in proc.stderr.strip().splitlines() if not PROGRESS_LINE.match(x)]
    check(proc.returncode == 2, f"{name}: exit {proc.returncode}, want 2: {proc.stderr.strip()[-400:]}")
    check("Traceback" not in proc.stderr, f"{name}: a traceback")
    check(len(lines) == 1, f"{name}: {len(lines)} lines on stderr, want 1")
    check(bool(lines) and os.path.basename(damaged) in lines[0], f"{name}: the line names no {damaged}: {lines}")
    check(snapshot(case_dir) == before, f"{name}: the report added or changed files")

finish("report on damaged directories")
