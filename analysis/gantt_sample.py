"""The Gantt charts of a report: which runs get one (all, or for a sweep an
evenly spaced sample of its points) and what report.md says about the rest."""

import os

import gantt
import sweep_labels
from progress import Progress


def gantt_candidates(coll):
    """Per row, its first run with a timeline.csv (rows without one left out), in row order."""
    found = []
    for row in coll.rows:
        run_dir = next((d for d in row.run_dirs if os.path.isfile(os.path.join(d, "timeline.csv"))), None)
        if run_dir:
            found.append((row, run_dir))
    return found


def evenly_spaced(items, count):
    """`count` items spread evenly from the first to the last (all when there are no more)."""
    if count >= len(items):
        return list(items)
    if count <= 0:
        return []
    if count == 1:
        return [items[0]]
    step = (len(items) - 1) / (count - 1)
    return [items[round(i * step)] for i in range(count)]


def draw(coll, limit):
    """gantt.png/svg for a sample of runs with a timeline.csv: for a sweep one run per point, `limit`
    points evenly spaced; otherwise the first `limit` runs (None: all). Returns (drawn paths, not drawn)."""
    if coll.kind == "sweep":
        candidates = gantt_candidates(coll)
    else:
        candidates = [(row, d) for row in coll.rows for d in row.run_dirs
                      if os.path.isfile(os.path.join(d, "timeline.csv"))]
    chosen = candidates if limit is None else evenly_spaced(candidates, limit)
    drawn = []
    progress = Progress("Gantt charts", len(chosen))
    for row, run_dir in chosen:
        base = gantt.draw(run_dir, title=f"{sweep_labels.cut(row.name, 100)}: pipeline stages")
        if base:
            drawn.append(os.path.relpath(base, coll.directory))
        progress.advance()
    progress.finish()
    return drawn, len(candidates) - len(chosen)


def section(gantts, skipped, kind):
    md = ["## Stage timelines", ""] + [f"![{g}]({g}.png)" for g in gantts]
    if skipped:
        sample = "one run per point, evenly spaced over the plan" if kind == "sweep" else "the first runs"
        md += ["", f"{len(gantts)} chart(s) drawn ({sample}); {skipped} more "
               f"{'point(s)' if kind == 'sweep' else 'run(s)'} have a timeline.csv: `latsim report DIR "
               "--gantt-limit N` draws N (each chart costs about a second)."]
    return md + [""]
