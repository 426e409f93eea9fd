"""The report of a see-through sweep: the passthrough stages table
(photon-to-photon beside the rig, the six stages with their sum check, the
camera frames shown, dropped and repeated), from a fixture whose figures are
chosen so that the expected cells follow by hand.

Usage: test_passthrough_report.py SOURCE_DIR SCRATCH_DIR
"""

import csv
import json
import os
import shutil
import subprocess
import sys

SOURCE_DIR, SCRATCH = sys.argv[1], sys.argv[2]
REPORT = os.path.join(SOURCE_DIR, "analysis", "report.py")
sys.path.insert(0, os.path.join(SOURCE_DIR, "analysis"))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import latsim_results  # noqa: E402
from sweep_checks import check, finish, write_report_fixture  # noqa: E402

STAGES = ["camera", "isp", "reprojection_queue", "reprojection", "display_wait", "scanout"]
# A 100 Hz display: camera 5, ISP 4, queue 0.5, composition 2.5, wait 3, scanout 6.21 ms, added up 21.21 ms.
STAGE_MS = [5.0, 4.0, 0.5, 2.5, 3.0, 6.21]
REFRESH_MS = 10.0


def summary(showings, dropped, rig):
    """A see-through run on a 100 Hz display whose camera frames are each shown `showings` times (1: at the
    display's rate, 2: at half of it) over 1 s. Each frame's first showing is the stages' 21.21 ms after its
    exposure; a showing again comes a refresh later, so photon-to-photon (per refresh) averages
    21.21 + 10 * (0 + 1 + ... + (showings - 1)) / showings."""
    shown = 100 // showings
    p2p = sum(STAGE_MS) + REFRESH_MS * sum(range(showings)) / showings
    figures = {f"{s}_ms": {"count": shown, "mean": v} for s, v in zip(STAGES, STAGE_MS)}
    figures.update({
        "motion_to_photon_ms": {"count": 100, "mean": 3.0, "p50": 3.0, "p99": 3.0, "max": 3.0,
                                "histogram": [[3.0, 100]]},
        "photon_to_photon_ms": {"count": 100, "mean": p2p, "p50": p2p, "p99": p2p, "max": p2p},
        "camera_frames": shown + dropped, "camera_frames_shown": shown, "camera_frames_dropped": dropped,
        "camera_frames_repeated": 100 - shown,
    })
    if rig:
        figures.update({"photon_to_photon_rig_ms": {"count": 4, "mean": p2p + 2.0},
                        "photon_to_photon_rig_shift_ms": {"count": 4, "mean": p2p + 0.25}})
    return {"latsim": {"version": "0.1.0", "git_revision": "fixture"},
            "headline": ["photon_to_photon_ms", "photon_to_photon_rig_ms"],
            "scenario": {"pipeline": {"type": "passthrough"}, "display": {"refresh_hz": 100}},
            "figures": figures, "events": 1000, "wall_s": 0.01}


# (refreshes per camera frame, rig, camera frames dropped in replications 0 and 1).
POINTS = [(1, True, (0, 0)), (2, True, (1, 3)), (1, False, (0, 0))]

shutil.rmtree(SCRATCH, ignore_errors=True)
root = os.path.join(SCRATCH, "sweep")
headline = [c for c, _, _ in latsim_results.HEADLINE]
check("photon_to_photon_mean_ms" in headline, "photon_to_photon_mean_ms is a results.csv column")
points = []
for showings, rig, drops in POINTS:
    replications = []
    for dropped in drops:
        s = summary(showings, dropped, rig)
        replications.append((s, {"mtp_mean_ms": 3.0, "mtp_p50_ms": 3.0, "mtp_p99_ms": 3.0, "mtp_max_ms": 3.0,
                                 "photon_to_photon_mean_ms": s["figures"]["photon_to_photon_ms"]["mean"]}))
    points.append((showings, replications))
write_report_fixture(root, "/pipeline/camera/refreshes_per_frame", points, headline)

proc = subprocess.run([sys.executable, REPORT, root], capture_output=True, text=True)
check(proc.returncode == 0, f"report.py exited {proc.returncode}: {proc.stderr}")
with open(os.path.join(root, "report.md"), encoding="utf-8") as f:
    md = f.read()
check("## Passthrough stages" in md, "passthrough stages section")
check("| photon-to-photon (ms) | rig, frame counting (ms) | rig, trajectory shift (ms) | `camera_ms` | `isp_ms` | "
      "`reprojection_queue_ms` | `reprojection_ms` | `display_wait_ms` | `scanout_ms` | stages' sum (ms) | "
      "photon-to-photon - sum (ms) | camera frames shown | camera frames dropped | camera frames repeated |" in md,
      "the stages in the order a camera frame goes through them")
# Point 0, every frame shown once: photon-to-photon = 5 + 4 + 0.5 + 2.5 + 3 + 6.21 = 21.21, the sum check 0;
# the rig 21.21 + 2 = 23.21 and 21.21 + 0.25 = 21.46; 100 frames shown, none dropped or repeated.
check("| 21.21 | 23.21 | 21.46 | 5.00 | 4.00 | 0.50 | 2.50 | 3.00 | 6.21 | 21.21 | +0.00 | 100 | 0 | 0 |" in md,
      "point 0's row")
# Point 1, each frame shown twice: half the refreshes show it 10 ms later, photon-to-photon 21.21 + 5 = 26.21, the
# sum check +5; rig 28.21 and 26.46; 50 shown, (1 + 3) / 2 = 2 dropped, 50 repeated.
check("| 26.21 | 28.21 | 26.46 | 5.00 | 4.00 | 0.50 | 2.50 | 3.00 | 6.21 | 21.21 | +5.00 | 50 | 2 | 50 |" in md,
      "point 1's row")
# Point 2, no rig: its two cells empty.
check("| 21.21 |  |  | 5.00 |" in md, "point 2's rig cells empty")
check("photon-to-photon mean (ms)" in md, "the latency table shows photon-to-photon where present")
check("Streaming stages" not in md, "no streaming section without streamed runs")

# A sweep without see-through runs has no passthrough section.
plain = os.path.join(SCRATCH, "plain")
shutil.copytree(root, plain)
for run in os.listdir(os.path.join(plain, "runs")):
    path = os.path.join(plain, "runs", run, "summary.json")
    with open(path) as f:
        s = json.load(f)
    s["scenario"]["pipeline"]["type"] = "double_buffer"
    s["headline"] = ["motion_to_photon_ms"]
    s["figures"] = {"motion_to_photon_ms": s["figures"]["motion_to_photon_ms"]}
    with open(path, "w") as f:
        json.dump(s, f)
with open(os.path.join(plain, "results.csv"), newline="") as f:
    table = list(csv.reader(f))
p2p_column = table[0].index("photon_to_photon_mean_ms")
with open(os.path.join(plain, "results.csv"), "w", newline="") as f:
    csv.writer(f, lineterminator="\n").writerows([[c if i != p2p_column or n == 0 else "" for i, c in enumerate(r)]
                                                  for n, r in enumerate(table)])
os.remove(os.path.join(plain, "report.md"))
proc = subprocess.run([sys.executable, REPORT, plain], capture_output=True, text=True)
check(proc.returncode == 0, f"report.py (plain) exited {proc.returncode}: {proc.stderr}")
with open(os.path.join(plain, "report.md"), encoding="utf-8") as f:
    md = f.read()
check("Passthrough stages" not in md, "no passthrough section without see-through runs")
check("photon-to-photon mean (ms)" not in md, "no photon-to-photon column where no row has it")

finish("passthrough report")
print("passthrough report: all checks passed")
