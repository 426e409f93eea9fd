"""Latency over time in `latsim report`: per refresh, the latency of the first
light of the field's first line shown, from each run's fields.csv (written
with `latsim run --ledger`), tracker.csv and the resolved display of its
summary.json.

First light is the photon time of docs/figures.md ("Instants"): the line's
written time, plus for a display with persistence the delay to the middle of
its lit interval (full: half the response time and half the hold until the row
is written again; rolling: the response time and half the flash; global: the
next retrace, the response time and half the flash). Motion-to-photon starts
at the older of the position's and the orientation's samples, rotation latency
at the orientation's. A pipeline that looks the orientation up per line at
scanout (address recalculation) writes -1 as orientation_measured_ps: that is
no time, and the orientation is then the newest sample the host could see when
the line was written (tracker.csv's visible_ps); without tracker.csv such a
field has no rotation latency. Empty or negative times are never read as
values.

A dense series (thousands of refreshes, or one alternating between two levels)
is drawn as a band of the 10th to 90th percentile and a line of the median per
window, over the raw series as a thin faint line: spread and trend both show.
"""

import bisect
import json
import math
import os
import sys
from fractions import Fraction

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import latsim_results  # noqa: E402
import plotting  # noqa: E402
import sweep_labels  # noqa: E402
from plotting import plt  # noqa: E402

# More curves than this on one plot cannot be told apart.
MAX_CURVES = 8
# Above this many refreshes in a curve, windows of percentiles are drawn over it.
DENSE_POINTS = 200
# Refreshes a window of a dense curve holds at least (enough that a periodic pattern, such as
# renders at a sixth of the refresh rate, does not alias into its median), and at most this many windows.
WINDOW_POINTS = 40
MAX_WINDOWS = 60
# The band of a window: these percentiles (and the median as its line).
BAND = (10, 90)
TICKS_PER_MS = 10**9


def _ticks(ms):
    return round(Fraction(str(ms)) * TICKS_PER_MS)


def _period_ticks(display):
    """The actual field period in picoseconds (refresh_hz as a number or "a/b", with its rate error)."""
    hz = Fraction(str(display["refresh_hz"]))
    ppb = round(float(display.get("rate_error_ppm", 0)) * 1000)
    return Fraction(10**12) / hz * Fraction(10**9, 10**9 + ppb)


class FirstLight:
    """Photon times of a field's lines, from its retrace and scanout start, by docs/figures.md's arithmetic."""

    def __init__(self, display):
        self.display = display
        self.period = _period_ticks(display)
        self.interlaced = bool(display.get("interlaced", False))
        self.persistence = display.get("persistence")

    def _slot_offset(self, line):
        """Ticks from the retrace to the writing of active line `line` (floored, as the display counts)."""
        d = self.display
        line_px = d["width_px"] + d.get("hblank_px", 0)
        lines = d["height_px"] // 2 if self.interlaced else d["height_px"]
        vblank = d.get("vblank_lines", 0)
        return math.floor((vblank + line) * line_px * self.period / ((lines + vblank) * line_px))

    def _after(self, field, fields):
        """Ticks from field `field`'s retrace to the retrace `fields` later: each retrace is the phase
        plus the floored multiple of the period."""
        return math.floor((field + fields) * self.period) - math.floor(field * self.period)

    def written(self, scanout_start_ps, line):
        """The written time of active line `line` of the field whose line 0 is written at scanout_start_ps."""
        if line == 0:
            return scanout_start_ps
        return scanout_start_ps - self._slot_offset(0) + self._slot_offset(line)

    def photon(self, field, retrace_ps, scanout_start_ps, line):
        written = self.written(scanout_start_ps, line)
        p = self.persistence
        if not p:
            return written
        response = _ticks(p.get("response_ms", 0))
        if p["type"] == "full":
            hold = self._after(field, 2 if self.interlaced else 1)
            return written + response // 2 + hold // 2
        lit = _ticks(p["lit_ms"])
        if p["type"] == "rolling":
            return written + response + lit // 2
        if p["type"] == "global":
            return retrace_ps + self._after(field, 1) + response + lit // 2
        raise ValueError(f"persistence type {p['type']!r} is not in docs/figures.md")


