#!/usr/bin/env python3
"""CTest plan_render_html and plan_render_browser: dss_plan --render writes one self-contained
HTML page replaying the plan (render_html.h).

  html     the page of the default problem (dss_arm7 in its shelf scene) refers to nothing
           outside itself and holds the path's states; an obstacle out of reach is marked
           pruned; a colliding motion has invalid stretches; --problems writes one page per
           problem; an unwritable file is a runtime error naming it; --render with
           --benchmark is a usage error.
  browser  headless Chromium screenshots of the page, checked pixel by pixel: the robot's
           orange covers a good part of the picture, the scene's blue is there, the picture is
           not uniform, the START badge (green) shows at first and the GOAL badge (purple) at
           #t=end with the robot elsewhere, and a page whose motion collides shows red at
           #t=collision. Exits 77 (CTest: skipped) when no Chromium is installed. The first
           screenshot is left in WORK_DIR/start.png (docs/figures/plan_render.png is one).

usage: test_render.py html|browser DSS_PLAN SOURCE_DIR WORK_DIR
"""
import base64
import json
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import zlib

SKIP = 77
failures = []


def check(cond, what):
    print(("ok:   " if cond else "FAIL: ") + what, flush=True)
    if not cond:
        failures.append(what)


def run(cmd, expect=0):
    print("$ " + " ".join(cmd), flush=True)
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=300)
    if expect is not None and p.returncode != expect:
        sys.stderr.write(p.stdout + p.stderr)
        sys.exit("FAIL: exit code %d (expected %d) from %s" % (p.returncode, expect, cmd[0]))
    return p


def page_data(html):
    m = re.search(r'<script type="application/json" id="dss-plan-data">(.*?)</script>', html, re.S)
    if not m:
        sys.exit("FAIL: no dss-plan-data block in the page")
    return json.loads(m.group(1))


