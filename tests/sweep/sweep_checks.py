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


def write_report_fixture(root, axis, points, headline):
    """A sweep directory as latsim writes one, made by hand for a report test: `points` is a list of (axis
    value, [(summary, results.csv values by column) for each replication]); each run's summary.json under
    runs/<run id>/, and results.csv with the `headline` columns (values a run lacks left empty)."""
    import json
    rows = []
    for point, (value, replications) in enumerate(points):
        for rep, (summary, values) in enumerate(replications):
            run_id = f"{point:08x}{rep:08x}"
            run_dir = os.path.join(root, "runs", run_id)
            os.makedirs(run_dir)
            with open(os.path.join(run_dir, "summary.json"), "w") as f:
                json.dump(summary, f)
            rows.append([run_id, point, value, 1, rep] + [values.get(c, "") for c in headline])
    with open(os.path.join(root, "results.csv"), "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["run_id", "point", axis, "seed", "replication"] + headline)
        w.writerows(rows)
