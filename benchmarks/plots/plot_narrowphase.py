#!/usr/bin/env python3
"""Draws the paper's narrow-phase figures (Hornus 2017, section 6) from dss_bench output.

Reads the CSV or JSON written by `dss_bench narrowphase --csv/--json` (optionally with
`--sweep`) and the JSON lines written by `dss_bench failure-rate --json`, and writes PNGs:

  narrowphase_<workload>.png   per workload: pairs per second, mean and maximum plane tests
                               (support evaluations) and failure rate against collision density
  narrowphase_speedup.png      DSS and Hybrid speed over GJK against density, all workloads
  narrowphase_sweep.png        the vertex-count sweep at ~50 % density (hill-climb vs scan)
  failure_rate.png             cap hits and wrong answers of DSS, GJK, Hybrid in float against
                               density (failure-rate runs), the long run marked
  failure_rate_iterations.png  histogram of plane tests per pair in the long run

Every figure carries the command that produced its data in a footer. Uses the Agg backend:
no display needed. Exits non-zero when an input is missing or holds no usable rows.
"""
import argparse
import csv
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402

WORKLOADS = [
    ("tetra", "random tetrahedra"),
    ("boxes", "oriented boxes"),
    ("poly16", "16-vertex polytopes"),
    ("frustum-spheres", "frustum vs spheres"),
    ("frustum-boxes", "frustum vs axis-aligned boxes"),
]

# One colour and marker per algorithm, the same in every figure.
STYLE = {
    "dss-exact": ("#1f77b4", "o", "-"),
    "dss-double": ("#2ca02c", "s", "-"),
    "dss-float": ("#17becf", "^", "-"),
    "gjk": ("#d62728", "v", "-"),
    "hybrid": ("#9467bd", "D", "-"),
    "fcl-convex": ("#8c564b", "x", "--"),
    "fcl-box": ("#e377c2", "+", "--"),
    "ccd-gjk": ("#7f7f7f", "<", ":"),
    "ccd-mpr": ("#bcbd22", ">", ":"),
    "dss-exact-scan": ("#1f77b4", "o", "--"),
    "dss-double-scan": ("#2ca02c", "s", "--"),
    "dss-float": ("#17becf", "^", "-"),
    "gjk-float": ("#d62728", "v", "-"),
    "hybrid-float": ("#9467bd", "D", "-"),
    "gjk-double": ("#ff9896", "v", "--"),
    "dss-double-fr": ("#2ca02c", "s", "--"),
}
ITERATING = ["dss-exact", "dss-double", "dss-float", "gjk", "hybrid"]


def style(algo):
    return STYLE.get(algo, ("black", ".", "-"))


def num(x):
    if x is None or x == "":
        return None
    return float(x)


def load_rows(path):
    """Rows of the narrowphase CSV or JSON as dicts with numeric fields converted."""
    if path.endswith(".json"):
        with open(path) as f:
            data = json.load(f)
        raw = data.get("rows", [])
    else:
        with open(path, newline="") as f:
            raw = list(csv.DictReader(f))
    rows = []
    for r in raw:
        rows.append({
            "workload": r["workload"],
            "sigma": float(r["sigma"]),
            "vertices": int(float(r["vertices"])),
            "pairs": int(float(r["pairs"])),
            "density": float(r["density"]),
            "algo": r["algo"],
            "mpairs": float(r["mpairs_per_s"]),
            "mean_it": num(r.get("mean_iterations")),
            "max_it": num(r.get("max_iterations")),
            "caps": num(r.get("cap_hits")),
            "wrong": float(r["wrong"]),
            "reference": r.get("reference", ""),
        })
    return rows


def footer(fig, command, note):
    text = "Data: " + command
    if note:
        text += "\n" + note
    fig.text(0.01, 0.005, text, fontsize=7, family="monospace", va="bottom", ha="left", wrap=True)


