#!/usr/bin/env python3
"""Generate the small convex-hull collision meshes of the project's own robots.

Each mesh is the convex hull of a few dozen points that we place by hand (rings of a
bearing housing, a rounded gripper body...). The hull is computed with an incremental
algorithm in exact rational arithmetic on the float32 values that the STL file stores, so
the written triangles are exactly the convex hull of the written vertices (no tolerance,
no coplanar-face ambiguity). Output: binary STL in metres, outward-facing triangles.

Usage:  python3 robots/tools/make_meshes.py        (from anywhere; stdlib only)
Writes: robots/dss_arm7/meshes/*.stl and robots/dss_mobile_base/meshes/*.stl and prints
        vertex / triangle counts. Re-running reproduces the committed files byte for byte.
"""

import math
import os
import struct
import sys
from fractions import Fraction

HERE = os.path.dirname(os.path.abspath(__file__))
ROBOTS = os.path.dirname(HERE)


def f32(x):
    """Round to the float32 value the STL file will store."""
    return struct.unpack("<f", struct.pack("<f", x))[0]


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def orient(a, b, c, p):
    """> 0 when p lies on the side of plane (a,b,c) its normal (b-a)x(c-a) points to."""
    return dot(cross(sub(b, a), sub(c, a)), sub(p, a))


def convex_hull(points_f):
    """Exact incremental 3-D hull. Returns (vertices, triangles) with outward orientation."""
    pts = []
    seen = set()
    for p in points_f:
        q = (f32(p[0]), f32(p[1]), f32(p[2]))
        if q not in seen:
            seen.add(q)
            pts.append(q)
    P = [tuple(Fraction(c) for c in p) for p in pts]
    n = len(P)
    # Initial non-degenerate tetrahedron.
    i0 = 0
    i1 = next(i for i in range(n) if P[i] != P[i0])
    i2 = next(i for i in range(n)
              if cross(sub(P[i1], P[i0]), sub(P[i], P[i0])) != (0, 0, 0))
    i3 = next(i for i in range(n) if orient(P[i0], P[i1], P[i2], P[i]) != 0)
    if orient(P[i0], P[i1], P[i2], P[i3]) > 0:
        i1, i2 = i2, i1
    faces = [(i0, i1, i2), (i0, i3, i1), (i1, i3, i2), (i2, i3, i0)]
    for f in faces:  # all faces must see the opposite vertex below them
        assert all(orient(P[f[0]], P[f[1]], P[f[2]], P[k]) <= 0 for k in (i0, i1, i2, i3))
    for k in range(n):
        if k in (i0, i1, i2, i3):
            continue
        visible = [f for f in faces if orient(P[f[0]], P[f[1]], P[f[2]], P[k]) > 0]
        if not visible:
            continue
        edges = set()
        for a, b, c in visible:
            edges.update(((a, b), (b, c), (c, a)))
        horizon = [e for e in edges if (e[1], e[0]) not in edges]
        vis = set(visible)
        faces = [f for f in faces if f not in vis] + [(a, b, k) for a, b in horizon]
    # Checks: closed 2-manifold (Euler), every input point inside or on every face plane.
    used = sorted({i for f in faces for i in f})
    E = len({tuple(sorted(e)) for a, b, c in faces for e in ((a, b), (b, c), (c, a))})
    assert len(used) - E + len(faces) == 2, "hull is not a closed polyhedron"
    for a, b, c in faces:
        assert all(orient(P[a], P[b], P[c], q) <= 0 for q in P), "hull is not convex"
    remap = {old: new for new, old in enumerate(used)}
    verts = [pts[i] for i in used]
    tris = [(remap[a], remap[b], remap[c]) for a, b, c in faces]
    return verts, tris


def write_stl(path, verts, tris, title):
    with open(path, "wb") as f:
        header = title.encode("ascii")[:80]
        f.write(header + b" " * (80 - len(header)))
        f.write(struct.pack("<I", len(tris)))
        for a, b, c in tris:
            n = cross(sub(verts[b], verts[a]), sub(verts[c], verts[a]))
            ln = math.sqrt(dot(n, n)) or 1.0
            f.write(struct.pack("<3f", n[0] / ln, n[1] / ln, n[2] / ln))
            for v in (verts[a], verts[b], verts[c]):
                f.write(struct.pack("<3f", *v))
            f.write(struct.pack("<H", 0))


