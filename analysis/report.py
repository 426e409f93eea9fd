"""latsim report: latency tables and plots from result files.

Usage: python3 report.py DIR [--gantt-limit N] [--top N] [--figure F]

DIR is a run directory (summary.json), a sweep directory (results.csv and
runs/*/summary.json) or a directory of run directories (each subdirectory with
a summary.json is one row). Writes into DIR: report.md, latency_table.csv
(every row), mtp_cdf.{png,svg}, mtp_histogram.{png,svg}, for sweeps
sweep_<axis>.{png,svg} (figures against each axis, mean and 95 % t-interval
over replications; a zip sweep: sweep_points.{png,svg}, by point label) and,
over two crossed axes, heatmap.{png,svg} of the chosen figure; registration_vs_latency.{png,svg} and a pose-prediction
section when any run predicts, and gantt.{png,svg} next to the summaries of
runs with a timeline.csv: every one, or for a sweep an evenly spaced sample of
GANTT_SAMPLE points unless --gantt-limit says otherwise. A sweep's table in
report.md holds the --top lowest and highest points by the chosen figure once
it has more than twice as many. A sweep reads its headline figures from
results.csv and one summary.json per point: the cost grows with the points
drawn, not with the runs. Long work prints progress lines on stderr. A pacing
table and pacing_pareto.{png,svg} when some row is paced (analysis/pacing_plot.py); a
devices table when rows report apparent latency and a camera measurement
(analysis/devices_table.py). A streaming stages table when rows stream
(analysis/streaming_table.py), and for a sweep streaming_pareto.{png,svg}, latency
against frames dropped (analysis/sweep_plots.py). A passthrough stages table when
rows report photon-to-photon latency (analysis/passthrough_table.py).
"""

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import command  # noqa: E402
import gantt_sample  # noqa: E402
import heatmap  # noqa: E402
import latency_over_time  # noqa: E402
import latsim_results as lr  # noqa: E402
import pacing_plot  # noqa: E402
import devices_table  # noqa: E402
import plotting  # noqa: E402
import prediction  # noqa: E402
import sweep_labels  # noqa: E402
import passthrough_table  # noqa: E402
import streaming_table  # noqa: E402
import sweep_plots  # noqa: E402
from plotting import plt  # noqa: E402
from progress import Progress  # noqa: E402

# More curves than this on one CDF or histogram plot cannot be told apart.
MAX_CURVES = 12
# Figures plotted against each sweep axis: (figure path, axis label); the
# rows' headline figure, when it is one drawn only when leading, is drawn
# first (sweep_figures). From the registry's "plot" entries.
SWEEP_FIGURES = [(f"{name}.{s['stat']}", s["axis"]) for name, plot in lr.PLOTS if plot.get("when") != "leading"
                 for s in plot.get("sweep", [])]
HEADLINE_SWEEP_FIGURES = {name: [(f"{name}.{s['stat']}", s["axis"]) for s in plot.get("sweep", [])]
                          for name, plot in lr.PLOTS if plot.get("when") == "leading"}
# Distributions drawn as CDF and histogram when rows have them: (figure, file
# prefix, axis label, title).
DISTRIBUTIONS = [(name, plot["file"], plot["axis"], plot["title"]) for name, plot in lr.PLOTS]
# Distributions drawn only when some row's pipeline leads with them.
LEADING_DISTRIBUTIONS = {name for name, plot in lr.PLOTS if plot.get("when") == "leading"}


# Columns the user chose (--figures, or the sweep file's "figures"): HEADLINE column names.
CHOSEN = []


def chosen_columns():
    return [table_figure(name) for name in CHOSEN]


def sweep_figures(coll):
    """What the sweep plots draw: the chosen columns, else the headline figure first."""
    if CHOSEN:
        return [(path, label) for _, path, label in chosen_columns()]
    return HEADLINE_SWEEP_FIGURES.get(lr.headline_figure(coll.rows), []) + SWEEP_FIGURES


