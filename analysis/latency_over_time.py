"""Latency over time in `latsim report`: per refresh, the latency of the
field's first line (its scanout start minus the measurement time of the pose
it shows), as OMNeT++ records vectors, from each run's fields.csv (written with
`latsim run --ledger`). Motion-to-photon takes the position's sample; rotation
latency the orientation's (behind a time warp, the warp's sample). Times are
the first line's write, before any persistence (docs/figures.md).
"""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import latsim_results  # noqa: E402
import plotting  # noqa: E402
from plotting import plt  # noqa: E402

# More curves than this on one plot cannot be told apart.
MAX_CURVES = 8


def read_fields(run_dir, eye=0):
    """[(scanout start s, mtp ms, rotation ms)] of one eye's fields, or None without fields.csv."""
    path = os.path.join(run_dir, "fields.csv")
    if not os.path.isfile(path):
        return None
    out = []
    rows = latsim_results.read_csv(path, required=("eye", "image", "scanout_start_ps", "measured_ps"))
    for line, row in enumerate(rows, start=2):
        if row["image"] in ("", "-1"):
            continue  # a field that showed no image has no latency
        try:
            if int(row["eye"]) != eye:
                continue
            start = int(row["scanout_start_ps"])
            position = int(row["measured_ps"])
            orientation = int(row.get("orientation_measured_ps") or row["measured_ps"])
        except ValueError as e:
            raise latsim_results.DamagedFile(path, f"line {line}: {e}") from None
        if max(abs(start), abs(position), abs(orientation)) > 10**24:
            raise latsim_results.DamagedFile(path, f"line {line}: a time beyond 1e24 ps, longer than any run")
        out.append((start * 1e-12, (start - position) * 1e-9, (start - orientation) * 1e-9))
    return out


def series(coll):
    """(row name, points) of the rows whose first run has a fields.csv, at most MAX_CURVES, evenly spaced."""
    found = []
    for row in coll.rows:
        if not row.run_dirs:
            continue
        points = read_fields(row.run_dirs[0])
        if points:
            found.append((row.name, points))
    if len(found) <= MAX_CURVES:
        return found
    step = (len(found) - 1) / (MAX_CURVES - 1)
    return [found[round(i * step)] for i in range(MAX_CURVES)]


def plot(coll):
    """latency_over_time.{png,svg}: motion-to-photon and rotation latency per refresh; None when no run has fields.csv."""
    drawn = series(coll)
    if not drawn:
        return None
    fig, (ax_mtp, ax_rot) = plt.subplots(2, 1, figsize=(9, 7), sharex=True)
    for (name, points), colour in zip(drawn, plotting.colours(len(drawn))):
        xs = [p[0] for p in points]
        ax_mtp.plot(xs, [p[1] for p in points], color=colour, label=name, linewidth=0.9)
        ax_rot.plot(xs, [p[2] for p in points], color=colour, label=name, linewidth=0.9)
    ax_mtp.set_ylabel("motion-to-photon, first line (ms)")
    ax_rot.set_ylabel("rotation latency, first line (ms)")
    ax_rot.set_xlabel("simulated time of the field's first line (s)")
    ax_mtp.set_title("Latency per refresh (eye 0, from fields.csv)")
    ax_mtp.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    base = "latency_over_time"
    plotting.save(fig, os.path.join(coll.directory, base))
    return base


def markdown(coll, base):
    if not base:
        return []
    shown = len(series(coll))
    return ["## Latency over time", "",
            "Per refresh, the latency of the field's first line: its scanout start minus the measurement time of "
            "the position (motion-to-photon) and of the orientation (rotation latency; behind a time warp, the "
            f"warp's sample), eye 0, from each run's `fields.csv` (`latsim run --ledger`); {shown} run(s) drawn.",
            "", f"![{base}]({base}.png)", ""]
