"""world_report.py: the report's section on the whole world step (scripts/bench-world.sh's
OUT_DIR/world/*.csv): chain scaling, the paper's scenes against QuickStep, small islands, the
physical limit, the crane's instruction count, long chains. Each target of the sparse world step
comes with its measured value and gap; make_report.py calls section() and collects the misses.
Standard library only (plus make_report's formatting and gnuplot helpers)."""
import csv
import math
import os
import re
import statistics
from collections import defaultdict

import make_report as common

PAPER_SCENES = ["crane", "winch", "parkour", "offshore", "forklift", "forwarder"]
CLASSIC_SCENES = ["motors", "chain", "buggy", "boxstack", "cannon", "islands"]
SCENE_METHODS = ["bpp", "quickstep-20", "quickstep-100", "quickstep-bpp"]
CHAIN_METHODS = ["bpp", "quickstep-20", "dantzig"]
CRANE_INSTRUCTIONS_BEFORE = 4.6e6  # per dWorldStep with bpp before the sparse form (issue 12, main at 74eb792)
SLOPE_TARGET = 1.15
LIMIT_TARGET = 2.0


def read_csv(path):
    if not os.path.exists(path):
        return []
    with open(path, newline="") as handle:
        return list(csv.DictReader(handle))


def num(text):
    return common.num(text)


def loglog_slope(points):
    """Least-squares slope of log y against log x over the points with x, y > 0."""
    pts = [(math.log(x), math.log(y)) for x, y in points if x > 0 and y > 0]
    if len(pts) < 2:
        return math.nan
    mx, my = statistics.mean(p[0] for p in pts), statistics.mean(p[1] for p in pts)
    sxx = sum((p[0] - mx) ** 2 for p in pts)
    return sum((p[0] - mx) * (p[1] - my) for p in pts) / sxx if sxx else math.nan


def ms(value):
    return "–" if math.isnan(value) else (f"{value:.3f} ms" if value < 100 else f"{value:.0f} ms")


def ratio(value):
    return "–" if math.isnan(value) else f"{value:.2f}"


def metres(value):
    return "–" if math.isnan(value) else f"{value:.1e} m"


# ------------------------------------------------------------------------------------------
# chain scaling


