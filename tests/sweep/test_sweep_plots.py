"""Every plot of `latsim report` reads on sweeps whose axes hold whole JSON objects.

Two tiny sweeps of the Valve Index profile are run with the latsim binary: a
zip over three devices (a labelled /description axis beside whole
/display/persistence and /tracker objects) and a Cartesian sweep of three
persistence objects (labelled) by two /transport objects (unlabelled). The
report is drawn in this process with plotting.save watched: every text of every
figure (titles, axis labels, ticks, legends, annotations) must hold no `{`, and
every PNG must be at most 2,000 px wide. Positive controls: the texts must hold
the labels derived below by hand, so a figure whose texts were not seen fails.

Usage: test_sweep_plots.py LATSIM SOURCE_DIR SCRATCH_DIR
"""

import json
import os
import shutil
import struct
import subprocess
import sys

LATSIM, SOURCE_DIR, SCRATCH = sys.argv[1], os.path.abspath(sys.argv[2]), os.path.abspath(sys.argv[3])
sys.path.insert(0, os.path.join(SOURCE_DIR, "analysis"))

import latsim_results  # noqa: E402
import plotting  # noqa: E402
import report  # noqa: E402
from matplotlib.text import Text  # noqa: E402

failures = []
checked = []
MAX_WIDTH_PX = 2000
BASE = os.path.join(SOURCE_DIR, "scenarios", "devices", "index_90hz.json")
PERSISTENCE = [{"type": "global", "lit_ms": 0.48, "response_ms": 1}, {"type": "global", "lit_ms": 1, "response_ms": 1},
               {"type": "rolling", "lit_ms": 2, "response_ms": 0.1}]
# By hand: the keys in which the three differ are all three, named by their last key, in sorted order.
PERSISTENCE_LABELS = ["lit_ms=0.48, response_ms=1, type=global", "lit_ms=1, response_ms=1, type=global",
                      "lit_ms=2, response_ms=0.1, type=rolling"]
DEVICES = ["Index 90 Hz", "Quest 2 72 Hz", "Vive 90 Hz"]
ZIP = {
    "description": "three devices side by side", "base": BASE, "mode": "zip", "replications": 2, "seed": 1,
    # The /tracker values replace the profile's IMU chain, which its fusion predictor needs: predict at constant velocity.
    "overrides": {"/duration_s": 0.2, "/host/prediction": {"type": "constant_velocity"}},
    "axes": [{"pointer": "/description", "label": "device", "values": DEVICES},
             {"pointer": "/display/persistence", "label": "persistence", "values": PERSISTENCE},
             {"pointer": "/tracker", "values": [{"rate_hz": 500, "internal_delay_ms": 0},
                                                {"rate_hz": 1000, "internal_delay_ms": 0},
                                                {"rate_hz": 500, "internal_delay_ms": 0}]},
             # Paced points bring the pacing plot; kept traces the Gantt charts and latency over time.
             {"pointer": "/pipeline/pacing", "values": [{"application": "fixed"}, {"application": "just_in_time"},
                                                        {"application": "monado"}]}],
}
CARTESIAN = {
    # A double buffer keeps a stage timeline: the Gantt chart's title names its point.
    "description": "persistence by transport", "base": os.path.join(SOURCE_DIR, "scenarios", "hmd_60hz_direct.json"),
    "replications": 2, "seed": 1,
    "overrides": {"/duration_s": 0.2, "/display/persistence": PERSISTENCE[0]},
    "axes": [{"pointer": "/display/persistence", "label": "persistence", "values": PERSISTENCE},
             {"pointer": "/transport", "values": [{"type": "usb_hid", "poll_hz": 1000}, {"type": "direct"}]}],
}


def check(condition, message):
    checked.append(message)
    if not condition:
        failures.append(message)
        print("FAILED:", message)


def sweep(name, spec, *options):
    path = os.path.join(SCRATCH, f"{name}.json")
    with open(path, "w") as f:
        json.dump(spec, f)
    out = os.path.join(SCRATCH, name)
    proc = subprocess.run([LATSIM, "sweep", path, "-o", out, *options], capture_output=True, text=True)
    check(proc.returncode == 0, f"latsim sweep {name}: {proc.stderr.strip()}")
    return out


# Every figure's texts, by the base name it is saved under.
TEXTS = {}
_save = plotting.save


def watched_save(fig, base_path):
    texts = [t.get_text() for t in fig.findobj(Text) if t.get_visible() and t.get_text()]
    TEXTS[os.path.relpath(base_path, SCRATCH)] = texts
    # The PNG alone: its width is what is judged, and the SVG would double the drawing time.
    _save(fig, base_path, formats=("png",))


def png_width(path):
    with open(path, "rb") as f:
        return struct.unpack(">II", f.read(24)[16:24])[0]


def draw(directory, *options):
    """Runs the report in this process (every module saves through plotting.save)."""
    TEXTS.clear()
    plotting.save = watched_save
    status = report.main(["report.py", directory, *options])
    check(status == 0, f"report {directory} exited {status}")
    return dict(TEXTS)


def judge(name, texts):
    check(texts, f"{name}: no figure seen")
    for base, lines in sorted(texts.items()):
        braces = [t for t in lines if "{" in t]
        check(not braces, f"{base}: text with a brace: {braces[:2]}")
        png = os.path.join(SCRATCH, base + ".png")
        width = png_width(png) if os.path.isfile(png) else None
        check(width is not None and width <= MAX_WIDTH_PX, f"{base}.png: {width} px wide")


