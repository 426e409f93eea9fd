"""Reading latsim result directories: a single run, a sweep, or a directory of runs.

Only result files are read (summary.json, results.csv, timeline.csv, a sweep's
results store); nothing here knows how the simulator works. Iteration is always in sorted or file
order so that every output derived from it is reproducible.
"""

import json
import math
import os
import struct
import zlib
from fractions import Fraction

import sweep_labels
from registry_names import name_pattern
from intervals import mean_ci95, t975  # noqa: F401 (the report's and the plots' intervals)
from latsim_store import SweepStore
from result_files import (STATISTICS, DamagedFile, LARGEST_NUMBER, ResultDoc, cell, checked_distributions,  # noqa: F401
                          checked_number, read_csv, read_json, read_summary_file)

# Every figure is declared once, in the figure registry of the simulator
# (results/figure_registry.json): its table columns and plot labels come from
# there.
REGISTRY_FILE = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "results", "figure_registry.json")


def read_registry(path=REGISTRY_FILE):
    """The figure registry: its figures, headlines, families and placeholders."""
    with open(path, encoding="utf-8") as f:
        return json.load(f)


REGISTRY = read_registry()
_COLUMNS = sorted((c for f in REGISTRY["figures"] for c in f.get("columns", [])), key=lambda c: c["order"])

# Headline columns of the latency table: (column name, figure path, unit label), in the registry's order
# (results.csv has them too, and the run's events and wall time).
HEADLINE = [(c["name"], c["figure"], c["label"]) for c in _COLUMNS if c.get("report", True)]

# Columns of what a viewer or a camera sees (/apparent_latency, /measurement,
# /controller): a default table shows them only when some row has them.
SEEN_COLUMNS = {c["name"] for c in _COLUMNS if c.get("shown") == "where present"}

# Columns a default table shows only when some row's pipeline leads with their figure.
LEADING_COLUMNS = {c["name"] for c in _COLUMNS if c.get("shown") == "when leading"}

# Headline figures (a pipeline's first declared one) that have table columns:
# figure name -> the (mean, p99) columns that stand for it.
HEADLINE_COLUMNS = {}
for _f in REGISTRY["figures"]:
    _by_stat = {c["figure"]: c["name"] for c in _f.get("columns", [])}
    if _f["name"] + ".mean" in _by_stat and _f["name"] + ".p99" in _by_stat:
        HEADLINE_COLUMNS[_f["name"]] = (_by_stat[_f["name"] + ".mean"], _by_stat[_f["name"] + ".p99"])

# Distributions drawn as CDFs, histograms and against sweep axes, in the registry's order:
# (figure, its "plot" entry).
PLOTS = [(f["name"], f["plot"]) for f in REGISTRY["figures"] if "plot" in f]




_KINDS = [(name_pattern(f["name"], REGISTRY.get("placeholders", {})), f["kind"]) for f in REGISTRY["figures"] if f["family"] != "summary"]


def figure_kind(name):
    """The registry's kind of the figure figures.json nests under `name`, or None."""
    return next((kind for pattern, kind in _KINDS if pattern.match(name)), None)


def figure_meaning(name):
    """The registry's one-line meaning of a figure (its glossary entry is in docs/figures.md)."""
    return next(f["meaning"] for f in REGISTRY["figures"] if f["name"] == name)


def is_figure_path(path):
    """Whether a table can hold `path`: a declared count, number or flag, or a
    distribution's statistic (name.stat), as a sweep file's "figures" may
    choose it (sweep::choosable_figures)."""
    if figure_kind(path) in ("count", "number", "flag"):
        return True
    name, _, stat = path.rpartition(".")
    return stat in STATISTICS and figure_kind(name) == "distribution"


def whole_names(names, max_chars=200):
    """Names joined by ", " and cut before the first whole name past max_chars ("..., … and N more")."""
    text = ""
    for i, name in enumerate(names):
        item = (", " if i else "") + name
        if i and len(text) + len(item) > max_chars:
            return text + f", … and {len(names) - i} more"
        text += item
    return text


def headline_figure(rows):
    """The figure the rows' pipelines declare first (summary.json "headline"), when
    they all agree and it has table columns; else motion-to-photon latency."""
    firsts = {(r.first_summary().get("headline") or ["motion_to_photon_ms"])[0] for r in rows if r.run_dirs}
    if len(firsts) == 1:
        (only,) = firsts
        if only in HEADLINE_COLUMNS:
            return only
    return "motion_to_photon_ms"

