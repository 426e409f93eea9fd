"""What the report's stage tables share (analysis/streaming_table.py,
analysis/passthrough_table.py): the rows whose pipeline reports a marker
figure, cell formats, and the section's markdown. Every figure is the mean
over a row's replications; a cell a row lacks stays empty."""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import latsim_results as lr  # noqa: E402


def rows_with(coll, marker):
    """The rows whose first run reports the figure at `marker` (a dotted path)."""
    return [r for r in coll.rows if r.run_dirs and lr.find_figure(r.first_summary(), marker) is not None]


def ms(value):
    return "" if value is None else f"{value:.2f}"


def signed_ms(value):
    return "" if value is None else f"{value:+.2f}"


def count(value):
    return "" if value is None else f"{value:g}"


def difference(a, b):
    """a - b, or None when either is missing."""
    return a - b if a is not None and b is not None else None


def section(title, intro, header, rows):
    """A `## title` section: the intro paragraph, then one table line per (name, cells); nothing without rows."""
    if not rows:
        return []
    md = [f"## {title}", "", intro, "", "| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    md += ["| " + " | ".join([name.replace("|", "\\|")] + cells) + " |" for name, cells in rows]
    return md + [""]
