#!/usr/bin/env python3
"""Every glossary figure of every shipped scenario, recomputed from the ledger.

Runs each scenario under scenarios/ (two simulated seconds) with --ledger and
recomputes, from frames.csv, fields.csv, tracker.csv and the resolved scenario
alone, each figure of docs/figures.md that the run reports, by its definition
there: photon times from the raster arithmetic (exact fractions), the newest
sample visible at a photon time from the tracker ledger. Nothing the recorder
computed is read back except the figure under test.

usage: check_glossary.py LATSIM SOURCE_DIR WORK_DIR [scenario ...]
"""
import bisect
import csv
import json
import math
import os
import re
import shutil
import subprocess
import sys
from fractions import Fraction

TICKS = 10**12
FAILURES = []


def fail(scenario, message):
    FAILURES.append(f"{scenario}: {message}")


def rate_period(value, ppm):
    """Actual period in seconds of a rate given as a number or "a/b", with a rate error."""
    if isinstance(value, str) and "/" in value:
        a, b = value.split("/")
        hz = Fraction(int(a), int(b))
    else:
        hz = Fraction(value).limit_denominator(10**9)
    ppb = round(ppm * 1000)
    return (1 / hz) * Fraction(10**9, 10**9 + ppb)


def ticks_of_ms(ms):
    return round(Fraction(ms) * 10**9)


class Raster:
    """Photon times of the display as docs/figures.md states them."""

    def __init__(self, d):
        self.period = rate_period(d["refresh_hz"], d.get("rate_error_ppm", 0))
        self.phase = ticks_of_ms(d["phase_ms"])
        self.width = d["width_px"]
        self.hblank = d["hblank_px"]
        self.vblank = d["vblank_lines"]
        self.lines = d["height_px"] // 2 if d["interlaced"] else d["height_px"]
        self.per_field_px = (self.lines + self.vblank) * (self.width + self.hblank)
        self.interlaced = d["interlaced"]
        self.persistence = d.get("persistence")

    def field_start(self, k):
        return self.phase + math.floor(k * self.period * TICKS)

    def offset(self, slot_px):
        return math.floor(slot_px * self.period * TICKS / self.per_field_px)

    def line_time(self, k, j):
        return self.field_start(k) + self.offset((self.vblank + j) * (self.width + self.hblank))

    def field_ms(self):
        return float(self.period * 1000)

    def photon(self, k, written):
        """The middle of the lit interval of a pixel of field k written at `written`."""
        p = self.persistence
        if p is None:
            return written
        response = ticks_of_ms(p.get("response_ms", 0))
        if p["type"] == "full":
            frames = 2 if self.interlaced else 1
            hold = self.field_start(k + frames) - self.field_start(k)
            return written + response // 2 + hold // 2
        lit = ticks_of_ms(p["lit_ms"])
        if p["type"] == "rolling":
            return written + response + lit // 2
        return self.field_start(k + 1) + response + lit // 2


def read_csv(path):
    with open(path) as f:
        return [{k: int(v) for k, v in row.items()} for row in csv.DictReader(f)]


def ms(ticks):
    return ticks * 1e-9


def close(a, b, rel=1e-9, abs_=1e-9):
    return abs(a - b) <= max(abs_, rel * max(abs(a), abs(b)))


def compare_dist(scenario, name, figures, values):
    if name not in figures:
        return
    got = figures[name]
    if got["count"] != len(values):
        fail(scenario, f"{name}: count {got['count']}, ledger gives {len(values)}")
        return
    if not values:
        return
    mean = math.fsum(values) / len(values)
    for key, want in (("min", min(values)), ("max", max(values)), ("mean", mean)):
        if not close(got[key], want, rel=1e-7):
            fail(scenario, f"{name}.{key}: {got[key]!r}, ledger gives {want!r}")


class Newest:
    """The newest sample the host can see at a time, from tracker.csv."""

    def __init__(self, rows):
        # Visibility never decreases in link order.
        self.visible = [r["visible_ps"] for r in rows]
        self.rows = rows

    def at(self, t):
        i = bisect.bisect_right(self.visible, t)
        return self.rows[i - 1] if i > 0 else None


def span_latencies(scenario, raster, fields, newest):
    """Per lit line: (motion-to-photon, rotation, translation, display) in ms, and image ages."""
    mtp, rot, trans, disp, age = [], [], [], [], []
    for row in fields:
        if row["first_x"] != 0 or row["last_x"] != 0:
            fail(scenario, "pixel-level ledger rows are not checked here")
            return None
        k = row["field"]
        if raster.field_start(k) != row["retrace_ps"]:
            fail(scenario, f"field {k}: retrace {row['retrace_ps']} but the raster gives {raster.field_start(k)}")
        start = raster.line_time(k, 0)
        for j in range(row["first_line"], row["last_line"] + 1):
            written = raster.line_time(k, j)
            photon = raster.photon(k, written)
            position = row["measured_ps"]
            orientation = row["orientation_measured_ps"]
            if row["orientation_at_scanout"]:
                s = newest.at(written)
                if s is not None:
                    orientation = s["measured_ps"]
            origin = min(orientation, position)
            mtp.append(ms(photon - origin))
            rot.append(ms(photon - orientation))
            trans.append(ms(photon - position))
            disp.append(ms(photon - start))
            if j == 0:
                age.append(ms(photon - origin))
    return mtp, rot, trans, disp, age