class NewestSample:
    """The measurement time of the newest sample the host can see at an instant (tracker.csv)."""

    def __init__(self, run_dir):
        self.visible, self.measured = [], []
        path = os.path.join(run_dir, "tracker.csv")
        if not os.path.isfile(path):
            return
        rows = []
        for row in _csv_rows(path):
            visible, measured = _time(row.get("visible_ps"), path), _time(row.get("measured_ps"), path)
            if visible is not None and measured is not None:
                rows.append((visible, measured))
        rows.sort()
        self.visible = [r[0] for r in rows]
        self.measured = [r[1] for r in rows]

    def at(self, t_ps):
        i = bisect.bisect_right(self.visible, t_ps)
        return self.measured[i - 1] if i > 0 else None


def _csv_rows(path):
    return latsim_results.read_csv(path)


def _time(text, path=None):
    """A time in picoseconds from a ledger cell; None for an empty cell or a negative sentinel.
    Text that is no integer, or a time beyond any run, is a damaged file."""
    if text is None or text == "":
        return None
    try:
        value = int(text)
    except ValueError:
        raise latsim_results.DamagedFile(path or "a result table", f"{text[:40]!r} is no time in picoseconds") from None
    if value > 10**24:
        raise latsim_results.DamagedFile(path or "a result table", "a time beyond 1e24 ps, longer than any run")
    return value if value >= 0 else None


def _display(run_dir):
    try:
        with open(os.path.join(run_dir, "summary.json"), encoding="utf-8") as f:
            return json.load(f).get("scenario", {}).get("display")
    except (OSError, ValueError):
        return None


def _first_rows(path, eye):
    """Per field of one eye, its shown row with the lowest first line, in field order."""
    first = {}
    for row in _csv_rows(path):
        try:
            if int(row["eye"]) != eye or int(row["image"]) < 0:
                continue
            field, line = int(row["field"]), int(row["first_line"])
        except (KeyError, TypeError, ValueError):
            continue
        if field not in first or line < int(first[field]["first_line"]):
            first[field] = row
    return [first[k] for k in sorted(first)]


def read_fields(run_dir, eye=0):
    """[(first light s, motion-to-photon ms, rotation latency ms or None)] per field of one eye that
    shows an image, or None without fields.csv or a resolved display in summary.json."""
    path = os.path.join(run_dir, "fields.csv")
    display = _display(run_dir)
    if not os.path.isfile(path) or not display:
        return None
    light = FirstLight(display)
    newest = None
    out = []
    for row in _first_rows(path, eye):
        retrace, start = _time(row.get("retrace_ps"), path), _time(row.get("scanout_start_ps"), path)
        position = _time(row.get("measured_ps"), path)
        if retrace is None or start is None or position is None:
            continue
        line = int(row["first_line"])
        photon = light.photon(int(row["field"]), retrace, start, line)
        orientation = _time(row.get("orientation_measured_ps"), path)
        if orientation is None and row.get("orientation_at_scanout") == "1":
            newest = newest or NewestSample(run_dir)
            orientation = newest.at(light.written(start, line))
        origin = position if orientation is None else min(position, orientation)
        rotation = None if orientation is None else (photon - orientation) * 1e-9
        out.append((photon * 1e-12, (photon - origin) * 1e-9, rotation))
    return out


def series(coll):
    """(row name, points) of the rows whose first run has a fields.csv, at most MAX_CURVES, evenly spaced."""
    found = []
    for row in coll.rows:
        if not row.run_dirs:
            continue
        points = read_fields(row.run_dirs[0])
        if points:
            found.append((row.name, points))
    if len(found) <= MAX_CURVES:
        return found
    step = (len(found) - 1) / (MAX_CURVES - 1)
    return [found[round(i * step)] for i in range(MAX_CURVES)]


