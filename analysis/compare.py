"""latsim compare's plots: the CDFs of each quantity's two sides, overlaid.

Usage: python3 compare.py DIR

Reads DIR/compare_values.json, written by `latsim compare` (the capture is
read by latsim's one capture reader, in C++; this script reads only that
result file), and writes DIR/compare_<quantity>.{png,svg} for every quantity
whose capture side has values: the capture's empirical CDF and the run's
(a run total is drawn as a vertical line). Exit 0, 1 when a plot cannot be
written, 2 when the file cannot be read.
"""

import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))


def plot(rows, out_dir):
    import plotting
    from plotting import plt
    for r in rows:
        a, b = sorted(r["capture"]), sorted(r["run"])
        if not a:
            continue
        fig, ax = plt.subplots(figsize=(6, 4))
        ax.step(a, [(i + 1) / len(a) for i in range(len(a))], where="post", label=f"capture (n = {len(a)})")
        if b and r["run_total_only"]:
            ax.axvline(b[0], color="C1", label=f"run ({b[0]:.4g})")
        elif b:
            ax.step(b, [(i + 1) / len(b) for i in range(len(b))], where="post", label=f"run (n = {len(b)})")
        title = f"{r['label']} [{r['standing']}]"
        if "ks" in r:
            title += f": KS D = {r['ks']:.4f}"
        ax.set(xlabel=r["label"], ylabel="fraction at or below", title=title, ylim=(0, 1.02))
        ax.legend(loc="lower right")
        plotting.save(fig, os.path.join(out_dir, f"compare_{r['key']}"))


def main(argv):
    if len(argv) != 1:
        print("usage: compare.py DIR", file=sys.stderr)
        return 2
    path = os.path.join(argv[0], "compare_values.json")
    try:
        with open(path, encoding="utf-8") as f:
            rows = json.load(f)
        if not isinstance(rows, list) or not all(isinstance(r, dict) for r in rows):
            raise ValueError("expected a list of quantities")
    except (OSError, ValueError, RecursionError) as e:
        print(f"compare: {path}: {' '.join(str(e).split())[:300]}", file=sys.stderr)
        return 2
    plot(rows, argv[0])
    return 0


if __name__ == "__main__":
    import command
    sys.exit(command.run_main("compare", main, sys.argv[1:]))
