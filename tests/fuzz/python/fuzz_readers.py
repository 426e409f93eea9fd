"""Fuzzes the Python readers of `latsim report` and of compare's plotting step.

Usage: fuzz_readers.py LATSIM SOURCE_DIR WORK_DIR --target report|compare
                       [--seconds S] [--runs N] [--seed K] [--replay-only] [--corpus-digest]

Seeds are made here by latsim itself: for report a run (with its ledger and
timeline), a directory of two runs and two sweeps (one with kept runs, one
with its results store alone); for compare, `latsim compare` on shipped captures (PresentMon, OVR
Metrics) beside runs of the scenarios made for them. The inputs under
tests/fuzz/regressions/py_<target>/ are replayed first (each must keep the
contract, in this process and in one of its own), then every seed file
unchanged, then mutated inputs (of the files the reader opens) until S seconds have passed since the start
(seeds included) or N executions are done. A finding
(the contract broken in a process of its own too) is written to
WORK_DIR/findings/<target>/<n>/ (case.json and input: copy it to the
regressions once fixed) and the exit status is 1. --replay-only stops
after the regressions and the unchanged seeds; --corpus-digest prints a
digest of the kept inputs (the same seed and N give the same digest).
"""

import argparse
import hashlib
import json
import os
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

from engine import Fuzzer, Input  # noqa: E402
from targets import ReaderTarget  # noqa: E402


def latsim(binary, *args):
    proc = subprocess.run([binary, *args], capture_output=True, text=True)
    if proc.returncode != 0:
        raise SystemExit(f"fuzz: latsim {' '.join(args)}: {proc.stderr.strip()[-300:]}")


def report_seeds(binary, source, seeds):
    """A run, a directory of runs and two sweeps, as latsim writes them."""
    base = os.path.join(source, "scenarios", "hmd_60hz_direct.json")
    run = os.path.join(seeds, "run")
    latsim(binary, "run", base, "--out", run, "--set", "/duration_s=0.5", "--ledger", "-q")
    runs = os.path.join(seeds, "runs")
    os.makedirs(runs)
    shutil.copytree(run, os.path.join(runs, "direct"))
    latsim(binary, "run", os.path.join(source, "scenarios", "hmd_60hz_tearing.json"), "--out",
           os.path.join(runs, "tearing"), "--set", "/duration_s=0.5", "-q")
    # Kept runs (summary.json) and, with "keep": "figures", the results store's segments alone.
    for name, keep in (("sweep", "first"), ("store", "figures")):
        sweep_file = os.path.join(seeds, "sweep.json")
        with open(sweep_file, "w") as f:
            json.dump({"base": base, "overrides": {"/duration_s": 0.5}, "keep": keep, "replications": 2,
                       "axes": [{"pointer": "/tracker/rate_hz", "values": [60, 120], "label": "tracker rate"}]}, f)
        latsim(binary, "sweep", sweep_file, "--out", os.path.join(seeds, name), "-j", "2")
        os.remove(sweep_file)
    return {name: os.path.join(seeds, name) for name in ("run", "runs", "sweep", "store")}


# compare's seeds: (name, capture under SOURCE_DIR, scenario made for it, compare's options).
COMPARE_SEEDS = [
    ("presentmon", "scenarios/measured/captures/test_case_0.csv", "scenarios/measured/current_cpu_gpu.json",
     ["--application", "dwm.exe"]),
    ("ovr_metrics", "scenarios/measured/captures/ovr-metrics/OGMV_1.csv", "scenarios/measured/quest2_ovr_72hz.json",
     []),
]


def compare_seeds(binary, source, seeds):
    """compare_values.json as `latsim compare` writes it, without its plots."""
    found = {}
    for name, capture, scenario, options in COMPARE_SEEDS:
        run = os.path.join(seeds, "runs", name)
        latsim(binary, "run", os.path.join(source, scenario), "--out", run, "--set", "/duration_s=2", "-q")
        out = os.path.join(seeds, name)
        latsim(binary, "compare", os.path.join(source, capture), run, "--out", out, "--no-plots", *options)
        for other in os.listdir(out):
            if other != "compare_values.json":
                os.remove(os.path.join(out, other))
        found[name] = out
    return found


