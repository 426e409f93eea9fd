#!/usr/bin/env python3
"""What the published fly-through figures say about Rendering Control's frames.

A reading of the published table (SPEC.md section 4), not a run of latsim
(docs/pxpl5.md, "What could spread a small model's latency"). Under the
start conditions of SPEC.md section 4, with COPY the bottleneck (31.2 ms a
stereo frame, the minimum case), the left eye's TRANSFORM of frame i starts
0.2 ms (EDIT) after COPY of frame i - 2's right eye ends, and frame i swaps at
the first allowed retrace after its own COPY, which starts at frame i - 1's
swap. Suppose that in a fraction p of frames, independently, something ends
the frame's COPY later by 2.13 ms (the slack before the retrace) plus a
uniform part of one allowed swap interval, so that the frame misses its
retrace. This finds the p that gives each published mean and the spread
that p then gives, for swaps at any field and at a frame's start only.

usage: pxpl5_slip_model.py
"""
import math
import random
import statistics

FIELD_MS = 1000.0 / 60.0
COPY_MS = 40 * 0.78          # both eyes' 20 regions at 780 us
SLACK_MS = 2 * FIELD_MS - COPY_MS
EDIT_MS = 0.2
PUBLISHED = {"Mig": (4.61, 0.589), "Molecules": (4.47, 0.502)}


def latency(p, frame_start, frames=200_000, seed=1):
    """Mean and standard deviation of the left eye's TRANSFORM start to swap, in fields."""
    rng = random.Random(seed)
    step = 2 if frame_start else 1
    swap, copy_end, fields = 0.0, [], []
    for i in range(frames):
        late = SLACK_MS + rng.uniform(0.0, step * FIELD_MS) if rng.random() < p else 0.0
        end = swap + COPY_MS + late
        k = math.floor(end / FIELD_MS + 1e-9) + 1
        if frame_start and k % 2:
            k += 1
        swap = k * FIELD_MS
        copy_end.append(end)
        if i >= 2:
            fields.append((swap - copy_end[i - 2] - EDIT_MS) / FIELD_MS)
    return statistics.mean(fields), statistics.pstdev(fields)


def fraction_for(mean, frame_start):
    """The fraction of late frames whose mean latency is `mean` (bisection)."""
    lo, hi = 0.0, 0.6
    for _ in range(30):
        mid = (lo + hi) / 2
        if latency(mid, frame_start, frames=60_000)[0] < mean:
            lo = mid
        else:
            hi = mid
    return (lo + hi) / 2


def main():
    print(f"no late frames: {latency(0.0, False)[0]:.3f} fields (the minimum case's left eye)")
    for swaps, frame_start in (("any field", False), ("frame start", True)):
        for model, (mean, sd) in PUBLISHED.items():
            p = fraction_for(mean, frame_start)
            m, s = latency(p, frame_start)
            print(f"{swaps:11s} {model:9s}: p = {p:.2f}, mean {m:.2f}, sd {s:.2f} (published {mean} / {sd})")


if __name__ == "__main__":
    main()