def chain_table(lines, world, targets):
    rows = read_csv(os.path.join(world, "chain.csv"))
    lines.append("### Chain scaling: a hanging chain of N ball-jointed links under a 100 kg load\n")
    if not rows:
        lines.append("Not measured (chain.csv missing; see the failures).\n")
        targets.add("chain: bpp's step time against rows, fitted slope", "–", f"≤ {SLOPE_TARGET}", False, measured_at_all=False)
        return
    lines.append("The sweeps' HangingChain (sweep_scenes.h), link : load mass ratio 1:1000, CFM 1e-10, h = 1/60, swinging "
                 "from 0.3 rad; one process per row, the whole `dWorldStep` (or `dWorldQuickStep`) timed alone, collision "
                 "excluded. Memory: the growth of the process's peak resident set over its value before the world was "
                 "built. Joint error: the largest anchor gap over all joints and steps (demos/scenes/joint_gap.h).\n")
    lines.append("| links | rows | method | steps | median step | mean step | slowest 1 % | bpp / method (median) | peak memory added | joint error |")
    lines.append("|---|---|---|---|---|---|---|---|---|---|")
    by = {(int(r["links"]), r["method"]): r for r in rows}
    links = sorted({int(r["links"]) for r in rows})
    for n in links:
        bpp = by.get((n, "bpp"))
        for method in CHAIN_METHODS:
            r = by.get((n, method))
            if not r:
                continue
            ratio = num(bpp["step_median_ms"]) / num(r["step_median_ms"]) if bpp else math.nan
            memory = (num(r["rss_peak_kb"]) - num(r["rss_before_kb"])) / 1024
            lines.append(f"| {n} | {r['rows']} | {method} | {r['completed']}/{r['steps']} | {ms(num(r['step_median_ms']))} | "
                         f"{ms(num(r['step_mean_ms']))} | {ms(num(r['step_slowest1_ms']))} | {common.fmt_x(ratio)} | "
                         f"{memory:.1f} MB | {metres(num(r['gap_max_m']))} |")
    lines.append("")
    bpp_rows = [by[(n, "bpp")] for n in links if (n, "bpp") in by]
    slope = loglog_slope([(num(r["rows"]), num(r["step_median_ms"])) for r in bpp_rows])
    mean_slope = loglog_slope([(num(r["rows"]), num(r["step_mean_ms"])) for r in bpp_rows])
    targets.add("chain: bpp's median step against rows, fitted log–log slope (mean step in brackets)",
                f"{slope:.2f} ({mean_slope:.2f})", f"≤ {SLOPE_TARGET}", slope <= SLOPE_TARGET, common.gap(slope, SLOPE_TARGET))
    growth = [(num(r["rows"]), num(r["rss_peak_kb"]) - num(r["rss_before_kb"])) for r in bpp_rows]
    mem_slope = loglog_slope(growth)
    per_row = ", ".join(f"{g / rows_:.2f}" for rows_, g in growth if rows_ > 0)
    targets.add("chain: bpp's peak memory added against rows, fitted log–log slope (kB per row at each N)",
                f"{mem_slope:.2f} ({per_row})", f"≤ {SLOPE_TARGET} (O(rows))", mem_slope <= SLOPE_TARGET,
                common.gap(mem_slope, SLOPE_TARGET))
    slower = []
    for n in links:
        b, q = by.get((n, "bpp")), by.get((n, "quickstep-20"))
        if b and q and num(b["step_median_ms"]) > num(q["step_median_ms"]):
            slower.append(f"{n} links: {num(b['step_median_ms']) / num(q['step_median_ms']):.2f}×")
    ratios = [num(by[(n, "quickstep-20")]["step_median_ms"]) / num(by[(n, "bpp")]["step_median_ms"])
              for n in links if (n, "bpp") in by and (n, "quickstep-20") in by]
    targets.add("chain: bpp's median step no slower than QuickStep-20's at every N (QuickStep-20 / bpp per N)",
                ", ".join(common.fmt_x(r) for r in ratios) + (f"; slower at {'; '.join(slower)}" if slower else ""),
                "≥ 1× at every N", not slower and bool(ratios))
    dantzig_pairs = [(n, by[(n, "bpp")], by[(n, "dantzig")]) for n in links if (n, "bpp") in by and (n, "dantzig") in by]
    chain_accuracy(world, dantzig_pairs, targets)
    chart_chain(world, rows, links, by)
    lines.append("![step time against rows](charts/chain-time.png) ![peak memory against rows](charts/chain-memory.png)\n")


def joint_errors_match(a, b):
    """bpp's largest joint gap against a reference's: equal up to 10 % or 1e-9 m."""
    return abs(a - b) <= 0.1 * max(a, b) + 1e-9


def chain_accuracy(world, dantzig_pairs, targets):
    cells, ok = [], True
    for n, b, d in dantzig_pairs:
        gb, gd = num(b["gap_max_m"]), num(d["gap_max_m"])
        ok = ok and joint_errors_match(gb, gd)
        cells.append(f"{n} links: {gb:.2e} vs dantzig {gd:.2e}")
    accuracy = read_csv(os.path.join(world, "chain-accuracy.csv"))
    by = {(int(r["links"]), r["method"]): r for r in accuracy}
    for (n, method), r in sorted(by.items()):
        if method == "bpp" or (n, "bpp") not in by:
            continue
        gb, gr = num(by[(n, "bpp")]["gap_max_m"]), num(r["gap_max_m"])
        ok = ok and joint_errors_match(gb, gr)
        cells.append(f"{n} links, {r['completed']} steps: {gb:.2e} vs {method} {gr:.2e}")
    targets.add("chain: bpp's joint error equals dantzig's where it runs, and the dense bpp-down's (bpp-sky's at "
                "30,003 rows) beyond (within 10 %)", "; ".join(cells) or "–", "equal", ok and bool(cells),
                measured_at_all=bool(cells))


