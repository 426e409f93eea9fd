"""Stage Gantt charts from a run's timeline.csv: one row per unit, one coloured
bar per stage interval, labelled with its frame, like the classic pipeline
diagrams of graphics hardware. Usable as a module or as
`python3 gantt.py RUN_DIR`."""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import latsim_results  # noqa: E402
import plotting  # noqa: E402
from plotting import plt  # noqa: E402

# Frames shown: enough to see the pipeline overlap, few enough to read.
FRAMES_SHOWN = 4
# Frames skipped at the start, where the pipeline is still filling.
WARMUP_FRAMES = 2


def read_timeline(path):
    """Timeline entries as dicts with numeric times, in file order; DamagedFile naming the line otherwise."""
    entries = []
    rows = latsim_results.read_csv(path, required=("stage", "frame", "eye", "unit", "start_ms", "end_ms"))
    for line, row in enumerate(rows, start=2):
        def number(column, kind=float):
            return latsim_results.cell(path, line, row, column, kind)
        entries.append({
            "stage": row["stage"],
            "frame": number("frame", int),
            "eye": number("eye", int),
            "unit": row["unit"],
            "start_ms": number("start_ms"),
            "end_ms": number("end_ms"),
            # Overlapping intervals of one unit are on separate lanes.
            "lane": number("lane", int) if row.get("lane") else 0,
        })
    return entries


def choose_window(entries):
    """(start_ms, end_ms, first frame, last frame) of the frames to draw."""
    frames = sorted({e["frame"] for e in entries})
    skip = WARMUP_FRAMES if len(frames) >= WARMUP_FRAMES + FRAMES_SHOWN else 0
    shown = frames[skip:skip + FRAMES_SHOWN]
    chosen = [e for e in entries if shown[0] <= e["frame"] <= shown[-1]]
    return min(e["start_ms"] for e in chosen), max(e["end_ms"] for e in chosen), shown[0], shown[-1]


# The display's own track: a field's vertical blank (when it has one) and
# its active scanout, from the retraces the run made.
DISPLAY_UNIT = "display"
DISPLAY_STAGES = ("VBLANK", "SCANOUT")


def retrace_times(entries):
    """The recorded retraces in ms: the start of each field's first display interval."""
    starts = {}
    for e in entries:
        if e["unit"] == DISPLAY_UNIT and e["stage"] in DISPLAY_STAGES:
            field = e["frame"]
            starts[field] = min(starts.get(field, e["start_ms"]), e["start_ms"])
    return [starts[k] for k in sorted(starts)]


def lane_label(unit, lane):
    """A Gantt row's name: the unit, and its lane when it has several."""
    return unit if lane == 0 else f"{unit} #{lane + 1}"


def draw(run_dir, title=None):
    """Writes gantt.png and gantt.svg into run_dir from its timeline.csv; returns the base path or None."""
    timeline = os.path.join(run_dir, "timeline.csv")
    if not os.path.isfile(timeline):
        return None
    entries = read_timeline(timeline)
    if not entries:
        return None
    summary_file = os.path.join(run_dir, "summary.json")
    summary = latsim_results.read_json(summary_file) if os.path.isfile(summary_file) else {}
    retraces = retrace_times(entries)
    work = [e for e in entries if e["unit"] != DISPLAY_UNIT]
    start_ms, end_ms, first, last = choose_window(work or entries)
    visible = [e for e in entries if e["end_ms"] >= start_ms and e["start_ms"] <= end_ms]

    # Rows: the lanes of each unit together, units in order of first
    # appearance (which the simulator makes deterministic).
    order = []
    for e in entries:
        if e["unit"] not in order:
            order.append(e["unit"])
    lanes = sorted({(order.index(e["unit"]), e["lane"]) for e in entries})
    rows = [(order[u], lane) for u, lane in lanes]
    stages = sorted({e["stage"] for e in entries})
    colour = dict(zip(stages, plotting.colours(len(stages))))

    fig, ax = plt.subplots(figsize=(12, 0.45 * len(rows) + 1.8))
    span_ms = max(end_ms - start_ms, 1e-9)
    for e in visible:
        y = rows.index((e["unit"], e["lane"]))
        left = max(e["start_ms"], start_ms)
        width = max(min(e["end_ms"], end_ms) - left, span_ms * 1e-4)
        ax.barh(y, width, left=left, height=0.7, color=colour[e["stage"]], edgecolor="black", linewidth=0.4)
        if width > span_ms / 40:
            label = str(e["frame"]) + ("" if e["eye"] < 0 else "LR"[e["eye"] % 2])
            ax.text(left + width / 2, y, label, ha="center", va="center", fontsize=7)
    shown_retraces = [t for t in retraces if start_ms <= t <= end_ms]
    for t in shown_retraces:
        ax.axvline(t, color="grey", linestyle="--", linewidth=0.8)
    ax.set_yticks(range(len(rows)))
    ax.set_yticklabels([lane_label(u, lane) for u, lane in rows])
    ax.invert_yaxis()
    ax.set_xlim(start_ms, end_ms)
    ax.set_xlabel("simulated time (ms)")
    ax.set_ylabel("unit")
    pipeline = summary.get("scenario", {}).get("pipeline", {}).get("type", "")
    ax.set_title(title or f"{os.path.basename(os.path.normpath(run_dir))} {pipeline}: stages of frames {first}-{last}")
    handles = [plt.Rectangle((0, 0), 1, 1, color=colour[s]) for s in stages]
    labels = list(stages)
    if shown_retraces:
        handles.append(plt.Line2D([0], [0], color="grey", linestyle="--"))
        labels.append("vertical retrace")
    ax.legend(handles, labels, loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8, title="stage")
    base = os.path.join(run_dir, "gantt")
    plotting.save(fig, base)
    return base


def main(argv):
    if len(argv) < 2:
        print("usage: gantt.py RUN_DIR...", file=sys.stderr)
        return 2
    for run_dir in argv[1:]:
        if draw(run_dir) is None:
            print(f"{run_dir}: no timeline.csv", file=sys.stderr)
            return 1
    return 0


if __name__ == "__main__":
    import command  # noqa: E402  (the contract of every analysis command: one line, never a traceback)
    sys.exit(command.run_main("gantt", main, sys.argv))
