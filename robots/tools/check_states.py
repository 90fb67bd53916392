#!/usr/bin/env python3
"""Clearance of the start and goal of a request whose robot moves on an SRDF planar or
floating virtual joint (stdlib + PyYAML; independent of the dss library).

Usage (from the repository root):
  python3 robots/tools/check_states.py URDF SRDF SCENE REQUEST [MIN_GAP]
e.g.
  python3 robots/tools/check_states.py robots/dss_mobile_base/dss_mobile_base.urdf \
      robots/dss_mobile_base/dss_mobile_base.srdf robots/dss_mobile_base/scenes/aisle.yaml \
      robots/dss_mobile_base/scenes/aisle_request.yaml

The base pose comes from the request: start_state.multi_dof_joint_state (planar: x, y and the
yaw of the transform) and the goal's joint constraints (base/x, base/y, base/theta or
base/trans_x ... base/rot_w). Every robot collision element and every obstacle primitive is
replaced by an oriented box that contains it (cylinder: its bounding box; sphere: a cube;
mesh: the box of its vertices in the element frame). The gap of two boxes is bounded from
below by the largest gap between their projections on the 15 separating axes, so every gap
printed is a lower bound of the true distance. Checked: robot vs obstacles, robot vs itself
(link pairs the SRDF does not disable), joint limits, base inside the workspace. Also reports
whether the straight interpolation start -> goal certainly collides (the centre of a robot
element's box inside an obstacle primitive itself, a box, cylinder or sphere; that centre lies
inside the element for boxes, cylinders, spheres and our meshes, which are symmetric about it). Exit status 0 when every gap is at
least MIN_GAP (default 0.03 m) and every state is within limits and the workspace.
"""
import math
import os
import struct
import sys
import xml.etree.ElementTree as ET

import yaml

ROT = ["rot_x", "rot_y", "rot_z", "rot_w"]


def mat(R, v):
    return [sum(R[i][k] * v[k] for k in range(3)) for i in range(3)]


