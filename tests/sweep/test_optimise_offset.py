#!/usr/bin/env python3
"""latsim optimise finds the render start offset of a 90 Hz frame_stages design.

The design (written here, not read from a shipped file): a 90 Hz display with
no persistence, a CPU stage I of 1 ms that starts `offset_ms` after a retrace
and reads the pose, then a GPU stage G of 6 ms; the image is shown at the first
retrace after G ends (vsync, no compositor).

Hand derivation. The period is T = 1000/90 = 11.111 ms. A frame started at
retrace k + o completes at o + 7 ms. While o + 7 <= T it is shown at retrace
k + 1, so its motion-to-photon is (T - o) + d, where d (the time from the
retrace to the photons, plus the tracker sample's age) does not depend on o
to within the tracker's period: the tracker samples at 1 MHz, so a sample is at
most 1 us old (at 1 kHz the age would step by up to 1 ms as o moves, and the
figure would have plateaus wider than the tolerance). The figure falls with o. Beyond o = T - 7 = 4.111 ms the frame misses its
retrace. So the best offset with no missed frame is o* = T - 7 ms, and there
motion-to-photon is 7 ms + d, T - o* less than at o = 0 (the retrace start of
today): mtp(0) - mtp(o*) = 4.111 ms.

The optimiser's tolerance is 0.01 ms, so |o - o*| <= 0.01 ms, and the gain
within 0.01 ms of 4.111 ms.
"""
import json
import os
import subprocess
import sys
import tempfile

latsim, work = sys.argv[1], sys.argv[2]
os.makedirs(work, exist_ok=True)

T_ms = 1000.0 / 90.0
work_ms = 1.0 + 6.0
best_expected = T_ms - work_ms          # 4.1111 ms
tolerance = 0.01

scenario = {
    "description": "90 Hz, vsync, CPU 1 ms then GPU 6 ms; the CPU stage starts offset_ms after each retrace",
    "duration_s": 1,
    "seed": 1,
    "motion": {"type": "constant", "axis": [0, 1, 0], "rate_deg_s": 120, "position_m": [0, 1.6, 0]},
    "tracker": {"rate_hz": 1000000, "phase_ms": 0, "internal_delay_ms": 0},
    "transport": {"type": "direct"},
    "display": {"refresh_hz": 90, "width_px": 1080, "height_px": 1200, "vblank_lines": 40, "hblank_px": 0,
                "hfov_deg": 100, "scanout": "line"},
    "pipeline": {
        "type": "frame_stages",
        "processors": [{"name": "cpu"}, {"name": "gpu"}],
        "stages": [
            {"name": "I", "on": "cpu", "start": "retrace", "offset_ms": 0, "samples_pose": True,
             "cost": {"fixed_ms": 1}},
            {"name": "G", "on": "gpu", "cost": {"fixed_ms": 6}},
        ],
    },
}

with tempfile.TemporaryDirectory(dir=work) as tmp:
    path = os.path.join(tmp, "offset_90hz.json")
    with open(path, "w") as f:
        json.dump(scenario, f)
    out = os.path.join(tmp, "opt")
    r = subprocess.run([latsim, "optimise", path, "--vary", "/pipeline/stages/0/offset_ms=0:10",
                        "--minimise", "motion_to_photon_ms", "--constraint", "frames_missed<=0",
                        "--tolerance", str(tolerance), "--out", out],
                       capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"optimise failed ({r.returncode}): {r.stderr}")
    with open(os.path.join(out, "optimise.json")) as f:
        result = json.load(f)

    best = result["best"]
    o = best["value"] if "value" in best else best["x"]
    assert abs(o - best_expected) <= tolerance + 1e-9, f"best offset {o} ms, expected {best_expected:.4f} ms"

    # The gain against the retrace start (offset 0), from the trials.
    def mtp(trial):
        fig = trial["figures"]["motion_to_photon_ms"]
        return fig["mean"] if isinstance(fig, dict) else fig

    at_zero = [t for t in result["tried"] if abs((t["value"] if "value" in t else t["x"])) < 1e-12]
    assert at_zero, "the lower end was not tried"
    gain = mtp(at_zero[0]) - mtp(best)
    assert abs(gain - best_expected) <= tolerance + 0.005, f"gain {gain} ms, expected {best_expected:.4f} ms"
    print(f"best offset {o:.4f} ms (derived {best_expected:.4f}), gain {gain:.4f} ms")