def chart_chain(world, rows, links, by):
    charts = os.path.join(os.path.dirname(world), "charts")
    time_plots, memory_plots = [], []
    for k, method in enumerate(CHAIN_METHODS):
        series = [(num(by[(n, method)]["rows"]), num(by[(n, method)]["step_median_ms"]), num(by[(n, method)]["step_mean_ms"]),
                   (num(by[(n, method)]["rss_peak_kb"]) - num(by[(n, method)]["rss_before_kb"])) / 1024)
                  for n in links if (n, method) in by]
        if not series:
            continue
        path = common.write_dat(charts, f"chain-{method}.dat", series)
        time_plots.append(f"'{path}' using 1:2 with linespoints lw 2 pt {k + 5} lc {k + 1} title '{method} median', "
                          f"'{path}' using 1:3 with linespoints dt 2 lw 1 pt {k + 5} lc {k + 1} title '{method} mean'")
        memory_plots.append(f"'{path}' using 1:4 with linespoints lw 2 pt {k + 5} lc {k + 1} title '{method}'")
    common.run_gnuplot(charts, "chain-time",
                       "set title 'Hanging chain: whole dWorldStep against rows (log-log)'\nset logscale xy\n"
                       "set xlabel 'rows (3 per ball joint)'\nset ylabel 'step time (ms)'\nset key top left\n"
                       "set grid\nplot " + ", ".join(time_plots))
    common.run_gnuplot(charts, "chain-memory",
                       "set title 'Hanging chain: peak memory added against rows (log-log)'\nset logscale xy\n"
                       "set xlabel 'rows'\nset ylabel 'peak resident memory added (MB)'\nset key top left\n"
                       "set grid\nplot " + ", ".join(memory_plots))


# ------------------------------------------------------------------------------------------
# the paper's scenes against QuickStep


def scenes_table(lines, world, targets):
    rows = read_csv(os.path.join(world, "scenes.csv"))
    lines.append("### The paper's scenes: whole step against QuickStep (and QuickStep routed to bpp)\n")
    if not rows:
        lines.append("Not measured (scenes.csv missing; see the failures).\n")
        targets.add("scenes: bpp's median step ≤ QuickStep-20's on the crane and the offshore rig", "–", "≤ 1×", False,
                    measured_at_all=False)
        return
    lines.append("Each scene stepped four times in one process, the worlds in turn (the order rotated every step): "
                 "`dWorldStep` with bpp; `dWorldQuickStep` at 20 and 100 iterations; `dWorldQuickStep` routed to bpp "
                 "(`dWorldSetQuickStepMLCPSolver`, issue 14). Time: the step call alone. Joint error: the largest anchor "
                 "gap of the world's ball, hinge, universal and hinge-2 joints (hinge-2 across its suspension axis), "
                 "largest and median over the steps. *Criterion*: the scene's own success criterion at the end (the "
                 "quick mode's shorter runs cannot meet the criteria that need the whole scene).\n")
    lines.append("| scene | method | median step | mean step | slowest 1 % | method / bpp (median) | joint error max | median | criterion |")
    lines.append("|---|---|---|---|---|---|---|---|---|")
    by = {(r["scene"], r["method"]): r for r in rows}
    for scene in PAPER_SCENES:
        bpp = by.get((scene, "bpp"))
        for method in SCENE_METHODS:
            r = by.get((scene, method))
            if not r:
                continue
            ratio = num(r["step_median_ms"]) / num(bpp["step_median_ms"]) if bpp else math.nan
            lines.append(f"| {scene} | {method} | {ms(num(r['step_median_ms']))} | {ms(num(r['step_mean_ms']))} | "
                         f"{ms(num(r['step_slowest1_ms']))} | {common.fmt_x(ratio)} | {metres(num(r['gap_max_m']))} | "
                         f"{metres(num(r['gap_median_m']))} | {r['success']} |")
    lines.append("")
    for scene in ("crane", "offshore"):
        b, q = by.get((scene, "bpp")), by.get((scene, "quickstep-20"))
        if not b or not q:
            targets.add(f"{scene}: bpp's median step ≤ QuickStep-20's", "–", "≤ 1×", False, measured_at_all=False)
            continue
        ratio = num(b["step_median_ms"]) / num(q["step_median_ms"])
        targets.add(f"{scene}: bpp's median step / QuickStep-20's (joint error bpp vs QuickStep-20)",
                    f"{ratio:.2f} ({num(b['step_median_ms']):.3f} vs {num(q['step_median_ms']):.3f} ms; "
                    f"{num(b['gap_max_m']):.1e} vs {num(q['gap_max_m']):.1e} m)", "≤ 1", ratio <= 1.0, common.gap(ratio, 1.0))
    routed = [(s, by.get((s, "quickstep-bpp")), by.get((s, "quickstep-20"))) for s in PAPER_SCENES]
    lines.append("Issue 14, QuickStep routed to bpp against QuickStep-20 (median step ratio; joint error):\n")
    lines.append("| scene | routed / QuickStep-20 | routed / bpp's dWorldStep | joint error routed | QuickStep-20 |")
    lines.append("|---|---|---|---|---|")
    for scene, routed_row, quick in routed:
        if not routed_row or not quick:
            continue
        bpp = by.get((scene, "bpp"))
        lines.append(f"| {scene} | {common.fmt_x(num(routed_row['step_median_ms']) / num(quick['step_median_ms']))} | "
                     f"{common.fmt_x(num(routed_row['step_median_ms']) / num(bpp['step_median_ms'])) if bpp else '–'} | "
                     f"{metres(num(routed_row['gap_max_m']))} | {metres(num(quick['gap_max_m']))} |")
    lines.append("")


