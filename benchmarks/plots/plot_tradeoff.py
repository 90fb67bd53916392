#!/usr/bin/env python3
"""Pareto plots of `dss_bench tradeoff` output: cost against accuracy, one point per setting.

Reads the CSV written by `dss_bench tradeoff --csv FILE` (one row per robot x setting) and
writes, per robot found in it:

  tradeoff_<robot>.png   four panels: cost per state (us, log) against the missed-collision
                         rate and against the false-alarm rate of states; cost per motion
                         against the missed and false-alarm rates of motions. One labelled
                         point per setting, coloured by the axis it varies; the points on the
                         Pareto front (no other setting both cheaper and more accurate) are
                         joined by a line.

With --summary FILE, also writes the per-robot tables as Markdown (what docs/tradeoff.md shows).

Rates: missed = missed / truth-colliding, false alarms = false alarms / truth-free (percent;
a symlog axis so that 0 stays visible). The command that produced the data is in the footer.
Uses the Agg backend. Exits non-zero when the CSV is missing or has no rows.
"""
import argparse
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

AXIS_STYLE = {
    "default": ("#000000", "*"),
    "geometry": ("#d62728", "o"),
    "arithmetic": ("#1f77b4", "s"),
    "padding": ("#2ca02c", "^"),
    "cap": ("#9467bd", "v"),
    "motion": ("#ff7f0e", "D"),
    "combination": ("#8c564b", "P"),
}
ROBOT_TITLE = {
    "panda": "Franka Panda (MBM scenes)",
    "ur5": "UR5 + Robotiq 2F-85 (MBM scenes)",
    "iiwa": "KUKA iiwa 14 (in MBM Panda scenes)",
}


def rate(k, n):
    return 100.0 * k / n if n > 0 else float("nan")


def pareto(points):
    """Indices of points (cost, error) on the lower-left front."""
    order = sorted(range(len(points)), key=lambda i: (points[i][0], points[i][1]))
    front, best = [], float("inf")
    for i in order:
        if points[i][1] < best:
            front.append(i)
            best = points[i][1]
    return front


def panel(ax, rows, cost_key, num_key, den_key, xlabel, ylabel, skip_motion_axis=False):
    pts = []
    for r in rows:
        if skip_motion_axis and r["axis"] == "motion":
            continue  # same state checker as the default: a duplicate point
        cost = float(r[cost_key] or 0)
        num = int(r[num_key] or 0)
        den = int(r[den_key] or 0)
        if cost <= 0 or den <= 0:
            continue
        pts.append((cost, rate(num, den), r))
    # Points that fall close together share one label (names joined), so that it stays readable.
    clusters = []
    for cost, err, r in sorted(pts, key=lambda p: p[0]):
        color, marker = AXIS_STYLE.get(r["axis"], ("#7f7f7f", "x"))
        ax.scatter([cost], [err], c=color, marker=marker, s=60 if r["axis"] == "default" else 34, zorder=3,
                   edgecolors="none")
        lx, ly = math.log10(cost), math.copysign(math.log10(1 + abs(err) / 0.1), err)
        for c in clusters:
            if abs(c["x"] - lx) < 0.15 and abs(c["y"] - ly) < 0.15:
                c["names"].append(r["setting"])
                break
        else:
            clusters.append({"x": lx, "y": ly, "cost": cost, "err": err, "names": [r["setting"]], "color": color})
    for c in clusters:
        words, lines = c["names"], [""]
        for w in words:
            if lines[-1] and len(lines[-1]) + len(w) > 34:
                lines.append("")
            lines[-1] += (", " if lines[-1] else "") + w
        color = c["color"] if len(words) == 1 else "#333333"
        ax.annotate("\n".join(lines), (c["cost"], c["err"]), textcoords="offset points", xytext=(4, 3),
                    fontsize=6.3, color=color, va="bottom")
    if pts:
        front = pareto([(c, e) for c, e, _ in pts])
        ax.plot([pts[i][0] for i in front], [pts[i][1] for i in front], "-", color="#bbbbbb", lw=1, zorder=1)
    ax.set_xscale("log")
    ax.set_yscale("symlog", linthresh=0.1)
    top = max([e for _, e, _ in pts] + [1.0])
    ax.set_ylim(-0.02, min(100.0, top) * 6)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.grid(True, which="both", alpha=0.3)
    if not pts:
        ax.text(0.5, 0.5, "no data", transform=ax.transAxes, ha="center")