def floats(b64):
    raw = base64.b64decode(b64)
    return struct.unpack("<%df" % (len(raw) // 4), raw)


def uints(b64):
    raw = base64.b64decode(b64)
    return struct.unpack("<%dI" % (len(raw) // 4), raw)


def first_json(stdout):
    return json.loads(next(l for l in stdout.splitlines() if l.startswith("{")))


# A start in free space and a goal inside the middle shelf board: the planner cannot reach
# the goal, so the page shows the straight start-goal motion with its invalid states in red.
COLLIDING_REQUEST = """\
start_state:
  joint_state:
    name: [joint1, joint2, joint3, joint4, joint5, joint6, joint7]
    position: [0, 0, 0, -1.6, 0, 1.6, 0]
goal_constraints:
  - joint_constraints:
%s
group_name: arm
"""


def colliding_request(path, goal):
    lines = "\n".join("      - {joint_name: joint%d, position: %r}" % (i + 1, v)
                      for i, v in enumerate(goal))
    with open(path, "w") as f:
        f.write(COLLIDING_REQUEST % lines)


def html_mode(dss_plan, source_dir, work):
    out = os.path.join(work, "plan.html")
    p = run([dss_plan, "--render", out])
    result = first_json(p.stdout)
    check(result["solved"], "the default problem is solved")
    with open(out, encoding="utf-8") as f:
        html = f.read()
    size = os.path.getsize(out)
    print("page: %s, %d bytes" % (out, size))
    check(size < 2_000_000, "the page is small (%d bytes < 2 MB)" % size)

    # Self-contained: nothing fetched from elsewhere when it is viewed.
    for needle in ["http://", "https://", "<link", "@import", "url(", "XMLHttpRequest", "fetch(",
                   "<iframe", "<img", "<object", "<embed"]:
        check(needle.lower() not in html.lower(), "the page holds no %r" % needle)
    check(re.search(r"\bsrc\s*=", html, re.I) is None, "the page holds no src= attribute")
    check(html.count("<script") == 2, "two inline scripts (data and viewer), no other")

    d = page_data(html)
    n = result["path_states"]
    check(n >= 2 and d["pathStates"] == n,
          "the page holds the path's %d states (dss_plan printed path_states %d)" % (d["pathStates"], n))
    t = floats(d["frames"]["t"])
    check(len(t) == d["frames"]["count"], "frame parameters: one per frame (%d)" % len(t))
    check(t[0] == 0 and t[-1] == n - 1 and all(a < b for a, b in zip(t, t[1:])),
          "frames run from state 0 to state %d, increasing" % (n - 1))
    check(all(float(k) in t for k in range(n)), "every path state is a frame")
    poses = floats(d["frames"]["poses"])
    check(len(poses) == 7 * len(d["links"]) * len(t), "frame poses: 7 floats per link per frame")
    check(d["solved"] and d["samplesInvalid"] == 0 and d["invalidSpans"] == [],
          "a solved path: no invalid state (%d checked)" % d["samplesChecked"])
    check(d["samplesChecked"] >= n, "every path state checked (%d samples)" % d["samplesChecked"])
    for s in d["shapes"]:
        v, tri = floats(s["v"]), uints(s["t"])
        if len(v) != 3 * s["vertices"] or len(tri) != 3 * s["triangles"] or \
                any(i >= s["vertices"] for i in tri):
            check(False, "shape data consistent: %s" % {k: s[k] for k in ("vertices", "triangles")})
            break
    else:
        check(True, "every shape's vertices and triangles consistent (%d shapes)" % len(d["shapes"]))
    check(all(s["triangles"] > 0 for s in d["shapes"]), "every shape has triangles")
    summary = re.search(r"kept (\d+) of (\d+) obstacles", p.stdout)
    kept = sum(o["kept"] for o in d["obstacles"])
    check(summary is not None and (kept, len(d["obstacles"])) == (int(summary.group(1)), int(summary.group(2))),
          "obstacles: %d kept of %d, as the model summary says (%s)"
          % (kept, len(d["obstacles"]), summary.group(0) if summary else "no summary"))
    check(len(d["elements"]) > 0 and len(d["links"]) > 0, "robot elements and links present")

    # --problems DIR: one page per problem, named FILE.<problem>.html.
    probs = os.path.join(work, "problems")
    os.makedirs(probs, exist_ok=True)
    arm = os.path.join(source_dir, "robots", "dss_arm7")
    for k in ("0001", "0002"):
        shutil.copy(os.path.join(arm, "scenes", "shelf.yaml"), os.path.join(probs, "scene%s.yaml" % k))
        shutil.copy(os.path.join(arm, "scenes", "shelf_request.yaml"), os.path.join(probs, "request%s.yaml" % k))
    robot = ["--robot", os.path.join(arm, "dss_arm7.urdf"), "--srdf", os.path.join(arm, "dss_arm7.srdf")]
    for f in os.listdir(work):
        if f.startswith("multi."):
            os.remove(os.path.join(work, f))
    p = run([dss_plan] + robot + ["--problems", probs, "--render", os.path.join(work, "multi.html")])
    pages = sorted(f for f in os.listdir(work) if f.startswith("multi."))
    check(pages == ["multi.problems_0001.html", "multi.problems_0002.html"],
          "--problems: one page per problem (%s)" % pages)
    for line, page in zip([l for l in p.stdout.splitlines() if l.startswith("{")], pages):
        with open(os.path.join(work, page), encoding="utf-8") as f:
            check(page_data(f.read())["pathStates"] == json.loads(line)["path_states"],
                  "%s holds its problem's path states" % page)

    # An obstacle out of the arm's reach: pruned from the collision model, on the page greyed.
    far_scene = os.path.join(work, "shelf_far_crate.yaml")
    with open(os.path.join(arm, "scenes", "shelf.yaml")) as f:
        text = f.read()
    with open(far_scene, "w") as f:
        f.write(text.rstrip("\n") + "\n" + FAR_CRATE)
    far_page = os.path.join(work, "far.html")
    p = run([dss_plan] + robot + ["--scene", far_scene, "--request",
                                  os.path.join(arm, "scenes", "shelf_request.yaml"), "--render", far_page])
    with open(far_page, encoding="utf-8") as f:
        d = page_data(f.read())
    pruned = [o["name"] for o in d["obstacles"] if not o["kept"]]
    check(pruned == ["far_crate", "far_plate", "far_wire"] and len(d["obstacles"]) == 14,
          "the out-of-reach obstacles are marked pruned, the 11 others kept (pruned: %s)" % pruned)
    by_name = {o["name"]: d["shapes"][o["shape"]] for o in d["obstacles"]}
    check(by_name["far_plate"]["triangles"] == 4,
          "a flat hull (a square) is drawn as its outline from both sides (%d triangles, 4 expected)"
          % by_name["far_plate"]["triangles"])
    check(by_name["far_wire"]["triangles"] == 0 and any("far_wire" in n for n in d["notes"]) and
          "far_wire" in p.stderr,
          "a hull with no area is listed in the page's notes and warned about (%s)" % d["notes"])

    # A motion that collides: invalid states found and marked.
    bad = os.path.join(work, "colliding_request.yaml")
    colliding_request(bad, COLLIDING_GOAL)
    bad_page = os.path.join(work, "colliding.html")
    p = run([dss_plan] + robot + ["--scene", os.path.join(arm, "scenes", "shelf.yaml"), "--request", bad,
                                   "--time", "0.2", "--render", bad_page], expect=3)
    with open(bad_page, encoding="utf-8") as f:
        d = page_data(f.read())
    check(not d["solved"] and d["samplesInvalid"] > 0 and len(d["invalidSpans"]) > 0,
          "an unsolvable problem: %d of %d checked states invalid, in %d stretches"
          % (d["samplesInvalid"], d["samplesChecked"], len(d["invalidSpans"])))
    # Each stretch with its cause: the colliding pairs at its first invalid state, which the
    # arm's reach into the shelf makes a link against a shelf board.
    causes = d.get("invalidCauses", [])
    check(len(causes) == len(d["invalidSpans"]) and
          all(c.startswith("link ") and " with " in c for c in causes) and
          any("scene object 'shelf_" in c for c in causes),
          "each invalid stretch names its colliding pairs (%s)" % causes[:3])

    # Errors: an unwritable file (runtime error, exit 1, naming it); with --benchmark (usage).
    missing = os.path.join(work, "no_such_dir", "plan.html")
    p = run([dss_plan, "--time", "1", "--render", missing], expect=None)
    check(p.returncode == 1 and missing in p.stderr,
          "unwritable file: exit 1 and a message naming it (%d: %s)" % (p.returncode, p.stderr.strip()[-200:]))
    p = run([dss_plan, "--benchmark", "--render", out], expect=None)
    check(p.returncode == 2 and "--render" in p.stderr, "--render with --benchmark: a usage error")
    p = run([dss_plan, "--help"])
    check("--render FILE" in p.stdout, "--help documents --render")


# Obstacles far behind the arm (appended to the shelf scene's collision objects): a crate, a
# flat plate and a wire (points on a line: no area to draw).
FAR_CRATE = """\
    - header:
        frame_id: world
      id: far_crate
      primitives:
        - type: box
          dimensions: [0.4, 0.4, 0.6]
      primitive_poses:
        - position: [-0.6, 1.9, 0.3]
          orientation: [0, 0, 0, 1]
    - header:
        frame_id: world
      id: far_plate
      meshes:
        - vertices: [[0, 0, 0], [0.3, 0, 0], [0.3, 0.3, 0], [0, 0.3, 0], [0.15, 0.15, 0]]
      mesh_poses:
        - position: [0.2, 1.9, 0.0]
          orientation: [0, 0, 0, 1]
    - header:
        frame_id: world
      id: far_wire
      meshes:
        - vertices: [[0, 0, 0], [0, 0, 0.2], [0, 0, 0.5]]
      mesh_poses:
        - position: [0.6, 1.9, 0.0]
          orientation: [0, 0, 0, 1]
"""

# The goal of the colliding request: the arm reaching into the middle shelf board.
COLLIDING_GOAL = [0.0, 1.2, 0.0, -0.9, 0.0, 0.5, 0.0]


# ---- PNG decoding (8-bit RGB/RGBA, not interlaced: what Chromium writes) ----
def read_png(path):
    with open(path, "rb") as f:
        raw = f.read()
    if raw[:8] != b"\x89PNG\r\n\x1a\n":
        sys.exit("FAIL: %s is not a PNG" % path)
    pos, idat, header = 8, b"", None
    while pos < len(raw):
        length, kind = struct.unpack(">I4s", raw[pos:pos + 8])
        body = raw[pos + 8:pos + 8 + length]
        pos += 12 + length
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        elif kind == b"IEND":
            break
    width, height, depth, colour, _, _, interlace = header
    if depth != 8 or colour not in (2, 6) or interlace:
        sys.exit("FAIL: %s: unsupported PNG (depth %d, colour type %d, interlace %d)"
                 % (path, depth, colour, interlace))
    bpp = 3 if colour == 2 else 4
    stride = width * bpp
    data = zlib.decompress(idat)
    rows, prev = [], bytearray(stride)
    for y in range(height):
        ftype = data[y * (stride + 1)]
        line = bytearray(data[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b = prev[i]
            c = prev[i - bpp] if i >= bpp else 0
            if ftype == 1:
                line[i] = (line[i] + a) & 255
            elif ftype == 2:
                line[i] = (line[i] + b) & 255
            elif ftype == 3:
                line[i] = (line[i] + ((a + b) >> 1)) & 255
            elif ftype == 4:
                pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        prev = line
    pixels = []
    for line in rows:
        pixels.extend(tuple(line[i:i + 3]) for i in range(0, stride, bpp))
    return width, height, pixels


def hue(p):
    r, g, b = p
    mx, mn = max(p), min(p)
    if mx == mn:
        return None
    if mx == r:
        h = 60.0 * (g - b) / (mx - mn)
    elif mx == g:
        h = 60.0 * (b - r) / (mx - mn) + 120
    else:
        h = 60.0 * (r - g) / (mx - mn) + 240
    return h % 360


def saturated(p, lo, hi, min_sat=0.45, min_max=50):
    mx = max(p)
    if mx < min_max or (mx - min(p)) < min_sat * mx:
        return False
    h = hue(p)
    return h is not None and lo <= h <= hi


# The page's colours (render_viewer.html): robot orange (240, 140, 30) shaded, hue 31 degrees;
# invalid red (215, 30, 30), hue 0; kept obstacles (86, 120, 168), hue 215; START badge
# #1e9e46, GOAL badge #6b3fb6.
def robot(p):
    return saturated(p, 22, 40)


def red(p):
    return saturated(p, 0, 6) or saturated(p, 354, 360)


def blue(p):
    return saturated(p, 205, 225, min_sat=0.3)


def exact(rgb, tol=6):
    return lambda p: all(abs(a - b) <= tol for a, b in zip(p, rgb))


START_GREEN = exact((0x1E, 0x9E, 0x46))
GOAL_PURPLE = exact((0x6B, 0x3F, 0xB6))


def find_chromium():
    for name in ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable"):
        path = shutil.which(name)
        if path:
            return path
    return None


def screenshot(chromium, page, fragment, png):
    if os.path.exists(png):
        os.remove(png)
    profile = tempfile.mkdtemp(prefix="dss_render_chromium_")
    try:
        cmd = [chromium, "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
               "--no-first-run", "--disable-background-networking", "--disable-component-update",
               "--disable-sync", "--hide-scrollbars", "--user-data-dir=" + profile,
               "--screenshot=" + png, "--window-size=800,600",
               "file://" + os.path.abspath(page) + fragment]
        print("$ " + " ".join(cmd), flush=True)
        p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=180)
        if p.returncode != 0 or not os.path.exists(png):
            sys.stderr.write(p.stdout + p.stderr)
            sys.exit("FAIL: chromium exit code %d, screenshot %s" % (p.returncode, png))
    finally:
        shutil.rmtree(profile, ignore_errors=True)
    return read_png(png)


def browser_mode(dss_plan, source_dir, work):
    chromium = find_chromium()
    if chromium is None:
        print("SKIPPED: no chromium found (install the Debian package chromium)")
        sys.exit(SKIP)
    page = os.path.join(work, "plan.html")
    run([dss_plan, "--render", page])

    w, h, start = screenshot(chromium, page, "", os.path.join(work, "start.png"))
    total = w * h
    check(w >= 700 and h >= 500, "screenshot %d x %d" % (w, h))
    frac = lambda pixels, test: sum(1 for p in pixels if test(p)) / float(total)
    robot_start = frac(start, robot)
    check(robot_start >= 0.02, "start: %.1f%% of the pixels are the robot's orange (>= 2%%)" % (100 * robot_start))
    check(frac(start, blue) >= 0.01, "start: the kept obstacles' blue is there (%.1f%%)" % (100 * frac(start, blue)))
    colours = len(set((r >> 3, g >> 3, b >> 3) for r, g, b in start))
    lum = [0.299 * r + 0.587 * g + 0.114 * b for r, g, b in start]
    mean = sum(lum) / total
    spread = (sum((x - mean) ** 2 for x in lum) / total) ** 0.5
    check(colours >= 40 and spread >= 8, "start: not a blank picture (%d colours, luminance spread %.1f)"
          % (colours, spread))
    green = sum(1 for p in start if START_GREEN(p))
    check(green >= 300, "start: the START badge shows (%d green pixels)" % green)
    check(sum(1 for p in start if GOAL_PURPLE(p)) < 50, "start: no GOAL badge")
    check(frac(start, red) < 0.001, "start: nothing red (a valid path)")

    _, _, end = screenshot(chromium, page, "#t=end", os.path.join(work, "end.png"))
    robot_end = frac(end, robot)
    check(robot_end >= 0.02, "end: %.1f%% of the pixels are the robot's orange" % (100 * robot_end))
    check(sum(1 for p in end if GOAL_PURPLE(p)) >= 300, "end: the GOAL badge shows")
    check(sum(1 for p in end if START_GREEN(p)) < 50, "end: no START badge")
    moved = sum(1 for a, b in zip(start, end) if robot(a) != robot(b)) / float(total)
    check(moved >= 0.005, "the robot is elsewhere at the goal (%.1f%% of the pixels changed robot/not robot)"
          % (100 * moved))

    bad_page = os.path.join(work, "colliding.html")
    arm = os.path.join(source_dir, "robots", "dss_arm7")
    bad = os.path.join(work, "colliding_request.yaml")
    colliding_request(bad, COLLIDING_GOAL)
    run([dss_plan, "--robot", os.path.join(arm, "dss_arm7.urdf"), "--srdf", os.path.join(arm, "dss_arm7.srdf"),
         "--scene", os.path.join(arm, "scenes", "shelf.yaml"), "--request", bad, "--time", "0.2",
         "--render", bad_page], expect=3)
    _, _, hit = screenshot(chromium, bad_page, "#t=collision", os.path.join(work, "collision.png"))
    red_hit = frac(hit, red)
    check(red_hit >= 0.01, "collision: %.1f%% of the pixels are red (the robot in an invalid state)"
          % (100 * red_hit))
    check(frac(hit, robot) < 0.002, "collision: the robot is drawn red, not orange")


def main():
    if len(sys.argv) != 5 or sys.argv[1] not in ("html", "browser"):
        sys.exit(__doc__)
    mode, dss_plan, source_dir, work = sys.argv[1:]
    os.makedirs(work, exist_ok=True)
    (html_mode if mode == "html" else browser_mode)(dss_plan, source_dir, work)
    if failures:
        sys.exit("FAIL: %d check(s)" % len(failures))
    print("all checks passed")


if __name__ == "__main__":
    main()