# ------------------------------------------------------------------------------------------
# instruction count


def callgrind_target(lines, world, targets):
    rows = {r["method"]: r for r in read_csv(os.path.join(world, "callgrind.csv"))}
    lines.append("### Instructions per dWorldStep on the crane (callgrind)\n")
    if "bpp" not in rows:
        lines.append("Not measured (valgrind missing or failed; see the failures).\n")
        targets.add("crane: callgrind instructions per bpp dWorldStep", "–", f"≤ {CRANE_INSTRUCTIONS_BEFORE / 3:.3g}",
                    False, measured_at_all=False)
        return
    lines.append("`valgrind --tool=callgrind --toggle-collect=dWorldStep` (and `dWorldQuickStep`) over the crane scene, "
                 "total over every step divided by the steps: repeatable under any load. Before the sparse form: "
                 f"{CRANE_INSTRUCTIONS_BEFORE:.3g} per step with bpp.\n")
    lines.append("| method | steps | instructions | per step | of the count before |")
    lines.append("|---|---|---|---|---|")
    for method, r in rows.items():
        per = num(r["per_step"])
        lines.append(f"| {method} | {r['steps']} | {num(r['instructions']):.4g} | {per:.4g} | {per / CRANE_INSTRUCTIONS_BEFORE:.2f} |")
    lines.append("")
    breakdown(lines, world, max(1, int(num(rows["bpp"]["steps"]))))
    per = num(rows["bpp"]["per_step"])
    target = CRANE_INSTRUCTIONS_BEFORE / 3
    targets.add("crane: callgrind instructions per bpp dWorldStep (fraction of 4.6 M)", f"{per:.3g} ({per / CRANE_INSTRUCTIONS_BEFORE:.2f})",
                f"≤ {target:.3g} (a third)", per <= target, common.gap(per, target))


def breakdown(lines, world, steps):
    """Where bpp's crane step goes: callgrind's inclusive counts of the step's main functions."""
    path = os.path.join(world, "callgrind-crane-bpp.txt")
    if not os.path.exists(path):
        return
    wanted = [("dxStepIsland(", "ODE: one island's step (all below)"),
              ("solve_island(", "ode-bpp: the solver call (all below)"),
              ("IslandView::of(", "assembling A from J (O(nnz)) and the view"),
              ("ode_bpp::solve(", "validation, ordering, pivoting, residuals"),
              ("solve_frozen(", "pivoting: both fixed-bound solves"),
              ("skyline_cholesky(", "skyline factorizations"),
              ("skyline_solve(", "triangular solves"),
              ("SkylineSolver::prepare(", "loading the envelope"),
              ("compute_residuals(", "residuals of the Result"),
              ("validate_matrix(", "validation of A"),
              ("RowStateMemory::recall(", "warm start: recall"),
              ("RowStateMemory::remember(", "warm start: remember"),
              ("dxStepIsland_Stage0_Bodies(", "ODE: body inertia, forces"),
              ("dxStepIsland_Stage2a(", "ODE: J and J M^-1 (Stage 2a)"),
              ("dxStepIsland_Stage4(", "ODE: integration")]
    with open(path) as handle:
        text = handle.readlines()
    found = []
    for key, label in wanted:
        for line in text:
            match = re.match(r"\s*([\d,]+)\s+\(\s*([\d.]+)%\)", line)
            if key in line and match:
                found.append((label, int(match.group(1).replace(",", "")), float(match.group(2))))
                break
    if not found:
        return
    lines.append(f"Where bpp's crane step goes (callgrind, inclusive instructions per step, over {steps} steps):\n")
    lines.append("| part | instructions per step | share of dWorldStep |")
    lines.append("|---|---|---|")
    for label, count, share in found:
        lines.append(f"| {label} | {count / steps:.4g} | {share:.1f} % |")
    lines.append("")


