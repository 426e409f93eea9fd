"""latsim compare's plots: the CDFs of each quantity's two sides, overlaid.

Usage: python3 compare.py DIR

Reads DIR/compare_values.json, written by `latsim compare` (the capture is
read by latsim's one capture reader, in C++; this script reads only that
result file), and writes DIR/compare_<quantity>.{png,svg} for every quantity
whose capture side has values: the capture's empirical CDF and the run's
(a run total is drawn as a vertical line). Exit 0, 1 when a plot cannot be
written, 2 when the file cannot be read.
"""

import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from latsim_results import DamagedFile, read_json  # noqa: E402

# A quantity as compare_values_json (sweep/compare.cpp) writes it: each member's type.
QUANTITY = {"key": str, "label": str, "standing": str, "capture": list, "run": list, "run_total_only": bool}
# A key names the plot's file (compare_<key>.png): a word, never a path.
KEY = re.compile(r"[A-Za-z0-9_]{1,64}")


def _is_number(value):
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def checked_quantities(path, rows):
    """rows when every quantity is as latsim writes it; DamagedFile naming the file and the pointer otherwise
    (numbers are already within read_json's bounds)."""
    for i, row in enumerate(rows):
        if not isinstance(row, dict):
            raise DamagedFile(path, f"/{i}: expected an object, found {type(row).__name__}")
        for key, kind in QUANTITY.items():
            if not isinstance(row.get(key), kind):
                raise DamagedFile(path, f"/{i}/{key}: expected {kind.__name__}, found {type(row.get(key)).__name__}")
        if not KEY.fullmatch(row["key"]):
            raise DamagedFile(path, f"/{i}/key: not a quantity's name")
        for side in ("capture", "run"):
            bad = next((j for j, v in enumerate(row[side]) if not _is_number(v)), None)
            if bad is not None:
                raise DamagedFile(path, f"/{i}/{side}/{bad}: expected a number")
        if "ks" in row and not (_is_number(row["ks"]) and 0 <= row["ks"] <= 1):
            raise DamagedFile(path, f"/{i}/ks: expected a distance between 0 and 1")
    return rows


def _text(label):
    """A label drawn as written: a "$" would start matplotlib's math text."""
    return label.replace("$", r"\$")


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
        title = _text(f"{r['label']} [{r['standing']}]")
        if "ks" in r:
            title += f": KS D = {r['ks']:.4f}"
        ax.set(xlabel=_text(r["label"]), ylabel="fraction at or below", title=title, ylim=(0, 1.02))
        ax.legend(loc="lower right")
        plotting.save(fig, os.path.join(out_dir, f"compare_{r['key']}"))


def main(argv):
    if len(argv) != 1:
        print("usage: compare.py DIR", file=sys.stderr)
        return 2
    path = os.path.join(argv[0], "compare_values.json")
    rows = checked_quantities(path, read_json(path, expected=list))
    try:
        plot(rows, argv[0])
    except (ValueError, TypeError, ArithmeticError, IndexError, KeyError) as e:
        # The file is this script's only input: what a checked file still cannot be drawn from is its fault.
        raise DamagedFile(path, f"cannot be drawn ({type(e).__name__}: {e})") from None
    return 0


if __name__ == "__main__":
    import command
    reads = os.path.join(sys.argv[1], "compare_values.json") if len(sys.argv) == 2 else None
    sys.exit(command.run_main("compare", main, sys.argv[1:], reads=reads))
