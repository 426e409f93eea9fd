"""latsim in Python: build a scenario in code, run it, and get its figures as
dicts and its tables as pandas DataFrames, without files.

    import latsim
    r = latsim.run("scenarios/hmd_60hz_direct.json", set={"/duration_s": 1})
    r.figures["motion_to_photon_ms"]["mean"]
    t = latsim.sweep("scenarios/devices/devices_sweep.json")   # one row per run
    latsim.mean_ci(t, "motion_to_photon_ms.mean", by="/description")

Tables are tidy: one row per run (sweep point and replication), one column
per scalar figure by its figures.json name, a distribution's statistics after
a dot (motion_to_photon_ms.mean, .p50, .p99, ...), axis values as typed
columns named by their pointer (a whole JSON object by the sweep's label
for it).

A scenario or sweep is a file path or a dict holding the same JSON. Bad input
raises latsim.ScenarioError (a ValueError) whose text is the line `latsim`
prints, naming the file ("<dict>" for a dict) and the JSON pointer; a failed
simulation raises latsim.RunFailure. The simulation runs with the GIL
released, and Ctrl-C (a notebook's interrupt) stops it at its next event with
KeyboardInterrupt, writing nothing.
"""
import json
import os
import tempfile

from ._latsim import RunFailure, ScenarioError, git_revision, version
from . import _latsim
from . import _tables
from ._results import Result
from ._tables import mean_ci

__all__ = ["run", "sweep", "load", "load_run", "compare", "mean_ci", "schema", "Result", "ScenarioError",
           "RunFailure", "version", "git_revision"]
__version__ = version

# The name a scenario or sweep given as a dict goes by in messages.
DICT_NAME = "<dict>"


def _json_default(value):
    # NumPy scalars and arrays, which notebooks hand over as often as numbers.
    if hasattr(value, "tolist"):
        return value.tolist()
    raise TypeError(f"{type(value).__name__} is not JSON: give numbers, strings, booleans, lists or dicts")


def _source(document, base_dir, what):
    """(name, text): a path and no text, or the name standing for a dict and its JSON text."""
    if isinstance(document, (str, os.PathLike)):
        return os.fspath(document), None
    if isinstance(document, dict):
        name = DICT_NAME if base_dir is None else os.path.join(os.fspath(base_dir), DICT_NAME)
        return name, json.dumps(document, default=_json_default)
    raise TypeError(f"{what} must be a file path or a dict, not {type(document).__name__}")


def _overrides(values):
    """--set's "/pointer=value" strings from a dict of pointer -> value."""
    if values is None:
        return []
    if not isinstance(values, dict):
        raise TypeError(f"set must be a dict from JSON pointer to value, not {type(values).__name__}")
    out = []
    for pointer, value in values.items():
        if not isinstance(pointer, str) or not pointer.startswith("/"):
            raise ValueError(f"set: {pointer!r} is not a JSON pointer (it starts with '/')")
        out.append(f"{pointer}={json.dumps(value, default=_json_default)}")
    return out


def _check_count(name, value, allow_none):
    if value is None and allow_none:
        return None
    if isinstance(value, bool) or not isinstance(value, int) or value < 0 or value >= 2**64:
        raise ValueError(f"{name} must be an integer from 0 to 2^64 - 1, not {value!r}")
    return value


def _check_out(out):
    if out is None:
        return ""
    out = os.fspath(out)
    if not out:
        raise ValueError("out must name a directory")
    if "\0" in out:
        raise ValueError("out: a path with a NUL character (it would be cut short: another directory)")
    if os.path.exists(out) and not os.path.isdir(out):
        raise ValueError(f"out: {out!r} exists and is not a directory")
    # As latsim run's --out (app/command_line.cpp): a name no file system
    # holds is refused before the run, not found when its files are written.
    shown = repr(out if len(out) <= 60 else out[:60] + "…") + ("" if len(out) <= 60 else f" ({len(out)} characters)")
    if len(os.fsencode(out)) >= 4096:
        raise ValueError(f"out: {shown} is longer than a path may be (4095 bytes)")
    if any(len(os.fsencode(part)) > 255 for part in out.split(os.sep)):
        raise ValueError(f"out: {shown} has a name longer than a file name may be (255 bytes)")
    return out


