"""Every shipped scenario validates against `latsim schema --format
json-schema` with an off-the-shelf JSON Schema validator: each file as
written (a file that includes a base may leave required sections to it), and
each scenario as it runs, every default applied (`latsim validate --resolved`).
The sweep files' base scenarios are shipped scenarios, so they are covered.

Usage: validate_scenarios.py LATSIM SOURCE_DIR
"""

import glob
import json
import os
import subprocess
import sys

import jsonschema

LATSIM, SOURCE = sys.argv[1], sys.argv[2]

schema = json.loads(subprocess.run([LATSIM, "schema", "--format", "json-schema"], check=True,
                                   capture_output=True, text=True).stdout)
validator_class = jsonschema.validators.validator_for(schema)
validator_class.check_schema(schema)
validator = validator_class(schema)



def is_sweep(path):
    """A sweep file (a base scenario and axes) is not a scenario, wherever it lives."""
    with open(path) as fh:
        return "axes" in json.load(fh)


# base.json files are only halves of scenarios: they are checked through the files that include them.
files = sorted(f for f in glob.glob(os.path.join(SOURCE, "scenarios", "**", "*.json"), recursive=True)
               if "/sweeps/" not in f and not f.endswith("/base.json") and not is_sweep(f))
failures = 0
for f in files:
    with open(f) as fh:
        raw = json.load(fh)
    resolved = json.loads(subprocess.run([LATSIM, "validate", "--resolved", f], check=True, capture_output=True,
                                         text=True).stdout)
    for what, doc in (("as written", raw), ("resolved", resolved)):
        errors = sorted(validator.iter_errors(doc), key=lambda e: list(e.path))
        for e in errors:
            failures += 1
            print("FAIL %s (%s): /%s: %s" % (os.path.relpath(f, SOURCE), what, "/".join(map(str, e.path)), e.message))
    # A scenario that is wrong must fail the schema too: the check is not vacuous.
    broken = dict(resolved, display=dict(resolved["display"], width_px="wide"))
    if validator.is_valid(broken):
        failures += 1
        print("FAIL %s: a string width_px passed the schema" % f)

if failures:
    sys.exit(1)
print("ok: %d scenarios valid against the JSON Schema, as written and resolved" % len(files))
