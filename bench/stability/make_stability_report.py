#!/usr/bin/env python3
"""Charts and report of the stability sweeps (scripts/stability.sh).

Reads the CSVs of stability_sweep (one per sweep) and writes, under OUT_DIR:
  charts/map-<pattern>.{png,svg}   outcome per method over mass ratio x CFM (one panel per method)
  charts/chain-length.{png,svg}    largest joint error against the number of links
  charts/timestep.{png,svg}        largest joint error against the time step
  report.md                        tables of every sweep, and every case where a bpp variant fails,
                                   with its cause and what Dantzig did at the same point

Usage: make_stability_report.py CSV_DIR OUT_DIR [--quick]
"""
import argparse
import collections
import csv
import math
import os
import subprocess
import sys

METHODS = ["dantzig", "bpp", "bpp-sky", "bpp-down", "bpp-chol", "pgs", "quickstep", "bpp-consistent"]
OUTCOMES = ["held", "solver-error", "drifted", "exploded"]
LETTER = {"held": "H", "solver-error": "S", "drifted": "D", "exploded": "X"}
COLOUR = {"held": "#2e9e44", "solver-error": "#e8c21a", "drifted": "#f07f1a", "exploded": "#c8102e"}
SWEEP_FILES = ["mass-cfm", "timestep", "loops", "chain-length", "friction"]


def load(csv_dir):
    """Rows of every sweep CSV present, as dicts with numbers converted."""
    sweeps = {}
    for name in SWEEP_FILES:
        path = os.path.join(csv_dir, name + ".csv")
        if not os.path.exists(path):
            continue
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
        for r in rows:
            for key in ("mass_ratio", "cfm", "step", "seconds", "tolerance", "max_joint_error", "max_penetration",
                        "worst_placement", "energy_drift", "final_slide", "friction_excess", "wall_seconds"):
                r[key] = float(r[key])
            for key in ("links", "steps_run", "lcp_internal_errors", "islands", "failures", "fallbacks",
                        "max_iterations", "not_spd", "regularized", "friction_not_consistent", "murty_pivots"):
                r[key] = int(float(r[key]))
        sweeps[name] = rows
    return sweeps


def power(v):
    """1e-08 -> '1e-8', 100 -> '1e2', 1 -> '1', 0 -> '0'."""
    if v == 0:
        return "0"
    e = math.log10(v)
    if abs(e - round(e)) < 1e-9:
        return "1" if round(e) == 0 else "1e%d" % round(e)
    return "%.2g" % v


def step_name(h):
    return "1/%d" % round(1 / h)


def sorted_unique(values):
    return sorted(set(values))


def run_gnuplot(script, base):
    """Renders the same plot commands to base.png and base.svg."""
    for term, ext in (("pngcairo size 1400,700 font ',10'", "png"), ("svg size 1400,700 font 'sans,10'", "svg")):
        full = "set terminal %s\nset output '%s.%s'\n%s\nunset output\n" % (term, base, ext, script)
        subprocess.run(["gnuplot"], input=full.encode(), check=True)


def map_chart(rows, pattern, charts, title):
    """One panel per method: a square per (mass ratio, CFM) coloured by outcome."""
    data = os.path.join(charts, "map-%s.dat" % pattern)
    methods = [m for m in METHODS if any(r["method"] == m for r in rows)]
    with open(data, "w") as f:
        for m in methods:
            f.write("# %s\n" % m)
            for r in rows:
                if r["method"] == m:
                    f.write("%g %g %d\n" % (math.log10(r["mass_ratio"]), math.log10(r["cfm"]) if r["cfm"] > 0 else -14,
                                            OUTCOMES.index(r["outcome"])))
            f.write("\n\n")
    ratios = sorted_unique(math.log10(r["mass_ratio"]) for r in rows)
    cfms = sorted_unique(math.log10(r["cfm"]) for r in rows if r["cfm"] > 0)
    palette = ", ".join("%d '%s'" % (i, COLOUR[o]) for i, o in enumerate(OUTCOMES))
    lines = [
        "set multiplot layout 2,4 title '%s   (green held, yellow solver error, orange drifted, red exploded)'" % title,
        "set palette defined (%s)" % palette,
        "set cbrange [0:3]", "unset colorbox",
        "set xrange [%g:%g]" % (ratios[0] - 0.5, ratios[-1] + 0.5),
        "set yrange [%g:%g]" % (cfms[0] - 1, cfms[-1] + 1),
        "set xlabel 'log10 mass ratio'", "set ylabel 'log10 CFM'",
        "set xtics 1", "set ytics 2", "set grid front",
    ]
    for i, m in enumerate(methods):
        lines.append("set title '%s'" % m)
        lines.append("plot '%s' index %d using 1:2:3 with points pt 5 ps 3.2 lc palette notitle" % (data, i))
    lines.append("unset multiplot")
    run_gnuplot("\n".join(lines), os.path.join(charts, "map-" + pattern))