# ------------------------------------------------------------------------------------------
# the physical limit


def frames_of(rows):
    """per (scene, step): the islands' rows (one frame = one world step)."""
    frames = defaultdict(list)
    for r in rows:
        frames[(r["scene"], int(r["step"]))].append(r)
    return frames


def one_step_per_solve(r):
    """True when the island took no pivot step beyond the first of each fixed-bound solve (Frozen
    friction solves an island with friction rows twice)."""
    return int(r["pivots"]) <= (2 if int(r["friction_rows"]) > 0 else 1)


def limit_table(lines, world, bench, targets):
    rows = read_csv(os.path.join(world, "limit.csv"))
    lines.append("### Distance to the physical limit\n")
    lines.append("The *physical limit* of an island is one Cholesky factorization of its final A_FF in envelope storage "
                 "(skyline_cholesky, the file's Cuthill–McKee order restricted to F) plus one solve (skyline_solve), timed "
                 "alone: no validation, ordering, warm start, assembly or residuals (bench/report/physical_limit.h). "
                 "*Inside ODE*: bpp's own time in the world step (the solver call as dMLCPIslandStats::seconds measures it: "
                 "assembly of A from J, validation, cached ordering, warm-started pivoting, residuals) over the limit of the "
                 "index set it returned, both summed over a frame's islands; an MLCP observer captures each island before "
                 "its solve and times the limit after it, outside the timed call. *Corpus*: the same over the captured "
                 "corpus, where bpp solves cold (ordering included, no warm start). *One step*: frames on whose every island "
                 "bpp took one pivot step per fixed-bound solve (two with friction rows, Frozen friction). *With A*: the "
                 "same one-step frames over the limit plus the least time to form A from J (the assembly with its pattern "
                 "known, timed alone after the solve: bench/world/assembly_time.h), work that the limit leaves out and "
                 "that no solver given ODE's sparse form can skip; the target stays on the limit alone.\n")
    lines.append("| scene | frames inside ODE | bpp / limit median | p95 | one-step frames | their median | with A | corpus frames | corpus median | corpus one-step median | old limit (re-solve) median |")
    lines.append("|---|---|---|---|---|---|---|---|---|---|---|")
    frames = frames_of(rows)
    for scene in PAPER_SCENES:
        ratios, simple, with_a = [], [], []
        for (s, _), islands in frames.items():
            if s != scene:
                continue
            t = sum(num(r["solve_us"]) for r in islands)
            lim = sum(num(r["physical_limit_us"]) for r in islands)
            if not (lim > 0) or any(r["status"] == "failed" for r in islands):
                continue
            ratios.append(t / lim)
            if all(one_step_per_solve(r) for r in islands):
                simple.append(t / lim)
                assembly = sum(num(r.get("assembly_us", "nan")) for r in islands)
                if assembly >= 0:
                    with_a.append(t / (lim + assembly))
        corpus = corpus_ratios(bench, scene)
        med_simple = common.quantile(simple, 0.5)
        lines.append(f"| {scene} | {len(ratios)} | {ratio(common.quantile(ratios, 0.5))} | {ratio(common.quantile(ratios, 0.95))} | "
                     f"{len(simple)} | {ratio(med_simple)} | {ratio(common.quantile(with_a, 0.5))} | {corpus['frames']} | "
                     f"{ratio(corpus['median'])} | {ratio(corpus['one_step'])} | {ratio(corpus['old'])} |")
        if ratios:
            targets.add(f"{scene}: bpp / physical limit inside ODE, median over one-step frames",
                        f"{med_simple:.2f} ({len(simple)} of {len(ratios)} frames)", f"≤ {LIMIT_TARGET}",
                        med_simple <= LIMIT_TARGET, common.gap(med_simple, LIMIT_TARGET), measured_at_all=bool(simple))
        else:
            targets.add(f"{scene}: bpp / physical limit inside ODE", "–", f"≤ {LIMIT_TARGET}", False, measured_at_all=False)
    lines.append("")


