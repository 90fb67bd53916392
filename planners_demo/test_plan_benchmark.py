#!/usr/bin/env python3
"""CTest plan_benchmark_log: dss_plan --benchmark writes OMPL benchmark logs that
ompl_benchmark_statistics (Debian package ompl-demos) loads into the SQLite database Planner
Arena reads, with one planner entry per checker and our extra per-run columns.

usage: test_plan_benchmark.py DSS_PLAN SOURCE_DIR WORK_DIR
"""
import json
import os
import shutil
import sqlite3
import subprocess
import sys

RUNS = 2
EXTRA_COLUMNS = ["validity_checks", "checking_time", "us_per_check", "invalid_states",
                 "narrow_phase_tests", "motion_checks"]
failures = []


def check(cond, what):
    print(("ok:   " if cond else "FAIL: ") + what)
    if not cond:
        failures.append(what)


def run(cmd, expect_ok=True):
    print("$ " + " ".join(cmd), flush=True)
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=300)
    if expect_ok and p.returncode != 0:
        sys.stderr.write(p.stdout + p.stderr)
        sys.exit("FAIL: exit code %d from %s" % (p.returncode, cmd[0]))
    return p


def load_db(stats, logs, db):
    if os.path.exists(db):
        os.remove(db)
    run([sys.executable, stats] + logs + ["-d", db])
    return sqlite3.connect(db)