def density_axis(ax):
    ax.set_xscale("log")
    ax.set_xlabel("collision density (% of pairs intersecting, log scale)")
    ticks = [0.1, 0.2, 0.5, 1, 2, 5, 10, 20, 50, 100]
    lo, hi = ax.get_xlim()
    ax.set_xticks([t for t in ticks if lo <= t <= hi * 1.0001] or ticks)
    ax.xaxis.set_major_formatter(matplotlib.ticker.FuncFormatter(lambda v, _: "%g" % v))
    ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax.grid(True, which="both", alpha=0.3)


def series(rows, algo, key):
    pts = sorted((100 * r["density"], r[key]) for r in rows if r["algo"] == algo and r[key] is not None)
    return [p for p in pts if p[0] > 0]


def plot_workload(rows, name, title, out, command, note):
    rows = [r for r in rows if r["workload"] == name]
    if not rows:
        return None
    algos = [a for a in STYLE if any(r["algo"] == a for r in rows)]
    zero = sorted({r["sigma"] for r in rows if r["density"] <= 0})
    pairs = max(r["pairs"] for r in rows)
    fig, axes = plt.subplots(2, 2, figsize=(13, 9.5))
    (ax_speed, ax_mean), (ax_max, ax_fail) = axes

    for a in algos:
        c, m, ls = style(a)
        pts = series(rows, a, "mpairs")
        if pts:
            ax_speed.plot([p[0] for p in pts], [p[1] for p in pts], color=c, marker=m, ls=ls, label=a)
    density_axis(ax_speed)
    ax_speed.set_ylabel("speed (million pairs per second)")
    ax_speed.set_ylim(bottom=0)
    ax_speed.set_title("pairs per second (median over repetitions)")
    ax_speed.legend(fontsize=8, ncol=2)

    for ax, key, what in ((ax_mean, "mean_it", "mean"), (ax_max, "max_it", "maximum")):
        for a in ITERATING:
            c, m, ls = style(a)
            pts = series(rows, a, key)
            if pts:
                ax.plot([p[0] for p in pts], [p[1] for p in pts], color=c, marker=m, ls=ls, label=a)
        density_axis(ax)
        ax.set_ylabel("plane tests per pair (support evaluations, count)")
        ax.set_ylim(bottom=0)
        ax.set_title(what + " plane tests per pair")
        ax.legend(fontsize=8)

    # Failure rate: cap hits / pairs (solid) and wrong answers / pairs (dotted), symlog so that
    # zero stays visible at the bottom.
    for a in algos:
        c, m, _ = style(a)
        caps = series(rows, a, "caps")
        wrong = [(d, w / pairs_of(rows, a, d)) for d, w in series(rows, a, "wrong")]
        if caps:
            ax_fail.plot([p[0] for p in caps], [p[1] / pairs_of(rows, a, p[0]) for p in caps], color=c,
                         marker=m, ls="-", label=a + " cap hits")
        if wrong and any(w > 0 for _, w in wrong):
            ax_fail.plot([p[0] for p in wrong], [p[1] for p in wrong], color=c, marker=m, ls=":",
                         mfc="none", label=a + " wrong")
    density_axis(ax_fail)
    linthresh = 0.5 / pairs
    ax_fail.set_yscale("symlog", linthresh=linthresh)
    ax_fail.set_ylim(bottom=0)
    ax_fail.set_ylabel("fraction of pairs (symlog; linear below %.1g)" % linthresh)
    ax_fail.set_title("failure rate: cap hits (solid), wrong answers (dotted, if any)")
    ax_fail.legend(fontsize=7, ncol=2)
    if not any((r["caps"] or 0) > 0 or r["wrong"] > 0 for r in rows):
        ax_fail.text(0.5, 0.5, "no cap hits and no wrong answers in this run\n(see failure_rate.png for float at cap 20)",
                     transform=ax_fail.transAxes, ha="center", fontsize=10, color="gray")

    extra = ""
    if zero:
        extra = "; spreads with density 0 not shown on the log axis: sigma = " + ", ".join("%g" % s for s in zero)
    fig.suptitle("Narrow phase, %s: %d pairs per spread, reference %s%s" %
                 (title, pairs, rows[0]["reference"], extra), fontsize=11)
    footer(fig, command, note)
    fig.tight_layout(rect=(0, 0.05, 1, 0.96))
    path = os.path.join(out, "narrowphase_%s.png" % name)
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path


