#!/usr/bin/env python3
"""Conservative stand-alone checks for the project's own robot models (stdlib + PyYAML).

This is a cross-check written independently of the dss library: forward kinematics from
the URDF, and *bounding* approximations of every collision element, so each verdict is
one-sided and safe:

  * "free" verdicts use OUTER bounds. Each robot collision element is replaced by a capsule
    that contains it (sphere: itself; cylinder: axis segment + radius; box: segment along
    its longest edge + half-diagonal of the cross-section; mesh: segment along the best of
    the three element axes through the STL vertices' extent + the largest distance of a
    vertex to it, which contains the convex hull). Obstacles are replaced by oriented boxes
    that contain them (box: itself; cylinder and sphere: their bounding box). A pose is
    reported free only if every capsule is more than MARGIN away from every obstacle box
    and from every capsule of a link pair that the SRDF does not disable.
  * "collides" verdicts use INNER witnesses: the centre of a sphere element, points on a
    cylinder's axis, the centre of a box element and the vertex centroid of a mesh hull
    (all inside their element) are tested against obstacles that are real boxes; a witness
    point inside a box proves a collision.
  * "never" (SRDF disable_collisions reason="Never") is proved by branch and bound over the
    joints between the two links: at the centre of a joint-space cell the capsule distance
    d is computed; every point of the distal link moves at most sum_j rho_j * halfwidth_j
    inside the cell (rho_j bounds the lever arm of joint j, 1 for a prismatic joint), so
    d - that bound > MARGIN proves the whole cell free. A cell centre where the outer bounds
    overlap ends the attempt ("overlap": the pair may or may not collide; it stays enabled).

Usage (paths relative to the repository root):
  python3 robots/tools/check_robot.py never robots/dss_arm7/dss_arm7.urdf robots/dss_arm7/dss_arm7.srdf
  python3 robots/tools/check_robot.py scene robots/dss_arm7/dss_arm7.urdf robots/dss_arm7/dss_arm7.srdf \
          robots/dss_arm7/scenes/shelf.yaml robots/dss_arm7/scenes/shelf_request.yaml
  python3 robots/tools/check_robot.py pose URDF SRDF q1 q2 ...   (self-collision of one pose)
Exit status 0 when every claim holds, 1 otherwise.
"""

import math
import os
import struct
import sys
import xml.etree.ElementTree as ET

MARGIN = 0.002  # metres; "free" requires a gap larger than this between outer bounds


# ---------------------------------------------------------------- small linear algebra
def vadd(a, b):
    return [a[0] + b[0], a[1] + b[1], a[2] + b[2]]


def vsub(a, b):
    return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]


def vscale(a, s):
    return [a[0] * s, a[1] * s, a[2] * s]


def vdot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def vnorm(a):
    return math.sqrt(vdot(a, a))