def main():
    dss_plan, source_dir, work = sys.argv[1], sys.argv[2], sys.argv[3]
    stats = shutil.which("ompl_benchmark_statistics")
    if stats is None:
        sys.exit("FAIL: ompl_benchmark_statistics not found: install the Debian package ompl-demos "
                 "(apt-get install ompl-demos); it turns OMPL benchmark logs into the SQLite "
                 "database Planner Arena reads")
    os.makedirs(work, exist_ok=True)

    # 1. The default demo (our dss_arm7 in its shelf scene), default checkers dss,fcl-hull.
    log = os.path.join(work, "demo.log")
    p = run([dss_plan, "--benchmark", "--runs", str(RUNS), "--time", "1", "--log", log])
    lines = [json.loads(l) for l in p.stdout.splitlines() if l.startswith("{")]
    check([l["planner"] for l in lines] == ["geometric_RRTConnect[dss]", "geometric_RRTConnect[fcl-hull]"],
          "stdout: one summary per planner entry, in order: %s" % [l["planner"] for l in lines])
    check(all(l["runs"] == RUNS for l in lines), "stdout: %d runs per entry" % RUNS)

    con = load_db(stats, [log], os.path.join(work, "demo.db"))
    c = con.cursor()
    names = sorted(r[0] for r in c.execute("SELECT name FROM plannerConfigs"))
    check(names == ["geometric_RRTConnect[dss]", "geometric_RRTConnect[fcl-hull]"],
          "plannerConfigs: RRTConnect[dss] and RRTConnect[fcl-hull] (got %s)" % names)
    exp = c.execute("SELECT name, runcount, timelimit, dss_mode, dss_max_iterations, version "
                    "FROM experiments").fetchall()
    check(exp == [("dss_arm7/shelf", RUNS, 1.0, "exact", 64, "OMPL 1.5.2")], "experiments row: %s" % exp)
    columns = [r[1] for r in c.execute("PRAGMA table_info(runs)")]
    for col in EXTRA_COLUMNS + ["cap_hits"]:
        check(col in columns, "runs has column %s" % col)
    if failures:
        sys.exit("FAIL: %d check(s)" % len(failures))

    rows = c.execute(
        "SELECT p.name, r.solved, r.time, r.validity_checks, r.checking_time, r.us_per_check, "
        "r.invalid_states, r.narrow_phase_tests, r.motion_checks, r.cap_hits, r.correct_solution "
        "FROM runs r JOIN plannerConfigs p ON r.plannerid = p.id ORDER BY p.name, r.id").fetchall()
    print("database rows (planner, solved, time, validity_checks, checking_time, us_per_check, "
          "invalid_states, narrow_phase_tests, motion_checks, cap_hits, correct_solution):")
    for r in rows:
        print("  ", r)
    for name in names:
        mine = [r for r in rows if r[0] == name]
        check(len(mine) == RUNS, "%s: %d runs" % (name, RUNS))
        for r in mine:
            _, solved, t, checks, ctime, us, invalid, pairs, motions, caps, correct = r
            check(solved == 1 and correct == 1, "%s: solved, and the solution checks correct" % name)
            check(checks is not None and checks > 0, "%s: validity checks > 0 (%s)" % (name, checks))
            check(ctime is not None and 0 < ctime <= t, "%s: 0 < checking time <= run time (%s <= %s)"
                  % (name, ctime, t))
            check(us is not None and abs(us - ctime * 1e6 / checks) <= 1e-6 * us + 1e-9,
                  "%s: us per check = checking time / checks" % name)
            check(invalid is not None and 0 <= invalid <= checks, "%s: 0 <= invalid states <= checks" % name)
            check(pairs is not None and pairs > 0, "%s: narrow phase tests > 0 (%s)" % (name, pairs))
            check(motions is not None and motions > 0, "%s: motion checks > 0 (%s)" % (name, motions))
            if name.endswith("[dss]"):
                check(caps is not None and caps >= 0, "%s: cap hits recorded (%s)" % (name, caps))
            else:
                check(caps is None, "%s: no cap hits column value (not a DSS checker)" % name)

    # Paired seeds: run j of every entry samples the same states, so where the checkers agree
    # (they do on this scene) both entries make the same checks and find the same path.
    by_entry = {name: [r for r in rows if r[0] == name] for name in names}
    dss_rows, fcl_rows = by_entry["geometric_RRTConnect[dss]"], by_entry["geometric_RRTConnect[fcl-hull]"]
    check([r[3] for r in dss_rows] == [r[3] for r in fcl_rows],
          "paired seeds: run j makes the same number of validity checks under dss and fcl-hull (%s, %s)"
          % ([r[3] for r in dss_rows], [r[3] for r in fcl_rows]))

    # 2. Several problems: one log per problem, all loaded into one database; a planner list and
    #    the DSS options recorded.
    probs = os.path.join(work, "problems")
    os.makedirs(probs, exist_ok=True)
    arm = os.path.join(source_dir, "robots", "dss_arm7")
    for k in ("0001", "0002"):
        shutil.copy(os.path.join(arm, "scenes", "shelf.yaml"), os.path.join(probs, "scene%s.yaml" % k))
        shutil.copy(os.path.join(arm, "scenes", "shelf_request.yaml"), os.path.join(probs, "request%s.yaml" % k))
    base = os.path.join(work, "multi.log")
    run([dss_plan, "--benchmark", "--runs", "1", "--time", "1", "--log", base,
         "--robot", os.path.join(arm, "dss_arm7.urdf"), "--srdf", os.path.join(arm, "dss_arm7.srdf"),
         "--problems", probs, "--planner", "RRTConnect,RRT", "--checker", "dss",
         "--mode", "double", "--max-iterations", "32"])
    logs = [os.path.join(work, "multi.problems_%s.log" % k) for k in ("0001", "0002")]
    check(all(os.path.exists(l) for l in logs), "one log per problem: %s" % logs)
    con = load_db(stats, logs, os.path.join(work, "multi.db"))
    c = con.cursor()
    exp = c.execute("SELECT name, dss_mode, dss_max_iterations FROM experiments ORDER BY name").fetchall()
    check(exp == [("problems/0001", "double", 32), ("problems/0002", "double", 32)], "experiments: %s" % exp)
    n = c.execute("SELECT p.name, COUNT(*) FROM runs r JOIN plannerConfigs p ON r.plannerid = p.id "
                  "GROUP BY p.name ORDER BY p.name").fetchall()
    check(n == [("geometric_RRTConnect[dss]", 2), ("geometric_RRT[dss]", 2)], "runs per planner: %s" % n)

    # 3. Bad options: a clear message and a non-zero exit.
    for args, needle in [(["--benchmark", "--max-iterations", "0"], "--max-iterations"),
                         (["--benchmark", "--mode", "quad"], "--mode"),
                         (["--benchmark", "--runs", "2x"], "--runs"),
                         (["--benchmark", "--checker", "dss,bullet"], "unknown checker 'bullet'"),
                         (["--benchmark", "--checker", "dss,dss"], "listed twice"),
                         (["--checker", "dss,fcl-hull"], "needs --benchmark"),
                         (["--runs", "3"], "--runs needs --benchmark")]:
        p = run([dss_plan] + args, expect_ok=False)
        check(p.returncode != 0 and needle in p.stderr,
              "dss_plan %s: non-zero exit, message names '%s' (%s)" % (" ".join(args), needle,
                                                                       p.stderr.strip().splitlines()[0]
                                                                       if p.stderr.strip() else ""))

    if failures:
        sys.exit("FAIL: %d check(s)" % len(failures))
    print("all checks passed")


if __name__ == "__main__":
    main()