def corpus_ratios(bench, scene):
    """bpp's time over the physical limit on the corpus at CFM 1e-10, per frame (cold solves)."""
    islands = bench.get(f"{scene}-cfm1e-10", {})
    frames = defaultdict(lambda: [0.0, 0.0, 0.0, True])
    for (frame, _), methods in islands.items():
        r = methods.get("bpp")
        if not r or "physical_limit_us" not in r:
            continue
        f = frames[frame]
        f[0] += num(r["time_us"])
        f[1] += num(r["physical_limit_us"])
        f[2] += num(r["limit_us"])
        f[3] = f[3] and int(r["pivots"]) <= (2 if int(r.get("friction_rows") or 0) > 0 else 1)
    ratios = [f[0] / f[1] for f in frames.values() if f[1] > 0]
    return {"frames": len(ratios), "median": common.quantile(ratios, 0.5),
            "one_step": common.quantile([f[0] / f[1] for f in frames.values() if f[1] > 0 and f[3]], 0.5),
            "old": common.quantile([f[0] / f[2] for f in frames.values() if f[2] > 0], 0.5)}


# ------------------------------------------------------------------------------------------
# small islands


def classic_table(lines, world, targets):
    rows = read_csv(os.path.join(world, "classic.csv"))
    lines.append("### Small islands: the classic demos and the tiny-island scene, bpp against dantzig\n")
    if not rows:
        lines.append("Not measured (classic.csv missing; see the failures).\n")
        targets.add("small islands: bpp's solve ≤ dantzig's", "–", "≤ 1×", False, measured_at_all=False)
        return
    lines.append("Both worlds stepped in turn in one process. *Solve*: the time inside the MLCP solver call per island "
                 "(dMLCPStepStats::seconds over the step's islands), median over the steps (in brackets: total time over "
                 "total islands, which the slowest steps dominate); for dantzig ODE builds the dense A before the call, "
                 "for bpp the call assembles A from J itself. *Step*: the whole `dWorldStep` per island, the same way.\n")
    lines.append("| scene | islands per step | rows per island | bpp solve per island | dantzig | bpp / dantzig | "
                 "bpp step per island | dantzig | bpp / dantzig | same islands |")
    lines.append("|---|---|---|---|---|---|---|---|---|---|")
    by = {(r["scene"], r["method"]): r for r in rows}
    slower = []
    for scene in CLASSIC_SCENES:
        b, d = by.get((scene, "bpp")), by.get((scene, "dantzig"))
        if not b or not d:
            continue
        solve = num(b["solve_per_island_median_us"]) / num(d["solve_per_island_median_us"])
        step = num(b["step_per_island_median_us"]) / num(d["step_per_island_median_us"])
        if not solve <= 1.0:
            slower.append(f"{scene} {solve:.2f}×")
        lines.append(f"| {scene} | {num(b['islands_per_step']):.1f} | {num(b['rows_per_island']):.1f} | "
                     f"{per_island(b, 'solve')} | {per_island(d, 'solve')} | {solve:.2f}× | "
                     f"{per_island(b, 'step')} | {per_island(d, 'step')} | {step:.2f}× | {islands_note(b, d)} |")
    lines.append("")
    targets.add("small islands: bpp's median solve per island ≤ dantzig's on every classic demo and the tiny-island "
                "scene (bpp / dantzig where slower)", "; ".join(slower) or "none slower", "≤ 1× everywhere", not slower)


def per_island(row, what):
    """'median µs (mean µs)' of the solve or the step per island."""
    return f"{num(row[what + '_per_island_median_us']):.2f} µs ({num(row[what + '_per_island_us']):.2f})"


def islands_note(b, d):
    """'yes', or what dantzig's world had instead (see same_islands)."""
    if same_islands(b, d):
        return "yes"
    return f"no: {num(d['islands_per_step']):.1f} islands of {num(d['rows_per_island']):.1f} rows with dantzig"


