"""One meaning per count: every count of something that did not go to plan
(missed, dropped, late, re-projected, synthesised, skipped, ...) has one name,
one meaning of its own in the figure registry, one glossary entry in
docs/figures.md that names every pipeline reporting it, and its own name as
its label wherever a table shows it; the names retired for a second meaning
(frames_reprojected, compositions_late) and labels that read one count as
another ("missed frames", "frames missed", "missed refreshes") appear in no
table.

Usage: test_count_glossary.py SOURCE_DIR
"""
import json
import os
import re
import sys

SOURCE = sys.argv[1]
failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
        print(f"FAIL: {what}")


registry = json.load(open(os.path.join(SOURCE, "results", "figure_registry.json"), encoding="utf-8"))
glossary = open(os.path.join(SOURCE, "docs", "figures.md"), encoding="utf-8").read()

# A count of something that did not go to plan: a word of its name says so.
WORDS = {"missed", "misses", "dropped", "late", "rewarped", "reprojected", "synthesised", "skipped", "superseded",
         "incomplete", "torn", "lost"}
counts = [f for f in registry["figures"]
          if f["kind"] == "count" and WORDS & set(re.split(r"[._<>]", f["name"]))]
names = [f["name"] for f in counts]
# The counts the issue names, and the time warp's, must be among them.
for name in ("missed_refreshes", "frames_missed", "frames_rewarped", "frames_synthesised", "warps_late",
             "frames_dropped", "frames_late", "missed_fields", "records_dropped", "renders_skipped"):
    check(name in names, f"{name} is a count of the glossary set")
check(len(counts) >= 15, f"counts found: {names}")


def entry(name):
    """The text of the glossary entry `### name` up to the next heading, or None."""
    m = re.search(r"^### " + re.escape(name) + r"\n(.*?)(?=^#)", glossary, re.S | re.M)
    return m.group(1) if m else None


for f in counts:
    text = entry(f["name"])
    check(text is not None, f"{f['name']}: no glossary entry (### {f['name']}) in docs/figures.md")
    if text is None or f["pipelines"] == "all":
        continue
    for pipeline in f["pipelines"]:
        check(re.search(r"\b" + re.escape(pipeline) + r"\b", text) is not None,
              f"{f['name']}: its glossary entry does not say what it counts in {pipeline}")

# One meaning per name: no two counts share a meaning, and no count's name is
# another's with its words in another order (frames_missed / missed_frames).
all_counts = [f for f in registry["figures"] if f["kind"] == "count"]
meanings = {}
for f in all_counts:
    check(f["meaning"] not in meanings, f"{f['name']} and {meanings.get(f['meaning'])} share a meaning")
    meanings[f["meaning"]] = f["name"]
by_words = {}
for f in all_counts:
    key = tuple(sorted(re.split(r"[._]", f["name"])))
    check(key not in by_words, f"{f['name']} and {by_words.get(key)}: one count's words, two names")
    by_words[key] = f["name"]
for retired in ("frames_reprojected", "compositions_late"):
    check(retired not in [f["name"] for f in registry["figures"]], f"{retired}: a second name for a counted meaning")

# In every table a count is headed by its name.
for f in counts:
    for column in f.get("columns", []):
        check(column["label"] == f["name"] and column["name"] == f["name"],
              f"{f['name']}: results.csv and report column {column['name']} labelled {column['label']!r}")
sys.path.insert(0, os.path.join(SOURCE, "analysis"))
import pacing_plot  # noqa: E402
for header, path in pacing_plot.COLUMNS:
    if path in names:
        check(header == path, f"the pacing table heads {path} {header!r}")
# No table text reads one count as another.
CONFUSING = re.compile(r"missed frames|frames missed|missed refreshes|refreshes missed|late to latch", re.I)
for file in sorted(os.listdir(os.path.join(SOURCE, "analysis"))):
    if file.endswith(".py"):
        for number, line in enumerate(open(os.path.join(SOURCE, "analysis", file), encoding="utf-8"), start=1):
            if CONFUSING.search(line):
                check(False, f"analysis/{file}:{number}: a count under another name: {line.strip()}")

if failures:
    print(f"{len(failures)} check(s) failed")
    sys.exit(1)
print(f"ok: {len(counts)} counts, one name, one meaning, one glossary entry each")
