#!/usr/bin/env python3
"""latsim optimise tries only settings the varied key accepts.

A frequency given as a number takes at most 6 decimals (scenario/src/config.cpp
refuses more: "give frequencies with at most 6 decimals"); golden-section
probes such as lo + 0.381966 (hi - lo) have many. Every setting tried must be
a whole number of micro-hertz inside [lo, hi], and the search must end (exit
0) rather than stop at its first probe (exit 2). An integer key takes whole
numbers. An interval that holds no step of the key is refused before any run,
exit 2, one line naming the option.
"""
import json
import os
import subprocess
import sys
import tempfile

latsim, source, work = sys.argv[1], sys.argv[2], sys.argv[3]
os.makedirs(work, exist_ok=True)
scenario = os.path.join(source, "scenarios", "hmd_60hz_direct.json")


def optimise(vary, out):
    return subprocess.run([latsim, "optimise", scenario, "--set", "/duration_s=0.5", "--vary", vary,
                           "--minimise", "motion_to_photon_ms", "--out", out], capture_output=True, text=True)


with tempfile.TemporaryDirectory(dir=work) as tmp:
    for vary, lo, hi, scale in (("/tracker/rate_hz=100.1:200.7", 100.1, 200.7, 10**6),
                                ("/scene/triangles=1000.5:20000.5", 1000.5, 20000.5, 1)):
        out = os.path.join(tmp, vary.split("=")[0].replace("/", "_"))
        r = optimise(vary, out)
        assert r.returncode == 0, f"{vary}: exit {r.returncode}: {r.stderr}"
        with open(os.path.join(out, "optimise.json")) as f:
            tried = [t["value"] for t in json.load(f)["tried"]]
        # The interval's golden-section probes: 2 first, one a step, the 2 ends.
        assert len(tried) >= 5, tried
        for v in tried:
            assert lo <= v <= hi, f"{vary}: {v} outside [{lo}, {hi}]"
            # The key's own test (config.cpp): |hz x 1e6 - its nearest integer| <= 1e-3.
            assert abs(v * scale - round(v * scale)) <= 1e-3, f"{vary}: {v} is not a whole number of steps of 1/{scale}"
        print(f"{vary}: {len(tried)} settings, each a whole number of 1/{scale}")

    r = optimise("/tracker/rate_hz=100.0000001:100.0000004", os.path.join(tmp, "none"))
    assert r.returncode == 2, f"exit {r.returncode}: {r.stderr}"
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and "--vary" in lines[0] and "1e-6" in lines[0], r.stderr
    assert not os.path.exists(os.path.join(tmp, "none")), "refused, yet wrote its directory"
    print("an interval without a micro-hertz step: refused, one line")
