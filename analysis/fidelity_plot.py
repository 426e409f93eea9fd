"""The accuracy/cost picture of `latsim fidelity`: a metric's error against the
finest level plotted over what each level cost in wall time, with events and
memory in the labels. Usage: python3 fidelity_plot.py DIR (reads DIR/fidelity.csv,
writes DIR/fidelity.png and .svg)."""

import csv
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import plotting  # noqa: E402
from plotting import plt  # noqa: E402


def main(argv):
    if len(argv) != 2:
        print("usage: fidelity_plot.py DIR", file=sys.stderr)
        return 2
    table = os.path.join(argv[1], "fidelity.csv")
    try:
        with open(table, encoding="utf-8", newline="") as f:
            reader = csv.reader(f)
            header = next(reader)
            rows = list(reader)
    except (OSError, StopIteration) as e:
        print(f"fidelity_plot: {table}: {e}", file=sys.stderr)
        return 2
    knob, metric = header[1], header[2]
    values = [r[1] for r in rows]
    metric_values = [float(r[2]) for r in rows]
    abs_error = [float(r[3]) for r in rows]
    wall_s = [float(r[5]) for r in rows]
    events = [int(r[6]) for r in rows]
    rss_mb = [float(r[7]) for r in rows]

    fig, (ax_cost, ax_events) = plt.subplots(1, 2, figsize=(12, 4.8))
    ax_cost.plot(wall_s, abs_error, marker="o", color="tab:blue")
    for i, (x, y, v, m) in enumerate(zip(wall_s, abs_error, values, metric_values)):
        # Alternate above and below: neighbouring levels often cost almost the same.
        ax_cost.annotate(f"{v}: {m:.6g}", (x, y), textcoords="offset points", xytext=(6, 8 if i % 2 == 0 else -16),
                         fontsize=8)
    if min(wall_s) > 0 and max(wall_s) / min(wall_s) > 10:
        ax_cost.set_xscale("log")
    ax_cost.margins(x=0.25, y=0.15)
    ax_cost.set_xlabel("wall time of the run (s)")
    ax_cost.set_ylabel(f"|error| of {metric} against {values[-1]}")
    ax_cost.set_title("Accuracy against cost (labels: level: value)")
    bars = ax_events.bar(range(len(values)), events, color="tab:orange")
    for bar, w, m in zip(bars, wall_s, rss_mb):
        ax_events.annotate(f"{w:.3g} s, {m:.0f} MB", (bar.get_x() + bar.get_width() / 2, bar.get_height()),
                           textcoords="offset points", xytext=(0, 3), ha="center", fontsize=8)
    if max(events) > 0 and min(events) > 0 and max(events) / min(events) > 10:
        ax_events.set_yscale("log")
    ax_events.set_xticks(range(len(values)))
    ax_events.set_xticklabels(values)
    ax_events.set_xlabel(knob)
    ax_events.set_ylabel("events")
    ax_events.set_title("Cost of each level (labels: wall time, peak memory)")
    fig.suptitle(f"Fidelity of {knob}")
    plotting.save(fig, os.path.join(argv[1], "fidelity"))
    return 0


if __name__ == "__main__":
    import command  # noqa: E402  (the contract of every analysis command: one line, never a traceback)
    sys.exit(command.run_main("fidelity_plot", main, sys.argv))
