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

    fig, (ax_cost, ax_value) = plt.subplots(1, 2, figsize=(12, 4.8))
    ax_cost.plot(wall_s, abs_error, marker="o", color="tab:blue")
    for x, y, v, n, m in zip(wall_s, abs_error, values, events, rss_mb):
        ax_cost.annotate(f"{v}\n{n:,} events, {m:.0f} MB", (x, y), textcoords="offset points", xytext=(6, 6),
                         fontsize=8)
    if min(wall_s) > 0 and max(wall_s) / min(wall_s) > 10:
        ax_cost.set_xscale("log")
    ax_cost.set_xlabel("wall time of the run (s)")
    ax_cost.set_ylabel(f"|error| of {metric} against {values[-1]}")
    ax_cost.set_title("Accuracy against cost")
    ax_value.bar(range(len(values)), metric_values, color="tab:orange")
    ax_value.set_xticks(range(len(values)))
    ax_value.set_xticklabels(values)
    ax_value.set_xlabel(knob)
    ax_value.set_ylabel(metric)
    ax_value.set_title(f"{metric} at each level")
    fig.suptitle(f"Fidelity of {knob}")
    plotting.save(fig, os.path.join(argv[1], "fidelity"))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
