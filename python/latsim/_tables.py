"""Tidy tables of runs: one row per run (sweep point and replication), one
column per scalar figure.

A figure's columns carry its figures.json name, dotted where it nests
(`counts.fields`), and a distribution's statistics follow its name
(`motion_to_photon_ms.mean`, `.p50`, `.p99`, ...), as results.sqlite names
them. Columns come in the figure registry's order (results/figure_registry.json,
which the package carries: no figure is listed here), then by name. Axis
values are typed columns named by their pointer; a value that is a whole JSON
object or array is named by the sweep's label for it (analysis/sweep_labels.py,
also carried).
"""
import json
import os
import sqlite3

from . import _intervals
from . import _registry_names
from . import _sweep_labels

# The figure registry the build copied beside this file.
_REGISTRY_FILE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "figure_registry.json")
_registry_cache = []


def registry():
    """The figure registry (results/figure_registry.json) as a dict."""
    if not _registry_cache:
        with open(_REGISTRY_FILE, encoding="utf-8") as f:
            _registry_cache.append(json.load(f))
    return _registry_cache[0]


def _declarations():
    """[(pattern, declaration)] of every figure, in registry order."""
    reg = registry()
    placeholders = reg.get("placeholders", {})
    return [(_registry_names.name_pattern(f["name"], placeholders), f) for f in reg["figures"]]


_declared = []


def declaration(name):
    """(registry position, the figure's declaration) of a figure name (no statistic), or (None, None)."""
    if not _declared:
        _declared.extend(_declarations())
    for position, (pattern, figure) in enumerate(_declared):
        if pattern.match(name):
            return position, figure
    return None, None


def _is_distribution(node):
    return isinstance(node, dict) and "count" in node and "mean" in node


def flatten(figures, prefix=""):
    """{column: value} of figures.json's figures: numbers and flags by dotted
    name, a distribution's numeric statistics as name.stat (its histogram
    left out), as results.sqlite holds them; words and lists are no scalars."""
    out = {}
    for key, node in figures.items():
        name = f"{prefix}{key}"
        if isinstance(node, bool):
            out[name] = 1.0 if node else 0.0
        elif isinstance(node, (int, float)):
            out[name] = node
        elif _is_distribution(node):
            for stat, value in node.items():
                if isinstance(value, (int, float)) and not isinstance(value, bool):
                    out[f"{name}.{stat}"] = value
        elif isinstance(node, dict):
            out.update(flatten(node, name + "."))
    return out


# A distribution's statistics in the order figures.json gives them.
STATISTICS = ("count", "mean", "stddev", "min", "p50", "p90", "p99", "p999", "max")


def _column_key(column, distributions):
    figure, stat = column, None
    if "." in column and column.rsplit(".", 1)[0] in distributions:
        figure, stat = column.rsplit(".", 1)
    position, _ = declaration(figure)
    stat_rank = STATISTICS.index(stat) if stat in STATISTICS else (len(STATISTICS) if stat else -1)
    return (position if position is not None else len(registry()["figures"]), figure, stat_rank, column)


def order_columns(columns):
    """Figure columns in registry order, a distribution's statistics in STATISTICS order."""
    distributions = {c.rsplit(".", 1)[0] for c in columns if c.endswith(".mean")}
    return sorted(columns, key=lambda c: _column_key(c, distributions))


def _frame(rows, leading):
    import pandas
    figure_columns = order_columns(sorted({c for row in rows for c in row} - set(leading)))
    return pandas.DataFrame(rows, columns=list(leading) + figure_columns)


def run_table(summaries, names=None):
    """One row per run summary (summary.json's content): its run name, seed and
    replication where known, then every scalar figure, then events and wall_s."""
    rows = []
    for i, summary in enumerate(summaries):
        row = {"run": names[i] if names else i}
        scenario = summary.get("scenario", {})
        if isinstance(scenario, dict) and "seed" in scenario:
            row["seed"] = scenario["seed"]
        row["replication"] = summary.get("replication", 0)
        row.update(flatten(summary.get("figures", {})))
        rows.append(row)
    table = _frame(rows, ["run", "seed", "replication"])
    for column in ("events", "wall_s"):
        table[column] = [s.get(column) for s in summaries]
    return table


def _typed_axis(values, label):
    """An axis's values as one typed column: numbers, words and flags as
    they are; whole JSON objects and arrays by the sweep's label for them."""
    if not any(isinstance(v, (dict, list)) for v in values):
        return list(values)
    texts = [json.dumps(v, sort_keys=True) for v in values]
    labels = _sweep_labels.value_labels(list(dict.fromkeys(texts)), label)
    return [labels[t] for t in texts]


