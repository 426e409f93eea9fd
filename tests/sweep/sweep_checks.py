"""What the program-level sweep tests share: recorded checks and the tables they compare."""

import csv
import os
import sys

checked, failures = [], []


def check(condition, message):
    checked.append(message)
    if not condition:
        failures.append(message)
        print("FAILED:", message)


def finish(name):
    """Prints the count of checks and exits 1 if any failed."""
    print(f"{name}: {len(checked) - len(failures)} checks passed, {len(failures)} failed")
    sys.exit(1 if failures else 0)


def table(directory):
    """results.csv rows without wall_s, the one column that measures the machine rather than the model."""
    with open(os.path.join(directory, "results.csv"), newline="") as f:
        rows = list(csv.reader(f))
    drop = rows[0].index("wall_s")
    return [[c for i, c in enumerate(r) if i != drop] for r in rows]
