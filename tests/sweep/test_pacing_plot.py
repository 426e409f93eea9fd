"""analysis/pacing_plot.py: the Pareto front and missed frames per minute on
hand-made rows, and the report section it writes for a directory of runs.

Usage: test_pacing_plot.py SOURCE_DIR SCRATCH_DIR
"""

import json
import os
import shutil
import subprocess
import sys

SOURCE_DIR, SCRATCH = sys.argv[1], sys.argv[2]
sys.path.insert(0, os.path.join(SOURCE_DIR, "analysis"))

import latsim_results as lr  # noqa: E402
import pacing_plot  # noqa: E402

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAILED:", message)


# (missed, latency): (1, 20) and (5, 15) and (10, 12) trade one for the
# other; (6, 16) is beaten by (5, 15) on both; (1, 21) by (1, 20) on latency.
points = [(1, 20), (5, 15), (6, 16), (10, 12), (1, 21)]
check(pacing_plot.pareto_front(points) == [0, 1, 3], "front of the hand-made points, by missed frames")


def summary(missed, mtp_mean, duration_s=30, late=None):
    figures = {"motion_to_photon_ms": {"mean": mtp_mean, "p99": mtp_mean + 10, "count": 10,
                                       "histogram": [[mtp_mean - 1, 5], [mtp_mean, 5]]},
               "frames_missed": missed}
    if late is not None:
        figures["frames_late_to_latch"] = late
    return {"latsim": {"version": "0", "git_revision": "fixture"},
            "scenario": {"duration_s": duration_s, "pipeline": {"type": "frame_stages"}}, "figures": figures}


row = lr.Row("r", [], [summary(10, 20), summary(20, 20)])
check(abs(pacing_plot.missed_per_minute(row) - 30.0) < 1e-9, "10 and 20 missed in 30 s: 30 a minute on average")

root = os.path.join(SCRATCH, "pacing_runs")
shutil.rmtree(root, ignore_errors=True)
for name, s in [("fixed", summary(60, 18)), ("monado", summary(30, 16, late=40)), ("jit", summary(6, 19, late=8))]:
    os.makedirs(os.path.join(root, name))
    with open(os.path.join(root, name, "summary.json"), "w") as f:
        json.dump(s, f)
out = subprocess.run([sys.executable, os.path.join(SOURCE_DIR, "analysis", "report.py"), root],
                     capture_output=True, text=True)
check(out.returncode == 0, f"report ran: {out.stderr}")
report = open(os.path.join(root, "report.md")).read() if out.returncode == 0 else ""
check("## Pacing: latency against frames_missed" in report, "the pacing section is written")
check("| monado | 60 | 16 |" in report, "monado's row: 30 missed in 30 s is 60 a minute, MTP mean 16")
check(os.path.isfile(os.path.join(root, "pacing_pareto.png")), "the Pareto plot is drawn")

if failures:
    print(f"FAIL: {len(failures)} check(s)")
    sys.exit(1)
print("ok: pacing plot")