def line_chart(rows, x_key, charts, name, title, xlabel, x_transform):
    """Largest joint error per method against x_key (log y), with the run's tolerance."""
    data = os.path.join(charts, name + ".dat")
    methods = [m for m in METHODS if any(r["method"] == m for r in rows)]
    with open(data, "w") as f:
        for m in methods:
            f.write("# %s\n" % m)
            for r in sorted((r for r in rows if r["method"] == m), key=lambda r: r[x_key]):
                err = max(r["max_joint_error"], 1e-12)
                f.write("%g %g %g\n" % (x_transform(r[x_key]), err, r["tolerance"]))
            f.write("\n\n")
    plots = ["'%s' index %d using 1:2 with linespoints lw 2 title '%s'" % (data, i, m) for i, m in enumerate(methods)]
    plots.append("'%s' index 0 using 1:3 with lines dt 2 lc 'black' title 'tolerance'" % data)
    script = "\n".join([
        "set title '%s'" % title, "set logscale y", "set format y '10^{%L}'",
        "set xlabel '%s'" % xlabel, "set ylabel 'largest joint error [m]'", "set key outside right",
        "set grid", "plot " + ", ".join(plots)])
    run_gnuplot(script, os.path.join(charts, name))


def outcome_counts_table(rows):
    lines = ["| method | " + " | ".join(OUTCOMES) + " | runs |", "|---" * (len(OUTCOMES) + 2) + "|"]
    for m in METHODS:
        mine = [r for r in rows if r["method"] == m]
        if not mine:
            continue
        c = collections.Counter(r["outcome"] for r in mine)
        lines.append("| %s | %s | %d |" % (m, " | ".join(str(c[o]) for o in OUTCOMES), len(mine)))
    return lines


def letter_grid(rows, pattern, col_key, col_name):
    """Rows: method x CFM; columns: col_key values; cells: H/S/D/X."""
    mine = [r for r in rows if r["pattern"] == pattern]
    cols = sorted_unique(r[col_key] for r in mine)
    cfms = sorted(sorted_unique(r["cfm"] for r in mine), reverse=True)
    by = {(r["method"], r["cfm"], r[col_key]): r for r in mine}
    head = "| method | CFM | " + " | ".join(col_name(c) for c in cols) + " |"
    lines = [head, "|---" * (len(cols) + 2) + "|"]
    for m in METHODS:
        for cfm in cfms:
            cells = [LETTER[by[(m, cfm, c)]["outcome"]] if (m, cfm, c) in by else "" for c in cols]
            if any(cells):
                lines.append("| %s | %s | %s |" % (m, power(cfm), " | ".join(cells)))
    return lines


def error_grid(rows, col_key, col_name):
    """Rows: pattern x method; cells: outcome letter and largest joint error."""
    cols = sorted_unique(r[col_key] for r in rows)
    by = {(r["pattern"], r["method"], r["mass_ratio"], r[col_key]): r for r in rows}
    lines = ["| pattern | method | ratio | " + " | ".join(col_name(c) for c in cols) + " |",
             "|---" * (len(cols) + 3) + "|"]
    for p in sorted_unique(r["pattern"] for r in rows):
        for ratio in sorted_unique(r["mass_ratio"] for r in rows if r["pattern"] == p):
            for m in METHODS:
                cells = []
                for c in cols:
                    r = by.get((p, m, ratio, c))
                    cells.append("%s %.1e" % (LETTER[r["outcome"]], r["max_joint_error"]) if r else "")
                if any(cells):
                    lines.append("| %s | %s | %s | %s |" % (p, m, power(ratio), " | ".join(cells)))
    return lines


def point_key(r):
    return (r["sweep"], r["pattern"], r["mass_ratio"], r["cfm"], r["step"], r["links"])


