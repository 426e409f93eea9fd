"""The Python report renders all three layouts of result directory, from a
fixture this script generates, and renders them reproducibly.

Usage: test_report.py SOURCE_DIR SCRATCH_DIR
"""

import csv
import hashlib
import json
import os
import shutil
import subprocess
import sys

SOURCE_DIR, SCRATCH = sys.argv[1], sys.argv[2]
REPORT = os.path.join(SOURCE_DIR, "analysis", "report.py")
sys.path.insert(0, os.path.join(SOURCE_DIR, "analysis"))

import latsim_results  # noqa: E402

failures = []
checked = []


def check(condition, message):
    checked.append(message)
    if not condition:
        failures.append(message)
        print("FAILED:", message)


def summary(pipeline, mtp_mean_ms, refresh_hz=60):
    lower = [mtp_mean_ms - 8 + 2 * i for i in range(8)]
    return {
        "latsim": {"version": "0.1.0", "git_revision": "fixture"},
        "scenario": {"pipeline": {"type": pipeline}, "display": {"refresh_hz": refresh_hz}},
        "figures": {
            "motion_to_photon_ms": {"count": 100, "mean": mtp_mean_ms, "p50": mtp_mean_ms, "p99": mtp_mean_ms + 7,
                                    "max": mtp_mean_ms + 8, "histogram": [[e, 5 + (i % 3) * 10] for i, e in enumerate(lower)]},
            "render_latency_ms": {"count": 10, "mean": 16.7},
            "render_latency_fields": {"count": 10, "mean": 1.0},
            "registration_error_arcmin": {"count": 100, "mean": mtp_mean_ms / 10, "p99": mtp_mean_ms / 5},
            "frame_rate_hz": 60, "missed_refreshes": 0,
        },
        "events": 1000, "wall_s": 0.01,
    }


def write_run(run_dir, s, timeline=True):
    os.makedirs(run_dir, exist_ok=True)
    with open(os.path.join(run_dir, "summary.json"), "w") as f:
        json.dump(s, f)
    if timeline:
        with open(os.path.join(run_dir, "timeline.csv"), "w") as f:
            f.write("stage,frame,eye,unit,start_ms,end_ms\n")
            for frame in range(8):
                t = frame * 16.683
                f.write(f"TRANSFORM,{frame},-1,GP,{t:.3f},{t + 5:.3f}\n")
                f.write(f"RENDER,{frame},0,R1,{t + 5:.3f},{t + 12:.3f}\n")
                f.write(f"RENDER,{frame},1,R2,{t + 5:.3f},{t + 12.5:.3f}\n")
                f.write(f"SCANOUT,{frame},-1,display,{t + 16.683:.3f},{t + 33.366:.3f}\n")