def pairs_of(rows, algo, density_pct):
    for r in rows:
        if r["algo"] == algo and abs(100 * r["density"] - density_pct) < 1e-9:
            return r["pairs"]
    return 1


kMaxRatio = 2.5  # speed ratios above are drawn at the top edge with their value written


def plot_speedup(rows, out, command, note):
    fig, axes = plt.subplots(1, 3, figsize=(16, 5.5), sharey=True)
    any_point = False
    for ax, algo in zip(axes, ["dss-double", "dss-float", "hybrid"]):
        for i, (name, title) in enumerate(WORKLOADS):
            wr = [r for r in rows if r["workload"] == name]
            by_sigma = {}
            for r in wr:
                by_sigma.setdefault(r["sigma"], {})[r["algo"]] = r
            pts = []
            for s, d in by_sigma.items():
                if algo in d and "gjk" in d and d[algo]["density"] > 0:
                    pts.append((100 * d[algo]["density"], d[algo]["mpairs"] / d["gjk"]["mpairs"]))
            pts.sort()
            if pts:
                any_point = True
                off = [p for p in pts if p[1] > kMaxRatio]
                pts = [(d, min(v, kMaxRatio)) for d, v in pts]
                line, = ax.plot([p[0] for p in pts], [p[1] for p in pts], marker="os^Dv"[i], label=title)
                for d, v in off:
                    ax.annotate("%.1f" % v, (d, kMaxRatio), fontsize=7, color=line.get_color(),
                                xytext=(2, -10), textcoords="offset points")
        ax.set_ylim(0, kMaxRatio * 1.02)
        ax.axhspan(1.10, 1.25, color="green", alpha=0.12, label="paper: 10-25 % faster")
        ax.axhline(1.0, color="black", lw=0.8)
        density_axis(ax)
        ax.set_title("%s speed / gjk speed (same run)" % algo)
        ax.legend(fontsize=8)
    axes[0].set_ylabel("speed ratio over GJK (dimensionless; > 1 is faster)")
    if not any_point:
        plt.close(fig)
        return None
    fig.suptitle("DSS and Hybrid against our decision GJK (double), ratio of median speeds "
                 "(ratios above %g drawn at the top edge, value written)" % kMaxRatio, fontsize=11)
    footer(fig, command, note)
    fig.tight_layout(rect=(0, 0.06, 1, 0.95))
    path = os.path.join(out, "narrowphase_speedup.png")
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path


