#!/usr/bin/env python3
"""Writes scenarios/objects/room_lowpoly.obj: the furnished room of the
built-in `room` scene (6 x 2.7 x 8 m, x in [-3, 3], y in [0, 2.7], z in
[-4, 4]) with a few hundred triangles instead of two thousand, the size of
scene a single-GP Slats system drew at 60 fields/s. Walls, floor and ceiling
are 2 x 2 quads; every piece of furniture is one or a few boxes."""

import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "scenarios", "objects", "room_lowpoly.obj")


class Obj:
    def __init__(self):
        self.lines = []
        self.vertices = 0
        self.triangles = 0

    def obj(self, name):
        self.lines.append(f"o {name}")

    def quad(self, corner, u, v, colour):
        """Two triangles spanning corner, corner+u, corner+u+v, corner+v."""
        pts = [corner,
               tuple(c + a for c, a in zip(corner, u)),
               tuple(c + a + b for c, a, b in zip(corner, u, v)),
               tuple(c + b for c, b in zip(corner, v))]
        for p in pts:
            self.lines.append("v %.3f %.3f %.3f %.2f %.2f %.2f" % (p + colour))
        self.vertices += 4
        self.lines.append("f -4 -3 -2")
        self.lines.append("f -4 -2 -1")
        self.triangles += 2

    def split_quad(self, corner, u, v, colour, n=2):
        """An n x n grid of quads, so a wall is not all in one region."""
        du = tuple(a / n for a in u)
        dv = tuple(b / n for b in v)
        for i in range(n):
            for j in range(n):
                c = tuple(o + i * a + j * b for o, a, b in zip(corner, du, dv))
                self.quad(c, du, dv, colour)

    def box(self, lo, hi, colour):
        (x0, y0, z0), (x1, y1, z1) = lo, hi
        dx, dy, dz = x1 - x0, y1 - y0, z1 - z0
        self.quad((x0, y0, z0), (dx, 0, 0), (0, dy, 0), colour)
        self.quad((x0, y0, z1), (dx, 0, 0), (0, dy, 0), colour)
        self.quad((x0, y0, z0), (0, 0, dz), (0, dy, 0), colour)
        self.quad((x1, y0, z0), (0, 0, dz), (0, dy, 0), colour)
        self.quad((x0, y0, z0), (dx, 0, 0), (0, 0, dz), colour)
        self.quad((x0, y1, z0), (dx, 0, 0), (0, 0, dz), colour)


def main():
    o = Obj()
    o.obj("floor")
    o.split_quad((-3.0, 0.0, -4.0), (6.0, 0, 0), (0, 0, 8.0), (0.5, 0.35, 0.18))
    o.obj("ceiling")
    o.split_quad((-3.0, 2.7, -4.0), (6.0, 0, 0), (0, 0, 8.0), (0.9, 0.9, 0.88))
    o.obj("wall_north")
    o.split_quad((-3.0, 0.0, -4.0), (6.0, 0, 0), (0, 2.7, 0), (0.75, 0.8, 0.7))
    o.obj("wall_south")
    o.split_quad((-3.0, 0.0, 4.0), (6.0, 0, 0), (0, 2.7, 0), (0.7, 0.75, 0.8))
    o.obj("wall_west")
    o.split_quad((-3.0, 0.0, -4.0), (0, 0, 8.0), (0, 2.7, 0), (0.8, 0.72, 0.65))
    o.obj("wall_east")
    o.split_quad((3.0, 0.0, -4.0), (0, 0, 8.0), (0, 2.7, 0), (0.8, 0.78, 0.6))
    wood = (0.45, 0.28, 0.15)
    o.obj("table")
    o.box((-0.8, 0.72, -2.0), (0.8, 0.77, -1.1), wood)
    for x in (-0.75, 0.7):
        for z in (-1.95, -1.2):
            o.box((x, 0.0, z), (x + 0.05, 0.72, z + 0.05), wood)
    for k in range(2):
        x = -0.45 + 0.7 * k
        o.obj(f"chair_{k}")
        o.box((x, 0.0, -0.95), (x + 0.42, 0.46, -0.55), (0.7, 0.2, 0.15))
        o.box((x, 0.46, -0.57), (x + 0.42, 0.95, -0.53), (0.7, 0.2, 0.15))
    o.obj("shelf")
    o.box((-2.92, 0.0, -3.95), (-2.88, 1.83, -3.6), wood)
    o.box((-1.72, 0.0, -3.95), (-1.68, 1.83, -3.6), wood)
    for k in range(4):
        y = 0.45 * k
        o.box((-2.9, y, -3.95), (-1.7, y + 0.04, -3.6), wood)
    o.obj("books")
    o.box((-2.8, 0.04, -3.9), (-2.3, 0.34, -3.65), (0.7, 0.25, 0.2))
    o.box((-2.2, 0.49, -3.9), (-1.8, 0.79, -3.65), (0.2, 0.45, 0.7))
    o.obj("sofa")
    fabric = (0.2, 0.35, 0.6)
    o.box((2.1, 0.0, -1.0), (2.9, 0.45, 1.2), fabric)
    o.box((2.7, 0.45, -1.0), (2.9, 0.9, 1.2), fabric)
    o.box((2.1, 0.45, -1.0), (2.7, 0.65, -0.8), fabric)
    o.box((2.1, 0.45, 1.0), (2.7, 0.65, 1.2), fabric)
    o.obj("cabinet")
    o.box((1.2, 0.0, -3.95), (2.6, 0.9, -3.45), (0.85, 0.85, 0.8))
    o.obj("lamp")
    o.box((2.35, 0.9, -3.8), (2.45, 1.3, -3.7), (0.2, 0.2, 0.2))
    o.box((2.25, 1.3, -3.9), (2.55, 1.5, -3.6), (0.95, 0.9, 0.5))
    o.obj("picture")
    o.box((-1.0, 1.2, 3.95), (1.0, 2.2, 3.99), (0.15, 0.1, 0.05))
    o.quad((-0.9, 1.3, 3.94), (1.8, 0, 0), (0, 0.8, 0), (0.8, 0.5, 0.2))
    header = [
        "# A furnished room of %d triangles: the built-in `room` scene's layout" % o.triangles,
        "# (6 x 2.7 x 8 m) with 2 x 2 quads for walls, floor and ceiling and boxes for",
        "# the furniture; written by scripts/make_lowpoly_room.py.",
        "# Vertex colours use the \"v x y z r g b\" extension (linear RGB).",
    ]
    with open(OUT, "w", encoding="utf-8") as f:
        f.write("\n".join(header + o.lines) + "\n")
    print(f"{OUT}: {o.triangles} triangles", file=sys.stderr)


if __name__ == "__main__":
    main()