def make_sweep(root):
    """Two axes (refresh 60 / 60000/1001, poll 0/10/20), 3 replications."""
    axes = ["/display/refresh_hz", "/transport/poll_interval_ms"]
    rows, point = [], 0
    for refresh in ["60", "60000/1001"]:
        for poll in [0, 10, 20]:
            for rep in range(3):
                run_id = f"{point:08x}{rep:08x}"
                mean = 30 + poll / 2 + rep * 0.5 + (0.1 if refresh == "60" else 0)
                write_run(os.path.join(root, "runs", run_id), summary("double_buffer", mean, refresh), timeline=point == 0)
                rows.append([run_id, point, refresh, poll, 1, rep, mean])
            point += 1
    with open(os.path.join(root, "results.csv"), "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["run_id", "point"] + axes + ["seed", "replication", "mtp_mean_ms"])
        w.writerows(rows)


def make_big_sweep(root):
    """30 points (a = 1..5 x b = 10..60) x 3 replications, every headline column in results.csv as
    latsim writes it; MTP mean = 10 a + b / 10 + replication. Only replication 0 has a readable
    summary.json (and a timeline): the report must read one summary per point, not one per run."""
    headline = [c for c, _, _ in latsim_results.HEADLINE]
    rows, point = [], 0
    for a in range(1, 6):
        for b in range(10, 70, 10):
            for rep in range(3):
                run_id = f"{point:08x}{rep:08x}"
                mean = 10 * a + b / 10 + rep
                run_dir = os.path.join(root, "runs", run_id)
                write_run(run_dir, summary("double_buffer", mean), timeline=rep == 0)
                if rep > 0:
                    with open(os.path.join(run_dir, "summary.json"), "w") as f:
                        f.write("not read by the report")
                values = {"mtp_mean_ms": mean, "mtp_p50_ms": mean, "mtp_p99_ms": mean + 7, "mtp_max_ms": mean + 8,
                          "render_latency_ms": 16.7, "render_latency_fields": 1, "frame_rate_hz": 60,
                          "registration_error_mean_arcmin": mean / 10, "registration_error_p99_arcmin": mean / 5}
                # Rotation latency is not a double buffer's figure: its cells stay empty.
                rows.append([run_id, point, a, b, 1, rep] + [values.get(c, "") for c in headline])
            point += 1
    with open(os.path.join(root, "results.csv"), "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["run_id", "point", "/a", "/b", "seed", "replication"] + headline)
        w.writerows(rows)


def run_report(directory, *options):
    proc = subprocess.run([sys.executable, REPORT, directory, *options], capture_output=True, text=True)
    check(proc.returncode == 0, f"report.py {directory} exited {proc.returncode}: {proc.stderr}")
    return proc


def digest(directory):
    """Hashes of every output file under directory, by relative path."""
    out = {}
    for base, _, files in sorted(os.walk(directory)):
        for name in sorted(files):
            if name.endswith((".png", ".svg", ".md")) or name == "latency_table.csv":
                path = os.path.join(base, name)
                with open(path, "rb") as f:
                    out[os.path.relpath(path, directory)] = hashlib.sha256(f.read()).hexdigest()
    return out


shutil.rmtree(SCRATCH, ignore_errors=True)
sweep_dir, runs_dir, single_dir = (os.path.join(SCRATCH, n) for n in ("sweep", "runs", "single"))
make_sweep(sweep_dir)
for name, pipeline, mean in [("hmd_double_buffer", "double_buffer", 45.0), ("pxpl5_slats", "pxpl5_slats", 25.0)]:
    write_run(os.path.join(runs_dir, name), summary(pipeline, mean))
os.makedirs(os.path.join(runs_dir, "not_a_run"))
write_run(single_dir, summary("arp", 12.0))

for d in (sweep_dir, runs_dir, single_dir):
    run_report(d)
    for name in ("report.md", "latency_table.csv", "mtp_cdf.png", "mtp_cdf.svg", "mtp_histogram.png", "mtp_histogram.svg"):
        check(os.path.isfile(os.path.join(d, name)), f"{d}: {name} missing")

# Sweep: one plot per axis; the latency table averages replications per point.
for name in ("sweep_refresh_hz.png", "sweep_refresh_hz.svg", "sweep_poll_interval_ms.png"):
    check(os.path.isfile(os.path.join(sweep_dir, name)), f"sweep: {name} missing")
with open(os.path.join(sweep_dir, "latency_table.csv")) as f:
    table = list(csv.DictReader(f))
check(len(table) == 6, f"sweep table has {len(table)} rows, expected 6 points")
check(table[1]["/transport/poll_interval_ms"] == "10" and table[1]["replications"] == "3", "sweep table row 1 axis values")
check(abs(float(table[1]["mtp_mean_ms"]) - 35.6) < 1e-9, f"sweep point 1 mean {table[1]['mtp_mean_ms']} != 35.6")
check(os.path.isfile(os.path.join(sweep_dir, "runs", "0000000000000000", "gantt.png")), "sweep: Gantt chart missing")

# Directory of runs: one row per subdirectory with a summary, sorted by name.
with open(os.path.join(runs_dir, "latency_table.csv")) as f:
    table = list(csv.DictReader(f))
check([r["name"] for r in table] == ["hmd_double_buffer", "pxpl5_slats"], f"runs table names {[r['name'] for r in table]}")
check(table[1]["pipeline"] == "pxpl5_slats" and table[1]["mtp_p99_ms"] == "32", "runs table figures")
for name in ("hmd_double_buffer", "pxpl5_slats"):
    check(os.path.isfile(os.path.join(runs_dir, name, "gantt.svg")), f"{name}: gantt.svg missing")
with open(os.path.join(runs_dir, "report.md")) as f:
    md = f.read()
check("| pxpl5_slats | pxpl5_slats |" in md and "hmd_double_buffer/gantt.png" in md, "runs report.md content")

# A sweep too large for one table: the lowest and highest --top points by hand
# (mean over replications 10 a + b / 10 + 1), a heat map, a sample of Gantt charts.
big_dir = os.path.join(SCRATCH, "big")
make_big_sweep(big_dir)
run_report(big_dir, "--top", "4", "--gantt-limit", "4")
with open(os.path.join(big_dir, "report.md")) as f:
    md = f.read()
lowest = md[md.index("### Lowest"):md.index("### Highest")]
highest = md[md.index("### Highest"):md.index("## ", md.index("### Highest") + 4)]
names = lambda text: [line.split(" | ")[0].lstrip("| ") for line in text.splitlines() if line.startswith("| /a=")]
check(names(lowest) == ["/a=1, /b=10", "/a=1, /b=20", "/a=1, /b=30", "/a=1, /b=40"], f"lowest 4: {names(lowest)}")
check(names(highest) == ["/a=5, /b=30", "/a=5, /b=40", "/a=5, /b=50", "/a=5, /b=60"], f"highest 4: {names(highest)}")
check("| /a=5, /b=60 | double_buffer | 3 | 57 |" in highest, "highest point's mean over replications should be 57")
with open(os.path.join(big_dir, "latency_table.csv")) as f:
    check(len(list(csv.DictReader(f))) == 30, "the full table should keep all 30 points")
check(os.path.isfile(os.path.join(big_dir, "heatmap.png")) and "heatmap.png" in md, "heat map missing")
# 4 of 30 points evenly spaced: round(i * 29 / 3) = points 0, 10, 19, 29 (replication 0 of each).
drawn = sorted(d for d in os.listdir(os.path.join(big_dir, "runs"))
               if os.path.isfile(os.path.join(big_dir, "runs", d, "gantt.png")))
check(drawn == [f"{p:08x}{0:08x}" for p in (0, 10, 19, 29)], f"Gantt sample {drawn}")
check("26 more point(s) have a timeline.csv" in md, "report.md should say how many points have no chart")
import heatmap  # noqa: E402
coll = latsim_results.load(big_dir)
check(heatmap.choose_axes(coll) == ("/b", "/a"), f"heat map axes {heatmap.choose_axes(coll)}")
_, panels = heatmap.grids(coll, "/b", "/a", "motion_to_photon_ms.mean")
grid = panels[()]
check(all(abs(grid[i][j] - (10 * (i + 1) + (j + 1) + 1)) < 1e-9 for i in range(5) for j in range(6)),
      f"heat map cells {grid}")
proc = subprocess.run([sys.executable, REPORT, big_dir, "--figure", "nonsense"], capture_output=True, text=True)
check(proc.returncode == 2 and len(proc.stderr.strip().splitlines()) == 1, f"bad --figure: {proc.stderr}")

# Behind a time warp the headline is rotation latency: the table leads with it,
# the default sort column is its mean, and its CDF is drawn. Two warped runs
# (rotation latency 9 and 7 ms; their application poses' MTP 30 and 31 ms)
# beside nothing else: sorted by the headline the 7 ms one comes first.
warp_dir = os.path.join(SCRATCH, "warped")
for name, mtp, rot in [("warp_a", 30.0, 9.0), ("warp_b", 31.0, 7.0)]:
    s = summary("frame_stages", mtp)
    s["headline"] = ["rotation_latency_ms", "application_frame_rate_hz", "frames_missed", "motion_to_photon_ms"]
    s["figures"]["rotation_latency_ms"] = {"count": 100, "mean": rot, "p50": rot, "p99": rot + 3, "max": rot + 4,
                                           "histogram": [[rot - 2 + i, 10] for i in range(4)]}
    write_run(os.path.join(warp_dir, name), s, timeline=False)
run_report(warp_dir, "--title", "warped designs")
with open(os.path.join(warp_dir, "report.md")) as f:
    md = f.read()
check(md.startswith("# latsim report: warped designs"), "--title names the report")
check("| name | pipeline | rotation latency mean (ms) | rotation latency p99 (ms) |" in md,
      "a warped set's table should lead with rotation latency")
check("| warp_b | frame_stages | 7 | 10 |" in md, "rotation latency mean and p99 of warp_b")
check(os.path.isfile(os.path.join(warp_dir, "rotation_cdf.png")) and "rotation_cdf.png" in md, "rotation CDF missing")
with open(os.path.join(warp_dir, "latency_table.csv")) as f:
    table = list(csv.DictReader(f))
check(table[0]["rotation_latency_mean_ms"] == "9" and table[1]["rotation_latency_p99_ms"] == "10",
      "latency_table.csv rotation columns")
import report  # noqa: E402
coll = latsim_results.load(warp_dir)
check(report.default_figure(coll)[0] == "rotation_latency_mean_ms", "default --figure behind a warp")
check(report.sweep_figures(coll)[0][0] == "rotation_latency_ms.mean", "sweep plots lead with rotation latency")
# A double buffer's set keeps motion-to-photon first and shows no rotation column.
coll = latsim_results.load(runs_dir)
check(report.default_figure(coll)[0] == "mtp_mean_ms", "default --figure without a warp")
with open(os.path.join(runs_dir, "report.md")) as f:
    header = [line for line in f.read().splitlines() if line.startswith("| name | pipeline |")][0]
    check("MTP mean (ms)" in header and "rotation latency" not in header, "no rotation column without the figure")
    check("controller" not in header and "apparent" not in header, "no controller or apparent column without them")

# A run that tracks a controller shows its columns; one that does not leaves them empty.
ctl_dir = os.path.join(SCRATCH, "controller")
for name, age in [("with_controller", 18.5), ("without", None)]:
    s = summary("double_buffer", 30.0)
    if age is not None:
        s["figures"]["controller_latency_ms"] = {"count": 10, "mean": age}
        s["figures"]["controller_apparent_latency_ms_steady"] = {"count": 10, "mean": -0.5}
    write_run(os.path.join(ctl_dir, name), s, timeline=False)
run_report(ctl_dir)
with open(os.path.join(ctl_dir, "report.md")) as f:
    md = f.read()
check("controller latency mean (ms) | controller apparent latency, steady (ms) |" in md
      and "onset" not in md and "camera measurement" not in md, "controller columns shown only where a row has them")
check(any(line.startswith("| with_controller |") and "| 18.5 | -0.5 |" in line for line in md.splitlines()),
      "controller columns of the run that has them")

# The prediction table names each row: two points of one pipeline and predictor
# (a multi-axis sweep gives many) are told apart by their point's name.
import prediction  # noqa: E402
pred_dir = os.path.join(SCRATCH, "predicting")
for name, mtp in [("refresh=60, horizon=10", 30.0), ("refresh=90, horizon=10", 20.0)]:
    s = summary("double_buffer", mtp)
    s["scenario"]["host"] = {"prediction": {"type": "constant_velocity"}}
    write_run(os.path.join(pred_dir, name), s, timeline=False)
table = prediction.markdown(latsim_results.load(pred_dir))
check("| point | pipeline | predictor | MTP mean (ms) |" in "\n".join(table), "prediction table has a point column")
check(any(line.startswith("| refresh=90, horizon=10 | double_buffer | constant_velocity | 20 |") for line in table),
      f"prediction table rows {table}")

# Latency over time from fields.csv: field 2 starts scanout at 32 ms with a
# pose measured at 30 ms and its orientation re-measured at 31 ms: 2 ms
# motion-to-photon, 1 ms rotation latency; eye 1 and imageless fields are not drawn.
import latency_over_time  # noqa: E402
lot_dir = os.path.join(SCRATCH, "over_time")
write_run(os.path.join(lot_dir, "warped"), summary("frame_stages", 20.0), timeline=False)
with open(os.path.join(lot_dir, "warped", "fields.csv"), "w") as f:
    f.write("field,eye,image,frame,sample,measured_ps,orientation_at_scanout,orientation_measured_ps,first_line,"
            "first_x,last_line,last_x,retrace_ps,scanout_start_ps\n")
    f.write("2,0,0,0,30,30000000000,0,31000000000,0,0,479,0,32000000000,32000000000\n")
    f.write("2,1,1,0,30,30000000000,0,31000000000,0,0,479,0,32000000000,32000000000\n")
    f.write("3,0,-1,-1,,,0,,0,0,479,0,48000000000,48000000000\n")
points = latency_over_time.read_fields(os.path.join(lot_dir, "warped"))
check(points == [(0.032, 2.0, 1.0)], f"latency over time points {points}")
run_report(lot_dir)
with open(os.path.join(lot_dir, "report.md")) as f:
    check("## Latency over time" in f.read() and os.path.isfile(os.path.join(lot_dir, "latency_over_time.png")),
          "latency over time plot missing")

# Phase luck in the table: a sweep's headline mean with its 95 % interval over
# replications; point (60, 10) has means 35.1, 35.6, 36.1 (sd 0.5), so
# 4.303 x 0.5 / sqrt(3) = 1.242. And a pipeline's analytic phase average.
with open(os.path.join(sweep_dir, "report.md")) as f:
    md = f.read()
check("| MTP mean (ms) | 95 % interval |" in md, "sweep table: interval column")
check("| 35.6 | ± 1.24 |" in md, "sweep table: interval of point 1")
an_dir = os.path.join(SCRATCH, "analytic")
s = summary("double_buffer", 31.95)
s["figures"]["analytic"] = {"motion_to_photon_ms": {"mean": 35.68, "min": 19.4, "max": 51.97}}
write_run(os.path.join(an_dir, "hmd"), s, timeline=False)
run_report(an_dir)
with open(os.path.join(an_dir, "report.md")) as f:
    md = f.read()
check("MTP mean over phases, analytic (ms) |" in md and "| 35.68 |" in md, "analytic phase average column")

# The user chooses the columns: --figures, or the sweep file's "figures" (plan.json); on a copy, so that
# the reproducibility check below compares untouched renderings.
chosen_dir = os.path.join(SCRATCH, "chosen")
shutil.copytree(sweep_dir, chosen_dir)
run_report(chosen_dir, "--figures", "mtp_p99_ms,registration_error_mean_arcmin")
with open(os.path.join(chosen_dir, "report.md")) as f:
    header = [line for line in f.read().splitlines() if line.startswith("| name |")][0]
check(header.endswith("| MTP p99 (ms) | 95 % interval | registration error mean (arcmin) |") and "MTP mean" not in header,
      f"--figures columns: {header}")
proc = subprocess.run([sys.executable, REPORT, chosen_dir, "--figures", "mtp_p99_ms,nonsense"],
                      capture_output=True, text=True)
check(proc.returncode == 2 and "nonsense" in proc.stderr and len(proc.stderr.strip().splitlines()) == 1,
      f"bad --figures: {proc.stderr}")
# The choices listed are cut at a whole name: each before "…" is a column name.
listed = proc.stderr.split("expected some of ", 1)[1].split(", \u2026")[0].split(", ")
check(all(name in [c for c, _, _ in latsim_results.HEADLINE] for name in listed), f"whole names: {listed}")
# Any figure a run reports, by its path, is a column too: a results.csv column's path names that
# column (motion_to_photon_ms.p50 is mtp_p50_ms), any other figure's path heads its own.
run_report(chosen_dir, "--figures", "mtp_p99_ms,motion_to_photon_ms.p50,motion_to_photon_ms.p90")
with open(os.path.join(chosen_dir, "report.md")) as f:
    header = [line for line in f.read().splitlines() if line.startswith("| name |")][0]
check(header.endswith("| MTP p99 (ms) | 95 % interval | MTP p50 (ms) | motion_to_photon_ms.p90 |"),
      f"figures chosen by their paths: {header}")
with open(os.path.join(chosen_dir, "plan.json"), "w") as f:
    json.dump({"axes": [], "figures": ["frame_rate_hz"]}, f)
run_report(chosen_dir)
with open(os.path.join(chosen_dir, "report.md")) as f:
    header = [line for line in f.read().splitlines() if line.startswith("| name |")][0]
check("| frame rate (Hz) |" in header and "MTP" not in header, f"plan.json figures columns: {header}")

# Progress lines: none for work that ends within 2 s, then one every 2 s.
import io  # noqa: E402
from progress import Progress  # noqa: E402
now, out = [0.0], io.StringIO()
p = Progress("charts", 5, clock=lambda: now[0], out=out)
for t in (0.5, 1.9, 2.1, 3.0, 4.2):
    now[0] = t
    p.advance()
p.finish()
check(out.getvalue().splitlines() == ["report: charts 3/5", "report: charts 5/5", "report: charts 5/5 done"],
      f"progress lines {out.getvalue().splitlines()}")
quiet = io.StringIO()
p = Progress("quick", 2, clock=lambda: 1.0, out=quiet)
p.advance()
p.finish()
check(quiet.getvalue() == "", "short work printed progress")

# Reproducible: a second rendering is byte-identical.
before = digest(SCRATCH)
for d in (sweep_dir, runs_dir, single_dir):
    run_report(d)
after = digest(SCRATCH)
changed = sorted(k for k in before if before[k] != after.get(k))
check(not changed, f"outputs differ between two renderings: {changed}")
check(len(before) >= 25, f"only {len(before)} output files")

# Statistics helpers.
check(abs(latsim_results.t975(2) - 4.303) < 1e-9, "t975(2)")
check(abs(latsim_results.t975(35) - 2.030) < 0.002, f"t975(35) = {latsim_results.t975(35)}")
check(abs(latsim_results.t975(10 ** 6) - 1.960) < 0.001, "t975(large)")
mean, half = latsim_results.mean_ci95([1.0, 2.0, 3.0])
check(mean == 2.0 and abs(half - 4.303 / 3 ** 0.5) < 1e-9, f"mean_ci95 {mean} {half}")
check(latsim_results.as_number("60000/1001") == 60000 / 1001 and latsim_results.as_number("serial") is None, "as_number")
# Sweep row names: a label swept along with whole objects names the row alone.
axes = ["/description", "/pipeline"]
check(latsim_results.row_name({"/description": "Slats", "/pipeline": '{"type": "pxpl5_slats"}'}, axes) == "Slats",
      "row name from a label beside object values")
# Axes are named by their pointer (a last key such as fixed_ms does not say
# which stage's), or by the label the sweep file declares.
check(latsim_results.row_name({"/a": "1", "/b": "2"}, ["/a", "/b"]) == "/a=1, /b=2", "row name from plain values")
latsim_results.AXIS_LABELS["/pipeline/stages/2/cost/fixed_ms"] = "G cost"
check(latsim_results.row_name({"/pipeline/stages/2/cost/fixed_ms": "5", "/b": "2"},
                              ["/pipeline/stages/2/cost/fixed_ms", "/b"]) == "G cost=5, /b=2", "row name from a label")
latsim_results.AXIS_LABELS.clear()

# A directory with nothing in it is bad input.
empty = os.path.join(SCRATCH, "empty")
os.makedirs(empty)
proc = subprocess.run([sys.executable, REPORT, empty], capture_output=True, text=True)
check(proc.returncode == 2 and "no summary.json" in proc.stderr, f"empty dir: exit {proc.returncode} {proc.stderr}")

print(f"report fixture: {len(checked) - len(failures)} checks passed, {len(failures)} failed")
sys.exit(1 if failures else 0)
