"""What latsim.run returns: the figures and summary as dicts, the tables as DataFrames."""
import json
import os
import warnings


def _pandas():
    # Imported when a table is asked for: the figures need no pandas.
    import pandas
    return pandas


def _ledger_frame(table):
    pd = _pandas()
    return pd.DataFrame(table["values"], columns=list(table["columns"]))


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

    def __init__(self, summary_text, tables, out, asked):
        self.summary = json.loads(summary_text)
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
    def fingerprint(self):
        """The run's event fingerprint (hex), as figures.json records it."""
        return self.summary["fingerprint"]

    def __repr__(self):
        mtp = self.figures.get("motion_to_photon_ms", {})
        mean = f", motion_to_photon_ms mean {mtp['mean']:.3f}" if mtp.get("count") else ""
        return f"<latsim.Result {self.summary.get('events', 0)} events{mean}, tables {sorted(self._tables)}>"
