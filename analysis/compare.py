"""latsim compare: a frame-timing capture beside a run's (or another capture).

Usage: python3 compare.py CAPTURE RUN [--out DIR] [--application NAME] [--process-id N]

CAPTURE is a PresentMon CSV (any of its three column generations); RUN is a
run directory (its presentmon.csv) or another such CSV. For each quantity
(frame interval, CPU busy, GPU busy, present to display) writes into DIR
(default: RUN/compare, or beside a RUN file): compare.md and compare.csv
(count, mean, p50 and p99 of each side, and the two-sample Kolmogorov-Smirnov
distance) and compare_<column>.{png,svg}, the two empirical CDFs overlaid.
Percentiles interpolate linearly between order statistics (numpy's default).
Exit 0, 1 when the output cannot be written, 2 on bad input (one line on
stderr, nothing written).
"""

import argparse
import bisect
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import frame_capture_csv as fc  # noqa: E402


def ks_distance(a, b):
    """sup |F_a(x) - F_b(x)| over the pooled sample points (F: empirical CDFs, right-continuous)."""
    if not a or not b:
        return None
    sa, sb = sorted(a), sorted(b)
    n, m = len(sa), len(sb)
    # Both CDFs are steps that change only at sample points: the supremum is at one of them.
    return max(abs(bisect.bisect_right(sa, x) / n - bisect.bisect_right(sb, x) / m) for x in set(sa) | set(sb))


def percentile(values, q):
    """The q-th percentile, linear between order statistics: rank q/100 * (n - 1) from 0."""
    s = sorted(values)
    rank = q / 100 * (len(s) - 1)
    low = int(rank)
    if low + 1 >= len(s):
        return s[-1]
    return s[low] + (s[low + 1] - s[low]) * (rank - low)


def stats(values):
    if not values:
        return {"count": 0, "mean": None, "p50": None, "p99": None}
    return {"count": len(values), "mean": sum(values) / len(values), "p50": percentile(values, 50),
            "p99": percentile(values, 99)}


def table_rows(capture, run):
    """One row per quantity: its key, label, the two sides' statistics and their KS distance."""
    rows = []
    for key, label, _ in fc.QUANTITIES:
        a, b = capture.values[key], run.values[key]
        rows.append({"column": key, "label": label, "capture": stats(a), "run": stats(b),
                     "ks": ks_distance(a, b), "capture_column": capture.columns.get(key),
                     "run_column": run.columns.get(key)})
    return rows


def fmt(v, digits=4):
    return "" if v is None else f"{v:.{digits}f}"


def csv_text(rows):
    lines = ["column,capture_count,capture_mean_ms,capture_p50_ms,capture_p99_ms,"
             "run_count,run_mean_ms,run_p50_ms,run_p99_ms,ks_distance"]
    for r in rows:
        c, u = r["capture"], r["run"]
        lines.append(",".join([r["column"], str(c["count"]), fmt(c["mean"], 6), fmt(c["p50"], 6), fmt(c["p99"], 6),
                               str(u["count"]), fmt(u["mean"], 6), fmt(u["p50"], 6), fmt(u["p99"], 6),
                               fmt(r["ks"], 6)]))
    return "\n".join(lines) + "\n"


def describe(capture):
    who = f" ({capture.process[0]} {capture.process[1]})".replace(" )", ")") if capture.process else ""
    return f"`{capture.path}`{who}, {capture.rows} frames"


def markdown(rows, capture, run):
    out = ["# Capture and run compared", "",
           f"- capture: {describe(capture)}", f"- run: {describe(run)}", "",
           "Per quantity, the frames that have it: count, mean, p50 and p99 in ms, and the two-sample "
           "Kolmogorov-Smirnov distance D = sup |F_capture - F_run| (0: the same distribution of values; 1: "
           "disjoint).", "",
           "| quantity | column (capture / run) | capture n | mean | p50 | p99 | run n | mean | p50 | p99 | KS D |",
           "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        c, u = r["capture"], r["run"]
        cols = f"{r['capture_column'] or '-'} / {r['run_column'] or '-'}"
        out.append(f"| {r['label']} | {cols} | {c['count']} | {fmt(c['mean'])} | {fmt(c['p50'])} | {fmt(c['p99'])} | "
                   f"{u['count']} | {fmt(u['mean'])} | {fmt(u['p50'])} | {fmt(u['p99'])} | {fmt(r['ks'])} |")
    skipped = [f"{r['column']}: capture {capture.skipped[r['column']]}, run {run.skipped[r['column']]}"
               for r in rows if capture.skipped[r["column"]] or run.skipped[r["column"]]]
    if skipped:
        out += ["", "Frames without the value (NA, empty, or never displayed), not counted: " + "; ".join(skipped) + "."]
    return "\n".join(out) + "\n"


def plot(rows, capture, run, out_dir):
    import plotting
    from plotting import plt
    for r in rows:
        a, b = sorted(capture.values[r["column"]]), sorted(run.values[r["column"]])
        if not a and not b:
            continue
        fig, ax = plt.subplots(figsize=(6, 4))
        for values, name in ((a, "capture"), (b, "run")):
            if values:
                ax.step(values, [(i + 1) / len(values) for i in range(len(values))], where="post",
                        label=f"{name} (n = {len(values)})")
        title = r["label"] if r["ks"] is None else f"{r['label']}: KS D = {r['ks']:.4f}"
        ax.set(xlabel=r["label"], ylabel="fraction of frames at or below", title=title, ylim=(0, 1.02))
        ax.legend(loc="lower right")
        plotting.save(fig, os.path.join(out_dir, f"compare_{r['column']}"))


def main(argv):
    parser = argparse.ArgumentParser(prog="latsim compare", description=__doc__.split("\n\n")[0])
    parser.add_argument("capture")
    parser.add_argument("run")
    parser.add_argument("--out")
    parser.add_argument("--application", help="the capture's process to compare, by Application")
    parser.add_argument("--process-id", help="the capture's process to compare, by ProcessID")
    args = parser.parse_args(argv)
    run_file = os.path.join(args.run, "presentmon.csv") if os.path.isdir(args.run) else args.run
    out_dir = args.out or (os.path.join(args.run, "compare") if os.path.isdir(args.run)
                           else os.path.join(os.path.dirname(os.path.abspath(args.run)), "compare"))
    try:
        capture = fc.read_capture(args.capture, args.application, args.process_id)
        run = fc.read_capture(run_file)
        if os.path.exists(out_dir) and not os.path.isdir(out_dir):
            raise fc.BadCapture(f"--out {out_dir}: exists and is not a directory")
    except fc.BadCapture as e:
        print(f"compare: {e}", file=sys.stderr)
        return 2
    rows = table_rows(capture, run)
    try:
        import plotting
        os.makedirs(out_dir, exist_ok=True)
        plotting.write_text(os.path.join(out_dir, "compare.csv"), csv_text(rows))
        plotting.write_text(os.path.join(out_dir, "compare.md"), markdown(rows, capture, run))
        plot(rows, capture, run, out_dir)
    except OSError as e:
        print(f"compare: cannot write {e.filename}: {e.strerror}", file=sys.stderr)
        return 1
    print(f"compare: wrote {out_dir}/compare.md")
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv[1:]))
    except KeyboardInterrupt:
        sys.exit(130)