def sweep_table(directory):
    """The tidy table of a sweep directory, from its plan.json and results.sqlite."""
    import pandas
    with open(os.path.join(directory, "plan.json"), encoding="utf-8") as f:
        plan = json.load(f)
    database = os.path.join(directory, "results.sqlite")
    if not os.path.isfile(database):
        raise ValueError(f"{directory}: no results.sqlite (run `latsim sweep ... --collect` to write the tables)")
    with sqlite3.connect(f"file:{database}?mode=ro", uri=True) as db:
        finished = {r[0]: r[1:] for r in db.execute("SELECT run_id, events, wall_s FROM runs")}
        values = {}
        for run_id, name, value in db.execute("SELECT run_id, name, value FROM figures"):
            values.setdefault(run_id, {})[name] = value
        for run_id, name, stat, value in db.execute("SELECT run_id, name, stat, value FROM distributions"):
            values.setdefault(run_id, {})[f"{name}.{stat}"] = value
    axes = plan.get("axes", [])
    pointers = [a["pointer"] for a in axes]
    runs = [r for r in plan["runs"] if r["run_id"] in finished]
    columns = {}
    for a, axis in enumerate(axes):
        columns[axis["pointer"]] = _typed_axis([r["values"][a] for r in runs], axis.get("label", axis["pointer"]))
    rows = []
    for r in runs:
        row = {"run_id": r["run_id"], "point": r["point"]}
        row.update({p: columns[p][len(rows)] for p in pointers})
        row.update({"seed": r["seed"], "replication": r["replication"]})
        row.update(values.get(r["run_id"], {}))
        rows.append(row)
    leading = ["run_id", "point"] + pointers + ["seed", "replication"]
    table = _frame(rows, leading) if rows else pandas.DataFrame(columns=leading)
    table["events"] = [finished[r["run_id"]][0] for r in runs]
    table["wall_s"] = [finished[r["run_id"]][1] for r in runs]
    table.attrs["axes"] = {a["pointer"]: a.get("label", a["pointer"]) for a in axes}
    return table


def _read_json(path):
    with open(path, encoding="utf-8") as f:
        return json.load(f)


def load(directory):
    """The tidy table of a run directory (one row), a sweep directory (one row
    per finished run) or a directory of run directories (one row each, named
    by their directory)."""
    directory = os.fspath(directory)
    if os.path.isfile(os.path.join(directory, "plan.json")):
        return sweep_table(directory)
    if os.path.isfile(os.path.join(directory, "summary.json")):
        return run_table([_read_json(os.path.join(directory, "summary.json"))],
                         [os.path.basename(os.path.normpath(directory))])
    names = sorted(e for e in os.listdir(directory) if os.path.isfile(os.path.join(directory, e, "summary.json")))
    if not names:
        raise ValueError(f"{directory}: neither a run directory (summary.json) nor a sweep directory (plan.json), "
                         "nor a directory of run directories")
    return run_table([_read_json(os.path.join(directory, n, "summary.json")) for n in names], names)


def mean_ci(table, figure="motion_to_photon_ms.mean", by=None):
    """Mean of a figure column over replications with its 95 % Student t
    interval, one row per group: columns n, mean, half_width, low, high.

    by -- the columns that make a group (default: the sweep's axes, else none)
    """
    import pandas
    if figure not in table.columns:
        raise KeyError(f"no column {figure!r}: a figure's column is its figures.json name, a distribution's "
                       "statistic after a dot (motion_to_photon_ms.mean)")
    if by is None:
        by = list(table.attrs.get("axes", {})) or None
    groups = table.groupby(by, sort=False, dropna=False)[figure] if by else [((), table[figure])]
    rows, index = [], []
    for key, values in groups:
        values = [float(v) for v in values if v == v]  # NaN: the run lacks the figure
        n = len(values)
        mean, half = _intervals.mean_ci95(values) if n else (float("nan"), float("nan"))
        rows.append({"n": n, "mean": mean, "half_width": half, "low": mean - half, "high": mean + half})
        index.append(key)
    if not by:
        return pandas.DataFrame(rows)
    names = [by] if isinstance(by, str) else list(by)
    keys = [k if isinstance(k, tuple) else (k,) for k in index]
    return pandas.DataFrame(rows, index=pandas.MultiIndex.from_tuples(keys, names=names) if len(names) > 1
                            else pandas.Index([k[0] for k in keys], name=names[0]))
