"""Pacing in `latsim report`: one table of each row's motion-to-photon and
frames_missed, and a Pareto plot of mean and p99 motion-to-photon against
frames_missed per minute (pacing_pareto.{png,svg}); the rows no other row
beats on both are joined as the front (docs/pacing.md).
"""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import latsim_results as lr  # noqa: E402
import plotting  # noqa: E402
import sweep_labels  # noqa: E402
from plotting import plt  # noqa: E402

# Table columns: (header, figure path). Counts are headed by their figure
# names, each with one meaning (the registry's, docs/figures.md), the same in
# every table.
COLUMNS = [
    ("MTP mean (ms)", "motion_to_photon_ms.mean"),
    ("MTP p99 (ms)", "motion_to_photon_ms.p99"),
    ("frames_missed", "frames_missed"),
    ("frames_late_to_latch", "frames_late_to_latch"),
    ("latch slack mean (ms)", "latch_slack_ms.mean"),
    ("wake-up error mean (ms)", "wake_up_error_ms.mean"),
    ("half_rate_periods", "half_rate_periods"),
]
# The counts the caption defines.
DEFINED = ("frames_missed", "frames_late_to_latch")


def missed_per_minute(row):
    """Mean over replications of frames_missed per simulated minute (None without either)."""
    rates = []
    for s in row.summaries:
        missed = lr.find_figure(s, "frames_missed")
        duration = s.get("scenario", {}).get("duration_s")
        if missed is not None and isinstance(duration, (int, float)) and duration > 0:
            rates.append(missed * 60.0 / duration)
    return sum(rates) / len(rates) if rates else None


def is_pacing_collection(coll):
    """More than one row, and some row paced (it reports frames_late_to_latch)."""
    if len(coll.rows) < 2:
        return False
    # Replication 0 alone says whether a point is paced: one file a point.
    return any(lr.find_figure(r.first_summary(), "frames_late_to_latch") is not None for r in coll.rows)


def pareto_front(points):
    """Indices of the points (x, y) no other point is at most on both and below on one."""
    front = []
    for i, (x, y) in enumerate(points):
        dominated = any(ox <= x and oy <= y and (ox < x or oy < y) for j, (ox, oy) in enumerate(points) if j != i)
        if not dominated:
            front.append(i)
    return sorted(front, key=lambda i: points[i][0])


def plot(coll):
    """Draws pacing_pareto.{png,svg}; returns its base name, or None when there is nothing to compare."""
    if not is_pacing_collection(coll):
        return None
    rows = [r for r in coll.rows if missed_per_minute(r) is not None and r.mean("motion_to_photon_ms.mean") is not None]
    if len(rows) < 2:
        return None
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8))
    for ax, (path, label) in zip(axes, [("motion_to_photon_ms.mean", "mean"), ("motion_to_photon_ms.p99", "p99")]):
        pts = [(missed_per_minute(r), r.mean(path)) for r in rows if r.mean(path) is not None]
        named = [r for r in rows if r.mean(path) is not None]
        ax.scatter([p[0] for p in pts], [p[1] for p in pts], color="tab:blue", zorder=3)
        front = pareto_front(pts)
        ax.plot([pts[i][0] for i in front], [pts[i][1] for i in front], color="tab:red", label="Pareto front")
        ax.set_xlabel("frames_missed per minute")
        ax.set_ylabel(f"{label} motion-to-photon (ms)")
        ax.legend(fontsize=8)
        plotting.annotate_apart(ax, pts, [sweep_labels.cut(lr.point_name(r, coll)) for r in named])
    fig.suptitle("Latency against frames_missed (lower left is better)")
    plotting.save(fig, os.path.join(coll.directory, "pacing_pareto"))
    return "pacing_pareto"


def markdown(coll, plot_base):
    """The report section: the table, and the plot when drawn."""
    if not is_pacing_collection(coll):
        return []
    header = ["name", "frames_missed / min"] + [h for h, _ in COLUMNS]
    meanings = "; ".join(f"`{name}`: {lr.figure_meaning(name)}" for name in DEFINED)
    lines = ["## Pacing: latency against frames_missed", "",
             f"{meanings} (docs/figures.md, docs/pacing.md).", "",
             "| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    for r in coll.rows:
        cells = [lr.point_name(r, coll), lr_fmt(missed_per_minute(r))] + [lr_fmt(r.mean(p)) for _, p in COLUMNS]
        lines.append("| " + " | ".join(c.replace("|", "\\|") for c in cells) + " |")
    lines.append("")
    if plot_base:
        lines += [f"![{plot_base}]({plot_base}.png)", ""]
    return lines


def lr_fmt(value):
    return "" if value is None else f"{value:.4g}"