def plot_robot(robot, rows, out, command, note):
    r0 = rows[0]
    fig, axes = plt.subplots(2, 2, figsize=(13, 9.5))
    panel(axes[0][0], rows, "us_per_state", "state_missed", "truth_colliding_states", "cost per state (us, thread CPU, log)",
          "missed collisions (% of truth-colliding states)", skip_motion_axis=True)
    truth_free = [dict(r, truth_free_states=str(int(r["states"]) - int(r["truth_colliding_states"]))) for r in rows]
    panel(axes[0][1], truth_free, "us_per_state", "state_false_alarms", "truth_free_states",
          "cost per state (us, thread CPU, log)", "false alarms (% of truth-free states)", skip_motion_axis=True)
    panel(axes[1][0], rows, "us_per_motion", "motion_missed", "truth_colliding_motions",
          "cost per motion (us, thread CPU, log)", "missed collisions (% of truth-colliding motions)")
    truth_free_m = [dict(r, truth_free_motions=str(int(r["motions"]) - int(r["truth_colliding_motions"]))) for r in rows]
    panel(axes[1][1], truth_free_m, "us_per_motion", "motion_false_alarms", "truth_free_motions",
          "cost per motion (us, thread CPU, log)", "false alarms (% of truth-free motions)")
    axes[0][0].set_title("states: safety (missed collisions)", fontsize=10)
    axes[0][1].set_title("states: conservatism (false alarms)", fontsize=10)
    axes[1][0].set_title("motions: safety", fontsize=10)
    axes[1][1].set_title("motions: conservatism", fontsize=10)
    handles = [plt.Line2D([], [], color=c, marker=m, ls="", label=a) for a, (c, m) in AXIS_STYLE.items()]
    handles.append(plt.Line2D([], [], color="#bbbbbb", label="Pareto front"))
    fig.legend(handles=handles, loc="upper right", fontsize=8, ncol=4, bbox_to_anchor=(0.99, 0.995))
    fig.suptitle(
        f"{ROBOT_TITLE.get(robot, robot)}: cost vs accuracy against the exact-mesh truth\n"
        f"{r0['states']} states ({r0['truth_colliding_states']} colliding), {r0['motions']} motions "
        f"({r0['truth_colliding_motions']} colliding), {r0['scenes']} scenes; motion truth sampled at "
        f"{float(r0['delta_m']) * 1e3:g} mm",
        fontsize=11, x=0.02, ha="left")
    footer = f"command: {command}"
    if note:
        footer += f"\n{note}"
    footer += ("\ndefault = hull, exact, cap 64, no padding, discrete motion checks at 1 % of the extent; "
               "every other point changes one axis (or the combination named); rates on a symlog axis (0 stays visible)")
    fig.text(0.01, 0.005, footer, fontsize=7, family="monospace", va="bottom")
    fig.tight_layout(rect=(0, 0.06, 1, 0.93))
    path = os.path.join(out, f"tradeoff_{robot}.png")
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def pct(k, n):
    if n <= 0:
        return "-"
    v = 100.0 * k / n
    return "0" if k == 0 else (f"{v:.3f} %" if v < 0.1 else f"{v:.2f} %")


def summary(rows, path):
    robots = []
    for r in rows:
        if r["robot"] not in robots:
            robots.append(r["robot"])
    out = []
    for robot in robots:
        rr = [r for r in rows if r["robot"] == robot]
        r0 = rr[0]
        ns, nsc = int(r0["states"]), int(r0["truth_colliding_states"])
        nm, nmc = int(r0["motions"]), int(r0["truth_colliding_motions"])
        out.append(f"### {ROBOT_TITLE.get(robot, robot)}\n")
        out.append(f"{ns} states ({nsc} colliding in the truth), {nm} motions ({nmc} colliding), "
                   f"{r0['scenes']} scenes; `{r0['command']}`\n")
        out.append("| setting | model | us/state | missed | false alarms | cap hits | us/motion | missed (motions) "
                   "| false alarms (motions) | plans solved | median plan ms (CPU) | solved paths colliding in truth |")
        out.append("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
        for r in rr:
            st, sc = int(r["states"]), int(r["truth_colliding_states"])
            mo, mc = int(r["motions"]), int(r["truth_colliding_motions"])
            miss = f"{r['state_missed']} ({pct(int(r['state_missed']), sc)})"
            if int(r["fcl_gap_claims"] or 0):
                miss += f" [{r['fcl_gap_claims']} FCL at a certified gap]"
            fa = f"{r['state_false_alarms']} ({pct(int(r['state_false_alarms']), st - sc)})"
            mm = f"{r['motion_missed']} ({pct(int(r['motion_missed']), mc)})"
            mf = f"{r['motion_false_alarms']} ({pct(int(r['motion_false_alarms']), mo - mc)})"
            plan = "-" if not r["plan_problems"] else f"{r['plan_solved']}/{r['plan_problems']}"
            pv = float(r["plan_median_cpu_ms"] or "nan")
            pms = "-" if not r["plan_problems"] else (f"{pv:.1f}" if math.isfinite(pv) else "failed (median)")
            bad = "-" if not r["plan_problems"] else r["plan_paths_truth_colliding"]
            model = os.path.basename(r["model"])
            out.append(f"| {r['setting']} | {model} | {float(r['us_per_state']):.2f} | {miss} | {fa} | {r['state_cap_hits']} "
                       f"| {float(r['us_per_motion']):.1f} | {mm} | {mf} | {plan} | {pms} | {bad} |")
        out.append("")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--data", required=True, help="CSV from dss_bench tradeoff --csv")
    ap.add_argument("--out", required=True, help="folder for the PNGs")
    ap.add_argument("--note", default="", help="run note for the footer")
    ap.add_argument("--summary", default="", help="also write the tables as Markdown to this file")
    args = ap.parse_args()
    if not os.path.isfile(args.data):
        print(f"plot_tradeoff.py: {args.data}: not found", file=sys.stderr)
        return 1
    with open(args.data, newline="") as f:
        rows = list(csv.DictReader(f))
    os.makedirs(args.out, exist_ok=True)
    if not rows:
        # A run without the shared robots writes a header only: nothing to draw, not an error.
        print(f"plot_tradeoff.py: {args.data}: no rows (robots skipped), no figure drawn")
        return 0
    robots = []
    for r in rows:
        if r["robot"] not in robots:
            robots.append(r["robot"])
    for robot in robots:
        rr = [r for r in rows if r["robot"] == robot]
        print(plot_robot(robot, rr, args.out, rr[0]["command"], args.note))
    if args.summary:
        summary(rows, args.summary)
        print(args.summary)
    return 0


if __name__ == "__main__":
    sys.exit(main())
