"""latsim report: latency tables and plots from result files.

Usage: python3 report.py DIR [--gantt-limit N]

DIR is a run directory (summary.json), a sweep directory (results.csv and
runs/*/summary.json) or a directory of run directories (each subdirectory with
a summary.json is one row). Writes into DIR: report.md, latency_table.csv,
mtp_cdf.{png,svg}, mtp_histogram.{png,svg}, for sweeps sweep_<axis>.{png,svg}
(figures against each axis, mean and 95 % t-interval over replications),
registration_vs_latency.{png,svg} and a pose-prediction section when any run
predicts, a pacing table and pacing_pareto.{png,svg} when some row is paced
(analysis/pacing_plot.py), and gantt.{png,svg} next to every summary whose run
has a timeline.csv.
"""

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import gantt  # noqa: E402
import latsim_results as lr  # noqa: E402
import pacing_plot  # noqa: E402
import plotting  # noqa: E402
import prediction  # noqa: E402
from plotting import plt  # noqa: E402

# More curves than this on one CDF or histogram plot cannot be told apart.
MAX_CURVES = 12
# Figures plotted against each sweep axis: (figure path, axis label).
SWEEP_FIGURES = [
    ("motion_to_photon_ms.mean", "mean motion-to-photon (ms)"),
    ("motion_to_photon_ms.p99", "p99 motion-to-photon (ms)"),
    ("registration_error_arcmin.mean", "mean registration error (arcmin)"),
]


def fmt(value, digits=6):
    return "" if value is None else f"{value:.{digits}g}"


def curve_rows(coll):
    """Rows whose distributions are drawn; evenly spaced when there are too many."""
    rows = [r for r in coll.rows if r.summaries and "motion_to_photon_ms" in r.summaries[0].get("figures", {})]
    if len(rows) <= MAX_CURVES:
        return rows
    step = (len(rows) - 1) / (MAX_CURVES - 1)
    return [rows[round(i * step)] for i in range(MAX_CURVES)]


def write_latency_table(coll):
    header = ["name", "pipeline"] + coll.axes + ["replications"] + [c for c, _, _ in lr.HEADLINE]
    lines = [",".join(_csv(h) for h in header)]
    for row in coll.rows:
        cells = [row.name, row.pipeline()] + [row.axis_values[a] for a in coll.axes] + [str(len(row.summaries))]
        cells += [fmt(row.mean(path)) for _, path, _ in lr.HEADLINE]
        lines.append(",".join(_csv(c) for c in cells))
    plotting.write_text(os.path.join(coll.directory, "latency_table.csv"), "\n".join(lines) + "\n")


def _csv(text):
    text = str(text)
    return '"' + text.replace('"', '""') + '"' if any(c in text for c in ',"\n') else text


def plot_distributions(coll):
    """mtp_cdf and mtp_histogram from the histogram buckets of replication 0 of each row."""
    rows = curve_rows(coll)
    if not rows:
        return []
    palette = plotting.colours(len(rows))
    fig_cdf, ax_cdf = plt.subplots(figsize=(8, 5))
    fig_hist, ax_hist = plt.subplots(figsize=(8, 5))
    for row, colour in zip(rows, palette):
        dist = row.summaries[0]["figures"]["motion_to_photon_ms"]
        edges, counts = lr.histogram_edges(dist)
        total = sum(counts)
        if total <= 0:
            continue
        cumulative, xs, ys = 0.0, [edges[0]], [0.0]
        for upper, count in zip(edges[1:], counts):
            cumulative += count
            xs.append(upper)
            ys.append(cumulative / total)
        ax_cdf.plot(xs, ys, color=colour, label=row.name, drawstyle="default")
        density = [c / total / max(hi - lo, 1e-12) for lo, hi, c in zip(edges, edges[1:], counts)]
        ax_hist.stairs(density, edges, color=colour, label=row.name, linewidth=1.2)
    ax_cdf.set_xlabel("motion-to-photon latency (ms)")
    ax_cdf.set_ylabel("fraction of samples at or below")
    ax_cdf.set_ylim(0, 1.02)
    ax_cdf.set_title("Motion-to-photon latency, cumulative distribution")
    ax_hist.set_xlabel("motion-to-photon latency (ms)")
    ax_hist.set_ylabel("probability density (1/ms)")
    ax_hist.set_title("Motion-to-photon latency, histogram")
    for ax in (ax_cdf, ax_hist):
        ax.legend(fontsize=7, loc="best")
    base = coll.directory
    plotting.save(fig_cdf, os.path.join(base, "mtp_cdf"))
    plotting.save(fig_hist, os.path.join(base, "mtp_histogram"))
    return ["mtp_cdf", "mtp_histogram"]