def replay(target, fuzzer, directory):
    """Every regression input of the target; the names of those that break the contract."""
    failed = []
    for name in sorted(os.listdir(directory)) if os.path.isdir(directory) else []:
        with open(os.path.join(directory, name, "case.json")) as f:
            case = json.load(f)
        content = None
        if not case.get("removed"):
            with open(os.path.join(directory, name, "input"), "rb") as f:
                content = f.read()
        item = Input(case["seed"], case["file"], case["kind"], content)
        verdict = fuzzer.one(item) or target.confirm(item, None)
        print(f"fuzz: regression {name}: {verdict or 'keeps the contract'}")
        if verdict:
            failed.append(name)
    return failed


def save_findings(fuzzer, directory):
    for number, (item, verdict) in enumerate(fuzzer.findings.values(), start=1):
        where = os.path.join(directory, str(number))
        os.makedirs(where, exist_ok=True)
        with open(os.path.join(where, "case.json"), "w") as f:
            json.dump({"seed": item.seed, "file": item.file, "kind": item.kind, "removed": item.content is None,
                       "verdict": verdict}, f, indent=1)
            f.write("\n")
        if item.content is not None:
            with open(os.path.join(where, "input"), "wb") as f:
                f.write(item.content)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("latsim")
    parser.add_argument("source")
    parser.add_argument("work")
    parser.add_argument("--target", choices=("report", "compare"), required=True)
    parser.add_argument("--seconds", type=float, default=60.0)
    parser.add_argument("--runs", type=int, default=None)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--replay-only", action="store_true")
    parser.add_argument("--corpus-digest", action="store_true")
    args = parser.parse_args()
    started = time.monotonic()
    if os.environ.get("PYTHONHASHSEED") != "0":
        # Sets iterate in an order of their hash: coverage, and so the corpus, would differ run to run.
        os.environ["PYTHONHASHSEED"] = "0"
        os.execv(sys.executable, [sys.executable, *sys.argv])
    binary, source = os.path.abspath(args.latsim), os.path.abspath(args.source)
    work = os.path.join(os.path.abspath(args.work), args.target)
    shutil.rmtree(work, ignore_errors=True)
    seeds_dir = os.path.join(work, "seeds")
    os.makedirs(seeds_dir)
    make = report_seeds if args.target == "report" else compare_seeds
    seeds = make(binary, source, seeds_dir)
    script = os.path.join(source, "analysis", f"{args.target}.py")
    target = ReaderTarget(args.target, script, seeds, work, binary)
    fuzzer = Fuzzer(target, args.seed, [os.path.join(source, "analysis")])
    failed = replay(target, fuzzer, os.path.join(source, "tests", "fuzz", "regressions", f"py_{args.target}"))
    spent = fuzzer.run(0 if args.replay_only else args.seconds - (time.monotonic() - started), args.runs)
    if args.replay_only:
        print(f"fuzz: {args.target}: {len(failed)} of the regressions break the contract; the seeds keep it")
        return 1 if failed else 0
    save_findings(fuzzer, os.path.join(work, "findings"))
    print(f"fuzz: {args.target}: seed {args.seed}: {fuzzer.executions} executions in {spent:.0f} s "
          f"({fuzzer.executions / max(spent, 1e-9):.1f}/s), {len(fuzzer.corpus)} kept inputs, "
          f"{len(fuzzer.seen)} transitions, {len(fuzzer.findings)} findings"
          f"{f' (see {work}/findings)' if fuzzer.findings else ''}, "
          f"{fuzzer.unconfirmed} not reproduced in a process of its own; {time.monotonic() - started:.0f} s in all")
    if args.corpus_digest:
        digest = hashlib.sha256()
        for item in fuzzer.corpus:
            digest.update(f"{item.seed}\0{item.file}\0{len(item.content)}\0".encode() + item.content)
        print(f"fuzz: corpus digest {digest.hexdigest()[:16]}")
    return 1 if failed or fuzzer.findings else 0


if __name__ == "__main__":
    sys.exit(main())
