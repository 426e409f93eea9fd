#!/usr/bin/env python3
"""Timelines a user can trust.

1. Every shipped scenario's timeline.json (Chrome trace events, as Perfetto
   reads them) has no improperly nested slice: on each track, two slices are
   either disjoint or one lies within the other. Every flow arrow has both
   ends, each bound to a slice of its track at its time; counters are numbers.
2. The Gantt chart's retrace lines sit at the retraces the run made: with a
   display phase and vertical blank lines, field k starts at
   phase + k x period, computed here from the scenario's numbers alone.

usage: test_timeline.py LATSIM SOURCE_DIR WORK_DIR
"""
import json
import os
import shutil
import subprocess
import sys
from fractions import Fraction

LATSIM, SOURCE, WORK = sys.argv[1], sys.argv[2], sys.argv[3]
sys.path.insert(0, os.path.join(SOURCE, "analysis"))
import gantt  # noqa: E402

# Time stamps are microseconds with six decimals (exact picoseconds); slices
# are compared in picoseconds, as integers.
def ps(us):
    return round(Fraction(str(us)) * 1_000_000)


def shipped_scenarios():
    """Complete scenario files: not sweeps (a base and axes), not bases."""
    found = []
    for root, _, files in os.walk(os.path.join(SOURCE, "scenarios")):
        for name in files:
            path = os.path.join(root, name)
            if not name.endswith(".json") or "/sweeps/" in path or name == "base.json":
                continue
            with open(path, encoding="utf-8") as f:
                if '"axes":' in f.read():
                    continue
            found.append(path)
    return sorted(found)


def nesting_problems(trace):
    """Slices of one track that overlap without nesting, and loose flow ends."""
    problems = []
    by_tid = {}
    for e in trace["traceEvents"]:
        if e.get("ph") == "X":
            start = ps(e["ts"])
            by_tid.setdefault(e["tid"], []).append((start, start + ps(e["dur"]), e["name"]))
    for tid, slices in by_tid.items():
        # Sorted by start, longest first: each slice must end within every
        # open slice that contains its start.
        slices.sort(key=lambda s: (s[0], -s[1]))
        stack = []
        for start, end, name in slices:
            while stack and stack[-1][1] <= start and not (stack[-1][0] == stack[-1][1] == start):
                stack.pop()
            if stack and end > stack[-1][1]:
                problems.append(f"tid {tid}: {name} [{start}, {end}] ps overlaps {stack[-1][2]} "
                                f"[{stack[-1][0]}, {stack[-1][1]}] ps")
                if len(problems) > 5:
                    return problems
            stack.append((start, end, name))
    ends = {}
    for e in trace["traceEvents"]:
        if e.get("ph") in ("s", "f"):
            ends.setdefault(e["id"], []).append(e)
            at = ps(e["ts"])
            if not any(s <= at <= t for s, t, _ in by_tid.get(e["tid"], [])):
                problems.append(f"flow {e['id']} ({e['ph']}): no slice of tid {e['tid']} at {at} ps")
        elif e.get("ph") == "C":
            if not all(isinstance(v, (int, float)) for v in e["args"].values()):
                problems.append(f"counter {e['name']}: a value that is not a number")
    for flow_id, pair in ends.items():
        if sorted(e["ph"] for e in pair) != ["f", "s"]:
            problems.append(f"flow {flow_id}: ends {[e['ph'] for e in pair]}")
    return problems


def run(scenario, out, *sets):
    args = [LATSIM, "run", scenario, "--out", out]
    for s in sets:
        args += ["--set", s]
    done = subprocess.run(args, capture_output=True, text=True)
    if done.returncode != 0:
        raise SystemExit(f"{scenario}: exit {done.returncode}: {done.stderr.strip()}")


def check_every_scenario():
    failures = 0
    checked = 0
    for scenario in shipped_scenarios():
        out = os.path.join(WORK, "nesting")
        shutil.rmtree(out, ignore_errors=True)
        run(scenario, out, "/duration_s=0.3")
        path = os.path.join(out, "timeline.json")
        if not os.path.isfile(path):
            continue
        with open(path, encoding="utf-8") as f:
            trace = json.load(f)
        checked += 1
        problems = nesting_problems(trace)
        if problems:
            failures += 1
            print(f"FAIL {os.path.relpath(scenario, SOURCE)}:", *problems[:6], sep="\n  ")
    print(f"timeline nesting: {checked} scenarios checked, {failures} with problems")
    return failures == 0 and checked > 20


def check_retraces():
    # 75 Hz with a 3.5 ms phase and 45 blank lines before 600 active ones:
    # field k starts (its vertical blank begins) at 3.5 + k x 1000/75 ms.
    scenario = os.path.join(SOURCE, "scenarios", "hmd_60hz_direct.json")
    out = os.path.join(WORK, "retraces")
    shutil.rmtree(out, ignore_errors=True)
    run(scenario, out, "/duration_s=0.2", "/display/refresh_hz=75", "/display/phase_ms=3.5",
        "/display/vblank_lines=45", "/display/height_px=600")
    entries = gantt.read_timeline(os.path.join(out, "timeline.csv"))
    retraces = gantt.retrace_times(entries)
    period = Fraction(1000, 75)
    expected = [float(Fraction(7, 2) + k * period) for k in range(len(retraces))]
    ok = len(retraces) >= 14 and all(abs(a - b) < 1e-6 for a, b in zip(retraces, expected))
    # The active scanout starts 45 of 645 line times after the retrace.
    scanouts = sorted(e["start_ms"] for e in entries if e["unit"] == "display" and e["stage"] == "SCANOUT")
    blank = float(period * Fraction(45, 645))
    ok = ok and all(abs(s - (r + blank)) < 1e-6 for s, r in zip(scanouts, retraces))
    # The chart draws its dashed lines there (the lines of the figure itself).
    base = gantt.draw(out)
    ok = ok and base is not None and os.path.isfile(base + ".png")
    print(f"retraces: {retraces[:3]} ... against {expected[:3]} ...: {'ok' if ok else 'FAIL'}")
    return ok


def main():
    os.makedirs(WORK, exist_ok=True)
    ok = check_retraces()
    ok = check_every_scenario() and ok
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