def plot_sweep_axis(coll, axis):
    """Figures against one axis; one line per combination of the other axes' values."""
    others = [a for a in coll.axes if a != axis]
    series = {}
    for row in coll.rows:
        key = tuple(row.axis_values[a] for a in others)
        series.setdefault(key, []).append(row)
    keys = list(series)  # first-appearance order follows the plan
    axis_values = []
    for row in coll.rows:
        if row.axis_values[axis] not in axis_values:
            axis_values.append(row.axis_values[axis])
    numeric = all(lr.as_number(v) is not None for v in axis_values)
    x_of = (lambda v: lr.as_number(v)) if numeric else (lambda v: float(axis_values.index(v)))
    figures = [(p, label) for p, label in SWEEP_FIGURES if any(r.values(p) for r in coll.rows)]
    if not figures:
        return None
    fig, axes = plt.subplots(len(figures), 1, figsize=(8, 3.6 * len(figures)), squeeze=False)
    palette = plotting.colours(len(keys))
    name = lr.short_axis_name(axis, coll.axes)
    for (path, label), ax in zip(figures, axes[:, 0]):
        for key, colour in zip(keys, palette):
            points = sorted(((x_of(r.axis_values[axis]), lr.mean_ci95(r.values(path))) for r in series[key]
                             if r.values(path)), key=lambda p: p[0])
            if not points:
                continue
            xs = [p[0] for p in points]
            means = [p[1][0] for p in points]
            half = [p[1][1] for p in points]
            legend = ", ".join(f"{lr.short_axis_name(a, coll.axes)}={v}" for a, v in zip(others, key)) or "mean"
            ax.plot(xs, means, marker="o", color=colour, label=legend)
            ax.fill_between(xs, [m - h for m, h in zip(means, half)], [m + h for m, h in zip(means, half)],
                            color=colour, alpha=0.2, linewidth=0)
        ax.set_ylabel(label)
        ax.set_xlabel(f"{name} ({axis})")
        if not numeric:
            ax.set_xticks(range(len(axis_values)))
            ax.set_xticklabels(axis_values)
        # Outside the axes: with many series an inside legend hides the lines.
        ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    reps = max(len(r.summaries) for r in coll.rows)
    axes[0, 0].set_title(f"Against {name}: mean over {reps} replication(s), band = 95 % t-interval")
    base = "sweep_" + name.replace("/", "_").replace(".", "_")
    plotting.save(fig, os.path.join(coll.directory, base))
    return base


def draw_gantts(coll, limit):
    """gantt.png/svg next to every summary with a timeline.csv; returns (drawn paths, skipped count)."""
    drawn, skipped = [], 0
    for row in coll.rows:
        for run_dir in row.run_dirs:
            if not os.path.isfile(os.path.join(run_dir, "timeline.csv")):
                continue
            if limit is not None and len(drawn) >= limit:
                skipped += 1
                continue
            base = gantt.draw(run_dir, title=f"{row.name}: pipeline stages")
            if base:
                drawn.append(os.path.relpath(base, coll.directory))
    return drawn, skipped


def markdown_table(coll):
    header = ["name", "pipeline"] + (["replications"] if coll.kind == "sweep" else []) + [u for _, _, u in lr.HEADLINE]
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    for row in coll.rows:
        cells = [row.name, row.pipeline()] + ([str(len(row.summaries))] if coll.kind == "sweep" else [])
        cells += [fmt(row.mean(p), 4) for _, p, _ in lr.HEADLINE]
        lines.append("| " + " | ".join(c.replace("|", "\\|") for c in cells) + " |")
    return lines