def same_islands(b, d):
    """True when both worlds had the same islands: the same count and rows per step (a box stack
    that one solver lets fall apart splits into more, smaller islands: not comparable)."""
    return abs(num(b["islands_per_step"]) - num(d["islands_per_step"])) <= 0.02 * num(b["islands_per_step"]) and \
        abs(num(b["rows_per_island"]) - num(d["rows_per_island"])) <= 0.02 * num(b["rows_per_island"])


def islands_chart(lines, world):
    rows = read_csv(os.path.join(world, "islands.csv"))
    lines.append("### Time per island against island size\n")
    if not rows:
        lines.append("Not measured (islands.csv missing; see the failures).\n")
        return
    lines.append("Worlds of many copies of one island (bench/world/island_family.h: a frictionless resting sphere, 1 row; "
                 "a sphere with friction, 3; hanging chains, 3 per joint; box stacks, about 12 per face), bpp and dantzig "
                 "stepped in turn; per island: the solver call and the whole step, median over the steps. *Same islands*: "
                 "whether both worlds kept the same islands (a stack that falls apart under one solver splits into "
                 "others, and its times are then not comparable; the chart leaves it out).\n")
    lines.append("| family | rows per island | islands | bpp solve | dantzig solve | bpp / dantzig | bpp step | dantzig step | bpp / dantzig | same islands |")
    lines.append("|---|---|---|---|---|---|---|---|---|---|")
    by = defaultdict(dict)
    for r in rows:
        by[r["scene"]][r["method"]] = r
    series = defaultdict(list)
    for family, methods in sorted(by.items(), key=lambda kv: num(kv[1].get("bpp", {}).get("rows_per_island", "nan"))):
        b, d = methods.get("bpp"), methods.get("dantzig")
        if not b or not d:
            continue
        same = same_islands(b, d)
        if same:
            for m, r in methods.items():
                series[m].append((num(r["rows_per_island"]), num(r["solve_per_island_median_us"]),
                                  num(r["step_per_island_median_us"])))
        lines.append(f"| {family} | {num(b['rows_per_island']):.1f} | {num(b['islands_per_step']):.0f} | "
                     f"{num(b['solve_per_island_median_us']):.2f} µs | {num(d['solve_per_island_median_us']):.2f} µs | "
                     f"{num(b['solve_per_island_median_us']) / num(d['solve_per_island_median_us']):.2f}× | "
                     f"{num(b['step_per_island_median_us']):.2f} µs | {num(d['step_per_island_median_us']):.2f} µs | "
                     f"{num(b['step_per_island_median_us']) / num(d['step_per_island_median_us']):.2f}× | "
                     f"{islands_note(b, d)} |")
    lines.append("")
    charts = os.path.join(os.path.dirname(world), "charts")
    plots = []
    for k, method in enumerate(["bpp", "dantzig"]):
        points = sorted(series.get(method, []))
        if not points:
            continue
        path = common.write_dat(charts, f"islands-{method}.dat", points)
        plots.append(f"'{path}' using 1:2 with points pt {k + 5} ps 1.5 lc {k + 1} title '{method}: solver call', "
                     f"'{path}' using 1:3 with points pt {k + 9} ps 1.2 lc {k + 1} title '{method}: whole step'")
    if plots:
        common.run_gnuplot(charts, "island-size",
                           "set title 'Time per island against island size (log-log)'\nset logscale xy\n"
                           "set xlabel 'rows per island'\nset ylabel 'time per island (us)'\nset key top left\nset grid\n"
                           "plot " + ", ".join(plots))
        lines.append("![time per island against its size](charts/island-size.png)\n")


# ------------------------------------------------------------------------------------------
# long chains


# The sweeps' chain (demos/scenes/sweep_scenes.cpp): a 100 kg load, 0.5 m links whose rotational
# inertia is raised to that of a link as heavy as the load (I = M l^2 / 12 for a slender link).
SWEEP_LOAD_KG, SWEEP_LINK_M, GRAVITY = 100.0, 0.5, 9.81


def top_mode_step(links, ratio, h):
    """omega h of the topmost link's rotational mode, omega^2 = T l / I, under the tension of the
    whole chain T = (N m + M) g (docs/benchmarks.md, "Long chains"): an explicit step of that mode
    is unstable beyond about 2."""
    tension = (links * SWEEP_LOAD_KG / ratio + SWEEP_LOAD_KG) * GRAVITY
    inertia = SWEEP_LOAD_KG * SWEEP_LINK_M ** 2 / 12
    return h * math.sqrt(tension * SWEEP_LINK_M / inertia)