def check_images(scenario, raster, figures, frames, fields, duration_s):
    first = {}
    for row in fields:
        key = row["image"]
        if key not in first:
            first[key] = row
    if len(first) != len(frames):
        fail(scenario, f"{len(frames)} images in frames.csv, {len(first)} first shown in fields.csv")
        return
    render, render_fields, to_render = [], [], []
    for frame in frames:
        shown = first.get(frame["image"])
        if shown is None:
            fail(scenario, f"image {frame['image']} is in frames.csv but never in fields.csv")
            return
        written = raster.line_time(shown["field"], shown["first_line"])
        render.append(ms(written - frame["render_start_ps"]))
        render_fields.append(ms(written - frame["render_start_ps"]) / raster.field_ms())
        to_render.append(ms(frame["render_start_ps"] - frame["measured_ps"]))
    compare_dist(scenario, "render_latency_ms", figures, render)
    compare_dist(scenario, "render_latency_fields", figures, render_fields)
    compare_dist(scenario, "tracker_to_render_ms", figures, to_render)
    if "frame_rate_hz" in figures:
        # A later strip of a refresh's image is not another image.
        want = sum(1 for f in frames if f["eye"] == 0 and not f["continues_image"]) / duration_s
        if not close(figures["frame_rate_hz"], want):
            fail(scenario, f"frame_rate_hz {figures['frame_rate_hz']}, ledger gives {want}")


def check_missed(scenario, raster, figures, frames, fields, pipeline, duration_ticks):
    """double_buffer with vsync: every refresh after the first render began that shows no new image."""
    if "missed_refreshes" not in figures or pipeline.get("type") != "double_buffer" or not frames:
        return
    first_render = min(f["render_start_ps"] for f in frames)
    new_fields = {}
    for row in fields:
        if row["eye"] == 0:
            new_fields.setdefault(row["image"], row["field"])
    shown_in = set(new_fields.values())
    # A last field whose first line would be lit after the run shows nothing and is not judged.
    missed = sum(1 for k in range(figures["fields"])
                 if raster.field_start(k) > first_render and k not in shown_in
                 and raster.line_time(k, 0) <= duration_ticks)
    if figures["missed_refreshes"] != missed:
        fail(scenario, f"missed_refreshes {figures['missed_refreshes']}, ledger gives {missed}")


def check_prediction(scenario, scen, raster, figures, frames, fields, newest):
    """prediction_horizon_ms: per image of eye 0, and per field's middle line where the orientation is looked up."""
    if "prediction_horizon_ms" not in figures:
        return
    if scen["pipeline"]["type"] == "frameless":
        return  # per sampled pixel: not in the ledger
    fixed = scen["host"]["prediction"].get("horizon_ms")
    # A rotation warp predicts its orientation from its own sample (fields.csv's orientation_measured_ps).
    orientation = {row["image"]: row["orientation_measured_ps"] for row in fields if row["orientation_measured_ps"] >= 0}
    horizons = [ms(f["predicted_for_ps"] - orientation.get(f["image"], f["measured_ps"])) for f in frames if f["eye"] == 0]
    middle = raster.lines // 2
    for row in fields:
        if row["eye"] != 0 or not row["orientation_at_scanout"] or not row["first_line"] <= middle <= row["last_line"]:
            continue
        written = raster.line_time(row["field"], middle)
        s = newest.at(written)
        if s is None:
            continue
        # The newest sample predicted to the middle line's photon time (or its fixed horizon).
        target = s["measured_ps"] + ticks_of_ms(fixed) if fixed is not None else raster.photon(row["field"], written)
        horizons.append(ms(target - s["measured_ps"]))
    compare_dist(scenario, "prediction_horizon_ms", figures, horizons)


def check_link(scenario, scen, figures, tracker_rows, duration_s):
    compare_dist(scenario, "tracker_to_host_ms", figures, [ms(r["visible_ps"] - r["measured_ps"]) for r in tracker_rows])
    transport = scen.get("transport", {})
    if transport.get("type") != "serial":
        return
    compare_dist(scenario, "line_wait_ms", figures, [ms(r["start_ps"] - r["ready_ps"]) for r in tracker_rows])
    bits = transport["record_bytes"] * transport["bits_per_byte"]
    transmit = round(Fraction(bits) / Fraction(transport["baud"]).limit_denominator(10**6) * TICKS)
    offered = figures["tracker_samples"]
    want = offered * transmit * 1e-12 / duration_s
    if not close(figures["line_utilisation"], want, rel=1e-6):
        fail(scenario, f"line_utilisation {figures['line_utilisation']}, ledger gives {want}")
    unsent = offered - len(tracker_rows) - figures["records_dropped"]
    if not 0 <= unsent <= transport["buffer_records"]:
        fail(scenario, f"{offered} samples, {len(tracker_rows)} sent, {figures['records_dropped']} dropped: "
                       f"{unsent} cannot be waiting in a buffer of {transport['buffer_records']}")


