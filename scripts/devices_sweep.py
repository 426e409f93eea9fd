#!/usr/bin/env python3
"""Writes scenarios/devices/devices_sweep.json and workloads_sweep.json from the device files.

The devices sweep runs every device profile side by side (zip mode): the
i-th value of each axis is the i-th device file's own section, its includes
merged as the scenario reader merges them, so that each point of the sweep
is exactly that file (tests/scenarios/devices/test_devices.py checks it). Run it after
adding or changing a device file:

    python3 scripts/devices_sweep.py            # rewrites the sweep
    python3 scripts/devices_sweep.py --check    # exit 1 if the sweep is stale
"""

import json
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEVICES = os.path.join(ROOT, "scenarios", "devices")
SWEEP = os.path.join(DEVICES, "devices_sweep.json")
WORKLOADS = os.path.join(DEVICES, "workloads_sweep.json")
# The heavy workload: the game thread, the render thread and the GPU each busy
# for this share of a refresh period; the light one is the engine's
# (engine/base.json), whichever application the profile runs.
HEAVY_SHARES = (0.7, 0.5, 0.8)
LIGHT = os.path.join(DEVICES, "engine", "base.json")

# (file, label) in table order.
PROFILES = [
    ("index_80hz.json", "Valve Index 80 Hz"),
    ("index_90hz.json", "Valve Index 90 Hz"),
    ("index_120hz.json", "Valve Index 120 Hz"),
    ("index_144hz.json", "Valve Index 144 Hz"),
    ("index_144hz_monado.json", "Valve Index 144 Hz (Monado)"),
    ("vive_90hz.json", "HTC Vive 90 Hz"),
    ("vive_pro2_90hz.json", "HTC Vive Pro 2 90 Hz"),
    ("vive_pro2_120hz.json", "HTC Vive Pro 2 120 Hz"),
    ("beyond_75hz.json", "Bigscreen Beyond 75 Hz"),
    ("beyond_90hz.json", "Bigscreen Beyond 90 Hz"),
    ("psvr2_120hz.json", "PlayStation VR2 120 Hz"),
    ("rift_cv1_90hz.json", "Oculus Rift CV1 90 Hz"),
    ("rift_s_80hz.json", "Oculus Rift S 80 Hz"),
    ("quest2_72hz.json", "Quest 2 72 Hz"),
    ("quest2_90hz.json", "Quest 2 90 Hz"),
    ("quest2_120hz.json", "Quest 2 120 Hz"),
    ("quest3_72hz.json", "Quest 3 72 Hz"),
    ("quest3_90hz.json", "Quest 3 90 Hz"),
    ("quest3_120hz.json", "Quest 3 120 Hz"),
]
# The sections a device file sets; everything else is the rig's, the same for all.
SECTIONS = ["/display", "/tracker", "/transport", "/pipeline", "/controller", "/measurement"]
REPLICATIONS = 8


def merge(base, over):
    """As the scenario reader merges includes: objects key by key, an object whose type changes replaces."""
    for key, value in over.items():
        if key in base and isinstance(base[key], dict) and isinstance(value, dict) and \
                value.get("type", base[key].get("type")) == base[key].get("type"):
            merge(base[key], value)
        else:
            base[key] = value


def load(path):
    doc = json.load(open(path, encoding="utf-8"))
    include = doc.pop("include", None)
    if include is None:
        return doc
    merged = {}
    for name in include if isinstance(include, list) else [include]:
        merge(merged, load(os.path.join(os.path.dirname(path), name)))
    merge(merged, doc)
    return merged


def sweep():
    docs = [load(os.path.join(DEVICES, f)) for f, _ in PROFILES]
    axes = [{"pointer": "/description", "values": [label for _, label in PROFILES]}]
    for pointer in SECTIONS:
        axes.append({"pointer": pointer, "values": [d[pointer[1:]] for d in docs]})
    return {
        "description": "Every device profile of scenarios/devices/ side by side, in zip mode (a /description label axis "
                       "beside the whole sections each device file sets; written by scripts/devices_sweep.py, checked "
                       "by tests/scenarios/devices): latsim report writes the devices table of docs/devices.md and "
                       "docs/validation.md, each figure over " + str(REPLICATIONS) + " replications",
        "base": PROFILES[1][0],
        "mode": "zip",
        "replications": REPLICATIONS,
        "seed": 1,
        "axes": axes,
    }


def refresh_ms(doc):
    hz = doc["display"]["refresh_hz"]
    if isinstance(hz, str):
        num, den = (hz.split("/") + ["1"])[:2]
        hz = float(num) / float(den)
    return 1000.0 / float(hz)


def heavy(pipeline, period_ms):
    """The profile's pipeline with the heavy workload: each stage's cost a share of the period."""
    out = json.loads(json.dumps(pipeline))
    for stage, share in zip(out["stages"], HEAVY_SHARES):
        stage["cost"] = {"fixed_ms": round(share * period_ms, 4)}
    return out


def light(pipeline):
    """The profile's pipeline with the engine's light workload (engine/base.json's stage costs)."""
    out = json.loads(json.dumps(pipeline))
    for stage, engine_stage in zip(out["stages"], load(LIGHT)["pipeline"]["stages"]):
        stage["cost"] = dict(engine_stage["cost"])
    return out


def workloads():
    docs = [load(os.path.join(DEVICES, f)) for f, _ in PROFILES]
    labels, pipelines = [], []
    for (_, label), d in zip(PROFILES, docs):
        labels += [label + ", light", label + ", heavy"]
        pipelines += [light(d["pipeline"]), heavy(d["pipeline"], refresh_ms(d))]
    axes = [{"pointer": "/description", "values": labels}]
    for pointer in SECTIONS:
        key = pointer[1:]
        values = []
        for d in docs:
            values += [d[key], d[key]]
        axes.append({"pointer": pointer, "values": pipelines if key == "pipeline" else values})
    return {
        "description": "Every device profile with the engine's light workload (game thread 2 ms, render thread "
                       "1.5 ms, GPU 3 ms; the SteamVR and Monado profiles run VRChat's by default) and a heavy one (" +
                       ", ".join(f"{int(x * 100)} %" for x in HEAVY_SHARES) +
                       " of a refresh period on the game thread, the render thread and the GPU), side by side "
                       "(written by scripts/devices_sweep.py; docs/devices.md, 'Applications')",
        "base": PROFILES[1][0],
        "mode": "zip",
        "replications": 2,
        "seed": 1,
        "axes": axes,
    }


def main():
    files = [(SWEEP, sweep()), (WORKLOADS, workloads())]
    stale = []
    for path, doc in files:
        text = json.dumps(doc, indent=2, ensure_ascii=False) + "\n"
        if "--check" in sys.argv:
            if open(path, encoding="utf-8").read() != text:
                stale.append(os.path.basename(path))
            continue
        with open(path, "w", encoding="utf-8") as f:
            f.write(text)
        print(f"wrote {path}: {len(PROFILES)} devices")
    if stale:
        print(", ".join(stale) + " stale: run python3 scripts/devices_sweep.py")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