# results.csv columns by figure path (the tables write the same headline figures).
COLUMN_OF = {path: column for column, path, _ in HEADLINE}


class Row:
    """One line of the latency table: a run, or a sweep point with its replications.

    A sweep point reads its headline figures from results.csv and opens its
    runs' summary.json files only when asked for something else, so that a
    report of many runs costs what it draws, not what the sweep ran."""

    def __init__(self, name, run_dirs, summaries=None, axis_values=None, table_rows=None, read_summary=None):
        self.name = name
        self.run_dirs = run_dirs
        self._summaries = summaries
        self._first = summaries[0] if summaries else None
        self.axis_values = axis_values or {}
        self.table_rows = table_rows  # sweep only: this point's results.csv lines, by replication
        # A run's summary from its directory (a sweep's from its results store unless the run was kept).
        self._read = read_summary or (lambda d: read_summary_file(os.path.join(d, "summary.json")))

    @property
    def summaries(self):
        """Every replication's summary.json (read on first use)."""
        if self._summaries is None:
            self._summaries = [self._read(d) for d in self.run_dirs]
        return self._summaries

    def first_summary(self):
        """Replication 0's summary.json: one run's, whatever the replications."""
        if self._first is None:
            self._first = self._summaries[0] if self._summaries else self._read(self.run_dirs[0])
        return self._first

    def replications(self):
        return len(self.run_dirs)

    def pipeline(self):
        scenario = self.first_summary().get("scenario", {}) if self.run_dirs else {}
        return scenario.get("pipeline", {}).get("type", "")

    def values(self, path):
        """The figure at `path` in every replication that has it."""
        column = COLUMN_OF.get(path)
        if self.table_rows is not None and column is not None and column in self.table_rows[0]:
            found = [as_number(r[column]) if r[column] != "" else None for r in self.table_rows]
        else:
            found = [find_figure(s, path) for s in self.summaries]
        return [v for v in found if v is not None]

    def mean(self, path):
        vals = self.values(path)
        return sum(vals) / len(vals) if vals else None


class Collection:
    """The rows of one result directory and how it was laid out."""

    def __init__(self, kind, directory, rows, axes=None, runs=None):
        self.kind = kind  # "run", "runs" or "sweep"
        self.directory = directory
        self.rows = rows
        self.axes = axes or []
        self.figures = []  # the report's columns a sweep file chose ("figures")
        self.runs = runs or []  # sweep only: one dict per results.csv line
        self.value_labels = {}  # sweep only: {axis: {value text: tick or legend label}} (sweep_labels)
        self._point_names = None  # point_name's names, by row identity, made on first use

    def value_label(self, axis, value):
        """What a plot calls one swept value: never JSON (sweep_labels.value_labels, made from the
        rows' values on first use where load() did not)."""
        if axis not in self.value_labels:
            distinct = list(dict.fromkeys(r.axis_values[axis] for r in self.rows if axis in r.axis_values))
            self.value_labels[axis] = sweep_labels.value_labels(distinct, axis_label(axis))
        return self.value_labels[axis].get(value, value)


def find_figure(summary, path):
    """A number by dotted path, first under "figures" then from the root; a distribution means its mean."""
    for root in (summary.get("figures", {}), summary):
        node = root
        for key in path.split("."):
            if not isinstance(node, dict) or key not in node:
                node = None
                break
            node = node[key]
        if isinstance(node, dict) and "mean" in node:
            node = node["mean"]
            # A distribution's mean is a number in every file latsim writes:
            # anything else is damage, not an absent figure (a "mean" of "x"
            # was drawn as no value, exit 0).
            if not isinstance(node, (int, float)) or isinstance(node, bool):
                raise DamagedFile(getattr(summary, "source", "summary.json"),
                                  f"{path}: its mean holds {str(node)[:40]!r}, not a number")
        if isinstance(node, (int, float)) and not isinstance(node, bool):
            return float(node)
    return None


def as_number(text):
    """A swept value as a number when it is one ("60", "0.5", "60000/1001"), else None."""
    if isinstance(text, (int, float)) and not isinstance(text, bool):
        return float(text)
    try:
        value = float(Fraction(str(text)))
    except (ValueError, ZeroDivisionError):
        return None
    return value if math.isfinite(value) else None


def short_axis_name(pointer, pointers):
    """The last component of a pointer, or the whole pointer when that would be ambiguous
    (file names: sweep_<name>.png)."""
    last = pointer.rsplit("/", 1)[-1]
    clashes = [p for p in pointers if p.rsplit("/", 1)[-1] == last]
    return last if len(clashes) == 1 else pointer.strip("/").replace("/", ".")