def leads_with(rows, figure):
    """Whether some row's pipeline declares `figure` first in its headline (rotation latency behind a time warp)."""
    return any((r.first_summary().get("headline") or [None])[0] == figure for r in rows if r.run_dirs)


def table_columns(coll):
    """The latency table's columns: the headline's first. Rotation latency (which equals
    motion-to-photon where nothing re-projects the orientation) only when a row's
    pipeline leads with it; what a viewer or a camera sees only when a row has it."""
    if CHOSEN:
        return chosen_columns()
    headline = lr.headline_figure(coll.rows)
    if headline == "motion_to_photon_ms":
        ordered = list(lr.HEADLINE)
    else:
        lead = lr.HEADLINE_COLUMNS[headline]
        ordered = [h for h in lr.HEADLINE if h[0] in lead] + [h for h in lr.HEADLINE if h[0] not in lead]

    def shown(h):
        if h[0] in lr.LEADING_COLUMNS:
            return leads_with(coll.rows, h[1].split(".")[0])
        if h[0] in lr.SEEN_COLUMNS:
            return any(r.mean(h[1]) is not None for r in coll.rows)
        return True

    return [h for h in ordered if shown(h)]


def default_figure(coll):
    """The column a table is sorted by when --figure is not given: the headline's mean."""
    return table_figure(lr.HEADLINE_COLUMNS[lr.headline_figure(coll.rows)][0])
# Gantt charts a sweep's report draws by default: one per point, evenly spaced.
GANTT_SAMPLE = 6
# Points a sweep's table in report.md shows from each end by default.
TOP_DEFAULT = 10


def fmt(value, digits=6):
    return "" if value is None else f"{value:.{digits}g}"


def curve_rows(coll, figure="motion_to_photon_ms"):
    """Rows whose distributions of `figure` are drawn; evenly spaced when there are too many."""
    rows = [r for r in coll.rows
            if r.run_dirs and (r.first_summary().get("figures", {}).get(figure) or {}).get("histogram")]
    if len(rows) <= MAX_CURVES:
        return rows
    step = (len(rows) - 1) / (MAX_CURVES - 1)
    return [rows[round(i * step)] for i in range(MAX_CURVES)]


def write_latency_table(coll):
    header = ["name", "pipeline"] + coll.axes + ["replications"] + [c for c, _, _ in lr.HEADLINE]
    lines = [",".join(_csv(h) for h in header)]
    for row in coll.rows:
        cells = [row.name, row.pipeline()] + [row.axis_values[a] for a in coll.axes] + [str(row.replications())]
        cells += [fmt(row.mean(path)) for _, path, _ in lr.HEADLINE]
        lines.append(",".join(_csv(c) for c in cells))
    plotting.write_text(os.path.join(coll.directory, "latency_table.csv"), "\n".join(lines) + "\n")


def _csv(text):
    text = str(text)
    return '"' + text.replace('"', '""') + '"' if any(c in text for c in ',"\n') else text


def shown_range(histograms):
    """'low to high' over every histogram drawn, for a title that says what clipping left out."""
    edges = [e for e, c in histograms if e and sum(c) > 0]
    return f"{fmt(min(e[0] for e in edges), 4)} to {fmt(max(e[-1] for e in edges), 4)}"


def histogram_range(ax, histograms):
    """Sets a histogram's axes to show its mass (x clipped past thin tails, a log density under a spike)
    and returns what the title says about it."""
    shown = lr.mass_range(histograms)
    notes = []
    if shown and shown[2]:
        ax.set_xlim(shown[0], shown[1])
        share = 100 * lr.TAIL_FRACTION
        notes.append(f"x clipped to each curve's {share:g}\u2013{100 - share:g} % quantiles, "
                     f"full range {shown_range(histograms)}")
    if shown and lr.needs_log_density(histograms, shown[0], shown[1]):
        ax.set_yscale("log")
        notes.append("log density: a spike would hide the rest")
    return "\n(" + "; ".join(notes) + ")" if notes else " (full range, linear)"


