"""Heat maps of a sweep over two crossed axes: one figure's mean over
replications in each cell, one panel per combination of the other axes'
values. A zip sweep's axes are not crossed (its points are a list, not a
grid): it has no heat map. Ticks and titles are sweep_labels' labels."""

import os

import latsim_results as lr
import plotting
import sweep_labels
from plotting import plt

# Panels beyond this many would be too small to read; the report says so.
MAX_PANELS = 12
# The widest figure drawn (inches at 120 dpi: 1,680 px before its labels).
MAX_WIDTH_IN = 14.0


def ordered_values(coll, axis):
    """An axis's values in numeric order when all are numbers, else in plan order."""
    seen = sweep_labels.distinct(coll.rows, axis)
    if all(lr.as_number(v) is not None for v in seen):
        seen.sort(key=lr.as_number)
    return seen


def choose_axes(coll):
    """(x axis, y axis): of the pairs of crossed axes, the one with the most cells (x the longer
    axis; ties in plan order), or None when no two axes are crossed."""
    counts = {a: len(ordered_values(coll, a)) for a in coll.axes}
    best = None
    for i, a in enumerate(coll.axes):
        for b in coll.axes[i + 1:]:
            if not sweep_labels.crossed(coll.rows, a, b):
                continue
            x, y = (a, b) if counts[a] >= counts[b] else (b, a)
            key = (counts[a] * counts[b], counts[x])
            if best is None or key > best[0]:
                best = (key, (x, y))
    return best[1] if best else None


def grids(coll, x_axis, y_axis, path):
    """{other axes' values: grid[y][x] of means (None where missing)}, in plan order of first appearance."""
    xs, ys = ordered_values(coll, x_axis), ordered_values(coll, y_axis)
    others = [a for a in coll.axes if a not in (x_axis, y_axis)]
    x_of, y_of = {v: i for i, v in enumerate(xs)}, {v: i for i, v in enumerate(ys)}
    panels = {}
    for row in coll.rows:
        key = tuple(row.axis_values[a] for a in others)
        grid = panels.setdefault(key, [[None] * len(xs) for _ in ys])
        grid[y_of[row.axis_values[y_axis]]][x_of[row.axis_values[x_axis]]] = row.mean(path)
    return others, panels


def draw(coll, path, label):
    """heatmap.{png,svg} of `path` (a figure path such as motion_to_photon_ms.mean); returns
    (base name, panels drawn, panels in all) or None when the sweep has no two varied axes
    or no row has the figure."""
    chosen = choose_axes(coll)
    if chosen is None or not any(r.values(path) for r in coll.rows):
        return None
    x_axis, y_axis = chosen
    xs, ys = ordered_values(coll, x_axis), ordered_values(coll, y_axis)
    others, panels = grids(coll, x_axis, y_axis, path)
    keys = list(panels)[:MAX_PANELS]
    cells = [v for k in keys for line in panels[k] for v in line if v is not None]
    low, high = min(cells), max(cells)
    cols = min(3, len(keys))
    lines = (len(keys) + cols - 1) // cols
    width = min(MAX_WIDTH_IN, max(5.0, 0.45 * len(xs) + 2.5) * cols)
    # Upright x ticks take room below each panel: about 0.06 in a character at 7 points.
    x_labels = [sweep_labels.cut(coll.value_label(x_axis, v)) for v in xs]
    upright = len(xs) > 8 or max(map(len, x_labels)) > 6
    below_in = 0.06 * max(map(len, x_labels)) if upright else 0.0
    fig, axes = plt.subplots(lines, cols, figsize=(width, (0.4 * len(ys) + 1.8 + below_in) * lines), squeeze=False,
                             layout="constrained")
    image = None
    for ax, key in zip(axes.flat, keys):
        grid = [[float("nan") if v is None else v for v in line] for line in panels[key]]
        image = ax.imshow(grid, origin="lower", aspect="auto", cmap="viridis", vmin=low, vmax=high,
                          interpolation="nearest")
        ax.set_xticks(range(len(xs)))
        ax.set_xticklabels(x_labels, rotation=90 if upright else 0, fontsize=7)
        ax.set_yticks(range(len(ys)))
        ax.set_yticklabels([sweep_labels.cut(coll.value_label(y_axis, v)) for v in ys], fontsize=7)
        ax.set_xlabel(sweep_labels.cut(lr.axis_label(x_axis), 60))
        if ax in axes[:, 0]:
            ax.set_ylabel(sweep_labels.cut(lr.axis_label(y_axis), 60))
        ax.grid(False)
        if others:
            ax.set_title(sweep_labels.cut(", ".join(sweep_labels.named(lr.axis_label(a), coll.value_label(a, v), v)
                                                    for a, v in zip(others, key)), 60), fontsize=8)
    for ax in list(axes.flat)[len(keys):]:
        ax.axis("off")
    fig.colorbar(image, ax=axes.ravel().tolist(), label=label)
    fig.suptitle(f"{label}: mean over replications")
    base = "heatmap"
    plotting.save(fig, os.path.join(coll.directory, base))
    return base, len(keys), len(panels)