# Labels a sweep file declares for its axes ("label"), by pointer; set by load().
AXIS_LABELS = {}


def axis_label(pointer):
    """What tables and plots call an axis: its declared label, else its pointer (the
    last key alone, such as fixed_ms, does not say which stage's)."""
    return AXIS_LABELS.get(pointer, pointer)


def row_name(values, axes):
    """A sweep point's name from its axis values alone (sweep_labels.point_labels over one point)."""
    labels = {a: sweep_labels.value_labels([values[a]], axis_label(a)) for a in axes}
    return sweep_labels.point_labels([values], axes, axis_label, labels)[0]


def point_name(row, coll):
    """What tables and plots call a row: a sweep point by its axis values (sweep_labels.point_labels:
    a /description swept beside whole objects names it alone), anything else by its name."""
    if coll.kind != "sweep" or not coll.axes or not row.axis_values:
        return row.name
    if coll._point_names is None:
        values = [r.axis_values for r in coll.rows]
        for a in coll.axes:
            coll.value_label(a, values[0][a])  # makes the axis's labels where load() did not
        names = sweep_labels.point_labels(values, coll.axes, axis_label, coll.value_labels)
        coll._point_names = {id(r): name for r, name in zip(coll.rows, names)}
    return coll._point_names.get(id(row), row.name)


def load(directory):
    """Reads a run directory, a sweep directory, or a directory of run directories."""
    if os.path.isfile(os.path.join(directory, "results.csv")) and os.path.isdir(os.path.join(directory, "runs")):
        return _load_sweep(directory)
    if os.path.isfile(os.path.join(directory, "summary.json")):
        summary = read_summary_file(os.path.join(directory, "summary.json"))
        name = os.path.basename(os.path.normpath(directory))
        return Collection("run", directory, [Row(name, [directory], [summary])])
    rows = []
    for entry in sorted(os.listdir(directory)):
        run_dir = os.path.join(directory, entry)
        summary_file = os.path.join(run_dir, "summary.json")
        if os.path.isfile(summary_file):
            rows.append(Row(entry, [run_dir], [read_summary_file(summary_file)]))
    if not rows:
        raise ValueError(f"{directory}: no summary.json, results.csv or run subdirectories found")
    return Collection("runs", directory, rows)


def _load_sweep(directory):
    results = os.path.join(directory, "results.csv")
    runs = read_csv(results, required=("point", "replication", "run_id"))
    for line, run in enumerate(runs, start=2):
        run["point"], run["replication"] = cell(results, line, run, "point", int), cell(results, line, run, "replication", int)
        if not run["run_id"] or "/" in run["run_id"] or run["run_id"] in (".", ".."):
            raise DamagedFile(results, f"line {line}: run_id: not a run directory's name")
        for column, value in run.items():
            # A run id is a name (16 hex digits, all of them decimal digits about
            # once in 1,850 runs) and an axis value is the sweep file's input:
            # neither is a figure the bound guards.
            if column == "run_id" or column.startswith("/"):
                continue
            try:
                float(value)
            except (TypeError, ValueError):
                continue  # a name, a status, a fraction "num/den": not a figure
            cell(results, line, run, column)  # a number, then a finite one within bounds
    if not runs:
        raise ValueError(f"{directory}/results.csv: no finished runs")
    axes = [c for c in runs[0].keys() if c.startswith("/")]
    plan_file = os.path.join(directory, "plan.json")
    figures = []
    if os.path.isfile(plan_file):
        plan = read_json(plan_file)
        for axis in plan.get("axes", []):
            if isinstance(axis, dict) and axis.get("label") and axis.get("pointer"):
                AXIS_LABELS[axis["pointer"]] = str(axis["label"])
        figures = [str(f) for f in plan.get("figures", [])]
    by_point = {}
    for run in runs:
        by_point.setdefault(int(run["point"]), []).append(run)
    read = sweep_summary_reader(directory)
    points = [sorted(by_point[p], key=lambda r: int(r["replication"])) for p in sorted(by_point)]
    values = [{a: members[0][a] for a in axes} for members in points]
    labels = {}
    for a in axes:
        distinct = list(dict.fromkeys(v[a] for v in values))
        labels[a] = sweep_labels.value_labels(distinct, axis_label(a))
    names = sweep_labels.point_labels(values, axes, axis_label, labels)
    rows = [Row(name, [os.path.join(directory, "runs", r["run_id"]) for r in members], None, point_values, members,
                read)
            for name, members, point_values in zip(names, points, values)]
    coll = Collection("sweep", directory, rows, axes, runs)
    coll.figures = figures
    coll.value_labels = labels
    return coll