def mmul(A, B):
    return [[sum(A[i][k] * B[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


def compose(X, Y):  # poses are (R, p)
    return mmul(X[0], Y[0]), [a + b for a, b in zip(mat(X[0], Y[1]), X[1])]


def rpy(r, p, y):
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return [[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr], [-sp, cp * sr, cp * cr]]


def quat(q):  # [x, y, z, w], normalised here
    n = math.sqrt(sum(c * c for c in q))
    x, y, z, w = (c / n for c in q)
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]


def axis_angle(a, t):
    n = math.sqrt(sum(c * c for c in a))
    x, y, z = (c / n for c in a)
    c, s, C = math.cos(t), math.sin(t), 1 - math.cos(t)
    return [[c + x * x * C, x * y * C - z * s, x * z * C + y * s],
            [y * x * C + z * s, c + y * y * C, y * z * C - x * s],
            [z * x * C - y * s, z * y * C + x * s, c + z * z * C]]


def origin(el):
    o = el.find("origin")
    f = lambda k, d: [float(v) for v in (o.get(k, d) if o is not None else d).split()]
    return rpy(*f("rpy", "0 0 0")), f("xyz", "0 0 0")


def stl_box(path):  # (centre, half extents) of the vertices of a binary STL
    data = open(path, "rb").read()
    n = struct.unpack_from("<I", data, 80)[0]
    v = [struct.unpack_from("<3f", data, 84 + 50 * i + 12 * (k + 1)) for i in range(n) for k in range(3)]
    lo, hi = [min(p[i] for p in v) for i in range(3)], [max(p[i] for p in v) for i in range(3)]
    return [(a + b) / 2 for a, b in zip(lo, hi)], [(b - a) / 2 for a, b in zip(lo, hi)]


def load_robot(urdf):
    root, base = ET.parse(urdf).getroot(), os.path.dirname(os.path.abspath(urdf))
    elements = []  # (link, name, pose in link, half extents)
    for link in root.findall("link"):
        for i, col in enumerate(link.findall("collision")):
            X, g = origin(col), col.find("geometry")[0]
            if g.tag == "box":
                h = [float(s) / 2 for s in g.get("size").split()]
            elif g.tag == "cylinder":
                h = [float(g.get("radius"))] * 2 + [float(g.get("length")) / 2]
            elif g.tag == "sphere":
                h = [float(g.get("radius"))] * 3
            else:
                c, h = stl_box(os.path.join(base, g.get("filename")))
                X = compose(X, (rpy(0, 0, 0), c))
            name = col.get("name", "%s#%d" % (link.get("name"), i))
            elements.append((link.get("name"), name, X, h))
    joints = {}
    for j in root.findall("joint"):
        lim, ax, kind = j.find("limit"), j.find("axis"), j.get("type")
        joints[j.find("child").get("link")] = dict(
            name=j.get("name"), type=kind, parent=j.find("parent").get("link"), X=origin(j),
            axis=[float(v) for v in (ax.get("xyz") if ax is not None else "1 0 0").split()],
            limits=(float(lim.get("lower")), float(lim.get("upper")))
            if kind in ("revolute", "prismatic") else None)
    return elements, joints


def link_pose(link, joints, base, q):
    if link not in joints:
        return base
    j = joints[link]
    X = compose(link_pose(j["parent"], joints, base, q), j["X"])
    v = q.get(j["name"], 0.0)
    if j["type"] in ("revolute", "continuous"):
        return compose(X, (axis_angle(j["axis"], v), [0, 0, 0]))
    if j["type"] == "prismatic":
        return compose(X, (rpy(0, 0, 0), [a * v for a in j["axis"]]))
    return X


def gap(A, B):
    """Lower bound of the distance of oriented boxes A, B = (R, centre, half extents)."""
    (Ra, ca, ha), (Rb, cb, hb) = A, B
    cols = lambda R: [[R[i][k] for i in range(3)] for k in range(3)]
    ua, ub = cols(Ra), cols(Rb)
    cross = lambda a, b: [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
    d, best = [b - a for a, b in zip(ca, cb)], -float("inf")
    for ax in ua + ub + [cross(a, b) for a in ua for b in ub]:
        n = math.sqrt(sum(c * c for c in ax))
        if n < 1e-9:
            continue
        dot = lambda u: abs(sum(x * y for x, y in zip(u, ax))) / n
        reach = sum(h * dot(u) for h, u in zip(ha + hb, ua + ub))
        best = max(best, dot(d) - reach)
    return best


def inside(typ, local, h):
    """Whether a point (in the obstacle's frame) lies in the obstacle itself (h: obstacles())."""
    x, y, z = local
    if typ == "box":
        return all(abs(v) <= e for v, e in zip(local, h))
    if typ == "cylinder":
        return x * x + y * y <= h[0] * h[0] and abs(z) <= h[2]
    return x * x + y * y + z * z <= h[0] * h[0]  # sphere


def obstacles(scene):
    out = []
    for obj in scene["world"]["collision_objects"]:
        P = obj.get("pose", {"position": [0, 0, 0], "orientation": [0, 0, 0, 1]})
        X0 = (quat(P["orientation"]), list(P["position"]))
        for prim, pp in zip(obj["primitives"], obj["primitive_poses"]):
            R, c = compose(X0, (quat(pp["orientation"]), list(pp["position"])))
            d = prim["dimensions"]
            if prim["type"] == "box":
                h = [x / 2 for x in d]
            elif prim["type"] == "cylinder":
                h = [d[1], d[1], d[0] / 2]
            elif prim["type"] == "sphere":
                h = [d[0]] * 3
            else:
                raise ValueError(f"object {obj['id']}: unsupported primitive {prim['type']}")
            out.append((obj["id"], prim["type"], (R, c, h)))
    return out


def base_pose(kind, v):
    if kind == "planar":
        return rpy(0, 0, v["theta"]), [v["x"], v["y"], 0.0]
    return quat([v[k] for k in ROT]), [v["trans_x"], v["trans_y"], v["trans_z"]]


def from_transform(kind, t):
    (x, y, z), (qx, qy, qz, qw) = t["translation"], t["rotation"]
    if kind == "planar":  # MoveIt keeps x, y and the yaw
        return {"x": x, "y": y, "theta": math.atan2(2 * (qw * qz + qx * qy), 1 - 2 * (qy * qy + qz * qz))}
    return dict(zip(["trans_x", "trans_y", "trans_z"] + ROT, [x, y, z, qx, qy, qz, qw]))


def interpolate(kind, a, b, t):  # straight line of the group state (shortest angle / slerp)
    out = {k: a[k] + t * (b[k] - a[k]) for k in a}
    if kind == "planar":
        out["theta"] = a["theta"] + t * math.remainder(b["theta"] - a["theta"], 2 * math.pi)
    elif kind == "floating":
        qa, qb = [a[k] for k in ROT], [b[k] for k in ROT]
        c = sum(x * y for x, y in zip(qa, qb))
        qb, c = ([-x for x in qb], -c) if c < 0 else (qb, c)
        w = math.acos(min(1.0, c))
        s = [1 - t, t] if w < 1e-9 else [math.sin((1 - t) * w) / math.sin(w), math.sin(t * w) / math.sin(w)]
        out.update(zip(ROT, [s[0] * x + s[1] * y for x, y in zip(qa, qb)]))
    return out


def vj_values(vj, state):  # {"x": ...} from {"base/x": ...}
    return {k.split("/", 1)[1]: v for k, v in state.items() if k.startswith(vj + "/")}


def world_boxes(elements, joints, vj, kind, state):
    base = base_pose(kind, vj_values(vj, state))
    out = []
    for link, name, X, h in elements:
        R, c = compose(link_pose(link, joints, base, state), X)
        out.append((link, name, (R, c, h)))
    return out


def main(urdf, srdf, scene_path, request_path, min_gap=0.03):
    elements, joints = load_robot(urdf)
    s = ET.parse(srdf).getroot()
    vj_el = s.find("virtual_joint")
    vj, kind = vj_el.get("name"), vj_el.get("type")
    disabled = {frozenset((d.get("link1"), d.get("link2"))) for d in s.findall("disable_collisions")}
    scene, req = yaml.safe_load(open(scene_path)), yaml.safe_load(open(request_path))
    obs = obstacles(scene)
    lo, hi = req["workspace_parameters"]["min_corner"], req["workspace_parameters"]["max_corner"]

    def state_of(rs):
        js = rs.get("joint_state", {})
        q = dict(zip(js.get("name", []), js.get("position", [])))
        md = rs["multi_dof_joint_state"]
        for n, t in zip(md["joint_names"], md["transforms"]):
            q.update({n + "/" + k: v for k, v in from_transform(kind, t).items()})
        return q

    goal = {c["joint_name"]: c["position"] for c in req["goal_constraints"][0]["joint_constraints"]}
    start = state_of(req["start_state"])
    cases = [("start", start), ("goal", goal), ("scene robot_state", state_of(scene["robot_state"]))]
    ok = True
    for label, q in cases:
        for j in joints.values():
            if j["limits"] and not j["limits"][0] <= q[j["name"]] <= j["limits"][1]:
                print("%s: %s = %g outside its limits" % (label, j["name"], q[j["name"]])); ok = False
        axes = ["x", "y"] if kind == "planar" else ["trans_x", "trans_y", "trans_z"]
        margin = min(min(q[vj + "/" + a] - lo[i], hi[i] - q[vj + "/" + a]) for i, a in enumerate(axes))
        boxes = world_boxes(elements, joints, vj, kind, q)
        w = min((gap(b, o), n, oid) for _, n, b in boxes for oid, _, o in obs)
        pairs = [(gap(b1, b2), n1, n2) for i, (l1, n1, b1) in enumerate(boxes)
                 for l2, n2, b2 in boxes[i + 1:] if l1 != l2 and frozenset((l1, l2)) not in disabled]
        sg = min(pairs) if pairs else (float("inf"), "-", "-")
        print("%-17s world gap >= %.4f m (%s / %s)  self gap >= %.4f m (%s / %s)  "
              "workspace margin %.3f m" % (label, *w, *sg, margin))
        ok = ok and w[0] >= min_gap and sg[0] >= min_gap and margin >= 0
    hits = []
    for t in (i / 200 for i in range(201)):
        q = {k: start[k] + t * (goal[k] - start[k]) for k in goal if "/" not in k}
        m = interpolate(kind, vj_values(vj, start), vj_values(vj, goal), t)
        q.update({vj + "/" + k: v for k, v in m.items()})
        for _, n, (R, c, h) in world_boxes(elements, joints, vj, kind, q):
            for oid, typ, (Ro, co, ho) in obs:
                local = [sum(Ro[k][i] * (c[k] - co[k]) for k in range(3)) for i in range(3)]
                if inside(typ, local, ho):
                    hits.append((t, n, oid))
    print("straight line start -> goal: " + (
        "certainly collides for t in [%.3f, %.3f] (first: %s in %s)" % (hits[0][0], hits[-1][0], *hits[0][1:])
        if hits else "no certain collision found"))
    print("check:", "OK" if ok else "FAILED")
    return ok


if __name__ == "__main__":
    if len(sys.argv) not in (5, 6):
        sys.exit(__doc__)
    sys.exit(0 if main(*sys.argv[1:5], *[float(v) for v in sys.argv[5:]]) else 1)
