#!/usr/bin/env python3
"""Writes the bundled scene `dress_form/`: a tube skirt made for a slimmer body (written
as `source_body.obj`, the skirt's source body), and a dress-form avatar whose hips bulge
through it. Y is up, units are metres, the avatar is
1.7 m tall and off the origin, so the scene exercises welding, UV seams, materials and a
change of frame without any external data."""

import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "dress_form")
ORIGIN = (0.35, 0.0, -0.2)
HEIGHT = 1.7


def body_radius(s):
    """Radius of the dress form at height fraction s in [0, 1]."""
    hips = 0.040 * math.exp(-((s - 0.47) / 0.08) ** 2)
    waist = -0.025 * math.exp(-((s - 0.62) / 0.06) ** 2)
    return 0.135 + hips + waist + 0.02 * math.sin(math.pi * s)


def slim_radius(s):
    """Radius of the slimmer form the skirt was made on: no hips, 1 to 2 cm inside it."""
    return 0.125 + 0.02 * math.sin(math.pi * s)


def fmt(x):
    return repr(float(x))


def write_avatar(path, rings=44, segments=40, radius=body_radius,
                 header="# dress form avatar, Y up, metres\nmtllib avatar.mtl\no DressForm\n"):
    verts = []
    faces = []
    bottom = len(verts)
    verts.append((0.0, 0.0, 0.0))
    for i in range(1, rings):
        s = i / rings
        taper = math.sin(math.pi * s) ** 0.35  # rounds the ends off towards the poles
        r = radius(s) * taper
        for j in range(segments):
            a = 2 * math.pi * j / segments
            verts.append((1.1 * r * math.cos(a), HEIGHT * s, 0.9 * r * math.sin(a)))
    top = len(verts)
    verts.append((0.0, HEIGHT, 0.0))

    def ring(i, j):
        return 1 + (i - 1) * segments + (j % segments)

    for j in range(segments):
        faces.append((bottom, ring(1, j + 1), ring(1, j)))
    for i in range(1, rings - 1):
        for j in range(segments):
            a, b, c, d = ring(i, j), ring(i, j + 1), ring(i + 1, j + 1), ring(i + 1, j)
            faces.append((a, b, c))
            faces.append((a, c, d))
    for j in range(segments):
        faces.append((top, ring(rings - 1, j), ring(rings - 1, j + 1)))
    with open(path, "w") as f:
        f.write(header + "usemtl Form\n")
        for v in verts:
            f.write("v %s %s %s\n" % tuple(fmt(v[k] + ORIGIN[k]) for k in range(3)))
        for t in faces:
            f.write("f %d %d %d\n" % (t[0] + 1, t[1] + 1, t[2] + 1))
    with open(os.path.join(OUT, "avatar.mtl"), "w") as f:
        f.write("newmtl Form\nKd 0.8 0.75 0.7\n")


def write_garment(path, rows=14, segments=36):
    """A tube skirt of constant radius from below the hips to the waist. Its UV seam at
    angle 0 is a column of duplicated positions, as exporters write it."""
    s0, s1 = 0.36, 0.66
    radius = 0.160
    verts, uvs = [], []
    for i in range(rows + 1):
        s = s0 + (s1 - s0) * i / rows
        first = None
        for j in range(segments + 1):
            a = 2 * math.pi * j / segments
            p = (1.1 * radius * math.cos(a), HEIGHT * s, 0.9 * radius * math.sin(a))
            if j == 0:
                first = p
            if j == segments:
                p = first
            verts.append(p)
            uvs.append((j / segments, i / rows))

    def vid(i, j):
        return i * (segments + 1) + j

    faces = []
    for i in range(rows):
        for j in range(segments):
            a, b, c, d = vid(i, j), vid(i, j + 1), vid(i + 1, j + 1), vid(i + 1, j)
            faces.append((a, b, c))
            faces.append((a, c, d))
    with open(path, "w") as f:
        f.write("# tube skirt for a slimmer body, Y up, metres\nmtllib garment.mtl\n"
                "o TubeSkirt\n")
        for v in verts:
            f.write("v %s %s %s\n" % tuple(fmt(v[k] + ORIGIN[k]) for k in range(3)))
        for uv in uvs:
            f.write("vt %s %s\n" % (fmt(uv[0]), fmt(uv[1])))
        f.write("g skirt\nusemtl Fabric\ns 1\n")
        for t in faces:
            f.write("f %d/%d %d/%d %d/%d\n" % (t[0] + 1, t[0] + 1, t[1] + 1, t[1] + 1,
                                               t[2] + 1, t[2] + 1))
    with open(os.path.join(OUT, "garment.mtl"), "w") as f:
        f.write("newmtl Fabric\nKd 0.2 0.3 0.7\n")
    # The hem row hangs free: its faces are no-fit.
    with open(os.path.join(OUT, "no-fit.txt"), "w") as f:
        f.write(" ".join(str(vid(i, j)) for i in range(2) for j in range(segments + 1)) + "\n")


if __name__ == "__main__":
    os.makedirs(OUT, exist_ok=True)
    write_avatar(os.path.join(OUT, "avatar.obj"))
    write_garment(os.path.join(OUT, "garment.obj"))
    write_avatar(os.path.join(OUT, "source_body.obj"), radius=slim_radius,
                 header="# the slimmer form the skirt was made on, Y up, metres\no SourceForm\n")