def ring(axis, centre, radius, count, phase=0.0):
    """count points on a circle of the given radius around `axis` ('x','y','z')."""
    out = []
    for i in range(count):
        t = phase + 2.0 * math.pi * i / count
        u, v = radius * math.cos(t), radius * math.sin(t)
        if axis == "x":
            d = (0.0, u, v)
        elif axis == "y":
            d = (u, 0.0, v)
        else:
            d = (u, v, 0.0)
        out.append((centre[0] + d[0], centre[1] + d[1], centre[2] + d[2]))
    return out


def joint_housing(r_bearing, half_width, r_tube, z_tube_top, n=10):
    """A bearing drum around the link's y axis (the pitch joint at the link origin) merged
    with a round tube rising along z to the next roll joint; hull of 4 rings of n points."""
    pts = []
    pts += ring("y", (0.0, -half_width, 0.0), r_bearing, n)
    pts += ring("y", (0.0, +half_width, 0.0), r_bearing, n)
    pts += ring("z", (0.0, 0.0, z_tube_top - 0.035), r_tube, n, math.pi / n)
    pts += ring("z", (0.0, 0.0, z_tube_top), r_tube - 0.02, n, math.pi / n)
    return pts


def rounded_box(hx, hy, z0, z1, chamfer, bevel):
    """Octagonal prism (corners cut by `chamfer`) with its top ring inset by `bevel`."""
    def octagon(ax, ay, z):
        c = chamfer
        return [(ax, ay - c, z), (ax - c, ay, z), (-ax + c, ay, z), (-ax, ay - c, z),
                (-ax, -ay + c, z), (-ax + c, -ay, z), (ax - c, -ay, z), (ax, -ay + c, z)]
    pts = octagon(hx - bevel, hy - bevel, z0)
    pts += octagon(hx, hy, z0 + bevel)
    pts += octagon(hx, hy, z1 - bevel)
    pts += octagon(hx - bevel, hy - bevel, z1)
    return pts


def meshes():
    """(relative output path, title, point list). Dimensions in metres, link frames."""
    return [
        # dss_arm7 link2: J2 drum (y axis) + tube up to J3 (at z = 0.21).
        ("dss_arm7/meshes/shoulder.stl", "dss_arm7 shoulder housing (convex hull)",
         joint_housing(0.095, 0.085, 0.088, 0.185)),
        # dss_arm7 link4: J4 drum + tube up to J5 (at z = 0.20).
        ("dss_arm7/meshes/elbow.stl", "dss_arm7 elbow housing (convex hull)",
         joint_housing(0.088, 0.078, 0.080, 0.175)),
        # dss_arm7 link6: J6 drum + short neck up to J7 (at z = 0.08).
        ("dss_arm7/meshes/wrist.stl", "dss_arm7 wrist housing (convex hull)",
         joint_housing(0.072, 0.068, 0.062, 0.075, n=8)),
        # dss_arm7 tool: gripper body on the flange, 0.10 x 0.07 x 0.075.
        ("dss_arm7/meshes/gripper_body.stl", "dss_arm7 gripper body (convex hull)",
         rounded_box(0.035, 0.05, 0.0, 0.075, 0.012, 0.008)),
        # dss_mobile_base: bumper shell on top of the chassis box.
        ("dss_mobile_base/meshes/bumper_shell.stl", "dss_mobile_base bumper shell (convex hull)",
         rounded_box(0.33, 0.25, 0.0, 0.12, 0.07, 0.02)),
        # dss_mobile_base: small gripper at the end of the 2-DOF arm.
        ("dss_mobile_base/meshes/gripper.stl", "dss_mobile_base gripper (convex hull)",
         rounded_box(0.03, 0.04, 0.0, 0.06, 0.01, 0.006)),
    ]


def main():
    for rel, title, pts in meshes():
        verts, tris = convex_hull(pts)
        path = os.path.join(ROBOTS, rel)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        write_stl(path, verts, tris, title)
        lo = [min(v[i] for v in verts) for i in range(3)]
        hi = [max(v[i] for v in verts) for i in range(3)]
        print("%-40s %3d vertices %3d triangles  bbox [%s] .. [%s]" % (
            rel, len(verts), len(tris), " ".join("%.3f" % x for x in lo),
            " ".join("%.3f" % x for x in hi)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