def plot_sweep(rows, out, command, note):
    rows = [r for r in rows if r["workload"] == "sweep"]
    if not rows:
        return None
    algos = [a for a in STYLE if any(r["algo"] == a for r in rows)]
    fig, (ax, ax_ratio) = plt.subplots(1, 2, figsize=(15, 6))
    for a in algos:
        c, m, ls = style(a)
        pts = sorted((r["vertices"], r["mpairs"]) for r in rows if r["algo"] == a)
        ax.plot([p[0] for p in pts], [p[1] for p in pts], color=c, marker=m, ls=ls, label=a)
    ax.set_xscale("log", base=2)
    ax.set_yscale("log")
    ax.set_xlabel("vertices per polytope (log scale)")
    ax.set_ylabel("speed (million pairs per second, log scale)")
    ax.set_title("pairs per second against vertex count")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, ncol=2)
    for mode in ["dss-exact", "dss-double"]:
        c, m, _ = style(mode)
        climb = {r["vertices"]: r["mpairs"] for r in rows if r["algo"] == mode}
        scan = {r["vertices"]: r["mpairs"] for r in rows if r["algo"] == mode + "-scan"}
        vs = sorted(set(climb) & set(scan))
        if vs:
            ax_ratio.plot(vs, [climb[v] / scan[v] for v in vs], color=c, marker=m, label=mode)
    ax_ratio.axhline(1.0, color="black", lw=0.8)
    threshold = hill_climb_threshold()
    if threshold:
        for a in (ax, ax_ratio):
            a.axvline(threshold, color="gray", ls="--", lw=0.8)
        ax_ratio.text(threshold, ax_ratio.get_ylim()[1], " kHillClimbMinVertices = %d:\n below it both rows scan" % threshold,
                      fontsize=8, va="top", color="gray")
    ax_ratio.set_xscale("log", base=2)
    ax_ratio.set_xlabel("vertices per polytope (log scale)")
    ax_ratio.set_ylabel("speed with adjacency / speed with linear scan (dimensionless)")
    ax_ratio.set_title("where hill-climbing pays (> 1): the library climbs from its threshold up")
    ax_ratio.grid(True, which="both", alpha=0.3)
    for a in (ax, ax_ratio):
        a.xaxis.set_major_formatter(matplotlib.ticker.FuncFormatter(lambda v, _: "%g" % v))
    ax_ratio.legend(fontsize=8)
    dens = sorted(100 * r["density"] for r in rows if r["algo"] == "dss-exact")
    pairs = sorted({r["pairs"] for r in rows})
    fig.suptitle("Vertex-count sweep: random polytopes on the unit sphere, sigma %g, density %.0f-%.0f %%, "
                 "%s pairs per vertex count" % (rows[0]["sigma"], dens[0], dens[-1],
                                                "/".join(str(p) for p in pairs)), fontsize=11)
    footer(fig, command, note)
    fig.tight_layout(rect=(0, 0.06, 1, 0.95))
    path = os.path.join(out, "narrowphase_sweep.png")
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path


def hill_climb_threshold():
    """kHillClimbMinVertices from the library header next to this script (None if absent)."""
    header = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "include", "dss", "core",
                          "convex_hull.h")
    try:
        with open(header) as f:
            for line in f:
                if "kHillClimbMinVertices =" in line:
                    return int(line.split("=")[1].strip().rstrip(";"))
    except (OSError, ValueError):
        pass
    return None


def load_jsonl(path):
    out = []
    with open(path) as f:
        for line in f:
            line = line.strip()
            if line:
                out.append(json.loads(line))
    return out


NO_NOTE = "(the run recorded no build note; see docs/figures/README.md for its commit and machine load)"


def plot_failure_rate(scan, long_run, out, note):
    lines = scan + long_run
    if not lines:
        return None
    fig, (ax_cap, ax_wrong) = plt.subplots(1, 2, figsize=(15, 6))
    algos = []
    for ln in lines:
        for a in ln["algos"]:
            if a["algo"] not in algos:
                algos.append(a["algo"])
    for ax, key, what in ((ax_cap, "cap_hits", "cap hits (status iteration_limit)"),
                          (ax_wrong, "wrong", "wrong answers (against the exact reference)")):
        for algo in algos:
            c, m, ls = style(algo if algo != "dss-double" else "dss-double-fr")
            pts = []
            for ln in scan:
                for a in ln["algos"]:
                    if a["algo"] == algo and ln["density"] > 0:
                        pts.append((100 * ln["density"], a[key], ln["pairs"]))
            pts.sort()
            pos = [(d, k / n) for d, k, n in pts if k > 0]
            zero = [(d, 1.0 / n) for d, k, n in pts if k == 0]
            if pos:
                ax.plot([p[0] for p in pos], [p[1] for p in pos], color=c, marker=m, ls=ls, label=algo)
            if zero:
                ax.plot([p[0] for p in zero], [p[1] for p in zero], color=c, marker="v", ls="none", mfc="none",
                        label=algo + ": 0 seen (marker at 1/pairs)")
            for ln in long_run:
                for a in ln["algos"]:
                    if a["algo"] == algo:
                        d = 100 * ln["density"]
                        v = a[key] / ln["pairs"] if a[key] > 0 else 1.0 / ln["pairs"]
                        ax.plot([d], [v], color=c, marker="*" if a[key] > 0 else "v", ms=14,
                                mfc=c if a[key] > 0 else "none", ls="none")
        for ln in long_run:
            text = "long run, sigma %g, density %.1f %%, %.0e pairs:\n" % (ln["sigma"], 100 * ln["density"], ln["pairs"])
            text += "\n".join("  %s: %d (%.2g)" % (a["algo"], a[key], a[key] / ln["pairs"]) for a in ln["algos"])
            ax.text(0.02, 0.62, text, transform=ax.transAxes, fontsize=7, family="monospace", va="top",
                    bbox=dict(boxstyle="round", fc="white", alpha=0.85))
        ax.set_yscale("log")
        density_axis(ax)
        ax.set_ylabel("fraction of pairs (log scale)")
        ax.set_title(what)
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=7, loc="lower left")
    cap = lines[0]["max_iterations_cap"]
    desc = ("Failure rate on random tetrahedra (float-rounded vertices), cap %d plane tests; "
            "lines: density scan, stars: long run" % cap)
    if long_run:
        desc += " (%.0e pairs)" % long_run[0]["pairs"]
    fig.suptitle(desc, fontsize=11)
    cmds = []
    for ln in (scan[:1] + long_run[:1]):
        cmds.append(ln["command"])
    notes = [ln.get("note") or NO_NOTE for ln in (scan[:1] + long_run[:1])]
    footer(fig, "  |  ".join(cmds), "  |  ".join(notes))
    fig.tight_layout(rect=(0, 0.07, 1, 0.95))
    path = os.path.join(out, "failure_rate.png")
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path


