#!/usr/bin/env python3
"""Numbers quoted in the docs are the numbers the runs give.

A quoted figure is marked in the Markdown with an HTML comment right after it:

    tear gap max 6.16 px<!-- fig arp/gallery_experiment.json tear_gap_px.max -->

naming a scenario (under scenarios/) and one of its figures (keys under
"figures" in its figures.json, joined by dots, list items as [i]; a key
holding dots is written in quotes, e.g. "analytic.x".mean). An optional word xN scales the run's value before it is
compared (e.g. x1000 for seconds quoted in ms, x100 for a percentage); words
/pointer=value run a variant of the scenario, as `latsim run --set` does
(e.g. /pipeline/cull_back_faces=false), for figures of what an assumption's
other values give.
The number checked is the last one between the previous marker (or the
start of the line) and this marker; thousands separators are allowed. It must
equal the run's figure rounded to the decimals quoted (half a unit of the
last quoted digit, plus a little for binary fractions).

Each scenario runs once, with its own duration and seed.

usage: check_doc_figures.py LATSIM SOURCE_DIR WORK_DIR [doc.md ...]   (default: every docs/*.md)
"""
import json
import os
import re
import shutil
import subprocess
import sys

MARK = re.compile(r"<!--\s*fig\s+(\S+\.json)\s+(\S+)((?:\s+[^\s-][^\s]*)*)\s*-->")
NUMBER = re.compile(r"-?\d{1,3}(?:,\d{3})+(?:\.\d+)?|-?\d+(?:\.\d+)?")
def default_docs(source):
    """Every Markdown file in docs/, in name order."""
    folder = os.path.join(source, "docs")
    return sorted(os.path.join("docs", name) for name in os.listdir(folder) if name.endswith(".md"))


def lookup(figures, path):
    """figures.json value at a path like a.b[2]."c.d".e."""
    value = figures
    for token in re.findall(r'"[^"]*"|\[\d+\]|[^.\[\]"]+', path):
        if token.startswith("["):
            value = value[int(token[1:-1])]
        else:
            value = value[token.strip('"')]
    return value


def quoted_marks(text):
    """(line number, quoted number as text, scenario, path, scale, sets) of every marker."""
    marks = []
    for lineno, line in enumerate(text.splitlines(), 1):
        start = 0
        for m in MARK.finditer(line):
            numbers = NUMBER.findall(line[start:m.start()])
            scale, sets = 1.0, []
            for word in m.group(3).split():
                if word.startswith("/"):
                    sets.append(word)
                elif word.startswith("x"):
                    scale = float(word[1:])
                else:
                    raise ValueError(f"line {lineno}: a marker word must be xN or /pointer=value, not {word!r}")
            marks.append((lineno, numbers[-1] if numbers else None, m.group(1), m.group(2), scale, tuple(sets)))
            start = m.end()
    return marks


def run(latsim, source, work, scenario, sets, cache):
    key = (scenario,) + sets
    if key in cache:
        return cache[key]
    out = os.path.join(work, scenario.replace("/", "_").replace(".json", "") + f"_{len(cache)}")
    shutil.rmtree(out, ignore_errors=True)
    command = [latsim, "run", os.path.join("scenarios", scenario), "--out", out, "-q"]
    for item in sets:
        command += ["--set", item]
    done = subprocess.run(command, cwd=source, capture_output=True, text=True)
    if done.returncode != 0:
        cache[key] = None
        print(f"{scenario} {' '.join(sets)}: run failed ({done.returncode}): {done.stderr.strip()}")
        return None
    with open(os.path.join(out, "figures.json")) as f:
        cache[key] = json.load(f)["figures"]
    return cache[key]


def main():
    latsim, source, work = sys.argv[1:4]
    docs = sys.argv[4:] or default_docs(source)
    os.makedirs(work, exist_ok=True)
    cache, failures, checked = {}, [], 0
    for doc in docs:
        with open(os.path.join(source, doc), encoding="utf-8") as f:
            text = f.read()
        for lineno, quoted, scenario, path, scale, sets in quoted_marks(text):
            where = f"{doc}:{lineno}"
            if quoted is None:
                failures.append(f"{where}: no number before the marker for {scenario} {path}")
                continue
            figures = run(latsim, source, work, scenario, sets, cache)
            if figures is None:
                failures.append(f"{where}: {scenario} did not run")
                continue
            try:
                value = float(lookup(figures, path)) * scale
            except (KeyError, IndexError, TypeError, ValueError) as e:
                failures.append(f"{where}: {scenario} has no figure {path} ({e!r})")
                continue
            decimals = len(quoted.split(".")[1]) if "." in quoted else 0
            number = float(quoted.replace(",", ""))
            tolerance = 0.5 * 10 ** -decimals * (1 + 1e-9) + 1e-12
            checked += 1
            if abs(value - number) > tolerance:
                failures.append(f"{where}: quotes {quoted} for {scenario} {path}, the run gives {value:.{decimals + 2}f}")
    for line in failures:
        print(line)
    print(f"{checked} quoted figures checked, {len(failures)} wrong")
    return 1 if failures or checked == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
