#!/usr/bin/env python3
"""Writes two skeleton-free scenes, each a flat garment patch placed over a body that pokes
through it: `patch_sphere/` (a 14x14 patch 1.5 wide across a unit sphere's pole) and
`patch_cone/` (a 14x14 patch 1 wide across the tip of a cone 1 tall). Z is up.

    scenes/make_skeleton_free.py OUT_DIR
"""
import math
import os
import sys


def write_obj(path, vertices, faces):
    with open(path, "w") as out:
        for v in vertices:
            out.write("v %.17g %.17g %.17g\n" % tuple(v))
        for f in faces:
            out.write("f %d %d %d\n" % tuple(i + 1 for i in f))


def uv_sphere(around=24, rings=16, radius=1.0):
    vertices = [(0.0, 0.0, radius)]
    for i in range(1, rings):
        theta = math.pi * i / rings
        for j in range(around):
            phi = 2.0 * math.pi * j / around
            vertices.append((radius * math.sin(theta) * math.cos(phi),
                             radius * math.sin(theta) * math.sin(phi), radius * math.cos(theta)))
    vertices.append((0.0, 0.0, -radius))
    ring = lambda i, j: 1 + (i - 1) * around + j % around
    faces = [(0, ring(1, j), ring(1, j + 1)) for j in range(around)]
    for i in range(1, rings - 1):
        for j in range(around):
            a, b, c, d = ring(i, j), ring(i, j + 1), ring(i + 1, j), ring(i + 1, j + 1)
            faces += [(a, c, b), (b, c, d)]
    south = len(vertices) - 1
    faces += [(ring(rings - 1, j), south, ring(rings - 1, j + 1)) for j in range(around)]
    return vertices, faces


def cone(around=32, height=1.0, radius=0.6):
    vertices = [(0.0, 0.0, height)]
    vertices += [(radius * math.cos(2 * math.pi * j / around),
                  radius * math.sin(2 * math.pi * j / around), 0.0) for j in range(around)]
    vertices.append((0.0, 0.0, 0.0))
    faces = [(0, 1 + j, 1 + (j + 1) % around) for j in range(around)]
    faces += [(around + 1, 1 + (j + 1) % around, 1 + j) for j in range(around)]
    return vertices, faces


def patch(cells, size, height):
    step = size / cells
    vertices = [(-size / 2 + step * i, -size / 2 + step * j, height)
                for j in range(cells + 1) for i in range(cells + 1)]
    faces = []
    for j in range(cells):
        for i in range(cells):
            a = j * (cells + 1) + i
            faces += [(a, a + 1, a + cells + 2), (a, a + cells + 2, a + cells + 1)]
    return vertices, faces


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    for name, body, garment in (("patch_sphere", uv_sphere(), patch(14, 1.5, 0.93)),
                                ("patch_cone", cone(), patch(14, 1.0, 0.95))):
        os.makedirs(os.path.join(out, name), exist_ok=True)
        write_obj(os.path.join(out, name, "avatar.obj"), *body)
        write_obj(os.path.join(out, name, "garment.obj"), *garment)


if __name__ == "__main__":
    main()
