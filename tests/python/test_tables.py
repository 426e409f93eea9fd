"""The Python tables (issue "tables first"): tidy sweep and run tables against
results.csv and figures.json, latsim.load of every kind of directory, the
95 % interval helper against a hand computation, Result.presentmon and
latsim.compare against the command's own files, repr against `latsim run`'s
headline lines, the ledger's -1 sentinel read as no value, and a figure
chosen by its path in a sweep file.

Usage: test_tables.py LATSIM SOURCE_DIR SCRATCH_DIR   (PYTHONPATH holds the module)
"""
import json
import math
import os
import shutil
import sys

import pandas

import latsim

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import module_checks  # noqa: E402
from module_checks import check  # noqa: E402

LATSIM, SOURCE, SCRATCH = sys.argv[1:4]
shutil.rmtree(SCRATCH, ignore_errors=True)
os.makedirs(SCRATCH)


def cli(*args):
    return module_checks.cli(LATSIM, *args, cwd=SOURCE)


# --- 1. The interval helper against a hand computation -----------------------
# Three replications 10, 12, 14: mean 12; sample variance ((-2)^2 + 0 + 2^2) / 2 = 4,
# s = 2; Student t with 2 degrees of freedom at 97.5 % is 4.303 (any table);
# half width 4.303 * 2 / sqrt(3) = 4.96867...
hand = pandas.DataFrame({"/x": [1, 1, 1, 2, 2], "m": [10.0, 12.0, 14.0, 5.0, 7.0]})
ci = latsim.mean_ci(hand, "m", by="/x")
check(list(ci.index) == [1, 2] and list(ci["n"]) == [3, 2], f"groups and their sizes: {ci}")
check(ci.loc[1, "mean"] == 12.0, "mean of 10, 12, 14")
check(abs(ci.loc[1, "half_width"] - 4.303 * 2 / math.sqrt(3)) < 1e-9, f"t-interval half width {ci.loc[1, 'half_width']}")
check(abs(ci.loc[1, "low"] - (12 - 4.303 * 2 / math.sqrt(3))) < 1e-9, "low end")
# Two values 5, 7: s = sqrt(2), t(1) = 12.706, half width 12.706 * sqrt(2) / sqrt(2) = 12.706.
check(abs(ci.loc[2, "half_width"] - 12.706) < 1e-9, f"two replications: {ci.loc[2, 'half_width']}")

# --- 2. A sweep with an object-valued axis, as a tidy table ------------------
base = os.path.join(SOURCE, "scenarios", "hmd_60hz_direct.json")
sweep_doc = {
    "base": base, "mode": "zip", "replications": 3,
    "overrides": {"/duration_s": 0.5, "/host/prediction": {"type": "none"}},
    "axes": [{"pointer": "/display/refresh_hz", "values": [60, 120]},
             {"pointer": "/host/prediction", "values": [{"type": "none"}, {"type": "constant_velocity"}]}],
}
out = os.path.join(SCRATCH, "sweep")
table = latsim.sweep(sweep_doc, jobs=2, out=out)
check(len(table) == 6, f"one row per run: {len(table)}")
check(list(table.columns[:6]) == ["run_id", "point", "/display/refresh_hz", "/host/prediction", "seed", "replication"],
      f"leading columns {list(table.columns[:6])}")
check(table["/display/refresh_hz"].dtype.kind == "i", "a numeric axis is a numeric column")
check(all("{" not in str(v) for v in table["/host/prediction"]), f"object values by label: {set(table['/host/prediction'])}")
check(table["/host/prediction"].nunique() == 2, "two labels for two objects")
for name in ("motion_to_photon_ms.mean", "motion_to_photon_ms.p50", "motion_to_photon_ms.p99", "frame_rate_hz",
             "counts.fields", "events", "wall_s"):
    check(name in table.columns, f"column {name}")
check(table.columns.get_loc("motion_to_photon_ms.mean") < table.columns.get_loc("motion_to_photon_ms.p99"),
      "a distribution's statistics in figures.json's order")
# Every results.csv column the registry gives is the same number in the tidy table.
csv = pandas.read_csv(os.path.join(out, "results.csv"), float_precision="round_trip")
registry = json.load(open(os.path.join(SOURCE, "results", "figure_registry.json")))
columns = [c for f in registry["figures"] for c in f.get("columns", []) if c["name"] not in ("wall_s",)]
compared = 0
for c in columns:
    if c["name"] in csv.columns and c["figure"] in table.columns:
        a, b = csv[c["name"]].tolist(), table[c["figure"]].tolist()
        check(all((x == y) or (x != x and y != y) for x, y in zip(a, b)), f"{c['figure']} is results.csv's {c['name']}")
        compared += 1
check(compared >= 8, f"results.csv columns compared: {compared}")
# Each run's row holds its figures.json figures (a kept run's summary, here through the results store).
check(latsim.load(out).drop(columns=["wall_s"]).equals(table.drop(columns=["wall_s"])), "latsim.load(sweep dir)")
# The interval helper on the sweep: three replications a point, grouped by the axes by default.
ci = latsim.mean_ci(table)
check(len(ci) == 2 and list(ci["n"]) == [3, 3], f"mean_ci per point: {ci}")
point0 = table[table["point"] == 0]["motion_to_photon_ms.mean"].tolist()
m = sum(point0) / 3
s = math.sqrt(sum((v - m) ** 2 for v in point0) / 2)
check(abs(ci["mean"].iloc[0] - m) < 1e-12 and abs(ci["half_width"].iloc[0] - 4.303 * s / math.sqrt(3)) < 1e-9,
      "the sweep's interval by hand")