def plot_distributions(coll):
    """A CDF and a histogram (e.g. mtp_cdf, mtp_histogram) of each distribution in DISTRIBUTIONS that
    a row has, from the histogram buckets of replication 0 of each row."""
    drawn = []
    for figure, prefix, xlabel, title in DISTRIBUTIONS:
        if figure in LEADING_DISTRIBUTIONS and not leads_with(coll.rows, figure):
            continue
        rows = curve_rows(coll, figure)
        if not rows:
            continue
        palette = plotting.colours(len(rows))
        fig_cdf, ax_cdf = plt.subplots(figsize=(8, 5))
        fig_hist, ax_hist = plt.subplots(figsize=(8, 5))
        histograms = [lr.histogram_edges(row.first_summary()["figures"][figure]) for row in rows]
        for row, colour, (edges, counts) in zip(rows, palette, histograms):
            total = sum(counts)
            if total <= 0:
                continue
            cumulative, xs, ys = 0.0, [edges[0]], [0.0]
            for upper, count in zip(edges[1:], counts):
                cumulative += count
                xs.append(upper)
                ys.append(cumulative / total)
            ax_cdf.plot(xs, ys, color=colour, label=sweep_labels.cut(row.name), drawstyle="default")
            density = [c / total / max(hi - lo, 1e-12) for lo, hi, c in zip(edges, edges[1:], counts)]
            ax_hist.stairs(density, edges, color=colour, label=sweep_labels.cut(row.name), linewidth=1.2)
        ax_cdf.set_xlabel(xlabel)
        ax_cdf.set_ylabel("fraction of samples at or below")
        ax_cdf.set_ylim(0, 1.02)
        ax_cdf.set_title(f"{title}, cumulative distribution")
        ax_hist.set_xlabel(xlabel)
        ax_hist.set_ylabel(f"probability density (1/{xlabel.rsplit('(', 1)[-1].rstrip(')')})")
        ax_hist.set_title(f"{title}, histogram" + histogram_range(ax_hist, histograms), fontsize=10)
        for ax in (ax_cdf, ax_hist):
            ax.legend(fontsize=7, loc="best")
        base = coll.directory
        plotting.save(fig_cdf, os.path.join(base, f"{prefix}_cdf"))
        plotting.save(fig_hist, os.path.join(base, f"{prefix}_histogram"))
        drawn += [f"{prefix}_cdf", f"{prefix}_histogram"]
    return drawn


def table_figure(name):
    """(column, figure path, label) of a headline figure named by column or by path, or of any
    figure a table can hold named by its path (frames_missed, display_ms.p99), or None."""
    for column, path, label in lr.HEADLINE:
        if name in (column, path):
            return column, path, label
    if lr.is_figure_path(name):
        return name, name, name
    return None


def cut_rows(coll, top, figure):
    """(lowest, highest) `top` rows by the figure's mean when a sweep has more than 2 * top rows, else None."""
    if coll.kind != "sweep" or top <= 0 or len(coll.rows) <= 2 * top:
        return None
    _, path, _ = figure
    valued = [(row.mean(path), i, row) for i, row in enumerate(coll.rows)]
    ranked = sorted((v, i, row) for v, i, row in valued if v is not None)
    missing = [row for v, _, row in valued if v is None]
    ordered = [row for _, _, row in ranked] + missing
    return ordered[:top], ordered[-top:]


ANALYTIC_MTP = "analytic.motion_to_photon_ms.mean"


def interval_text(row, path):
    """'± h' of the 95 % t-interval of a figure's mean over a row's replications ('' for fewer than two)."""
    values = row.values(path)
    if len(values) < 2:
        return ""
    return "± " + fmt(lr.mean_ci95(values)[1], 3)


def analytic_mtp(row):
    """The phase-averaged motion-to-photon a pipeline computes without events (it does not depend on the
    drawn phases, so replication 0's stands for the point), or None."""
    return lr.find_figure(row.first_summary(), ANALYTIC_MTP) if row.run_dirs else None