def check_counts(scenario, scen, raster, figures, duration_ticks):
    fields = 0
    while raster.field_start(fields) < duration_ticks:
        fields += 1
    if figures["fields"] != fields:
        fail(scenario, f"fields {figures['fields']}, the raster gives {fields}")
    t = scen["tracker"]
    if t.get("jitter_ms", 0) == 0:
        period = rate_period(t["rate_hz"], t.get("rate_error_ppm", 0))
        phase = ticks_of_ms(t["phase_ms"])
        # An IMU chain's samples are its reports: every report_every readings.
        step = t.get("imu", {}).get("report_every", 1)
        samples = 0
        while phase + math.floor(samples * step * period * TICKS) < duration_ticks:
            samples += 1
        if figures["tracker_samples"] != samples:
            fail(scenario, f"tracker_samples {figures['tracker_samples']}, the tracker's clock gives {samples}")


def check_scenario(latsim, source, work, path):
    name = os.path.relpath(path, source)
    out = os.path.join(work, name.replace("/", "_").removesuffix(".json"))
    shutil.rmtree(out, ignore_errors=True)
    proc = subprocess.run([latsim, "run", path, "--out", out, "--set", "/duration_s=2", "--ledger", "-q"],
                          capture_output=True, text=True)
    if proc.returncode != 0:
        fail(name, f"run failed ({proc.returncode}): {proc.stderr.strip()}")
        return
    doc = json.load(open(os.path.join(out, "figures.json")))
    figures, scen = doc["figures"], doc["scenario"]
    duration_s = scen["duration_s"]
    duration_ticks = round(Fraction(duration_s) * TICKS)
    raster = Raster(scen["display"])
    frames = read_csv(os.path.join(out, "frames.csv"))
    fields = read_csv(os.path.join(out, "fields.csv"))
    tracker_rows = read_csv(os.path.join(out, "tracker.csv"))
    newest = Newest(tracker_rows)
    spans = span_latencies(name, raster, fields, newest)
    if spans is None:
        return
    mtp, rot, trans, disp, age = spans
    if scen["pipeline"]["type"] == "frameless" and scen["pipeline"].get("strategy", "frameless") == "frameless":
        # Each sampled pixel is computed wholly from one sample: one latency under four names.
        for other in ("rotation_latency_ms", "translation_latency_ms", "pixel_age_ms"):
            for key in ("count", "min", "max", "mean"):
                if figures[other][key] != figures["motion_to_photon_ms"][key]:
                    fail(name, f"{other}.{key} differs from motion_to_photon_ms.{key} for whole-pixel samples")
        if fields:
            fail(name, "frameless rendering shows no whole images, yet fields.csv has rows")
    else:
        compare_dist(name, "motion_to_photon_ms", figures, mtp)
        compare_dist(name, "rotation_latency_ms", figures, rot)
        compare_dist(name, "translation_latency_ms", figures, trans)
        compare_dist(name, "display_ms", figures, disp)
        compare_dist(name, "image_age_ms", figures, age)
    check_images(name, raster, figures, frames, fields, duration_s)
    check_missed(name, raster, figures, frames, fields, scen["pipeline"], duration_ticks)
    check_prediction(name, scen, raster, figures, frames, fields, newest)
    check_link(name, scen, figures, tracker_rows, duration_s)
    check_counts(name, scen, raster, figures, duration_ticks)
    return figures


def is_sweep(path):
    """A sweep file (a base and axes) is not a scenario, wherever it lives."""
    with open(path) as f:
        return '"axes":' in f.read()


def documented(source):
    text = open(os.path.join(source, "docs", "figures.md")).read()
    return set(re.findall(r"^### (\w+)$", text, re.M))


def main():
    latsim, source, work = sys.argv[1:4]
    os.makedirs(work, exist_ok=True)
    paths = sys.argv[4:] or sorted(
        os.path.join(root, f)
        for root, _, files in os.walk(os.path.join(source, "scenarios"))
        for f in files
        if f.endswith(".json") and "/sweeps" not in root and f != "base.json"
        and not is_sweep(os.path.join(root, f)))
    glossary = documented(source)
    for path in paths:
        figures = check_scenario(latsim, source, work, path)
        if figures is None:
            continue
        # A figure under a glossary-like name that the glossary does not define is a new meaning.
        for key in figures:
            if key.endswith(("_latency_ms", "_age_ms")) and key not in glossary and not key.startswith(
                    "translation_latency_memory"):
                fail(path, f"figure {key} looks like a glossary figure but docs/figures.md does not define it")
    if FAILURES:
        print("\n".join(FAILURES))
        print(f"FAIL: {len(FAILURES)} problem(s)")
        sys.exit(1)
    print(f"ok: {len(paths)} scenarios obey docs/figures.md")


if __name__ == "__main__":
    main()
