"""The report of a streamed sweep: the streaming stages table (ALVR's stage
names, the tool's total beside the camera's motion-to-photon latency) and the
Pareto plot of latency against frames dropped, from a fixture whose figures
are chosen so that the expected cells and front follow by hand.

Usage: test_streaming_report.py SOURCE_DIR SCRATCH_DIR
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
import sweep_plots  # noqa: E402
from sweep_checks import check, finish, write_report_fixture  # noqa: E402

STAGES = ["game", "server_compositor", "encoder", "network", "decoder", "decoder_queue", "client_compositor",
          "vsync_queue"]


def summary(mtp, dropped):
    """A streamed run: stages 10, 1, 3, network, 4, 5, 1, 13 ms adding up to the tool's total of 40 +
    network; the camera's mean is `mtp`."""
    network = 2.0 + dropped / 10
    stages = dict(zip(STAGES, [10.0, 1.0, 3.0, network, 4.0, 5.0, 1.0, 13.0]))
    figures = {f"{s}_ms": {"count": 10, "mean": v} for s, v in stages.items()}
    figures.update({
        "motion_to_photon_ms": {"count": 10, "mean": mtp, "p50": mtp, "p99": mtp + 5, "max": mtp + 6,
                                "histogram": [[mtp - 1, 5], [mtp, 5]]},
        "reported_total_ms": {"count": 10, "mean": sum(stages.values())},
        "frames_dropped": dropped, "frames_late": 1, "frames_rewarped": dropped,
    })
    return {"latsim": {"version": "0.1.0", "git_revision": "fixture"}, "headline": ["motion_to_photon_ms"],
            "scenario": {"pipeline": {"type": "streaming"}, "display": {"refresh_hz": 90}},
            "figures": figures, "events": 1000, "wall_s": 0.01}


# Four points (bitrate, drops, MTP): A (100, 0, 50), B (200, 0, 52), C (300, 5, 45), D (400, 10, 60).
# By hand: B has A's drops and more latency, D more of both than A and C: the front is A then C.
POINTS = [(100, 0, 50.0), (200, 0, 52.0), (300, 5, 45.0), (400, 10, 60.0)]

shutil.rmtree(SCRATCH, ignore_errors=True)
root = os.path.join(SCRATCH, "sweep")
headline = [c for c, _, _ in latsim_results.HEADLINE]
points = []
for bitrate, dropped, mtp in POINTS:
    values = {"mtp_mean_ms": mtp, "mtp_p50_ms": mtp, "mtp_p99_ms": mtp + 5, "mtp_max_ms": mtp + 6,
              "reported_total_mean_ms": 37.0 + 2.0 + dropped / 10, "frames_dropped": dropped,
              "frames_late": 1, "frames_rewarped": dropped}
    points.append((bitrate, [(summary(mtp, dropped), values)] * 2))
write_report_fixture(root, "/pipeline/encoder/bitrate_mbps", points, headline)

proc = subprocess.run([sys.executable, REPORT, root], capture_output=True, text=True)
check(proc.returncode == 0, f"report.py exited {proc.returncode}: {proc.stderr}")
with open(os.path.join(root, "report.md"), encoding="utf-8") as f:
    md = f.read()
check("## Streaming stages" in md, "streaming stages section")
check("| `game` (ms) | `server_compositor` (ms) | `encoder` (ms) | `network` (ms) | `decoder` (ms) | "
      "`decoder_queue` (ms) | `client_compositor` (ms) | `vsync_queue` (ms) |" in md, "ALVR's stage names in order")
# Point C: camera 45, tool's total 10 + 1 + 3 + 2.5 + 4 + 5 + 1 + 13 = 39.5, camera - tool = +5.50.
check("| 45.00 | 39.50 | +5.50 | 10.00 | 1.00 | 3.00 | 2.50 | 4.00 | 5.00 | 1.00 | 13.00 | 5 | 1 | 5 |" in md,
      "point C's row")
check("![streaming_pareto](streaming_pareto.png)" in md, "Pareto plot in the report")
check(os.path.isfile(os.path.join(root, "streaming_pareto.png")), "streaming_pareto.png written")
check(sweep_plots.pacing_plot.pareto_front([(d, m) for _, d, m in POINTS]) == [0, 2], "front A, C")

# A sweep without streamed runs has neither.
plain = os.path.join(SCRATCH, "plain")
shutil.copytree(root, plain)
for run in os.listdir(os.path.join(plain, "runs")):
    path = os.path.join(plain, "runs", run, "summary.json")
    with open(path) as f:
        s = json.load(f)
    s["scenario"]["pipeline"]["type"] = "double_buffer"
    for name in ["reported_total_ms", "frames_dropped"] + [f"{st}_ms" for st in STAGES]:
        del s["figures"][name]
    with open(path, "w") as f:
        json.dump(s, f)
with open(os.path.join(plain, "results.csv"), newline="") as f:
    table = list(csv.reader(f))
drop = [table[0].index("reported_total_mean_ms"), table[0].index("frames_dropped")]
with open(os.path.join(plain, "results.csv"), "w", newline="") as f:
    csv.writer(f, lineterminator="\n").writerows([[c if i not in drop or n == 0 else "" for i, c in enumerate(r)]
                                                  for n, r in enumerate(table)])
for name in ("streaming_pareto.png", "streaming_pareto.svg", "report.md"):
    os.remove(os.path.join(plain, name))
proc = subprocess.run([sys.executable, REPORT, plain], capture_output=True, text=True)
check(proc.returncode == 0, f"report.py (plain) exited {proc.returncode}: {proc.stderr}")
with open(os.path.join(plain, "report.md"), encoding="utf-8") as f:
    md = f.read()
check("Streaming stages" not in md and "streaming_pareto" not in md, "no streaming section without streamed runs")
check(not os.path.exists(os.path.join(plain, "streaming_pareto.png")), "no Pareto plot without streamed runs")

finish("streaming report")
print("streaming report: all checks passed")