def markdown_table(coll, rows=None):
    """The table of report.md: the headline columns; for a sweep with replications, the 95 % interval of
    the headline mean; where a pipeline computes it, motion-to-photon averaged over the clock phases
    (phase luck: one run's mean is one draw of the phases)."""
    rows = coll.rows if rows is None else rows
    columns = table_columns(coll)
    lead = columns[0]
    interval = coll.kind == "sweep" and any(r.replications() > 1 for r in coll.rows)
    analytic = any(analytic_mtp(r) is not None for r in coll.rows)
    header = ["name", "pipeline"] + (["replications"] if coll.kind == "sweep" else []) + [u for _, _, u in columns]
    if interval:
        header.insert(header.index(lead[2]) + 1, "95 % interval")
    if analytic:
        header.append("MTP mean over phases, analytic (ms)")
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    for row in rows:
        cells = [row.name, row.pipeline()] + ([str(row.replications())] if coll.kind == "sweep" else [])
        values = [fmt(row.mean(p), 4) for _, p, _ in columns]
        if interval:
            values.insert(1, interval_text(row, lead[1]))
        cells += values
        if analytic:
            cells.append(fmt(analytic_mtp(row), 4))
        lines.append("| " + " | ".join(c.replace("|", "\\|") for c in cells) + " |")
    return lines


def table_section(coll, top, figure):
    """The latency table of report.md: every row, or a sweep's lowest and highest points by the figure."""
    md = ["## Latency table", ""]
    cut = cut_rows(coll, top, figure)
    if cut is None:
        return md + ["Also in `latency_table.csv`.", ""] + markdown_table(coll) + [""]
    low, high = cut
    label = figure[2]
    md += [f"{len(coll.rows)} points: the {top} lowest and the {top} highest by {label} (points without it last); "
           "every point is in `latency_table.csv`, every run in `results.csv` and `results.sqlite`; "
           "`--top N` shows more, `--figure` sorts by another column.", "",
           f"### Lowest {label}", ""] + markdown_table(coll, low) + ["", f"### Highest {label}", ""]
    return md + markdown_table(coll, high) + [""]


def sweep_subdirectories(coll):
    """The sweep directories inside a directory of runs, by name."""
    if coll.kind != "runs":
        return []
    found = []
    for entry in sorted(os.listdir(coll.directory)):
        sub = os.path.join(coll.directory, entry)
        if os.path.isfile(os.path.join(sub, "results.csv")) and os.path.isdir(os.path.join(sub, "runs")):
            found.append(sub)
    return found


def sweep_sections(coll):
    """For each sweep inside a directory of runs: its table and its distributions, drawn into it."""
    md = []
    for sub_dir in sweep_subdirectories(coll):
        name = os.path.basename(sub_dir)
        try:
            sub = lr.load(sub_dir)
        except (ValueError, OSError, KeyError) as e:
            md += [f"## Sweep `{name}`", "", f"Not readable: {e}", ""]
            continue
        read_point_summaries(sub)
        write_latency_table(sub)
        plots = plot_distributions(sub)
        md += [f"## Sweep `{name}`", "",
               f"{len(sub.rows)} points, {len(sub.runs)} runs; also in `{name}/latency_table.csv`; "
               f"`latsim report {name}` writes its own report ([{name}/report.md]({name}/report.md)).", ""]
        md += markdown_table(sub) + [""] + [f"![{name}/{p}]({name}/{p}.png)" for p in plots] + [""]
    return md