def conditioning_table(lines, world):
    rows = read_csv(os.path.join(world, "conditioning.csv"))
    lines.append("### Long chains: ODE's model, not the conditioning of A\n")
    if not rows:
        lines.append("Not measured (conditioning.csv missing; see the failures).\n")
        return
    lines.append("The sweeps' chain at mass ratio 40 (bench/world/chain_conditioning.cpp): every step the island is "
                 "solved three ways, bpp, bpp with two rounds of iterative refinement (residual in long double) and a "
                 "long-double sparse LDLᵀ, and one of them drives the world. Residual: |b − A x|∞/|b|∞ in long double; "
                 "error: distance to the long-double answer, relative; cond₂(A) by power iteration; ω: the fastest link's "
                 "angular speed; drift: ODE's linearised-joint estimate (ω h)² ℓ / (2 ERP).\n")
    lines.append("| links | rows | h | drives | joint gap | bpp residual | bpp error | refined error | cond₂(A) | ω max | drift estimate | top link ω h estimate |")
    lines.append("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        top = top_mode_step(int(r["links"]), num(r["ratio"]), num(r["step"]))
        lines.append(f"| {r['links']} | {r['rows']} | 1/{1 / num(r['step']):.0f} | {r['variant']} | {num(r['gap_max_m']):.1e} m | "
                     f"{num(r['residual_bpp_max']):.1e} | {num(r['error_bpp_max']):.1e} | {num(r['error_refined_max']):.1e} | "
                     f"{num(r['cond_max']):.1e} | {num(r['omega_max']):.2g} rad/s | {num(r['linearisation_drift_max_m']):.1e} m | "
                     f"{top:.2f} |")
    lines.append("")
    tension = read_csv(os.path.join(world, "tension.csv"))
    if tension:
        lines.append("The same tear with dantzig, on a shorter chain of heavier links (mass ratio 3, h = 1/60, the whole run):\n")
        lines.append("| links | rows | method | joint gap | top link ω h estimate |")
        lines.append("|---|---|---|---|---|")
        for r in tension:
            lines.append(f"| {r['links']} | {r['rows']} | {r['method']} | {num(r['gap_max_m']):.1e} m | "
                         f"{top_mode_step(int(r['links']), num(r['ratio']), 1 / 60):.2f} |")
        lines.append("")
    lines.append("Reading: the solve is accurate to about 1e-11 (refined: 1e-14) at cond₂(A) ≈ 1e7 whether the chain holds "
                 "or tears, and the long-double and refined solves tear it just the same; halving h holds it. "
                 "docs/benchmarks.md explains the mechanism.\n")


# ------------------------------------------------------------------------------------------


def section(lines, out_dir, bench, missed, failures):
    """The whole section; every part runs under make_report's section() guard."""
    world = os.path.join(out_dir, "world")
    lines.append("## The sparse world step: the whole step, method against method\n")
    if not os.path.isdir(world):
        lines.append("Not measured (scripts/bench-world.sh did not run; see the failures).\n")
        missed.append("sparse world step: not measured")
        return
    targets = common.Targets(missed, "sparse world step")
    body = []
    for name, function, args in (("chain scaling", chain_table, (body, world, targets)),
                                 ("scenes against QuickStep", scenes_table, (body, world, targets)),
                                 ("crane instructions", callgrind_target, (body, world, targets)),
                                 ("physical limit", limit_table, (body, world, bench, targets)),
                                 ("small islands", classic_table, (body, world, targets)),
                                 ("island sizes", islands_chart, (body, world)),
                                 ("long chains", conditioning_table, (body, world))):
        common.section(body, failures, name, function, *args)
    lines.append("### Targets of the sparse world step\n")
    lines.append("| target | measured | target | verdict |")
    lines.append("|---|---|---|---|")
    lines.extend(targets.rows)
    lines.append("")
    lines.append("Same answers: `tests/scenes/test_sparse_form.cpp` compares the sparse and the dense form on every scene "
                 "(x and 100 steps of trajectory); it is a test, run by `make test`, not a measurement.\n")
    lines.extend(body)