def percentile(sorted_values, q):
    """The q-th percentile (0..100) of sorted values, linear between order statistics."""
    position = (len(sorted_values) - 1) * q / 100.0
    low = math.floor(position)
    high = min(low + 1, len(sorted_values) - 1)
    return sorted_values[low] + (sorted_values[high] - sorted_values[low]) * (position - low)


def windows(xs, ys, count=None):
    """[(window start, window end, low percentile, median, high percentile)] over `count` equal windows
    of x holding points (default: WINDOW_POINTS refreshes a window on average, at most MAX_WINDOWS)."""
    if not xs:
        return []
    count = count or max(1, min(MAX_WINDOWS, len(xs) // WINDOW_POINTS))
    start, width = xs[0], (xs[-1] - xs[0]) / count or 1.0
    groups = {}
    for x, y in zip(xs, ys):
        groups.setdefault(min(count - 1, int((x - start) / width)), []).append(y)
    out = []
    for index in sorted(groups):
        values = sorted(groups[index])
        out.append((start + index * width, start + (index + 1) * width, percentile(values, BAND[0]),
                    percentile(values, 50), percentile(values, BAND[1])))
    return out


def _draw(ax, xs, ys, colour, label):
    if len(xs) <= DENSE_POINTS:
        ax.plot(xs, ys, color=colour, label=label, linewidth=0.9)
        return False
    # The raw series thin and light (its rare outliers stay visible), each window's band and median
    # as steps across the window's whole span.
    ax.plot(xs, ys, color=colour, linewidth=0.4, alpha=0.45)
    steps = [x for w in windows(xs, ys) for x in ((w[0],) + w[2:], (w[1],) + w[2:])]
    edges = [x[0] for x in steps]
    ax.fill_between(edges, [x[1] for x in steps], [x[3] for x in steps], color=colour, alpha=0.3, linewidth=0)
    ax.plot(edges, [x[2] for x in steps], color=colour, label=label, linewidth=1.6)
    return True


def plot(coll):
    """latency_over_time.{png,svg}: motion-to-photon and rotation latency of first light per refresh;
    None when no run has fields.csv."""
    drawn = series(coll)
    if not drawn:
        return None
    fig, (ax_mtp, ax_rot) = plt.subplots(2, 1, figsize=(9, 7), sharex=True)
    dense = False
    for (name, points), colour in zip(drawn, plotting.colours(len(drawn))):
        label = sweep_labels.cut(name)
        xs = [p[0] for p in points]
        dense = _draw(ax_mtp, xs, [p[1] for p in points], colour, label) or dense
        rotated = [(p[0], p[2]) for p in points if p[2] is not None]
        if rotated:
            dense = _draw(ax_rot, [p[0] for p in rotated], [p[1] for p in rotated], colour, label) or dense
    ax_mtp.set_ylabel("motion-to-photon, first light (ms)")
    ax_rot.set_ylabel("rotation latency, first light (ms)")
    ax_rot.set_xlabel("simulated time of the first light of the field's first line (s)")
    title = "Latency of each refresh's first light (eye 0, from fields.csv)"
    if dense:
        title += f"\nlong series: median per window, band {BAND[0]}th\u2013{BAND[1]}th percentile, raw series faint"
    ax_mtp.set_title(title, fontsize=10)
    ax_mtp.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    base = "latency_over_time"
    plotting.save(fig, os.path.join(coll.directory, base))
    return base


def markdown(coll, base):
    if not base:
        return []
    shown = len(series(coll))
    return ["## Latency over time", "",
            "Per refresh, the latency of the first light of the field's first line shown: its photon time "
            "(docs/figures.md: the written time plus the display's persistence delay) minus the measurement "
            "time of the older of the pose's samples (motion-to-photon) and of the orientation's sample "
            "(rotation latency; behind a time warp, the warp's sample; where the orientation is looked up at "
            "scanout, the newest sample visible when the line is written), eye 0, from each run's `fields.csv` "
            f"(`latsim run --ledger`); {shown} run(s) drawn. Series of more than {DENSE_POINTS} refreshes are "
            f"drawn as the median and the {BAND[0]}th to {BAND[1]}th percentile per window of time over the "
            "raw series.", "", f"![{base}]({base}.png)", ""]