def run(scenario, set=None, seed=None, replication=0, *, out=None, ledger=False, samples=False, timeline=False,
        profile=False, presentmon=False, base_dir=None):
    """Runs one scenario as `latsim run` does and returns a Result.

    scenario    -- a scenario file, or a dict of the same JSON (its include
                   and data files are found relative to base_dir, default the
                   working directory)
    set         -- overrides {"/json/pointer": value}, as --set
    seed        -- overrides the scenario's /seed; replication selects
                   independent random streams, as --replication
    out         -- a directory to write the run's files to (summary.json,
                   figures.json, ...), as --out; None writes nothing
    ledger      -- Result.frames, .fields and .tracker (and frames.csv, ... in out)
    samples     -- Result.samples (and samples.csv in out)
    timeline    -- Result.timeline (kept while the scenario's /output/timeline is on)
    profile     -- wall time per model in summary["models"], as --profile
    presentmon  -- Result.presentmon without out= (the run writes its files
                   into a temporary directory, read back and removed)
    """
    if presentmon and out is None:
        import pandas
        with tempfile.TemporaryDirectory(prefix="latsim-run-") as tmp:
            result = run(scenario, set, seed, replication, out=tmp, ledger=ledger, samples=samples,
                         timeline=timeline, profile=profile, base_dir=base_dir)
            table = os.path.join(tmp, "presentmon.csv")
            frames = pandas.read_csv(table) if os.path.exists(table) else None
            if timeline:
                result._tables["timeline"] = result.timeline.copy()
        result.out, result._presentmon = None, frames
        return result
    name, text = _source(scenario, base_dir, "scenario")
    overrides = _overrides(set)
    seed = _check_count("seed", seed, True)
    replication = _check_count("replication", replication, False)
    out_dir = _check_out(out)
    command_line = ["latsim.run", name]
    for o in overrides:
        command_line += ["--set", o]
    if seed is not None:
        command_line += ["--seed", str(seed)]
    if replication:
        command_line += ["--replication", str(replication)]
    if out_dir:
        command_line += ["--out", out_dir]
    command_line += [flag for flag, on in (("--ledger", ledger), ("--samples", samples), ("--profile", profile)) if on]
    summary_text, tables = _latsim.run(name, text, overrides, seed, replication, out_dir, bool(ledger), bool(samples),
                                       bool(profile), command_line)
    return Result(summary_text, tables, out_dir or None,
                  {"ledger": bool(ledger), "samples": bool(samples), "timeline": bool(timeline)})


def sweep(sweep, jobs=None, *, out=None, ledger=False, samples=False, base_dir=None):
    """Runs every run of a sweep as `latsim sweep` does and returns its tidy
    table (one row per run, in plan order: run_id, point, the axes, seed,
    replication, every scalar figure, events, wall_s), as latsim.load gives it.

    sweep  -- a sweep file, or a dict of the same JSON (its "base" relative to
              base_dir, default the working directory)
    jobs   -- runs at once (default: the CPUs this process may use)
    out    -- the sweep directory (kept; a sweep there is resumed); None runs
              in a temporary directory removed afterwards
    ledger, samples -- also write each run's frames.csv / samples.csv (with out)

    Raises RunFailure when runs failed, its .results holding the others' table.
    """
    name, text = _source(sweep, base_dir, "sweep")
    jobs = len(os.sched_getaffinity(0)) if jobs is None else jobs
    if isinstance(jobs, bool) or not isinstance(jobs, int) or not 1 <= jobs <= 4096:
        raise ValueError(f"jobs must be an integer from 1 to 4096, not {jobs!r}")
    if out is not None:
        return _sweep_into(name, text, _check_out(out), jobs, ledger, samples)
    with tempfile.TemporaryDirectory(prefix="latsim-sweep-") as tmp:
        return _sweep_into(name, text, os.path.join(tmp, "sweep"), jobs, ledger, samples)


def _sweep_into(name, text, out_dir, jobs, ledger, samples):
    outcome = _latsim.sweep(name, text, out_dir, jobs, bool(ledger), bool(samples))
    results = _tables.sweep_table(out_dir)
    failures = outcome["failures"]
    if failures:
        shown = "; ".join(failures[:3]) + ("; ..." if len(failures) > 3 else "")
        error = RunFailure(f"{len(failures)} of {outcome['runs']} runs failed: {shown}")
        error.model, error.at_s, error.results, error.failures = None, None, results, failures
        raise error
    return results


def schema(format="json-schema"):
    """Every scenario key: the JSON Schema as a dict, or format="markdown" for
    the reference as text (as `latsim schema` prints them)."""
    text = _latsim.schema(format)
    return json.loads(text) if format == "json-schema" else text


def load(directory):
    """The tidy table of any directory the `latsim` command writes: a run
    (one row), a sweep (one row per finished run, from results.sqlite and
    plan.json) or a directory of runs (one row each, named by directory)."""
    return _tables.load(directory)


def load_run(directory):
    """A run directory as a Result: its figures, and its per-frame and
    per-sample tables (frames, fields, tracker, samples, timeline,
    presentmon) where the run wrote them."""
    return Result.from_directory(directory)


def compare(capture, run, *, application="", process_id=None, ks_threshold=0.1, mean_tolerance=0.1):
    """Sets a capture beside a run as `latsim compare` does (its reader and
    verdicts, not a second comparison) and returns compare.csv as a
    DataFrame, one row per quantity; .attrs holds the warnings and notes.

    capture -- a PresentMon, OVR Metrics Tool, VrApi or SteamVR frame timing capture
    run     -- a run directory, a Result that wrote its files (out=), or another capture
    """
    import io
    import pandas
    if isinstance(run, Result):
        if run.out is None:
            raise ValueError("compare: the run wrote no files: run it with out=DIR")
        run = run.out
    if process_id is not None:
        process_id = _check_count("process_id", process_id, False)
    outcome = _latsim.compare(os.fspath(capture), os.fspath(run), application, process_id, float(ks_threshold),
                              float(mean_tolerance))
    table = pandas.read_csv(io.StringIO(outcome["csv"]), keep_default_na=False, na_values=[""])
    table.attrs.update(warnings=list(outcome["warnings"]), notes=list(outcome["notes"]),
                       capture=outcome["capture"], run=outcome["run"])
    return table
