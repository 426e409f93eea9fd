"""What latsim.run returns: the figures and summary as dicts, the tables as DataFrames."""
import json
import os
import warnings


def _pandas():
    # Imported when a table is asked for: the figures need no pandas.
    import pandas
    return pandas


def _without_sentinels(frame):
    """A ledger table with its "none" markers as missing values: simulated time
    starts at 0 and numbers (frame, image, sample) at 0, so a negative time or
    number is no value (fields.csv's orientation_measured_ps is -1 where the
    orientation is looked up per line at scanout). Such columns become
    pandas' nullable Int64; the others keep int64."""
    for column in frame.columns:
        if frame[column].dtype.kind == "i" and (frame[column] < 0).any():
            frame[column] = frame[column].astype("Int64").mask(frame[column] < 0)
    return frame


def _ledger_frame(table):
    pd = _pandas()
    return _without_sentinels(pd.DataFrame(table["values"], columns=list(table["columns"])))


def _read_table(out, name):
    """One of the run's files as a DataFrame (None when the run did not write it)."""
    path = os.path.join(out, name)
    if not os.path.exists(path):
        return None
    frame = _pandas().read_csv(path)
    return _without_sentinels(frame) if name in ("frames.csv", "fields.csv", "tracker.csv") else frame


def _samples_frame(columns):
    pd = _pandas()
    return pd.DataFrame({"t_ms": columns["t_ms"], "name": pd.Categorical(columns["name"]),
                         "value": columns["value"]})


def _timeline_frame(columns, out):
    """The stage timeline: from memory, or from timeline.csv when the run wrote
    its files (it then streams the timeline there instead of keeping it)."""
    pd = _pandas()
    names = ["stage", "frame", "eye", "unit", "start_ms", "end_ms"]
    if out is not None:
        path = os.path.join(out, "timeline.csv")
        if os.path.exists(path):
            return pd.read_csv(path)
        return pd.DataFrame({n: [] for n in names})
    return pd.DataFrame({n: columns[n] for n in names})


class Result:
    """One run of a scenario.

    figures   -- the figures (dict), as in figures.json
    summary   -- summary.json's content (dict): figures, resolved scenario,
                 warnings, events, fingerprint, wall time, ...
    warnings  -- legal but doubtful input (list of str)
    out       -- the run directory when files were written, else None
    frames, fields, tracker -- the ledger (frames.csv, fields.csv,
                 tracker.csv) as DataFrames, with ledger=True
    samples   -- every recorded sample (samples.csv: t_ms, name, value), with samples=True
    timeline  -- the stage timeline (timeline.csv: stage, frame, eye, unit,
                 start_ms, end_ms), with timeline=True
    """

    def __init__(self, summary_text, tables, out, asked, presentmon=None):
        self.summary = json.loads(summary_text)
        self._presentmon = presentmon
        self.figures = self.summary["figures"]
        self.warnings = self.summary.get("warnings", [])
        self.out = out
        self._tables = {}
        if asked["ledger"]:
            for name in ("frames", "fields", "tracker"):
                self._tables[name] = _ledger_frame(tables[name])
        if asked["samples"]:
            self._tables["samples"] = _samples_frame(tables["samples"])
        if asked["timeline"]:
            self._tables["timeline"] = _timeline_frame(tables["timeline"], out)
            if tables["timeline_dropped"]:
                warnings.warn(f"the timeline keeps its first {len(self._tables['timeline'])} entries: "
                              f"{tables['timeline_dropped']} more were counted, not kept "
                              "(raise /output/timeline_max_entries, 0 keeps all)", stacklevel=3)

    @classmethod
    def from_directory(cls, directory):
        """A run directory written by `latsim run` (or a sweep's kept run):
        summary.json, and whichever of frames.csv, fields.csv, tracker.csv,
        samples.csv, timeline.csv and presentmon.csv it holds."""
        directory = os.fspath(directory)
        with open(os.path.join(directory, "summary.json"), encoding="utf-8") as f:
            summary_text = f.read()
        result = cls(summary_text, None, directory, {"ledger": False, "samples": False, "timeline": False})
        for name in ("frames", "fields", "tracker", "samples", "timeline"):
            frame = _read_table(directory, name + ".csv")
            if frame is not None:
                result._tables[name] = frame
        return result

    def _table(self, name, flag):
        if name not in self._tables:
            raise AttributeError(f"Result.{name}: ask for it with latsim.run(..., {flag}=True)")
        return self._tables[name]

    frames = property(lambda self: self._table("frames", "ledger"),
                      doc="frames.csv: one row per image first shown (ledger=True)")
    fields = property(lambda self: self._table("fields", "ledger"),
                      doc="fields.csv: one row per run of spans of a field showing one image (ledger=True)")
    tracker = property(lambda self: self._table("tracker", "ledger"),
                       doc="tracker.csv: one row per tracker sample carried (ledger=True)")
    samples = property(lambda self: self._table("samples", "samples"),
                       doc="samples.csv: every recorded sample of every figure (samples=True)")
    timeline = property(lambda self: self._table("timeline", "timeline"),
                        doc="timeline.csv: which unit ran which stage of which frame, and when (timeline=True)")

    @property
    def table(self):
        """The run as a tidy table of one row: every scalar figure a column
        (motion_to_photon_ms.mean, counts.fields, ...), as latsim.load gives it."""
        from . import _tables
        return _tables.run_table([self.summary], [os.path.basename(os.path.normpath(self.out)) if self.out else 0])

    @property
    def presentmon(self):
        """presentmon.csv, the application's frames in PresentMon's columns
        (docs/figures.md), from a run with out= or presentmon=True; None for a
        pipeline without application frames."""
        if self._presentmon is None and self.out is None:
            raise AttributeError("Result.presentmon: ask for it with latsim.run(..., presentmon=True) or out=DIR")
        if self._presentmon is None:
            self._presentmon = _read_table(self.out, "presentmon.csv")
            if self._presentmon is None:
                return None
        return self._presentmon

    @property
    def headline(self):
        """The headline figures as `latsim run` prints them, in its order: {name: value or distribution}."""
        figures = self.figures
        return {name: figures[name] for name in self.summary.get("headline", []) if name in figures}

    @property
    def fingerprint(self):
        """The run's event fingerprint (hex), as figures.json records it."""
        return self.summary["fingerprint"]

    def __repr__(self):
        # The headline as `latsim run` prints it (app/run.cpp), in the same order and format.
        lines = [f"<latsim.Result {self.summary.get('events', 0)} events, tables {sorted(self._tables)}"]
        for name, value in self.headline.items():
            if isinstance(value, dict) and "mean" in value:
                lines.append(f"  {name}: mean {value['mean']:.3f}  p50 {value['p50']:.3f}  p99 {value['p99']:.3f}  "
                             f"max {value['max']:.3f}  ({value['count']} samples)")
            elif isinstance(value, int) and not isinstance(value, bool):
                lines.append(f"  {name}: {value}")
            elif isinstance(value, float):
                lines.append(f"  {name}: {value:.3f}")
        return "\n".join(lines) + ">"