def mmul(A, B):
    return [[sum(A[i][k] * B[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


def mvec(A, v):
    return [A[i][0] * v[0] + A[i][1] * v[1] + A[i][2] * v[2] for i in range(3)]


def mT(A):
    return [[A[j][i] for j in range(3)] for i in range(3)]


def rpy_matrix(r, p, y):
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return [[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
            [-sp, cp * sr, cp * cr]]


def axis_angle(axis, t):
    n = vnorm(axis)
    x, y, z = axis[0] / n, axis[1] / n, axis[2] / n
    c, s = math.cos(t), math.sin(t)
    C = 1 - c
    return [[c + x * x * C, x * y * C - z * s, x * z * C + y * s],
            [y * x * C + z * s, c + y * y * C, y * z * C - x * s],
            [z * x * C - y * s, z * y * C + x * s, c + z * z * C]]


def quat_matrix(q):  # q = [x, y, z, w]
    x, y, z, w = q
    n = math.sqrt(x * x + y * y + z * z + w * w)
    x, y, z, w = x / n, y / n, z / n, w / n
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]


class Pose:
    def __init__(self, R=None, p=None):
        self.R = R or [[1, 0, 0], [0, 1, 0], [0, 0, 1]]
        self.p = p or [0.0, 0.0, 0.0]

    def __mul__(self, o):
        return Pose(mmul(self.R, o.R), vadd(mvec(self.R, o.p), self.p))

    def apply(self, v):
        return vadd(mvec(self.R, v), self.p)


def parse_origin(el):
    o = el.find("origin") if el is not None else None
    if o is None:
        return Pose()
    xyz = [float(v) for v in o.get("xyz", "0 0 0").split()]
    rpy = [float(v) for v in o.get("rpy", "0 0 0").split()]
    return Pose(rpy_matrix(*rpy), xyz)


# ---------------------------------------------------------------- robot model
def read_stl_vertices(path):
    with open(path, "rb") as f:
        data = f.read()
    n = struct.unpack_from("<I", data, 80)[0]
    if len(data) != 84 + 50 * n:
        raise ValueError("%s: not a binary STL (size mismatch)" % path)
    verts = set()
    for i in range(n):
        off = 84 + 50 * i + 12
        for k in range(3):
            verts.add(struct.unpack_from("<3f", data, off + 12 * k))
    return [list(v) for v in verts]


def capsule_of_points(pts):
    """Outer capsule (a, b, r) of a point set, axis chosen among x, y, z (smallest volume)."""
    best = None
    cx = [(min(p[i] for p in pts) + max(p[i] for p in pts)) / 2 for i in range(3)]
    for ax in range(3):
        lo = min(p[ax] for p in pts)
        hi = max(p[ax] for p in pts)
        r = max(math.hypot(*[p[i] - cx[i] for i in range(3) if i != ax]) for p in pts)
        # shrink the segment while every point stays inside the capsule
        a = list(cx); b = list(cx)
        a[ax] = lo + r; b[ax] = hi - r
        if a[ax] > b[ax]:
            a[ax] = b[ax] = (lo + hi) / 2
        rr = max(seg_point_dist(a, b, p) for p in pts)
        vol = math.pi * rr * rr * (vnorm(vsub(b, a)) + 4.0 * rr / 3.0)
        if best is None or vol < best[0]:
            best = (vol, a, b, rr)
    return best[1], best[2], best[3]


def best_shrink(half, r2):
    """A capsule with segment [-half+s, half-s] and radius sqrt(r2+s^2) contains a
    cylinder/box of half-length `half` and cross-section radius^2 r2 for any 0<=s<=half;
    return the s of smallest capsule volume (flat shapes prefer a short segment)."""
    def vol(s):
        R = math.sqrt(r2 + s * s)
        return math.pi * R * R * (2 * (half - s) + 4.0 * R / 3.0)
    return min((half * i / 20 for i in range(21)), key=vol)


class Element:
    """One <collision>: outer capsule and inner witness points, both in the link frame."""

    def __init__(self, link, name, kind, X_LE, dims, mesh_pts=None):
        self.link, self.name, self.kind = link, name, kind
        if kind == "sphere":
            c = X_LE.p
            self.cap = (c, c, dims[0])
            self.inner = [c]
        elif kind == "cylinder":
            r, L = dims
            s = best_shrink(L / 2, r * r)
            a = X_LE.apply([0, 0, -L / 2 + s]); b = X_LE.apply([0, 0, L / 2 - s])
            self.cap = (a, b, math.sqrt(r * r + s * s))
            self.inner = [X_LE.apply([0, 0, L * t]) for t in (-0.5, -0.25, 0, 0.25, 0.5)]
        elif kind == "box":
            h = [d / 2 for d in dims]
            ax = max(range(3), key=lambda i: h[i])
            r2 = sum(h[i] ** 2 for i in range(3) if i != ax)
            s = best_shrink(h[ax], r2)
            e = [0, 0, 0]; e[ax] = h[ax] - s
            self.cap = (X_LE.apply(vscale(e, -1)), X_LE.apply(e), math.sqrt(r2 + s * s))
            self.inner = [X_LE.p]
        elif kind == "mesh":
            pts = [X_LE.apply(v) for v in mesh_pts]
            self.cap = capsule_of_points(pts)
            self.inner = [vscale([sum(p[i] for p in pts) for i in range(3)], 1.0 / len(pts))]
        else:
            raise ValueError("unknown geometry kind %s" % kind)
        self.reach = max(vnorm(self.cap[0]), vnorm(self.cap[1])) + self.cap[2]


class Robot:
    def __init__(self, urdf_path):
        self.path = urdf_path
        root = ET.parse(urdf_path).getroot()
        base = os.path.dirname(os.path.abspath(urdf_path))
        self.elements = {}
        for link in root.findall("link"):
            name = link.get("name")
            els = []
            for i, col in enumerate(link.findall("collision")):
                X = parse_origin(col)
                g = col.find("geometry")[0]
                ename = col.get("name", "%s#%d" % (name, i))
                if g.tag == "sphere":
                    els.append(Element(name, ename, "sphere", X, [float(g.get("radius"))]))
                elif g.tag == "cylinder":
                    els.append(Element(name, ename, "cylinder", X,
                                       [float(g.get("radius")), float(g.get("length"))]))
                elif g.tag == "box":
                    els.append(Element(name, ename, "box", X,
                                       [float(v) for v in g.get("size").split()]))
                elif g.tag == "mesh":
                    fn = g.get("filename")
                    if "://" in fn or g.get("scale"):
                        raise ValueError("%s: link %s: only relative mesh paths, no scale" % (urdf_path, name))
                    els.append(Element(name, ename, "mesh", X, None,
                                       read_stl_vertices(os.path.join(base, fn))))
                else:
                    raise ValueError("%s: link %s: unsupported geometry %s" % (urdf_path, name, g.tag))
            self.elements[name] = els
        self.joints = {}
        self.child_joint = {}
        for j in root.findall("joint"):
            d = {"name": j.get("name"), "type": j.get("type"),
                 "parent": j.find("parent").get("link"), "child": j.find("child").get("link"),
                 "X": parse_origin(j),
                 "axis": [float(v) for v in (j.find("axis").get("xyz") if j.find("axis") is not None else "1 0 0").split()]}
            lim = j.find("limit")
            if d["type"] == "continuous":
                d["lower"], d["upper"] = -math.pi, math.pi
            elif d["type"] in ("revolute", "prismatic"):
                d["lower"], d["upper"] = float(lim.get("lower")), float(lim.get("upper"))
            self.joints[d["name"]] = d
            self.child_joint[d["child"]] = d
        children = {j["child"] for j in self.joints.values()}
        roots = [l for l in self.elements if l not in children]
        assert len(roots) == 1, "expected one root link"
        self.root = roots[0]
        self.active = [j["name"] for j in self.joints.values() if j["type"] != "fixed"]

    def chain(self, link):
        """Joints from the root to `link`, root first."""
        out = []
        while link in self.child_joint:
            j = self.child_joint[link]
            out.append(j)
            link = j["parent"]
        return out[::-1]

    def joint_motion(self, j, q):
        if j["type"] in ("revolute", "continuous"):
            return Pose(axis_angle(j["axis"], q), None)
        if j["type"] == "prismatic":
            n = vnorm(j["axis"])
            return Pose(None, vscale(j["axis"], q / n))
        return Pose()

    def link_pose(self, link, qmap, start=None):
        """Pose of `link` in the frame of its ancestor `start` (root when None)."""
        X = Pose()
        active = start is None
        for j in self.chain(link):
            if not active:
                active = j["parent"] == start
                if not active:
                    continue
            X = X * j["X"] * self.joint_motion(j, qmap.get(j["name"], 0.0))
        return X

    def world_capsules(self, qmap):
        out = []
        for link, els in self.elements.items():
            X = self.link_pose(link, qmap)
            for e in els:
                a, b, r = e.cap
                out.append((e, X.apply(a), X.apply(b), r))
        return out


def read_srdf(path):
    root = ET.parse(path).getroot()
    disabled = {}
    for d in root.findall("disable_collisions"):
        disabled[frozenset((d.get("link1"), d.get("link2")))] = d.get("reason")
    states = {}
    for gs in root.findall("group_state"):
        states[(gs.get("group"), gs.get("name"))] = {j.get("name"): float(j.get("value")) for j in gs.findall("joint")}
    return disabled, states


# ---------------------------------------------------------------- distances
def seg_point_dist(a, b, p):
    ab = vsub(b, a)
    L2 = vdot(ab, ab)
    t = 0.0 if L2 == 0 else max(0.0, min(1.0, vdot(vsub(p, a), ab) / L2))
    return vnorm(vsub(p, vadd(a, vscale(ab, t))))


def seg_seg_dist(p1, q1, p2, q2):
    """Closest distance between segments [p1,q1] and [p2,q2] (Ericson, RTCD 5.1.9)."""
    d1, d2, r = vsub(q1, p1), vsub(q2, p2), vsub(p1, p2)
    a, e, f = vdot(d1, d1), vdot(d2, d2), vdot(d2, r)
    eps = 1e-15
    if a <= eps and e <= eps:
        return vnorm(r)
    if a <= eps:
        s, t = 0.0, max(0.0, min(1.0, f / e))
    else:
        c = vdot(d1, r)
        if e <= eps:
            t, s = 0.0, max(0.0, min(1.0, -c / a))
        else:
            b = vdot(d1, d2)
            den = a * e - b * b
            s = max(0.0, min(1.0, (b * f - c * e) / den)) if den > eps else 0.0
            t = (b * s + f) / e
            if t < 0.0:
                t, s = 0.0, max(0.0, min(1.0, -c / a))
            elif t > 1.0:
                t, s = 1.0, max(0.0, min(1.0, (b - c) / a))
    c1 = vadd(p1, vscale(d1, s))
    c2 = vadd(p2, vscale(d2, t))
    return vnorm(vsub(c1, c2))


class Obb:
    def __init__(self, oid, kind, R, c, h):
        self.id, self.kind, self.R, self.c, self.h = oid, kind, R, c, h

    def local(self, p):
        return mvec(mT(self.R), vsub(p, self.c))

    def point_dist(self, p):
        l = self.local(p)
        return math.sqrt(sum(max(0.0, abs(l[i]) - self.h[i]) ** 2 for i in range(3)))

    def contains(self, p):
        l = self.local(p)
        return all(abs(l[i]) <= self.h[i] for i in range(3))

    def seg_dist(self, a, b):
        """min over the segment of the point-box distance (a convex function of t)."""
        f = lambda t: self.point_dist(vadd(a, vscale(vsub(b, a), t)))
        lo, hi = 0.0, 1.0
        g = (math.sqrt(5) - 1) / 2
        x1, x2 = hi - g * (hi - lo), lo + g * (hi - lo)
        f1, f2 = f(x1), f(x2)
        for _ in range(60):
            if f1 <= f2:
                hi, x2, f2 = x2, x1, f1
                x1 = hi - g * (hi - lo); f1 = f(x1)
            else:
                lo, x1, f1 = x1, x2, f2
                x2 = lo + g * (hi - lo); f2 = f(x2)
        return min(f1, f2, f(0.0), f(1.0))


def load_scene_obbs(scene):
    obbs = []
    for obj in scene["world"]["collision_objects"]:
        X_WO = Pose()
        if "pose" in obj:
            X_WO = Pose(quat_matrix(obj["pose"]["orientation"]), list(obj["pose"]["position"]))
        for prim, pp in zip(obj["primitives"], obj["primitive_poses"]):
            X = X_WO * Pose(quat_matrix(pp["orientation"]), list(pp["position"]))
            d = prim["dimensions"]
            if prim["type"] == "box":
                h = [d[0] / 2, d[1] / 2, d[2] / 2]
            elif prim["type"] == "cylinder":  # [height, radius]
                h = [d[1], d[1], d[0] / 2]
            elif prim["type"] == "sphere":
                h = [d[0]] * 3
            else:
                raise ValueError("object %s: unsupported primitive %s" % (obj["id"], prim["type"]))
            obbs.append(Obb(obj["id"], prim["type"], X.R, X.p, h))
    return obbs


# ---------------------------------------------------------------- checks
def self_clearance(robot, disabled, qmap):
    """Smallest outer-capsule gap over link pairs not disabled; (gap, pair)."""
    caps = robot.world_capsules(qmap)
    best = (float("inf"), None)
    for i in range(len(caps)):
        for k in range(i + 1, len(caps)):
            e1, a1, b1, r1 = caps[i]
            e2, a2, b2, r2 = caps[k]
            if e1.link == e2.link or frozenset((e1.link, e2.link)) in disabled:
                continue
            g = seg_seg_dist(a1, b1, a2, b2) - r1 - r2
            if g < best[0]:
                best = (g, (e1.name, e2.name))
    return best


def world_clearance(robot, obbs, qmap):
    caps = robot.world_capsules(qmap)
    best = (float("inf"), None)
    for e, a, b, r in caps:
        for o in obbs:
            g = o.seg_dist(a, b) - r
            if g < best[0]:
                best = (g, (e.name, o.id))
    return best


def inner_hits(robot, obbs, qmap):
    hits = []
    for link, els in robot.elements.items():
        X = robot.link_pose(link, qmap)
        for e in els:
            for p in e.inner:
                pw = X.apply(p)
                for o in obbs:
                    if o.kind == "box" and o.contains(pw):
                        hits.append((e.name, o.id))
    return sorted(set(hits))


def prove_never(robot, la, lb, max_cells=150000):
    """Branch and bound; returns ('never', cells) or ('overlap', q): outer bounds overlap, no proof either way or ('unproved', cells)."""
    ca, cb = robot.chain(la), robot.chain(lb)
    if len(ca) > len(cb):
        la, lb, ca, cb = lb, la, cb, ca
    if [j["name"] for j in cb[:len(ca)]] != [j["name"] for j in ca]:
        return ("unproved", "links are not on one chain", 0)
    between = [j for j in cb[len(ca):] if j["type"] != "fixed"]
    ea, eb = robot.elements[la], robot.elements[lb]
    if not ea or not eb:
        return ("never", "a link has no geometry", 0)
    reach_b = max(e.reach for e in eb)
    # lever arm bound of each moving joint: path length from the joint to lb + lb's reach
    rho = []
    for idx, j in enumerate(between):
        if j["type"] == "prismatic":
            rho.append(1.0)
            continue
        pos = cb.index(j)
        rest = sum(vnorm(k["X"].p) for k in cb[pos + 1:])
        pris = sum(max(abs(k["upper"]), abs(k["lower"])) for k in cb[pos + 1:] if k["type"] == "prismatic")
        rho.append(rest + pris + reach_b)

    def dist(q):
        qmap = {j["name"]: v for j, v in zip(between, q)}
        X = robot.link_pose(lb, qmap, start=la)
        best = float("inf")
        for e1 in ea:
            a1, b1, r1 = e1.cap
            for e2 in eb:
                a2, b2, r2 = e2.cap
                best = min(best, seg_seg_dist(a1, b1, X.apply(a2), X.apply(b2)) - r1 - r2)
        return best

    stack = [[(j["lower"], j["upper"]) for j in between]]
    cells = 0
    while stack:
        cell = stack.pop()
        cells += 1
        if cells > max_cells:
            return ("unproved", "cell budget exhausted", cells)
        q = [(lo + hi) / 2 for lo, hi in cell]
        d = dist(q)
        if d <= 0:
            return ("overlap", q, cells)
        slack = sum(r * (hi - lo) / 2 for r, (lo, hi) in zip(rho, cell))
        if d - slack > MARGIN:
            continue
        k = max(range(len(cell)), key=lambda i: rho[i] * (cell[i][1] - cell[i][0]))
        lo, hi = cell[k]
        for half in ((lo, (lo + hi) / 2), ((lo + hi) / 2, hi)):
            c = list(cell); c[k] = half
            stack.append(c)
    return ("never", "%d joints" % len(between), cells)


def cmd_never(urdf, srdf):
    robot = Robot(urdf)
    disabled, _ = read_srdf(srdf)
    ok = True
    links = [l for l in robot.elements if robot.elements[l]]
    for i in range(len(links)):
        for k in range(i + 1, len(links)):
            pair = frozenset((links[i], links[k]))
            reason = disabled.get(pair)
            if reason == "Adjacent":
                continue
            verdict, info, cells = prove_never(robot, links[i], links[k])
            claimed = reason == "Never"
            flag = ""
            if claimed and verdict != "never":
                flag = "  <-- CLAIMED Never BUT NOT PROVED"
                ok = False
            elif not claimed and verdict == "never":
                flag = "  (could be disabled as Never)"
            if isinstance(info, list):
                info = "counterexample q=[%s]" % ", ".join("%.3f" % v for v in info)
            print("%-14s %-14s srdf=%-9s proof=%-9s %s cells=%d%s" % (
                links[i], links[k], reason or "-", verdict, info, cells, flag))
    # the adjacent claims must match the URDF tree (parent/child through fixed joints allowed)
    for pair, reason in disabled.items():
        a, b = sorted(pair)
        if reason == "Adjacent":
            ja, jb = robot.child_joint.get(a), robot.child_joint.get(b)
            if not ((ja and ja["parent"] == b) or (jb and jb["parent"] == a)):
                print("pair %s %s marked Adjacent but not parent/child" % (a, b)); ok = False
    print("never-check:", "OK" if ok else "FAILED")
    return ok


def qmap_from(names, values):
    return dict(zip(names, values))


def cmd_pose(urdf, srdf, values):
    robot = Robot(urdf)
    disabled, _ = read_srdf(srdf)
    qmap = qmap_from(robot.active, [float(v) for v in values])
    g, pair = self_clearance(robot, disabled, qmap)
    print("self clearance (outer capsules) %.4f m at %s" % (g, pair))
    return g > MARGIN


def cmd_scene(urdf, srdf, scene_path, request_path):
    import yaml
    robot = Robot(urdf)
    disabled, states = read_srdf(srdf)
    with open(scene_path) as f:
        scene = yaml.safe_load(f)
    with open(request_path) as f:
        req = yaml.safe_load(f)
    obbs = load_scene_obbs(scene)
    js = req["start_state"]["joint_state"]
    start = qmap_from(js["name"], js["position"])
    goal = {c["joint_name"]: c["position"] for c in req["goal_constraints"][0]["joint_constraints"]}
    rs = scene.get("robot_state", {}).get("joint_state", {})
    cases = [("start", start), ("goal", goal)]
    if rs.get("name"):
        cases.append(("scene robot_state", qmap_from(rs["name"], rs["position"])))
    ok = True
    for label, q in cases:
        for n in robot.active:
            j = robot.joints[n]
            if n not in q:
                print("%s: joint %s missing" % (label, n)); ok = False; continue
            if not (j["lower"] <= q[n] <= j["upper"]):
                print("%s: %s=%.4f outside [%.4f, %.4f]" % (label, n, q[n], j["lower"], j["upper"])); ok = False
        gs, ps = self_clearance(robot, disabled, q)
        gw, pw = world_clearance(robot, obbs, q)
        tcp = robot.link_pose("tcp", q).p if "tcp" in robot.elements else None
        print("%-17s self gap %.4f m (%s)  world gap %.4f m (%s)%s" % (
            label, gs, "%s/%s" % ps, gw, "%s/%s" % pw,
            "  tcp=[%.3f %.3f %.3f]" % tuple(tcp) if tcp else ""))
        if gs <= MARGIN or gw <= MARGIN:
            print("%s: NOT certified free" % label); ok = False
    names = robot.active
    first, last = None, None
    N = 200
    for i in range(N + 1):
        t = i / N
        q = {n: start[n] + t * (goal[n] - start[n]) for n in names}
        hits = inner_hits(robot, obbs, q)
        if hits:
            if first is None:
                first = (t, hits)
            last = (t, hits)
    if first is None:
        print("straight joint-space line: no certified collision found (planning may be unnecessary)")
        ok = False
    else:
        print("straight joint-space line: CERTAIN collision for t in [%.3f, %.3f] (sampled every %.3f), "
              "first witness %s" % (first[0], last[0], 1.0 / N, first[1][:3]))
    print("scene-check:", "OK" if ok else "FAILED")
    return ok


def main(argv):
    if len(argv) >= 4 and argv[1] == "never":
        return 0 if cmd_never(argv[2], argv[3]) else 1
    if len(argv) == 6 and argv[1] == "scene":
        return 0 if cmd_scene(*argv[2:6]) else 1
    if len(argv) >= 5 and argv[1] == "pose":
        return 0 if cmd_pose(argv[2], argv[3], argv[4:]) else 1
    print(__doc__)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv))
