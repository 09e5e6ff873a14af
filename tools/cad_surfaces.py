#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Writes closed test surfaces as binary STL, for measuring `femdem mesh` (docs/VALIDATION.md,
section 6, and docs/PERFORMANCE.md):

  sphere.stl    unit-radius icosphere, the icosahedron split 5 times (20480 triangles)
  cube.stl      the unit cube [0, 1]^3 (12 triangles)
  cylinder.stl  radius 0.5, height 2, 256 segments around (1024 triangles)

usage: tools/cad_surfaces.py OUTDIR
"""
import math
import os
import struct
import sys


def write_stl(path, points, triangles):
    with open(path, "wb") as f:
        f.write(b"femdem test surface".ljust(80, b" "))
        f.write(struct.pack("<I", len(triangles)))
        for a, b, c in triangles:
            f.write(struct.pack("<3f", 0.0, 0.0, 0.0))
            for i in (a, b, c):
                f.write(struct.pack("<3f", *points[i]))
            f.write(struct.pack("<H", 0))


def normalized(p):
    n = math.sqrt(sum(x * x for x in p))
    return tuple(x / n for x in p)


def icosphere(levels):
    t = (1.0 + math.sqrt(5.0)) / 2.0
    pts = [normalized(p) for p in [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t),
                                   (0, 1, t), (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1),
                                   (-t, 0, -1), (-t, 0, 1)]]
    tris = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
            (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
            (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(levels):
        mid = {}

        def m(a, b):
            key = (min(a, b), max(a, b))
            if key not in mid:
                pts.append(normalized(tuple(x + y for x, y in zip(pts[a], pts[b]))))
                mid[key] = len(pts) - 1
            return mid[key]

        nxt = []
        for a, b, c in tris:
            ab, bc, ca = m(a, b), m(b, c), m(c, a)
            nxt += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        tris = nxt
    return pts, tris


def cube():
    pts = [(i & 1, (i >> 1) & 1, (i >> 2) & 1) for i in range(8)]
    tris = [(0, 2, 1), (1, 2, 3), (4, 5, 6), (5, 7, 6), (0, 1, 4), (1, 5, 4), (2, 6, 3),
            (3, 6, 7), (0, 4, 2), (2, 4, 6), (1, 3, 5), (3, 7, 5)]
    return pts, tris


def cylinder(radius, height, n):
    pts = [(0.0, 0.0, 0.0), (0.0, 0.0, height)]
    for z in (0.0, height):
        for k in range(n):
            a = 2 * math.pi * k / n
            pts.append((radius * math.cos(a), radius * math.sin(a), z))
    tris = []
    for k in range(n):
        b0, b1 = 2 + k, 2 + (k + 1) % n
        t0, t1 = 2 + n + k, 2 + n + (k + 1) % n
        tris += [(0, b1, b0), (1, t0, t1), (b0, b1, t1), (b0, t1, t0)]
    return pts, tris


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "."
    os.makedirs(out, exist_ok=True)
    write_stl(os.path.join(out, "sphere.stl"), *icosphere(5))
    write_stl(os.path.join(out, "cube.stl"), *cube())
    write_stl(os.path.join(out, "cylinder.stl"), *cylinder(0.5, 2.0, 256))


if __name__ == "__main__":
    main()
