#!/usr/bin/env python3
"""Writes scenarios/pxpl5/data/flythrough.csv: the head path of the
fly-through model viewer of the Pixel-Planes 5 latency measurements (SPEC.md
section 4: the user walks and flies through a model, grabs it and scales it),
for a model 2 m across centred on the origin (scene `size_m` 2).

Grabbing, turning and scaling the model move the model, not the head; what
each eye sees depends only on where the eye is relative to the model, so the
path below is the eye's path in the model's own frame (a model scaled up by s
is seen as from 1/s of the distance). One lap of 60 s, then it loops:

  0-10 s   walk: straight at the model from 6 m to 2.5 m (0.35 m/s)
  10-30 s  fly round it once at 1.7 to 2.5 m, rising and sinking 0.6 m
  30-40 s  fly through it: in along a line passing 0.5 m from its centre, out
           the far side to 2.6 m, then turn back to face it
  40-50 s  grab it and turn it once round its vertical axis at arm's reach
           (1.5 m from its centre), tilting it +-20 degrees
  50-60 s  scale it up three times and let go: the distance falls from 1.5 m
           to 0.5 m, then the model shrinks back as the user steps away to 6 m

The head looks at the model's centre (during the fly-through: along the
flight, then back at the model) and looks round it all the time: +-15 degrees
of yaw at 0.23 Hz and +-8 degrees of pitch at 0.31 Hz. Samples every 20 ms,
t_s,px,py,pz,qw,qx,qy,qz (latsim's trace CSV); head frame x right, y up,
looking down -z. With --check it only compares the shipped file with what
it would write."""

import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "scenarios", "pxpl5", "data", "flythrough.csv")
LAP_S = 60.0
STEP_S = 0.02


def smooth(x):
    x = min(1.0, max(0.0, x))
    return x * x * (3.0 - 2.0 * x)


def lerp(a, b, s):
    return tuple(p + (q - p) * s for p, q in zip(a, b))


def orbit(angle, radius, height):
    return (radius * math.sin(angle), height, radius * math.cos(angle))


def position(t):
    """The eye's position in the model's frame at lap time t."""
    if t < 10.0:
        return (0.0, 0.3, 6.0 - 3.5 * smooth(t / 10.0) if t > 0 else 6.0)
    if t < 30.0:
        a = 2.0 * math.pi * smooth((t - 10.0) / 20.0)
        return orbit(a, 2.5 - 0.8 * math.sin(a / 2.0) ** 2, 0.3 + 0.6 * math.sin(a))
    if t < 40.0:
        s = smooth((t - 30.0) / 10.0)
        return lerp((0.0, 0.3, 2.5), (1.0, 0.3, -2.5), s)  # passes (0.5, 0.3, 0)
    if t < 50.0:
        s = smooth((t - 40.0) / 10.0)
        start = math.atan2(1.0, -2.5)  # where the fly-through ended
        radius = math.hypot(1.0, 2.5) + (1.5 - math.hypot(1.0, 2.5)) * smooth(4.0 * s)
        p = orbit(start + 2.0 * math.pi * s, radius, 0.3)
        tilt = math.radians(20.0) * math.sin(2.0 * math.pi * s)  # the model tilted about x
        return (p[0], p[1] * math.cos(tilt) - p[2] * math.sin(tilt), p[1] * math.sin(tilt) + p[2] * math.cos(tilt))
    s = (t - 50.0) / 10.0
    end = orbit(math.atan2(1.0, -2.5), 1.5, 0.3)
    near = tuple(c / 3.0 for c in end)  # scaled up three times
    if s < 0.4:
        return lerp(end, near, smooth(s / 0.4))
    return lerp(near, (0.0, 0.3, 6.0), smooth((s - 0.4) / 0.6))


def target(t):
    """Where the head points before it looks round: the model's centre, or
    ahead along the flight while flying through."""
    if 30.0 <= t < 40.0:
        ahead = position(min(t + 1.0, 39.99))
        here = position(t)
        forward = tuple(a - b for a, b in zip(ahead, here))
        length = math.sqrt(sum(c * c for c in forward)) or 1.0
        weight = smooth((t - 30.0) / 2.0) * (1.0 - smooth((t - 37.0) / 3.0))
        along = tuple(h + f / length for h, f in zip(here, forward))
        return lerp((0.0, 0.0, 0.0), along, weight) if weight < 1.0 else along
    return (0.0, 0.0, 0.0)


def look_quaternion(eye, goal, t):
    """Orientation looking from eye to goal (-z forward, y up), then turned
    by the look-round yaw and pitch; as (w, x, y, z)."""
    d = tuple(g - e for g, e in zip(goal, eye))
    yaw = math.atan2(-d[0], -d[2]) + math.radians(15.0) * math.sin(2.0 * math.pi * 0.23 * t)
    pitch = math.atan2(d[1], math.hypot(d[0], d[2])) + math.radians(8.0) * math.sin(2.0 * math.pi * 0.31 * t)
    cy, sy = math.cos(yaw / 2.0), math.sin(yaw / 2.0)
    cp, sp = math.cos(pitch / 2.0), math.sin(pitch / 2.0)
    # yaw about y, then pitch about the turned x axis: q = q_yaw * q_pitch
    return (cy * cp, cy * sp, sy * cp, -sy * sp)


def trace_text():
    rows = ["t_s,px,py,pz,qw,qx,qy,qz"]
    n = int(round(LAP_S / STEP_S))
    for i in range(n):
        t = i * STEP_S
        p = position(t)
        q = look_quaternion(p, target(t), t)
        rows.append(f"{t:.2f},{p[0]:.5f},{p[1]:.5f},{p[2]:.5f},{q[0]:.7f},{q[1]:.7f},{q[2]:.7f},{q[3]:.7f}")
    return "\n".join(rows) + "\n"


def main():
    """Writes the trace; with --check, says whether the shipped file is what this script writes."""
    text = trace_text()
    if sys.argv[1:] == ["--check"]:
        with open(OUT, encoding="ascii") as f:
            same = f.read() == text
        print("ok: flythrough.csv is what make_flythrough.py writes" if same
              else "FAIL: scenarios/pxpl5/data/flythrough.csv differs from scripts/make_flythrough.py (run it)")
        return 0 if same else 1
    with open(OUT, "w", encoding="ascii") as f:
        f.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
