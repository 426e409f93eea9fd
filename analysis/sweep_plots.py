"""Figures of a sweep against its axes, mean and 95 % t-interval over replications.

A Cartesian sweep gets one plot per axis, sweep_<axis>.{png,svg} (one line per
combination of the other axes' values). A zip sweep's axes move together, so a
plot against one of them alone would repeat the others in its legend: it gets
one plot, sweep_points.{png,svg}, its points in plan order along x, each named
by its label (a /description swept beside whole objects, say). Ticks, legends
and titles come from the sweep file's labels and sweep_labels (never JSON), and
every figure stays within 2,000 px.
"""

import os

import latsim_results as lr
import pacing_plot
import plotting
import sweep_labels
from plotting import plt

# Legend entries longer than this would make the figure wider than MAX_WIDTH_PX.
LEGEND_CHARS = 80
# More legend entries than this go into a note instead (one line each would be taller than the plot).
MAX_LEGEND = 12
# Ticks beyond this many are too dense to read: every n-th is labelled.
MAX_TICKS = 30


def _categorical_ticks(ax, labels):
    labels = [sweep_labels.cut(label) for label in labels]
    step = max(1, -(-len(labels) // MAX_TICKS))
    positions = list(range(0, len(labels), step))
    ax.set_xticks(positions)
    # About 100 characters of 7-point text fit across the plot side by side.
    rotate = sum(len(labels[i]) + 2 for i in positions) > 100
    ax.set_xticklabels([labels[i] for i in positions], rotation=40 if rotate else 0,
                       ha="right" if rotate else "center", rotation_mode="anchor", fontsize=7)


def _band(ax, xs, stats, colour, label, marker="o", linestyle="-"):
    means = [s[0] for s in stats]
    half = [s[1] for s in stats]
    ax.plot(xs, means, marker=marker, linestyle=linestyle, color=colour, label=label)
    ax.fill_between(xs, [m - h for m, h in zip(means, half)], [m + h for m, h in zip(means, half)],
                    color=colour, alpha=0.2, linewidth=0)


def _figure(figures):
    # One x axis for every panel: its ticks are labelled once, under the last.
    fig, axes = plt.subplots(len(figures), 1, figsize=(9, 3.6 * len(figures)), squeeze=False, sharex=True)
    return fig, axes[:, 0]


def _save(fig, coll, base):
    plotting.save(fig, os.path.join(coll.directory, base))
    return base


def _drawn_figures(coll, figures):
    return [(p, label) for p, label in figures if any(r.values(p) for r in coll.rows)]


def plot_axis(coll, axis, figures):
    """sweep_<axis>: the figures against one axis, one line per combination of the other axes' values."""
    figures = _drawn_figures(coll, figures)
    if not figures:
        return None
    others = [a for a in coll.axes if a != axis]
    series = {}
    for row in coll.rows:
        series.setdefault(tuple(row.axis_values[a] for a in others), []).append(row)
    keys = list(series)  # first-appearance order follows the plan
    axis_values = sweep_labels.distinct(coll.rows, axis)
    numeric = all(lr.as_number(v) is not None for v in axis_values)
    position = {v: float(i) for i, v in enumerate(axis_values)}
    x_of = lr.as_number if numeric else position.__getitem__
    fig, axes = _figure(figures)
    palette = plotting.colours(len(keys))
    for (path, label), ax in zip(figures, axes):
        for key, colour in zip(keys, palette):
            points = sorted(((x_of(r.axis_values[axis]), lr.mean_ci95(r.values(path))) for r in series[key]
                             if r.values(path)), key=lambda p: p[0])
            if not points:
                continue
            legend = "; ".join(coll.value_label(a, v) for a, v in zip(others, key))
            _band(ax, [p[0] for p in points], [p[1] for p in points], colour,
                  sweep_labels.cut(legend, LEGEND_CHARS) if legend else "mean")
        ax.set_ylabel(label)
        if not numeric:
            _categorical_ticks(ax, [coll.value_label(axis, v) for v in axis_values])
        if len(keys) <= MAX_LEGEND:
            # Outside the axes: with many series an inside legend hides the lines.
            title = "; ".join(sweep_labels.cut(lr.axis_label(a), 30) for a in others) or None
            ax.legend(fontsize=7, title=title, title_fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
        else:
            ax.text(1.01, 1.0, f"{len(keys)} lines: one per combination\nof the other axes (report.md's table)",
                    transform=ax.transAxes, fontsize=7, va="top")
    name = lr.axis_label(axis)
    axes[-1].set_xlabel(f"{name} ({axis})" if name != axis else axis)
    reps = max(r.replications() for r in coll.rows)
    axes[0].set_title(sweep_labels.cut(f"Against {lr.axis_label(axis)}", 60) +
                      f": mean over {reps} replication(s), band = 95 % t-interval")
    name = lr.short_axis_name(axis, coll.axes)
    return _save(fig, coll, "sweep_" + name.replace("/", "_").replace(".", "_"))


def plot_points(coll, figures):
    """sweep_points: the figures of a zip sweep's points, in plan order, each named by its label."""
    figures = _drawn_figures(coll, figures)
    if not figures:
        return None
    labels = [sweep_labels.cut(r.name) for r in coll.rows]
    fig, axes = _figure(figures)
    for (path, label), ax in zip(figures, axes):
        xs, stats = [], []
        for i, row in enumerate(coll.rows):
            if row.values(path):
                xs.append(i)
                stats.append(lr.mean_ci95(row.values(path)))
        means = [s[0] for s in stats]
        half = [s[1] for s in stats]
        # Points of a zip are not a curve: markers with error bars, no line between them.
        ax.errorbar(xs, means, yerr=half, fmt="o", color="tab:blue", ecolor="tab:blue", capsize=3, markersize=5)
        ax.set_ylabel(label)
        _categorical_ticks(ax, labels)
        ax.set_xlim(-0.5, len(coll.rows) - 0.5)
    axes[-1].set_xlabel("point (zip sweep: every axis moves together)")
    reps = max(r.replications() for r in coll.rows)
    axes[0].set_title(f"Each point: mean over {reps} replication(s), bar = 95 % t-interval")
    return _save(fig, coll, "sweep_points")


def draw(coll, figures, progress=None):
    """The sweep plots' base names: sweep_points for a zip sweep, else one sweep_<axis> per axis."""
    if sweep_labels.is_zip(coll.rows, coll.axes):
        base = plot_points(coll, figures)
        return [base] if base else []
    drawn = []
    for axis in coll.axes:
        base = plot_axis(coll, axis, figures)
        if base:
            drawn.append(base)
        if progress:
            progress.advance()
    return drawn



# The Pareto plot's figures: latency (y) against frames dropped (x), by their results.csv columns.
PARETO_LATENCY = "mtp_mean_ms"
PARETO_DROPPED = "frames_dropped"
# Front points labelled with their axis values; beyond this many the labels would pile up.
MAX_PARETO_LABELS = 12


def plot_pareto(coll):
    """streaming_pareto: each sweep point's mean latency against its mean frames dropped (means over
    replications), the Pareto front (pacing_plot.pareto_front) joined and labelled with the point's axis
    values as the sweep file names them; None when fewer than two points report frames dropped."""
    columns = {name: (path, label) for name, path, label in lr.HEADLINE}
    (y_path, y_label), (x_path, x_label) = columns[PARETO_LATENCY], columns[PARETO_DROPPED]
    rows = [r for r in coll.rows if r.values(x_path) and r.values(y_path)]
    if coll.kind != "sweep" or len(rows) < 2:
        return None
    points = [(lr.mean_ci95(r.values(x_path))[0], lr.mean_ci95(r.values(y_path))[0]) for r in rows]
    front = pacing_plot.pareto_front(points)
    fig, ax = plt.subplots(figsize=(9, 6))
    ax.scatter([p[0] for p in points], [p[1] for p in points], s=18, color="tab:grey", label="sweep point")
    ax.plot([points[i][0] for i in front], [points[i][1] for i in front], marker="o", color="tab:red",
            label="Pareto front (no point has fewer drops and less latency)")
    if len(front) <= MAX_PARETO_LABELS:
        names = [sweep_labels.cut(lr.point_name(rows[i], coll), LEGEND_CHARS) for i in front]
        plotting.annotate_apart(ax, [points[i] for i in front], names)
    if max(p[0] for p in points) > 10 * max(1.0, min(p[0] for p in points)):
        # Drops span decades (none on a clean link, hundreds on a saturated one): linear near 0, log beyond.
        ax.set_xscale("symlog", linthresh=1.0)
        ax.set_xlim(left=-0.5)  # no negative decades: a count of drops starts at 0
    ax.set_xlabel(f"{x_label}, mean over replications")
    ax.set_ylabel(f"{y_label}, mean over replications")
    reps = max(r.replications() for r in rows)
    ax.set_title(f"Latency against frames dropped (lower left is better): {len(rows)} points, {reps} replication(s)")
    ax.legend(fontsize=7, loc="upper right")
    return _save(fig, coll, "streaming_pareto")