def write_markdown(coll, drawn, top, figure, title=None):
    first = coll.rows[0].first_summary()
    version = first.get("latsim", {})
    md = [f"# latsim report: {title or os.path.basename(os.path.normpath(coll.directory))}", ""]
    kinds = {"run": "a single run", "runs": f"{len(coll.rows)} runs", "sweep": f"a sweep of {len(coll.rows)} points"}
    md.append(f"Results of {kinds[coll.kind]}, latsim {version.get('version', '?')} "
              f"(revision {version.get('git_revision', '?')}). Motion-to-photon (MTP) latency is photon time "
              "minus the time the pose used was measured; rotation latency, where a pipeline reports it, is "
              "photon time minus the time the orientation shown was measured (behind a time warp, the warp's "
              "sample); figures are means over replications.")
    md.append("")
    if coll.kind == "sweep":
        md.append(("Swept axes: " + ", ".join(f"`{a}`" for a in coll.axes) if coll.axes else
                   "No axis: replications of the base scenario") + f"; {len(coll.runs)} runs in all.")
        md.append("")
    md += table_section(coll, top, figure)
    md += sweep_sections(coll)
    plots = drawn["distributions"]
    if plots:
        shown = len(curve_rows(coll))
        md += ["## Distributions", ""]
        if shown < len(coll.rows):
            md += [f"{shown} of {len(coll.rows)} rows drawn, evenly spaced, replication 0 of each.", ""]
        md += [f"![{p}]({p}.png)" for p in plots] + [""]
    if drawn["sweep"] == ["sweep_points"]:
        md += ["## Figures per point", "",
               "A zip sweep's axes move together: each point is drawn by its label, a marker at the mean over "
               "replications with its 95 % Student-t interval; no heat map (no two axes are crossed).", ""]
        md += ["![sweep_points](sweep_points.png)", ""]
    elif drawn["sweep"]:
        md += ["## Figures against each swept axis", "",
               "Lines are means over replications; bands are 95 % Student-t intervals.", ""]
        md += [f"![{p}]({p}.png)" for p in drawn["sweep"]] + [""]
    if drawn["heatmap"]:
        base, panels, total = drawn["heatmap"]
        md += [f"## {figure[2]} over two axes", "",
               "Each cell is the mean over replications (`--figure` chooses another column); one panel per "
               "combination of the other axes" + (f", the first {panels} of {total}" if panels < total else "") +
               ".", "", f"![{base}]({base}.png)", ""]
    md += latency_over_time.markdown(coll, drawn["over_time"])
    md += list(pacing_plot.markdown(coll, drawn["pacing"]))
    md += devices_table.markdown(coll)
    md += streaming_table.markdown(coll)
    md += passthrough_table.markdown(coll)
    if drawn.get("pareto"):
        md += ["## Latency against frames dropped", "",
               "Each sweep point's mean motion-to-photon latency against its mean frames dropped; the red line "
               "joins the points no other point beats on both (the Pareto front), labelled with their axis "
               "values.", "", f"![{drawn['pareto']}]({drawn['pareto']}.png)", ""]
    if drawn["prediction"] or prediction.has_prediction(coll):
        md += prediction.markdown(coll)
        if drawn["prediction"]:
            md += [f"![{drawn['prediction']}]({drawn['prediction']}.png)", ""]
    if drawn["gantt"] or drawn["gantt_skipped"]:
        md += gantt_sample.section(drawn["gantt"], drawn["gantt_skipped"], coll.kind)
    elif coll.kind == "sweep":
        md += ["## Stage timelines", "", "No run of this sweep kept its timeline: `latsim sweep --keep first` "
               "keeps replication 0's of each point, `--keep runs=I,J` those of chosen runs.", ""]
    plotting.write_text(os.path.join(coll.directory, "report.md"), "\n".join(md))


def read_point_summaries(coll):
    """Reads one summary.json per row (the pipeline and the distributions come from it)."""
    progress = Progress("reading one summary per point", len(coll.rows))
    for row in coll.rows:
        row.first_summary()
        progress.advance()
    progress.finish()