def write_markdown(coll, plots, sweep_plots, gantts, skipped, prediction_plot=None, pacing_lines=()):
    first = coll.rows[0].summaries[0]
    version = first.get("latsim", {})
    md = [f"# latsim report: {os.path.basename(os.path.normpath(coll.directory))}", ""]
    kinds = {"run": "a single run", "runs": f"{len(coll.rows)} runs", "sweep": f"a sweep of {len(coll.rows)} points"}
    md.append(f"Results of {kinds[coll.kind]}, latsim {version.get('version', '?')} "
              f"(revision {version.get('git_revision', '?')}). Motion-to-photon (MTP) latency is photon time "
              "minus the time the pose used was measured; figures are means over replications.")
    md.append("")
    if coll.kind == "sweep":
        md.append("Swept axes: " + ", ".join(f"`{a}`" for a in coll.axes) + f"; {len(coll.runs)} runs in all.")
        md.append("")
    md += ["## Latency table", "", "Also in `latency_table.csv`.", ""] + markdown_table(coll) + [""]
    if plots:
        shown = len(curve_rows(coll))
        md += ["## Motion-to-photon distributions", ""]
        if shown < len(coll.rows):
            md += [f"{shown} of {len(coll.rows)} rows drawn, evenly spaced, replication 0 of each.", ""]
        md += [f"![{p}]({p}.png)" for p in plots] + [""]
    if sweep_plots:
        md += ["## Figures against each swept axis", "",
               "Lines are means over replications; bands are 95 % Student-t intervals.", ""]
        md += [f"![{p}]({p}.png)" for p in sweep_plots] + [""]
    md += list(pacing_lines)
    if prediction_plot or prediction.has_prediction(coll):
        md += prediction.markdown(coll)
        if prediction_plot:
            md += [f"![{prediction_plot}]({prediction_plot}.png)", ""]
    if gantts or skipped:
        md += ["## Stage timelines", ""]
        md += [f"![{g}]({g}.png)" for g in gantts]
        if skipped:
            md += ["", f"{skipped} more run(s) have a timeline.csv; raise --gantt-limit to draw them."]
        md.append("")
    plotting.write_text(os.path.join(coll.directory, "report.md"), "\n".join(md))


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("directory")
    parser.add_argument("--gantt-limit", type=int, default=None,
                        help="draw at most this many Gantt charts (default: every run with a timeline.csv)")
    args = parser.parse_args(argv[1:])
    if not os.path.isdir(args.directory):
        print(f"{args.directory}: not a directory", file=sys.stderr)
        return 2
    try:
        coll = lr.load(args.directory)
    except (ValueError, OSError, KeyError) as e:
        print(f"report: {e}", file=sys.stderr)
        return 2
    try:
        write_latency_table(coll)
        plots = plot_distributions(coll)
        sweep_plots = [p for p in (plot_sweep_axis(coll, a) for a in coll.axes) if p]
        gantts, skipped = draw_gantts(coll, args.gantt_limit)
        prediction_plot = prediction.plot_registration_vs_latency(coll) if prediction.has_prediction(coll) else None
        pacing_pareto = pacing_plot.plot(coll)
        write_markdown(coll, plots, sweep_plots, gantts, skipped, prediction_plot,
                       pacing_plot.markdown(coll, pacing_pareto))
    except OSError as e:
        # A full disk or a read-only directory: one line, no traceback.
        where = f"{e.filename}: " if e.filename else ""
        print(f"report: cannot write {where}{e.strerror or e}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print("report: interrupted; files written so far are whole", file=sys.stderr)
        return 130
    plots_drawn = len(plots) + len(sweep_plots) + len(gantts) + (1 if prediction_plot else 0)
    plots_drawn += 1 if pacing_pareto else 0
    print(f"report: {len(coll.rows)} row(s), {plots_drawn} plot(s) -> "
          f"{os.path.join(coll.directory, 'report.md')}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