# --- 3. One run: its table, repr, per-frame tables, presentmon ---------------
run_dir = os.path.join(SCRATCH, "run")
proc = cli("run", "scenarios/modern/timewarp_overload_144hz.json", "--set", "/duration_s=1", "--out", run_dir, "--ledger")
check(proc.returncode == 0, f"latsim run: {proc.stderr.strip()}")
headline_lines = [line for line in proc.stdout.splitlines()[1:] if not line.startswith("  events ")]
r = latsim.run(os.path.join(SOURCE, "scenarios", "modern", "timewarp_overload_144hz.json"), set={"/duration_s": 1},
               ledger=True, presentmon=True)
shown = repr(r).rstrip(">").splitlines()[1:]
check(shown == headline_lines, f"repr shows the command line's headline:\n{shown}\n{headline_lines}")
check(shown[0].startswith("  rotation_latency_ms:"), "behind a time warp rotation latency leads, as on the command line")
one = r.table
check(len(one) == 1 and one["motion_to_photon_ms.mean"][0] == r.figures["motion_to_photon_ms"]["mean"],
      "Result.table: one row of the figures")
check(one["frames_missed"][0] == r.figures["frames_missed"], "frames_missed is a column")
check(one["application_frame_rate_hz"][0] == r.figures["application_frame_rate_hz"], "so is application_frame_rate_hz")
loaded = latsim.load(run_dir)
check(loaded["frames_missed"][0] == one["frames_missed"][0] and loaded["run"][0] == "run", "latsim.load(run dir)")
expected_pm = pandas.read_csv(os.path.join(run_dir, "presentmon.csv"))
check(r.presentmon.equals(expected_pm), "Result.presentmon is the presentmon.csv latsim run writes")
files = latsim.load_run(run_dir)
check(files.frames.equals(r.frames), "load_run: frames.csv as the run's frames table")
check(files.presentmon.equals(expected_pm), "load_run: presentmon.csv")

# --- 4. The -1 sentinel of fields.csv is no value ----------------------------
gallery = latsim.run(os.path.join(SOURCE, "scenarios", "arp", "gallery.json"), set={"/duration_s": 0.3}, ledger=True)
fields = gallery.fields
at_scanout = fields["orientation_at_scanout"] == 1
check(at_scanout.any(), "gallery looks its orientation up at scanout")
check(fields.loc[at_scanout, "orientation_measured_ps"].isna().all(), "no time where the orientation is looked up")
check(not (fields["orientation_measured_ps"].dropna() < 0).any(), "no negative time left")
raw = pandas.read_csv(os.path.join(run_dir, "fields.csv"))
check(files.fields.drop(columns=["orientation_measured_ps"]).equals(raw.drop(columns=["orientation_measured_ps"])),
      "other columns as written")

# --- 5. latsim.compare is the command's table --------------------------------
proc = cli("compare", os.path.join(run_dir, "presentmon.csv"), run_dir, "--no-plots", "--out",
           os.path.join(SCRATCH, "compare"))
check(proc.returncode == 0, f"latsim compare: {proc.stderr.strip()}")
expected = pandas.read_csv(os.path.join(SCRATCH, "compare", "compare.csv"), keep_default_na=False, na_values=[""])
got = latsim.compare(os.path.join(run_dir, "presentmon.csv"), run_dir)
check(got.equals(expected), f"latsim.compare is compare.csv:\n{got}\n{expected}")
try:
    latsim.compare(os.path.join(SCRATCH, "no_such.csv"), run_dir)
    check(False, "a missing capture was compared")
except ValueError as e:
    check(str(e).startswith("compare: "), f"a missing capture: {e}")

# --- 6. Any figure by its path in a sweep file's "figures" --------------------
warp = {"base": os.path.join(SOURCE, "scenarios", "modern", "timewarp_overload_144hz.json"),
        "overrides": {"/duration_s": 0.5}, "axes": [],
        "figures": ["frames_missed", "application_frame_rate_hz", "mtp_mean_ms", "display_ms.p99"]}
chosen_out = os.path.join(SCRATCH, "chosen")
chosen = latsim.sweep(warp, jobs=1, out=chosen_out)
header = open(os.path.join(chosen_out, "results.csv")).readline().strip().split(",")
for name in ("frames_missed", "application_frame_rate_hz", "display_ms.p99"):
    check(name in header, f"results.csv has the chosen {name}")
check(pandas.read_csv(os.path.join(chosen_out, "results.csv"))["frames_missed"][0] == chosen["frames_missed"][0],
      "results.csv's frames_missed is the table's")
try:
    latsim.sweep(dict(warp, figures=["frames_missed", "no_such_figure"]))
    check(False, "an unknown figure was chosen")
except latsim.ScenarioError as e:
    text = str(e)
    check(e.pointer == "/figures/1", f"pointer of the refused figure: {e.pointer}")
    listed = text.split("expected one of ", 1)[1]
    check(" more" in listed and len(text) <= 400, f"a long list is cut, within one line: {text}")
    names = [n.strip().strip('"') for n in listed.split(", \u2026")[0].split(", ")]
    check(all(n in header or "." in n or n.isidentifier() for n in names), f"whole names: {names}")
    check(listed.split(", \u2026")[0].endswith('"'), f"the list ends at a whole name: {listed}")

module_checks.finish("ok: tidy tables, intervals, presentmon, compare, repr and chosen figures")
