"""Device profiles in `latsim report`: one table of what each headset's rows
report as a measurement would (docs/devices.md): motion-to-photon, apparent
latency at the start and onset of a movement and in steady motion, the
controller's apparent latency at the start of a flick, and the simulated
camera's frame-counting estimate, each as the mean over replications with its
standard deviation over them; beside the camera, every public measurement of
the device (analysis/devices_published.py) and the difference to each.
"""

import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import latsim_results as lr  # noqa: E402
from devices_published import PUBLISHED  # noqa: E402

# Table columns: (header, figure path).
COLUMNS = [
    ("MTP (ms)", "motion_to_photon_ms.mean"),
    ("apparent, start (ms)", "apparent_latency_ms_start.mean"),
    ("apparent, onset (ms)", "apparent_latency_ms_onset.mean"),
    ("apparent, steady (ms)", "apparent_latency_ms_steady.mean"),
    ("catch-up (ms)", "prediction_catch_up_ms.mean"),
    ("controller, start (ms)", "controller_apparent_latency_ms_start.mean"),
    ("camera, frame counting (ms)", "measured_latency_ms.mean"),
]
CAMERA = "measured_latency_ms.mean"


def published_cell(label, camera_mean):
    """Every public measurement of the device, each with the camera figure's difference to it."""
    entries = PUBLISHED.get(label, [])
    parts = []
    for value, unc, what, _ in entries:
        v = f"{value:.1f}" if unc is None else f"{value:.1f} ± {unc:.1f}"
        d = "" if camera_mean is None else f" ({camera_mean - value:+.1f})"
        parts.append(f"{v}{d}: {what}")
    return "; ".join(parts)


def is_devices_collection(coll):
    """Two rows or more that report both apparent latency and a camera measurement."""
    def measured(row):
        s = row.first_summary()
        return lr.find_figure(s, "apparent_latency_ms_steady") is not None and \
            lr.find_figure(s, "measured_latency_ms") is not None
    return len(coll.rows) >= 2 and sum(1 for r in coll.rows if measured(r)) >= 2


def mean_sd(values):
    """(mean, sample standard deviation) of the values; sd None for fewer than two."""
    if not values:
        return None, None
    m = sum(values) / len(values)
    if len(values) < 2:
        return m, None
    return m, math.sqrt(sum((v - m) ** 2 for v in values) / (len(values) - 1))


def cell(values):
    m, sd = mean_sd(values)
    if m is None:
        return ""
    return f"{m:.2f}" if sd is None else f"{m:.2f} ± {sd:.2f}"


def refresh_hz(row):
    """The display's refresh rate as the scenario gave it (a number or an exact rational)."""
    value = row.first_summary().get("scenario", {}).get("display", {}).get("refresh_hz")
    if isinstance(value, str) and "/" in value:
        num, den = value.split("/", 1)
        value = float(num) / float(den)
    return value


def rows_of(coll):
    """(label, rate, [cells], replications) per row, cells as 'mean ± sd' over
    replications, the last cell the published measurements with the differences."""
    out = []
    for r in coll.rows:
        rate = refresh_hz(r)
        label = lr.point_name(r, coll)
        camera, _ = mean_sd(r.values(CAMERA))
        cells = [cell(r.values(path)) for _, path in COLUMNS] + [published_cell(label, camera)]
        out.append((label, "" if rate is None else f"{float(rate):g}", cells, r.replications()))
    return out


def markdown(coll):
    """The report section (nothing unless the rows are device profiles)."""
    if not is_devices_collection(coll):
        return []
    header = (["device", "refresh (Hz)"] + [h for h, _ in COLUMNS] +
              ["published camera measurements (ms; the camera column's difference)", "replications"])
    lines = ["## Devices: what a headset measurement sees", "",
             "Each cell is the mean over replications ± their standard deviation. Apparent latency is the "
             "time shift between the shown and the true head motion at the centre pixel, at the start of a "
             "movement, in its first 100 ms and in steady motion, and the time from a movement's start until "
             "prediction has caught up; the controller's is the start of its flick; "
             "the camera column is the simulated rig's estimate per flick, beside every public measurement of "
             "the device (docs/figures.md, docs/devices.md, docs/validation.md).", "",
             "| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    for label, rate, cells, reps in rows_of(coll):
        lines.append("| " + " | ".join(c.replace("|", "\\|") for c in [label, rate] + cells + [str(reps)]) + " |")
    lines.append("")
    return lines