def draw_everything(coll, args, figure):
    """Writes latency_table.csv and every plot; returns what was drawn, by section."""
    read_point_summaries(coll)
    write_latency_table(coll)
    drawn = {"distributions": plot_distributions(coll)}
    progress = Progress("plots against the axes", len(coll.axes))
    drawn["sweep"] = sweep_plots.draw(coll, sweep_figures(coll), progress)
    progress.finish()
    drawn["pareto"] = sweep_plots.plot_pareto(coll)
    drawn["heatmap"] = heatmap.draw(coll, figure[1], figure[2]) if coll.kind == "sweep" else None
    limit = args.gantt_limit
    if limit is None and coll.kind == "sweep":
        limit = GANTT_SAMPLE
    drawn["gantt"], drawn["gantt_skipped"] = gantt_sample.draw(coll, limit)
    drawn["prediction"] = prediction.plot_registration_vs_latency(coll) if prediction.has_prediction(coll) else None
    drawn["pacing"] = pacing_plot.plot(coll)
    drawn["over_time"] = latency_over_time.plot(coll)
    return drawn


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("directory")
    parser.add_argument("--gantt-limit", type=int, default=None,
                        help=f"draw at most this many Gantt charts (default: for a sweep {GANTT_SAMPLE}, one per point "
                             "evenly spaced; otherwise every run with a timeline.csv)")
    parser.add_argument("--top", type=int, default=TOP_DEFAULT,
                        help=f"a sweep's table in report.md: this many lowest and highest points by --figure "
                             f"(default {TOP_DEFAULT}; 0: every point)")
    parser.add_argument("--figure", default=None,
                        help="the column the table is sorted by and the heat map shows: "
                             + ", ".join(c for c, _, _ in lr.HEADLINE) +
                             " (default: the mean of the figure the runs' pipelines declare first, e.g. "
                             "rotation_latency_mean_ms behind a time warp; else mtp_mean_ms)")
    parser.add_argument("--figures", default=None,
                        help="the columns of report.md's tables and the figures of the sweep plots, comma-separated: "
                             + ", ".join(c for c, _, _ in lr.HEADLINE) +
                             " (default: the sweep file's \"figures\", else the pipelines' headline first)")
    parser.add_argument("--title", default=None,
                        help="the report's title (default: the directory's name)")
    args = parser.parse_args(argv[1:])
    figure = table_figure(args.figure) if args.figure is not None else ()
    if figure is None:
        print(f"report: --figure {args.figure}: expected one of " + lr.whole_names([c for c, _, _ in lr.HEADLINE]) +
              ", or a figure's path (frames_missed, motion_to_photon_ms.p99)", file=sys.stderr)
        return 2
    if (args.gantt_limit is not None and args.gantt_limit < 0) or args.top < 0:
        print("report: --gantt-limit and --top take a count (0 or more)", file=sys.stderr)
        return 2
    if not os.path.isdir(args.directory):
        print(f"{args.directory}: not a directory", file=sys.stderr)
        return 2
    coll = lr.load(args.directory)
    chosen = args.figures.split(",") if args.figures else coll.figures
    unknown = [c for c in chosen if table_figure(c) is None]
    if unknown:
        where = "--figures" if args.figures else f"{args.directory}/plan.json: figures"
        print(f"report: {where}: {lr.whole_names(unknown)} is not a column nor a figure's path "
              "(frames_missed, motion_to_photon_ms.p99); expected some of " +
              lr.whole_names([c for c, _, _ in lr.HEADLINE]), file=sys.stderr)
        return 2
    CHOSEN[:] = [table_figure(c)[0] for c in chosen]
    if not figure:
        figure = table_figure(CHOSEN[0]) if CHOSEN else default_figure(coll)
    # A damaged file, a full disk or a stop request: one line, and what was
    # written so far taken back (command.run_main).
    drawn = draw_everything(coll, args, figure)
    write_markdown(coll, drawn, args.top, figure, args.title)
    plots_drawn = (len(drawn["distributions"]) + len(drawn["sweep"]) + len(drawn["gantt"]) +
                   (1 if drawn["heatmap"] else 0) + (1 if drawn["prediction"] else 0) + (1 if drawn["pacing"] else 0) +
                   (1 if drawn["over_time"] else 0))
    print(f"report: {len(coll.rows)} row(s), {plots_drawn} plot(s) -> "
          f"{os.path.join(coll.directory, 'report.md')}")
    return 0


if __name__ == "__main__":
    sys.exit(command.run_main("report", main, sys.argv, reads=sys.argv[1] if len(sys.argv) > 1 else None))