def plot_iteration_histogram(long_run, out, note):
    if not long_run:
        return None
    ln = long_run[0]
    fig, ax = plt.subplots(figsize=(11, 6))
    algos = [a for a in ln["algos"]]
    width = 0.8 / len(algos)
    for i, a in enumerate(algos):
        c, _, _ = style(a["algo"] if a["algo"] != "dss-double" else "dss-double-fr")
        h = a["iteration_histogram"]
        xs = [k + (i - (len(algos) - 1) / 2) * width for k in range(len(h)) if h[k] > 0]
        ys = [h[k] / ln["pairs"] for k in range(len(h)) if h[k] > 0]
        ax.bar(xs, ys, width=width, color=c, label="%s (max %d)" % (a["algo"], a["max_iterations"]))
    ax.set_yscale("log")
    ax.set_xlabel("plane tests (support evaluations) needed for the pair (count; the cap counts cap hits)")
    ax.set_ylabel("fraction of pairs (log scale)")
    ax.set_xticks(range(0, ln["max_iterations_cap"] + 1))
    ax.grid(True, axis="y", which="both", alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title("Plane tests per pair, random tetrahedra at %.1f %% density, %.0e pairs, cap %d" %
                 (100 * ln["density"], ln["pairs"], ln["max_iterations_cap"]))
    footer(fig, ln["command"], ln.get("note") or NO_NOTE)
    fig.tight_layout(rect=(0, 0.06, 1, 1))
    path = os.path.join(out, "failure_rate_iterations.png")
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path


def write_summary(rows, scan, long_run, path, command):
    """Markdown tables of the numbers the honest reading quotes (all ratios from one run)."""
    out = ["# Narrow-phase summary", "", "Data: `%s`" % command, ""]
    out.append("## Speed over `gjk` (ratio of median pairs/s, same run) and max plane tests")
    out.append("")
    out.append("| workload | sigma | density | dss-double/gjk | dss-float/gjk | dss-exact/gjk | hybrid/gjk | "
               "dss-double/fcl-box | max it dss-double | max it gjk | caps (dss/gjk/hybrid) | wrong (dss-exact/dss-double/dss-float/gjk/hybrid) |")
    out.append("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for name, _ in WORKLOADS:
        by_sigma = {}
        for r in rows:
            if r["workload"] == name:
                by_sigma.setdefault(r["sigma"], {})[r["algo"]] = r
        for sigma in sorted(by_sigma):
            d = by_sigma[sigma]
            if "gjk" not in d or "dss-double" not in d:
                continue
            g = d["gjk"]["mpairs"]

            def ratio(a, b="gjk"):
                return "%.2f" % (d[a]["mpairs"] / d[b]["mpairs"]) if a in d and b in d else "-"

            def it(a):
                return "%d" % d[a]["max_it"] if a in d and d[a]["max_it"] is not None else "-"

            def cnt(a, k):
                return "%d" % d[a][k] if a in d and d[a][k] is not None else "-"
            out.append("| %s | %g | %.1f %% | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
                name, sigma, 100 * d["gjk"]["density"], ratio("dss-double"), ratio("dss-float"), ratio("dss-exact"),
                ratio("hybrid"), ratio("dss-double", "fcl-box"), it("dss-double"), it("gjk"),
                "/".join(cnt(a, "caps") for a in ["dss-double", "gjk", "hybrid"]),
                "/".join(cnt(a, "wrong") for a in ["dss-exact", "dss-double", "dss-float", "gjk", "hybrid"])))
    out.append("")
    for title, lines in (("Failure-rate density scan", scan), ("Long failure-rate run", long_run)):
        if not lines:
            continue
        out.append("## %s (float-rounded tetrahedra, cap %d)" % (title, lines[0]["max_iterations_cap"]))
        out.append("")
        out.append("Command: `%s`" % lines[0]["command"])
        out.append("")
        out.append("| sigma | density | pairs | algo | cap hits | wrong | wrong, decided | max it |")
        out.append("|---|---|---|---|---|---|---|---|")
        for ln in lines:
            for a in ln["algos"]:
                out.append("| %g | %.1f %% | %.0e | %s | %d | %d | %d | %d |" % (
                    ln["sigma"], 100 * ln["density"], ln["pairs"], a["algo"], a["cap_hits"], a["wrong"],
                    a["wrong_decided"], a["max_iterations"]))
        out.append("")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")
    return path


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--data", help="narrowphase CSV or JSON (dss_bench narrowphase --csv/--json)")
    p.add_argument("--command", default=None, help="the command that produced --data (printed on the figures)")
    p.add_argument("--failure-scan", help="JSON lines of dss_bench failure-rate over several spreads")
    p.add_argument("--failure-long", help="JSON line(s) of the long dss_bench failure-rate run")
    p.add_argument("--note", default="", help="second footer line (machine, commit, date)")
    p.add_argument("--out", default="docs/figures", help="output folder for the PNGs")
    p.add_argument("--summary", help="also write the quoted numbers as markdown tables to this file")
    args = p.parse_args()
    os.makedirs(args.out, exist_ok=True)
    made = []
    if args.data:
        rows = load_rows(args.data)
        if not rows:
            sys.exit("plot_narrowphase: no rows in " + args.data)
        command = args.command or "dss_bench narrowphase (see %s)" % args.data
        for name, title in WORKLOADS:
            made.append(plot_workload(rows, name, title, args.out, command, args.note))
        made.append(plot_speedup(rows, args.out, command, args.note))
        made.append(plot_sweep(rows, args.out, command, args.note))
    scan = load_jsonl(args.failure_scan) if args.failure_scan else []
    long_run = load_jsonl(args.failure_long) if args.failure_long else []
    if args.failure_scan and not scan:
        sys.exit("plot_narrowphase: no lines in " + args.failure_scan)
    if args.failure_long and not long_run:
        sys.exit("plot_narrowphase: no lines in " + args.failure_long)
    made.append(plot_failure_rate(scan, long_run, args.out, args.note))
    made.append(plot_iteration_histogram(long_run, args.out, args.note))
    if args.summary:
        made.append(write_summary(rows if args.data else [], scan, long_run, args.summary,
                                  args.command or "dss_bench narrowphase"))
    made = [m for m in made if m]
    if not made:
        sys.exit("plot_narrowphase: nothing to draw (give --data and/or --failure-scan/--failure-long)")
    for m in made:
        print("wrote", m)


if __name__ == "__main__":
    main()