shutil.rmtree(SCRATCH, ignore_errors=True)
os.makedirs(SCRATCH)
zip_dir = sweep("zip", ZIP, "--keep", "first", "--ledger")
cart_dir = sweep("cartesian", CARTESIAN, "--keep", "first")

zip_texts = draw(zip_dir)
judge("zip", zip_texts)
points = zip_texts.get("zip/sweep_points", [])
check(all(d in points for d in DEVICES), f"zip: sweep_points ticks name the devices: {points}")
check(not any(b.startswith("zip/sweep_") and b != "zip/sweep_points" for b in zip_texts),
      f"zip: one plot by point, none per axis: {sorted(zip_texts)}")
drawn = sorted(b.split("/")[-1] for b in zip_texts)
check(all(p in drawn for p in ("pacing_pareto", "latency_over_time", "registration_vs_latency")),
      f"zip: every kind of plot drawn: {drawn}")
check("zip/heatmap" not in zip_texts and not os.path.exists(os.path.join(zip_dir, "heatmap.png")),
      "a zip sweep has no heat map")
with open(os.path.join(zip_dir, "report.md")) as f:
    md = f.read()
check("| Index 90 Hz |" in md and "heatmap" not in md, "zip report.md: rows by device, no heat map")
check(any(DEVICES[0] in t for t in zip_texts.get("zip/mtp_cdf", [])), "zip: CDF legend names the devices")

cart_texts = draw(cart_dir, "--gantt-limit", "1")
judge("cartesian", cart_texts)
gantt = [t for b, lines in cart_texts.items() if b.endswith("/gantt") for t in lines if "pipeline stages" in t]
check(gantt == ["persistence (lit_ms=0.48, response_ms=1, type=global), /transport (poll_hz=1000, type=usb_hid): "
               "pipeline stages"],
      f"a Gantt chart titled by its point: {gantt}")
persistence = cart_texts.get("cartesian/sweep_persistence", [])
check(all(label in persistence for label in PERSISTENCE_LABELS), f"persistence ticks by hand: {persistence}")
check(any(t.startswith("persistence (/display/persistence)") for t in persistence), "x axis named by its label")
# The transports differ in type and in poll_hz, which the direct link has not: "absent".
transport = cart_texts.get("cartesian/sweep_transport", [])
check("poll_hz=1000, type=usb_hid" in transport and "poll_hz=absent, type=direct" in transport,
      f"transport ticks by hand: {transport}")
with open(os.path.join(cart_dir, "report.md")) as f:
    md = f.read()
check("| persistence (lit_ms=0.48, response_ms=1, type=global), /transport (poll_hz=1000, type=usb_hid) |" in md,
      "a point of whole objects is named by each axis's label and its value's differing keys")
heat = cart_texts.get("cartesian/heatmap", [])
check(all(label in heat for label in PERSISTENCE_LABELS), f"heat map over the two crossed axes: {heat}")
import heatmap  # noqa: E402
import sweep_labels  # noqa: E402
coll = latsim_results.load(cart_dir)
check(heatmap.choose_axes(coll) == ("/display/persistence", "/transport"), f"heat map axes {heatmap.choose_axes(coll)}")
check(sweep_labels.is_zip(latsim_results.load(zip_dir).rows, [a["pointer"] for a in ZIP["axes"]]),
      "the zip sweep is recognised from its points")
check(not sweep_labels.is_zip(coll.rows, coll.axes), "the Cartesian sweep is not a zip")

# Histograms show their mass: 997 of 1,000 samples in [0, 1), 3 in [99, 100). The 0.5 % and 99.5 %
# quantiles are 5/997 and 995/997 (linear within the first bucket), under half the full range
# [0, 100]: clipped, padded by 5 % of their distance, the low end held at 0.
edges, counts = list(range(101)), [997] + [0] * 98 + [3]
low, high, clipped = latsim_results.mass_range([(edges, counts)])
span = (995 - 5) / 997
check(clipped and low == 0 and abs(high - (995 / 997 + 0.05 * span)) < 1e-12, f"mass range {low} {high} {clipped}")
# An even spread is shown whole.
check(latsim_results.mass_range([(edges, [10] * 100)]) == (0, 100, False), "an even histogram is not clipped")

# A spike over a spread: 600 samples in [0, 0.1) (density 6 per unit) and 400 in [0.1, 10) (density
# 0.4 / 9.9 = 0.04, under 5 % of 6): 40 % of the mass would be drawn at under 5 % of the height: log.
check(latsim_results.needs_log_density([([0, 0.1, 10], [600, 400])]), "a spike over a spread takes a log density")
# 600 in [0, 5) and 400 in [5, 10): densities 0.12 and 0.08, both visible on a linear axis.
check(not latsim_results.needs_log_density([([0, 5, 10], [600, 400])]), "an even histogram stays linear")
registration = [t for t in cart_texts.get("cartesian/mtp_histogram", []) if t.startswith("Motion-to-photon")]
check(registration and ("full range" in registration[0] or "clipped" in registration[0] or "log" in registration[0]),
      f"a histogram's title says its range: {registration}")

print(f"sweep plots: {len(checked) - len(failures)} checks passed, {len(failures)} failed")
sys.exit(1 if failures else 0)