def describe_point(r):
    return "%s, %s, ratio %s, CFM %s, h %s, N %d" % (r["sweep"], r["pattern"], power(r["mass_ratio"]), power(r["cfm"]),
                                                   step_name(r["step"]), r["links"])


COUNTERS = [("lcp_internal_errors", "LCP internal error"), ("failures", "to ODE's Dantzig"),
            ("max_iterations", "max-iterations"), ("not_spd", "not-spd"), ("regularized", "regularized"),
            ("friction_not_consistent", "friction-not-consistent"), ("murty_pivots", "Murty pivots")]


def solver_counters(r):
    """The non-zero trouble counters of a run (islands, or pivots for Murty)."""
    parts = ["%s %d" % (name, r[key]) for key, name in COUNTERS if r[key] > 0]
    return ", ".join(parts) if parts else "-"


def bpp_failures(sweeps):
    """Every run of a bpp variant that did not hold, beside Dantzig's outcome at the same point."""
    dantzig = {}
    for rows in sweeps.values():
        for r in rows:
            if r["method"] == "dantzig":
                dantzig[point_key(r)] = r
    lines = ["| point | method | outcome | cause | solver counters | Dantzig there |", "|---|---|---|---|---|---|"]
    count = 0
    for rows in sweeps.values():
        for r in rows:
            if not r["method"].startswith("bpp") or r["outcome"] == "held":
                continue
            count += 1
            d = dantzig.get(point_key(r))
            there = "%s %s" % (d["outcome"], d["cause"]) if d else "not run"
            lines.append("| %s | %s | %s | %s | %s | %s |" % (describe_point(r), r["method"], r["outcome"],
                                                              r["cause"] or "-", solver_counters(r), there.strip()))
    return count, lines