def sweep_summary_reader(directory):
    """Reads a sweep run's summary: its summary.json where the run was kept in
    full, else its record in the sweep's results store (opened on first use)."""
    store = []

    def read(run_dir):
        file = os.path.join(run_dir, "summary.json")
        if os.path.isfile(file):
            return read_summary_file(file)
        where = os.path.join(directory, "store")
        try:
            if not store:
                store.append(SweepStore(directory))
            summary = store[0].summary(os.path.basename(run_dir))
        except (ValueError, LookupError, TypeError, AttributeError, RecursionError, zlib.error, struct.error) as e:
            # A segment's frames are checked by their CRC: a record that still cannot be decoded was written so.
            raise DamagedFile(where, f"run {os.path.basename(run_dir)}: not a whole record ({type(e).__name__}: "
                                     f"{e})") from None
        if isinstance(summary, dict):
            checked_distributions(where, summary)
        if summary is None:
            raise ValueError(f"{directory}: run {os.path.basename(run_dir)} is in results.csv but not in the "
                             "results store (store/) nor in runs/")
        return summary
    return read


def histogram_edges(distribution):
    """(edges, counts) of a distribution's histogram: len(edges) == len(counts) + 1.

    Buckets are [lower edge, count]; each bucket ends where the next begins and
    the last ends at the distribution's max (or one bucket width on).
    """
    buckets = distribution.get("histogram") or []
    if not buckets:
        return [], []
    lowers = [float(b[0]) for b in buckets]
    counts = [float(b[1]) for b in buckets]
    width = lowers[-1] - lowers[-2] if len(lowers) > 1 else 0.0
    last = max(float(distribution.get("max", lowers[-1])), lowers[-1] + width)
    if last <= lowers[-1]:
        last = lowers[-1] + 1e-9
    return lowers + [last], counts


def quantile_of_buckets(edges, counts, fraction):
    """The value below which `fraction` of a histogram's mass lies, linear within a bucket."""
    total = sum(counts)
    target, below = fraction * total, 0.0
    for lo, hi, count in zip(edges, edges[1:], counts):
        if count > 0 and below + count >= target:
            return lo + (hi - lo) * max(0.0, target - below) / count
        below += count
    return edges[-1]


# The share of each curve's samples a histogram may leave out at either end.
TAIL_FRACTION = 0.005


def mass_range(histograms):
    """(low, high, clipped) of the x range a plot of these (edges, counts) shows: every curve's
    samples but TAIL_FRACTION at each end when that range is under half the full one (a long thin
    tail squashes the mass against one side); else the full range and clipped False."""
    shown = [(e, c) for e, c in histograms if e and sum(c) > 0]
    if not shown:
        return None
    full_low, full_high = min(e[0] for e, _ in shown), max(e[-1] for e, _ in shown)
    low = min(quantile_of_buckets(e, c, TAIL_FRACTION) for e, c in shown)
    high = max(quantile_of_buckets(e, c, 1.0 - TAIL_FRACTION) for e, c in shown)
    if high - low >= 0.5 * (full_high - full_low) or high <= low:
        return full_low, full_high, False
    pad = 0.05 * (high - low)
    return max(full_low, low - pad), min(full_high, high + pad), True


# A bucket drawn lower than this share of the tallest one is barely visible on a linear axis.
FAINT_SHARE = 0.05
# A log density axis is chosen when some curve has more of its mass than this in faint buckets.
FAINT_MASS = 0.25


def needs_log_density(histograms, low=None, high=None):
    """Whether a linear density axis would hide much of some curve's mass: a spike (a still head's
    near-zero registration error, say) that dwarfs where the rest of the samples lie. Only buckets
    within [low, high] count, when given."""
    densities = []
    for edges, counts in histograms:
        total = sum(counts)
        if total <= 0:
            continue
        densities.append([(c / total / max(hi - lo, 1e-12), c / total) for lo, hi, c in zip(edges, edges[1:], counts)
                          if (low is None or hi > low) and (high is None or lo < high)])
    tallest = max((d for curve in densities for d, _ in curve), default=0.0)
    if tallest <= 0:
        return False
    return any(sum(m for d, m in curve if d < FAINT_SHARE * tallest) > FAINT_MASS for curve in densities)