def cause_summary(sweeps):
    """Failures of the bpp variants grouped by outcome and by whether Dantzig failed there too."""
    dantzig = {point_key(r): r for rows in sweeps.values() for r in rows if r["method"] == "dantzig"}
    groups = collections.Counter()
    for rows in sweeps.values():
        for r in rows:
            if r["method"].startswith("bpp") and r["outcome"] != "held":
                d = dantzig.get(point_key(r))
                if d is None:
                    there = "Dantzig not run there"
                elif d["outcome"] in ("drifted", "exploded"):
                    there = "Dantzig drifted or exploded there too"
                elif d["outcome"] == "solver-error":
                    there = "Dantzig held physically there, with a solver error"
                else:
                    there = "Dantzig held there"
                groups[(r["outcome"], there)] += 1
    return ["- %s, %s: %d runs" % (o, b, n) for (o, b), n in sorted(groups.items())]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("csv_dir")
    ap.add_argument("out_dir")
    ap.add_argument("--quick", action="store_true")
    a = ap.parse_args()
    sweeps = load(a.csv_dir)
    if not sweeps:
        sys.exit("make_stability_report.py: no sweep CSV in " + a.csv_dir)
    charts = os.path.join(a.out_dir, "charts")
    os.makedirs(charts, exist_ok=True)

    md = ["# Stability where methods fail", "",
          "Generated by `make stability%s` (scripts/stability.sh). Outcome of every run (docs/stability.md): "
          "**H** held, **S** solver error (physics held, but Dantzig printed \"LCP internal error\", or an ode-bpp "
          "solve hit its pivot budget, broke down or took a fallback), **D** drifted (joint error, contact "
          "penetration or a placement beyond the tolerance tau = 0.02 ell + 1 mm + 2 W h CFM / ERP), **X** exploded "
          "(non-finite state, ODE abort, or an energy gain above g * (sum of masses) * scene height)."
          % (" STABILITY_ARGS=--quick" if a.quick else ""), ""]
    runs = sum(len(v) for v in sweeps.values())
    wall = sum(r["wall_seconds"] for v in sweeps.values() for r in v)
    md += ["%d runs, %.0f s of solver-process wall time in total." % (runs, wall), ""]

    if "mass-cfm" in sweeps:
        rows = sweeps["mass-cfm"]
        md += ["## Mass ratio x CFM", "",
               "Three heavy-on-light patterns (demos/scenes/sweep_scenes.h) at h = 1/60 for %g s each: `chain` "
               "(100 kg load on 10 light links), `stack` (100 kg box on 4 light boxes), `offshore` (1,000 kg base on "
               "the ground, 10-link light cable from its mast, 100 kg load; base : link = 10 x ratio)." %
               rows[0]["seconds"], ""]
        md += outcome_counts_table(rows) + [""]
        for p in sorted_unique(r["pattern"] for r in rows):
            map_chart([r for r in rows if r["pattern"] == p], p, charts, "%s: outcome over mass ratio x CFM" % p)
            md += ["### %s" % p, "", "![%s map](charts/map-%s.png)" % (p, p), "",
                   "Columns: mass ratio. Rows: method and CFM.", ""]
            md += letter_grid(rows, p, "mass_ratio", power) + [""]

    if "timestep" in sweeps:
        rows = sweeps["timestep"]
        md += ["## Time step", "", "Outcome and largest joint error [m] per time step, CFM %s." %
               power(rows[0]["cfm"]), ""]
        md += error_grid(rows, "step", step_name) + [""]
        hardest = max(r["mass_ratio"] for r in rows)
        line_chart([r for r in rows if r["pattern"] == "chain" and r["mass_ratio"] == hardest],
                   "step", charts, "timestep", "chain, largest mass ratio: joint error against the step rate",
                   "steps per second (1/h)", lambda h: 1 / h)
        md += ["![time step](charts/timestep.png)", ""]

    if "loops" in sweeps:
        rows = sweeps["loops"]
        md += ["## Closed loops", "",
               "A hanging ladder of parallelogram cells: four parallel hinges per cell, three redundant rows per "
               "loop. At CFM 0 the matrix A is singular (not SPD).", ""]
        md += outcome_counts_table(rows) + [""] + letter_grid(rows, "ladder", "mass_ratio", power) + [""]

    if "chain-length" in sweeps:
        rows = sweeps["chain-length"]
        md += ["## Long chains", "", "Hanging chain of N links, mass ratio %s, CFM %s: outcome and largest joint "
               "error [m]; solve wall time per run in the last table." % (power(rows[0]["mass_ratio"]),
                                                                           power(rows[0]["cfm"])), ""]
        md += error_grid(rows, "links", str) + [""]
        line_chart(rows, "links", charts, "chain-length", "hanging chain: joint error against length", "links N",
                   lambda n: n)
        md += ["![chain length](charts/chain-length.png)", ""]
        cols = sorted_unique(r["links"] for r in rows)
        md += ["| method | " + " | ".join("N=%d [s]" % n for n in cols) + " |", "|---" * (len(cols) + 1) + "|"]
        for m in METHODS:
            cells = ["%.2f" % r["wall_seconds"] for n in cols for r in rows if r["method"] == m and r["links"] == n]
            if cells:
                md.append("| %s | %s |" % (m, " | ".join(cells)))
        md.append("")

    if "friction" in sweeps:
        rows = sweeps["friction"]
        md += ["## Coupled friction", "",
               "A heavy box on a light box sliding on the ground (mu = 1, v0 = 2 m/s): physics stops both after "
               "v0^2 / (2 mu g) = 0.204 m. Largest relative friction-cone excess in the last column (Frozen "
               "friction, Dantzig's semantics, may exceed the cone; `bpp-consistent` is bpp with Consistent "
               "friction).", "",
               "| method | ratio | CFM | outcome | slide [m] | cone excess |", "|---|---|---|---|---|---|"]
        for r in rows:
            # the cone is read from ode-bpp's answers only (ODE's Dantzig rewrites the bounds in place)
            measured = r["method"] not in ("dantzig", "quickstep")
            md.append("| %s | %s | %s | %s | %.3f | %s |" % (r["method"], power(r["mass_ratio"]), power(r["cfm"]),
                                                            r["outcome"], r["final_slide"],
                                                            "%.1e" % r["friction_excess"] if measured else "n/a"))
        md.append("")

    count, table = bpp_failures(sweeps)
    md += ["## Where bpp fails", "",
           "Every run of a bpp variant (bpp, bpp-sky, bpp-down, bpp-chol, bpp-consistent) that did not hold: "
           "%d of %d." %
           (count, sum(1 for v in sweeps.values() for r in v if r["method"].startswith("bpp"))), ""]
    md += cause_summary(sweeps) + [""]
    md += table if count else ["None."]
    md.append("")

    with open(os.path.join(a.out_dir, "report.md"), "w") as f:
        f.write("\n".join(md))


if __name__ == "__main__":
    main()
