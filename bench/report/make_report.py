#!/usr/bin/env python3
"""make_report.py OUT_DIR MODE: tables, targets and charts from bench-report.sh's outputs.

Reads OUT_DIR/bench.csv (bench_corpus: one row per file x method variant, peers included),
OUT_DIR/steps/*.csv (ode-bpp-demo's per-island-per-step CSV) and, if present, OUT_DIR/bench_fig4.csv,
OUT_DIR/fig5.csv with OUT_DIR/fig5/*.dat, OUT_DIR/callgrind.csv, OUT_DIR/world/*.csv (the whole world
step, scripts/bench-world.sh; its section is world_report.py's) and OUT_DIR/failures.txt; writes
OUT_DIR/report.md and OUT_DIR/charts/*.png|svg (gnuplot). Standard library only. A section whose
inputs are missing or broken says so in the report instead of stopping it.

A frame is one captured step of one scene and regime; its solve time is the sum over its islands
(the paper does not parallelize islands, Sec. 4.2). Table 3 and Table 4 exclude frames without
tight variables, as the paper does; Table 3 also gives the average over all frames.
"""
import csv
import math
import os
import statistics
import subprocess
import sys
from collections import defaultdict

import contact_report
import world_report

SCENES = ["crane", "winch", "parkour", "offshore", "forklift", "forwarder"]
REGIMES = [("cfm1e-10", "ODE's default CFM 1e-10"), ("comp1e-8", "the paper's compliance 1e-8 (CFM = c/h)")]
TABLE3_METHODS = ["bpp-chol", "bpp-down", "bpp-sky", "bpp", "dantzig", "pgs-35"]
DIRECT = ["bpp-chol", "bpp-down", "bpp-sky", "bpp", "dantzig", "bpp-consistent"]
PGS = ["pgs-10", "pgs-35", "pgs-100", "pgs-300", "pgs-1000"]
# Table 3 of the paper: Downdating Skyline over Full Cholesky
PAPER_SPEEDUP = {"crane": 3.6, "winch": 1.3, "parkour": 1.4, "offshore": 2.3, "forklift": 1.5, "forwarder": 1.6}
PAPER_T3_MS = {"crane": (12.4, 4.7, 3.4), "winch": (2.0, 2.4, 1.6), "parkour": (3.0, 2.2, 2.1),
               "offshore": (6.7, 4.0, 2.9), "forklift": (1.2, 1.0, 0.8), "forwarder": (3.1, 2.5, 2.0)}
# Table 4 of the paper: min, max, mean, median; first row without skyline, second with
PAPER_T4 = {
    "crane": ((6.74e-12, 3.00e-10, 4.77e-11, 3.80e-11), (6.76e-12, 2.50e-10, 4.84e-11, 3.88e-11)),
    "winch": ((0, 7.29e-11, 6.60e-13, 1.31e-13), (0, 7.34e-11, 6.07e-13, 1.28e-13)),
    "parkour": ((3.17e-13, 1.81e-09, 4.93e-12, 7.18e-13), (2.71e-13, 7.99e-10, 1.85e-12, 7.36e-13)),
    "offshore": ((0, 2.00e-08, 1.50e-09, 6.55e-11), (0, 1.00e-08, 1.30e-09, 5.55e-11)),
    "forklift": ((0, 5.74e-11, 1.50e-12, 1.46e-12), (0, 1.17e-11, 1.35e-12, 1.36e-12)),
    "forwarder": ((1.11e-10, 7.00e-08, 4.04e-09, 3.22e-09), (1.11e-10, 7.00e-08, 4.04e-09, 3.22e-09)),
}
RESIDUAL_FLOOR = 1e-18  # zero residuals drawn at this height on log axes
# peers: bench_corpus names them <package>-<solver>[-<sweeps>]
PEER_PACKAGES = ("dart-", "bullet-", "siconos-")
PEER_DIRECT = ["dart-dantzig", "bullet-dantzig", "bullet-lemke", "siconos-lemke"]
PEER_ITERATIVE = ["dart-pgs", "bullet-pgs", "siconos-pgs"]


def num(text):
    try:
        return float(text)
    except (TypeError, ValueError):
        return math.nan


def finite(values):
    return [v for v in values if not math.isnan(v)]


def quantile(values, q):
    values = sorted(finite(values))
    if not values:
        return math.nan
    return values[min(len(values) - 1, int(q * (len(values) - 1) + 0.5))]


def fmt_ms(us):
    return "–" if math.isnan(us) else f"{us / 1000:.3f} ms"


def fmt_x(ratio):
    return "–" if math.isnan(ratio) or math.isinf(ratio) else f"{ratio:.2f}×"


def fmt_e(value):
    return "–" if math.isnan(value) else f"{value:.2e}"


def verdict(ok, measured=True, gap=""):
    """'met' or '**missed**', followed by the gap to the target when one is given."""
    if not measured:
        return "n/a (no frame with tight rows)"
    return ("met" if ok else "**missed**") + (f" ({gap})" if gap else "")


class Targets:
    """The rows of a section's target table, and its misses for the report's list, each prefixed
    with the section's name."""

    def __init__(self, missed, prefix):
        self.rows = []
        self.missed = missed
        self.prefix = prefix

    def add(self, what, measured, target, ok, gap="", measured_at_all=True):
        verdict_text = verdict(ok, measured_at_all, gap) if measured_at_all else "not measured"
        self.rows.append(f"| {what} | {measured} | {target} | {verdict_text} |")
        if measured_at_all and not ok:
            self.missed.append(f"{self.prefix}: {what}: {measured} (target {target})")
        if not measured_at_all:
            self.missed.append(f"{self.prefix}: {what}: not measured")


def gap(measured, target):
    """measured relative to target, in % (+ above, − below)."""
    if math.isnan(measured) or math.isnan(target) or target == 0:
        return ""
    return f"{100.0 * (measured / target - 1.0):+.0f} %".replace("-", "−")


def mean(values):
    values = finite(values)
    return sum(values) / len(values) if values else math.nan


# ------------------------------------------------------------------------------------------
# loading


def load_bench(path):
    """rows[group][(frame, island)][method] = row dict."""
    rows = defaultdict(lambda: defaultdict(dict))
    with open(path, newline="") as handle:
        for row in csv.DictReader(handle):
            rows[row["group"]][(int(row["frame"] or 0), int(row["island"] or 0))][row["method"]] = row
    return rows


def frames_of(islands):
    """frames[frame][method] = {time_us, residual, converged, tight, skipped, failed}; a frame is one
    captured step, its values summed (time) or maxed (residuals) over its islands. A method appears
    in a frame only when it ran on every island of the frame (peers run on a subset of frames;
    a peer that skipped an island, e.g. Lemke above its size limit, is left out of that frame)."""
    count = defaultdict(int)
    frames = defaultdict(lambda: defaultdict(lambda: {"time_us": 0.0, "limit_us": 0.0, "residual": 0.0, "nonfriction": 0.0,
                                                      "friction": 0.0, "converged": True, "tight": 0, "skipped": False,
                                                      "failed": 0, "islands": 0}))
    for (frame, _), methods in islands.items():
        count[frame] += 1
        for method, row in methods.items():
            f = frames[frame][method]
            f["islands"] += 1
            f["time_us"] += num(row["time_us"])
            f["limit_us"] += num(row["limit_us"])
            f["residual"] = max(f["residual"], num(row["relative_natural_residual"]))
            f["nonfriction"] = max(f["nonfriction"], num(row.get("nonfriction_residual")))
            f["friction"] = max(f["friction"], num(row["friction_error"]))
            f["converged"] = f["converged"] and row["status"] == "converged"
            f["skipped"] = f["skipped"] or row["status"] == "skipped"
            f["failed"] += row["status"] == "failed"
            f["tight"] += int(row["tight"] or 0)
    for frame, methods in frames.items():
        for method in [m for m, f in methods.items() if f["islands"] < count[frame] or f["skipped"]]:
            del methods[method]
    return frames


def having(frames, *methods):
    """The frames in which every one of methods ran."""
    return [f for f in frames if all(m in f for m in methods)]


def is_peer(method):
    return method.startswith(PEER_PACKAGES)


def frame_is_tight(methods):
    return "bpp-chol" in methods and methods["bpp-chol"]["tight"] > 0


def load_steps(out_dir, scene, name=None):
    """per solver: list of (step, step_ms, solve_ms summed over islands), from OUT_DIR/steps/NAME
    (default: the CFM 1e-10 run, <scene>-step.csv)."""
    path = os.path.join(out_dir, "steps", name or f"{scene}-step.csv")
    steps = defaultdict(dict)
    if not os.path.exists(path):
        return {}
    with open(path, newline="") as handle:
        for row in csv.DictReader(handle):
            key = int(row["step"])
            entry = steps[row["solver"]].setdefault(key, [num(row["step_ms"]), 0.0])
            entry[1] += num(row["solve_ms"])
    return {solver: [(k, v[0], v[1]) for k, v in sorted(per.items())] for solver, per in steps.items()}


def load_tight_fraction(out_dir, scene, regime):
    """per step: 100 * tight rows / rows over all islands (Fig. 3), from the bpp corpus run."""
    path = os.path.join(out_dir, "steps", f"{scene}-{regime}-bpp.csv")
    per_step = defaultdict(lambda: [0.0, 0, 0])
    if not os.path.exists(path):
        return []
    with open(path, newline="") as handle:
        for row in csv.DictReader(handle):
            entry = per_step[int(row["step"])]
            entry[0] = num(row["time"])
            entry[1] += int(row["tight"])
            entry[2] += int(row["rows"])
    return [(v[0], 100.0 * v[1] / v[2] if v[2] else 0.0) for _, v in sorted(per_step.items())]


# ------------------------------------------------------------------------------------------
# tables


def table3(lines, bench, regime):
    lines.append(f"### Table 3 — {dict(REGIMES)[regime]}\n")
    lines.append("Average solve time per frame (sum over islands). Row *T*: frames with tight variables "
                 "(the paper's selection); row *all*: every frame. In brackets: speed-up over bpp-chol / over dantzig.\n")
    lines.append("| scene | frames | " + " | ".join(TABLE3_METHODS) + " | paper (chol / down / sky) |")
    lines.append("|---|---|" + "---|" * len(TABLE3_METHODS) + "---|")
    for scene in SCENES:
        frames = frames_of(bench.get(f"{scene}-{regime}", {}))
        for label, selected in (("T", [f for f in frames.values() if frame_is_tight(f)]), ("all", list(frames.values()))):
            selected = having(selected, *TABLE3_METHODS)
            means = {m: mean([f[m]["time_us"] for f in selected]) for m in TABLE3_METHODS}
            cells = []
            for m in TABLE3_METHODS:
                cells.append(f"{fmt_ms(means[m])} ({fmt_x(means['bpp-chol'] / means[m])} / {fmt_x(means['dantzig'] / means[m])})")
            paper = " / ".join(f"{v} ms" for v in PAPER_T3_MS[scene]) if label == "T" else ""
            lines.append(f"| {scene} {label} | {len(selected)} | " + " | ".join(cells) + f" | {paper} |")
    lines.append("")


def table4(lines, bench, regime):
    lines.append(f"### Table 4 — factor error ‖L_deleted − chol(A_FF)‖_F, {dict(REGIMES)[regime]}\n")
    lines.append("Over the islands with tight rows (the method's own final set). Paper: first row without skyline "
                 "(vs. bpp-down), second with (vs. bpp-sky).\n")
    lines.append("| scene | method | islands | min | max | mean | median | paper min / max / mean / median |")
    lines.append("|---|---|---|---|---|---|---|---|")
    for scene in SCENES:
        islands = bench.get(f"{scene}-{regime}", {})
        for method, paper in (("bpp-down", PAPER_T4[scene][0]), ("bpp-sky", PAPER_T4[scene][1]), ("bpp", None)):
            errors = finite([num(m[method]["factor_error"]) for m in islands.values()
                             if method in m and int(m[method]["tight"]) > 0])
            stats = (min(errors), max(errors), mean(errors), statistics.median(errors)) if errors else (math.nan,) * 4
            paper_text = " / ".join(fmt_e(v) for v in paper) if paper else ""
            lines.append(f"| {scene} | {method} | {len(errors)} | " + " | ".join(fmt_e(v) for v in stats) + f" | {paper_text} |")
    lines.append("")


def convergence(lines, bench):
    lines.append("### Convergence rate (islands whose status is `converged`)\n")
    lines.append("| scene-regime | islands | " + " | ".join(DIRECT) + " | bpp fallbacks |")
    lines.append("|---|---|" + "---|" * len(DIRECT) + "---|")
    for regime, _ in REGIMES:
        for scene in SCENES:
            islands = bench.get(f"{scene}-{regime}", {})
            cells = []
            for m in DIRECT:
                rows = [i[m] for i in islands.values() if m in i]
                ok = sum(r["status"] == "converged" for r in rows)
                cells.append(f"{100.0 * ok / len(rows):.1f} %" if rows else "–")
            fallbacks = sum(1 for i in islands.values() if "bpp" in i and i["bpp"]["fallback"] != "-")
            lines.append(f"| {scene}-{regime} | {len(islands)} | " + " | ".join(cells) + f" | {fallbacks} |")
    lines.append("")


def callgrind(lines, out_dir):
    path = os.path.join(out_dir, "callgrind.csv")
    lines.append("### Instructions inside ode_bpp::solve (callgrind), one island with tight rows per scene\n")
    if not os.path.exists(path):
        lines.append("Not measured (valgrind missing or no frame with tight rows).\n")
        return
    with open(path, newline="") as handle:
        rows = {r["method"]: r for r in csv.DictReader(handle)}
    lines.append("Noise-free counterpart of the wall-clock ratios (same files, same number of solves per method).\n")
    lines.append("| method | files | solves | instructions | per solve | dantzig / method |")
    lines.append("|---|---|---|---|---|---|")
    dz = num(rows.get("dantzig", {}).get("instructions"))
    for method, r in rows.items():
        total, solves = num(r["instructions"]), num(r["solves"])
        if not total or not solves:  # nothing collected: the toggle missed ode_bpp::solve
            lines.append(f"| {method} | {r['files']} | {r['solves']} | not collected | – | – |")
            continue
        lines.append(f"| {method} | {r['files']} | {r['solves']} | {total:.4g} | {total / solves:.4g} | {fmt_x(dz / total)} |")
    lines.append("")


def whole_step(lines, out_dir):
    lines.append("### Whole step: collide + dWorldStep, dantzig vs bpp (CFM 1e-10, no capture)\n")
    lines.append("| scene | steps | dantzig median step | bpp median step | ratio | dantzig mean step | bpp mean step | ratio | "
                 "dantzig solve share | bpp solve share |")
    lines.append("|---|---|---|---|---|---|---|---|---|---|")
    for scene in SCENES:
        steps = load_steps(out_dir, scene)
        if "dantzig" not in steps or "bpp" not in steps:
            lines.append(f"| {scene} | – | | | | | | | | |")
            continue
        d, b = steps["dantzig"], steps["bpp"]
        dm, bm = statistics.median(s[1] for s in d), statistics.median(s[1] for s in b)
        da, ba = mean([s[1] for s in d]), mean([s[1] for s in b])
        dshare = sum(s[2] for s in d) / sum(s[1] for s in d)
        bshare = sum(s[2] for s in b) / sum(s[1] for s in b)
        lines.append(f"| {scene} | {len(d)} | {dm:.3f} ms | {bm:.3f} ms | {fmt_x(dm / bm)} | {da:.3f} ms | {ba:.3f} ms | "
                     f"{fmt_x(da / ba)} | {100 * dshare:.0f} % | {100 * bshare:.0f} % |")
    lines.append("")


# ------------------------------------------------------------------------------------------
# targets


def targets(lines, bench):
    lines.append("## Targets (issue 5), each measured value next to its target\n")
    lines.append("Speed-ups are ratios of the mean frame time over the frames with tight variables; "
                 "*frames < 1×* counts the frames where bpp was slower than bpp-chol. bpp/limit: per frame (all frames), "
                 "bpp's time over its limit's, both summed over the frame's islands. Converged: frames on whose every "
                 "island bpp's status is `converged` (all frames). In brackets after each verdict: the gap, the measured "
                 "value relative to the target.\n")
    lines.append("| scene-regime | bpp vs bpp-chol | target | verdict | frames < 1× | bpp vs dantzig | target | verdict | "
                 "bpp/limit median | p95 | target (median ≤ 2) | bpp converged (frames) | target ≥ 99 % |")
    lines.append("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    missed = []
    for regime, _ in REGIMES:
        for scene in SCENES:
            group = f"{scene}-{regime}"
            islands = bench.get(group, {})
            frames = having([f for f in frames_of(islands).values() if frame_is_tight(f)], "bpp-chol", "bpp", "dantzig")
            chol = mean([f["bpp-chol"]["time_us"] for f in frames])
            bpp = mean([f["bpp"]["time_us"] for f in frames])
            dz = mean([f["dantzig"]["time_us"] for f in frames])
            slower = sum(f["bpp"]["time_us"] > f["bpp-chol"]["time_us"] for f in frames)
            s_chol, s_dz = chol / bpp if bpp else math.nan, dz / bpp if bpp else math.nan
            t_chol = PAPER_SPEEDUP[scene]
            t_dz = 10.0 if scene in ("crane", "winch") else 1.0
            ok_chol = s_chol >= t_chol
            ok_dz = s_dz >= t_dz if scene in ("crane", "winch") else s_dz > 1.0
            ratios = [f["bpp"]["time_us"] / f["bpp"]["limit_us"] for f in frames_of(islands).values()
                      if "bpp" in f and f["bpp"]["limit_us"] > 0]
            med, p95 = quantile(ratios, 0.5), quantile(ratios, 0.95)
            bpp_frames = [f for f in frames_of(islands).values() if "bpp" in f]
            conv = 100.0 * sum(f["bpp"]["converged"] for f in bpp_frames) / len(bpp_frames) if bpp_frames else math.nan
            for ok, what, needs_tight in ((ok_chol, f"bpp vs bpp-chol {fmt_x(s_chol)} < {t_chol}×", True),
                                          (ok_dz, f"bpp vs dantzig {fmt_x(s_dz)} (target {'≥ 10×' if t_dz > 1 else '> 1×'})", True),
                                          (med <= 2.0, f"bpp/limit median {med:.2f} > 2", False),
                                          (conv >= 99.0, f"convergence {conv:.1f} % of frames < 99 %", False)):
                if not ok and (frames or not needs_tight):
                    missed.append(f"{group}: {what}")
            if not frames:
                missed.append(f"{group}: speed-up targets not measured (no captured frame with tight rows; "
                              "the full mode captures more frames)")
            have = bool(frames)
            lines.append(f"| {group} | {fmt_x(s_chol)} | ≥ {t_chol}× | {verdict(ok_chol, have, gap(s_chol, t_chol))} | "
                         f"{slower}/{len(frames)} | {fmt_x(s_dz)} | {'≥ 10×' if t_dz > 1 else '> 1×'} | "
                         f"{verdict(ok_dz, have, gap(s_dz, t_dz))} | {med:.2f} | {p95:.2f} | {verdict(med <= 2.0, True, gap(med, 2.0))} | "
                         f"{conv:.1f} % of {len(bpp_frames)} | {verdict(conv >= 99.0, True, gap(conv, 99.0))} |")
    lines.append("")
    residual_target(lines, bench, missed)
    return missed


def headline(lines, bench):
    lines.append("## Headline (all scenes pooled, per-frame ratios)\n")
    lines.append("| regime | frames with tight rows | median bpp frame | median bpp-chol / bpp | median dantzig / bpp | "
                 "median pgs-35 / bpp | median bpp / limit (all frames) | limit solves certified in one step | bpp islands converged |")
    lines.append("|---|---|---|---|---|---|---|---|---|")
    for regime, label in REGIMES:
        tight, every, islands = [], [], []
        for scene in SCENES:
            frames = frames_of(bench.get(f"{scene}-{regime}", {})).values()
            every.extend(f for f in frames if "bpp" in f)
            tight.extend(f for f in frames if frame_is_tight(f) and "bpp" in f)
            islands.extend(i["bpp"] for i in bench.get(f"{scene}-{regime}", {}).values() if "bpp" in i)

        def ratio(method, frames):
            return quantile([f[method]["time_us"] / f["bpp"]["time_us"] for f in frames if method in f and f["bpp"]["time_us"] > 0], 0.5)

        limit = quantile([f["bpp"]["time_us"] / f["bpp"]["limit_us"] for f in every if f["bpp"]["limit_us"] > 0], 0.5)
        conv = 100.0 * sum(r["status"] == "converged" for r in islands) / len(islands) if islands else math.nan
        certified = sum(r["limit_status"] == "converged" for r in islands)
        lines.append(f"| {label} | {len(tight)} | {fmt_ms(quantile([f['bpp']['time_us'] for f in tight], 0.5))} | "
                     f"{fmt_x(ratio('bpp-chol', tight))} | {fmt_x(ratio('dantzig', tight))} | {fmt_x(ratio('pgs-35', tight))} | "
                     f"{limit:.2f} | {certified} of {len(islands)} | {conv:.2f} % of {len(islands)} |")
    lines.append("")


def residual_target(lines, bench, missed):
    lines.append("### bpp's relative natural residual ≤ 1e-9 where cond(A) ≤ 1e7\n")
    lines.append("cond₂(A) from the eigenvalues of each island's A (bench_corpus --cond). Relative residual: "
                 "Result::relative_natural_residual (friction bounds from the solution's own normals). "
                 "bpp, like Dantzig, keeps the friction bounds of a first solve (FrictionMode::Frozen), so its "
                 "answer may break |x_t| ≤ μ x_n for the final normals and this residual then measures that, "
                 "not rounding; *bpp-consistent* (FrictionMode::Consistent) is shown beside it.\n")
    lines.append("| scene-regime | islands cond ≤ 1e7 | bpp ≤ 1e-9 | bpp max there | dantzig max there | bpp max friction error there | "
                 "verdict | bpp-consistent ≤ 1e-9 | bpp-consistent max there | islands cond > 1e7 | bpp median there | bpp max there |")
    lines.append("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for regime, _ in REGIMES:
        for scene in SCENES:
            group = f"{scene}-{regime}"
            rows = [i["bpp"] for i in bench.get(group, {}).values() if "bpp" in i]
            consistent = [num(i["bpp-consistent"]["relative_natural_residual"]) for i in bench.get(group, {}).values()
                          if "bpp-consistent" in i and num(i["bpp-consistent"]["cond"]) <= 1e7]
            friction = [num(r["friction_error"]) for r in rows if num(r["cond"]) <= 1e7]
            dantzig = [num(i["dantzig"]["relative_natural_residual"]) for i in bench.get(group, {}).values()
                       if "dantzig" in i and num(i["dantzig"]["cond"]) <= 1e7]
            good = [num(r["relative_natural_residual"]) for r in rows if num(r["cond"]) <= 1e7]
            bad = [num(r["relative_natural_residual"]) for r in rows if not num(r["cond"]) <= 1e7]
            ok = sum(v <= 1e-9 for v in good)
            met = ok == len(good)
            if not met:
                missed.append(f"{group}: residual > 1e-9 on {len(good) - ok} of {len(good)} islands with cond ≤ 1e7")
            lines.append(f"| {group} | {len(good)} | {ok} | {fmt_e(max(good) if good else math.nan)} | "
                         f"{fmt_e(max(dantzig) if dantzig else math.nan)} | "
                         f"{fmt_e(max(friction) if friction else math.nan)} | "
                         f"{verdict(met) if good else 'n/a (no island with cond ≤ 1e7)'} | "
                         f"{sum(v <= 1e-9 for v in consistent)}/{len(consistent)} | "
                         f"{fmt_e(max(consistent) if consistent else math.nan)} | "
                         f"{len(bad)} | {fmt_e(quantile(bad, 0.5))} | {fmt_e(max(bad) if bad else math.nan)} |")
    lines.append("")


def accuracy(lines, bench, missed):
    lines.append("### Accuracy: rows without friction, and friction bound consistency\n")
    lines.append("Per island. *Non-friction residual*: the relative natural residual over the rows with findex < 0, where "
                 "every method solves the same fixed-bound conditions (bench_corpus's nonfriction_residual). "
                 "*Friction error*: max over friction rows of max(0, |x_t| − μ x_n) (Result::friction_error). "
                 "Target: bpp no worse than dantzig on the first, island by island: bpp ≤ max(dantzig, 1e-9), i.e. both "
                 "below the solver's relative tolerance (Options::tolerance = 1e-9) count as equal; the column *bpp > dantzig* "
                 "counts the islands where bpp's is larger at all, rounding included. Second target: far below dantzig's. "
                 "bpp (Frozen friction) has dantzig's semantics and so its friction error; only bpp-consistent can meet it, "
                 "and the verdict is bpp-consistent's max ≤ 1e-3 × dantzig's max (n/a where dantzig's answers are consistent).\n")
    lines.append("| scene-regime | islands | bpp max | dantzig max | bpp > dantzig | bpp > max(dantzig, 1e-9) | verdict | "
                 "friction error median / max: dantzig | bpp | bpp-consistent | verdict |")
    lines.append("|---|---|---|---|---|---|---|---|---|---|---|")
    for regime, _ in REGIMES:
        for scene in SCENES:
            group = f"{scene}-{regime}"
            islands = [i for i in bench.get(group, {}).values() if "bpp" in i and "dantzig" in i]
            if not islands:
                lines.append(f"| {group} | 0 | | | | | n/a | | | | |")
                continue
            bpp = [num(i["bpp"]["nonfriction_residual"]) for i in islands]
            dz = [num(i["dantzig"]["nonfriction_residual"]) for i in islands]
            larger = sum(b > d for b, d in zip(bpp, dz))
            worse = sum(b > max(d, 1e-9) for b, d in zip(bpp, dz))
            ok = worse == 0
            if not ok:
                missed.append(f"{group}: bpp's non-friction residual above max(dantzig's, 1e-9) on {worse} of {len(islands)} islands")

            def fe(method):
                values = finite([num(i[method]["friction_error"]) for i in islands if method in i])
                return (quantile(values, 0.5), max(values)) if values else (math.nan, math.nan)
            fd, fb, fc = fe("dantzig"), fe("bpp"), fe("bpp-consistent")
            friction_ok = fc[1] <= 1e-3 * fd[1]
            if fd[1] > 0 and not friction_ok:
                missed.append(f"{group}: bpp-consistent's max friction error {fmt_e(fc[1])} not far below dantzig's {fmt_e(fd[1])}")
            friction_verdict = verdict(friction_ok) if fd[1] > 0 else "n/a (dantzig consistent)"
            lines.append(f"| {group} | {len(islands)} | {fmt_e(max(finite(bpp) or [math.nan]))} | {fmt_e(max(finite(dz) or [math.nan]))} | "
                         f"{larger} | {worse} | {verdict(ok)} | {fmt_e(fd[0])} / {fmt_e(fd[1])} | {fmt_e(fb[0])} / {fmt_e(fb[1])} | "
                         f"{fmt_e(fc[0])} / {fmt_e(fc[1])} | {friction_verdict} |")
    lines.append("")


def peer_methods(bench):
    """Peer method names present in the CSV, direct ones first, iterative ones by sweep count."""
    names = {m for group in bench.values() for island in group.values() for m in island if is_peer(m)}
    def key(name):
        base, _, sweeps = name.rpartition("-")
        return (1, base, int(sweeps)) if sweeps.isdigit() else (0, name, 0)
    return sorted(names, key=key)


def peer_frames(islands):
    """The frames (as frames_of gives them) on which some peer ran, or every frame when none did."""
    frames = frames_of(islands)
    ran = {frame for (frame, _), methods in islands.items() if any(is_peer(m) for m in methods)}
    return [frames[k] for k in sorted(ran or frames)]


def peers_table(lines, bench):
    peers = peer_methods(bench)
    lines.append("## Peers side by side\n")
    if not peers:
        lines.append("Not measured: bench_corpus was built without the peers (`make deps-peers` installs DART, Bullet and "
                     "Siconos from Debian; bench/peers builds the adapters when they are found), or --no-peers was given.\n")
        return
    lines.append("Same islands, same process, interleaved with ode_bpp's methods, on the frames where the peers ran "
                 "(a subset, see the header). Each cell: median over frames of the method's frame time divided by bpp's "
                 "on the same frame, then the median relative natural residual (friction bounds from the answer's own "
                 "normals, the same function for every method); below it failed islands (the peer said so) and frames "
                 "left out (skipped islands). DART's and Bullet's Dantzig and PGS take friction through findex as ODE "
                 "does; Bullet's Lemke and Siconos' solvers only know fixed bounds, so friction is frozen for them as in "
                 "ODE's Dantzig: a first solve with the friction rows at 0, then bounds ±μ x_n from those normals for a second solve.\n")
    methods = ["bpp", "bpp-consistent", "dantzig", "pgs-35", "pgs-300"] + peers
    for regime, label in REGIMES:
        lines.append(f"### {label}\n")
        lines.append("| method | " + " | ".join(SCENES) + " |")
        lines.append("|---|" + "---|" * len(SCENES))
        per_scene = {scene: peer_frames(bench.get(f"{scene}-{regime}", {})) for scene in SCENES}
        for m in methods:
            cells = []
            for scene in SCENES:
                frames = having(per_scene[scene], "bpp", m)
                islands = [i[m] for i in bench.get(f"{scene}-{regime}", {}).values() if m in i]
                failed = sum(r["status"] == "failed" for r in islands)
                ran = {k for k, i in bench.get(f"{scene}-{regime}", {}).items() if m in i}
                frames_ran = {k[0] for k in ran}
                left_out = len(frames_ran) - len(frames) if frames_ran else 0
                if not frames:
                    cells.append("–" if not islands else f"skipped on all {len(frames_ran)} frames")
                    continue
                ratio = quantile([f[m]["time_us"] / f["bpp"]["time_us"] for f in frames if f["bpp"]["time_us"] > 0], 0.5)
                res = quantile([f[m]["residual"] for f in frames], 0.5)
                extra = []
                if failed:
                    extra.append(f"{failed} failed")
                if left_out > 0 and is_peer(m):
                    extra.append(f"{left_out} fr. left out")
                cells.append(f"{fmt_x(ratio)} · {fmt_e(res)}" + (f"<br>{', '.join(extra)}" if extra else ""))
            lines.append(f"| {m} | " + " | ".join(cells) + " |")
        lines.append("")


# ------------------------------------------------------------------------------------------
# charts


def gq(text):
    """text as the body of a gnuplot single-quoted string (a quote is written twice)."""
    return text.replace("'", "''")


def gnuplot_terminals():
    probe = subprocess.run(["gnuplot", "-e", "set terminal pngcairo"], capture_output=True, text=True)
    png = "pngcairo size 1500,900 font ',10'" if probe.returncode == 0 and not probe.stderr.strip() else "png size 1500,900"
    return png, "svg size 1500,900 dynamic"


def run_gnuplot(charts, name, body):
    png, svg = gnuplot_terminals()
    script = os.path.join(charts, "data", f"{name}.gp")
    with open(script, "w") as handle:
        for terminal, ext in ((png, "png"), (svg, "svg")):
            handle.write(f"set terminal {terminal}\nset output '{os.path.join(charts, name)}.{ext}'\n{body}\nunset multiplot\n")
    result = subprocess.run(["gnuplot", script], capture_output=True, text=True)
    if result.returncode != 0:
        print(f"make_report: gnuplot failed on {name}: {result.stderr.strip()}", file=sys.stderr)


def write_dat(charts, name, rows):
    path = os.path.join(charts, "data", name)
    with open(path, "w") as handle:
        for row in rows:
            handle.write(" ".join(f"{v:.6g}" if isinstance(v, float) else str(v) for v in row) + "\n")
    return path


def chart_work_precision(charts, bench, regime):
    """One panel per scene: x the median frame time, y the median over frames of the relative natural
    residual (max over the frame's islands); direct methods are points, PGS (ours and the peers')
    curves over sweep counts. With peers, only the frames they ran on, so that every point and curve
    comes from the same frames (a method missing a frame, e.g. Lemke above its size limit, is drawn
    from the frames it has, and its key says how many)."""
    peers = peer_methods(bench)
    subset = " frames where the peers ran;" if peers else ""
    body = [f"set multiplot layout 2,3 margins 0.06,0.84,0.08,0.9 spacing 0.06,0.12 "
            f"title 'Work-precision, {gq(dict(REGIMES)[regime])} (median frame;{subset} residual floor {RESIDUAL_FLOOR:g})'",
            "set logscale xy", "set xlabel 'solve time per frame (ms)'", "set ylabel 'relative natural residual'",
            "set format y '%.0e'", "set offsets graph 0.02, graph 0.02, graph 0.1, graph 0.02"]
    direct = DIRECT + [m for m in PEER_DIRECT if m in peers]
    curves = [("pgs", PGS)] + [(base, [m for m in peers if m.rpartition("-")[0] == base]) for base in PEER_ITERATIVE]
    # one style per method on every panel, so that a single key (drawn once, right of the panels) serves all
    palette = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"]
    style = {m: f"pt {k + 4} ps 1.6 lc rgb '{palette[k % len(palette)]}'" for k, m in enumerate(direct)}
    curve_colors = ["#000000", "#6a3d9a", "#b15928", "#e7298a"]  # ours solid black, the peers dashed
    style.update({base: f"pt 7 ps 0.8 lw 2 {'dt 2 ' if k else ''}lc rgb '{curve_colors[k % len(curve_colors)]}'"
                  for k, (base, _) in enumerate(curves)})
    panels = []
    for scene in SCENES:
        frames = peer_frames(bench.get(f"{scene}-{regime}", {}))
        plots = []
        for k, m in enumerate(direct):
            have = having(frames, m)
            if not have:
                continue
            t = quantile([f[m]["time_us"] / 1000 for f in have], 0.5)
            r = max(RESIDUAL_FLOOR, quantile([f[m]["residual"] for f in have], 0.5))
            path = write_dat(charts, f"wp-{scene}-{regime}-{m}.dat", [(t, r)])
            plots.append(f"'{path}' using 1:2 with points {style[m]} title '{m}'")
        for base, members in curves:
            points = []
            for m in members:
                have = having(frames, m)
                if have:
                    t = quantile([f[m]["time_us"] / 1000 for f in have], 0.5)
                    r = max(RESIDUAL_FLOOR, quantile([f[m]["residual"] for f in have], 0.5))
                    points.append((t, r, m.rpartition("-")[2]))
            if not points:
                continue
            path = write_dat(charts, f"wp-{scene}-{regime}-{base}.dat", points)
            plots.append(f"'{path}' using 1:2 with linespoints {style[base]} title '{base} (sweeps)', "
                         f"'' using 1:2:3 with labels offset 0.8,0.8 font ',6' notitle")
        panels.append((scene, plots))
    widest = max(range(len(panels)), key=lambda k: len(panels[k][1]))
    for k, (scene, plots) in enumerate(panels):
        key = "set key at screen 0.995,0.88 right top font ',9' spacing 1.2" if k == widest else "unset key"
        body.append(f"{key if plots else 'unset key'}\n{panel(scene, plots, 'set logscale xy')}")
    run_gnuplot(charts, f"work-precision-{regime}", "\n".join(body))


def chart_fig5(charts, out_dir):
    """Fig. 5: per scene, the largest island's pattern before and after Cuthill-McKee, with the
    skyline edge (first column of each row's envelope) drawn over it. Returns the scenes drawn."""
    summary = os.path.join(out_dir, "fig5.csv")
    if not os.path.exists(summary):
        return []
    with open(summary, newline="") as handle:
        rows = list(csv.DictReader(handle))
    drawn = []
    for row in rows:
        scene, n = row["scene"], int(row["n"])
        prefix = os.path.join(out_dir, "fig5", scene)
        if not os.path.exists(f"{prefix}-before.dat"):
            continue
        panels = []
        for tag, title, env in (("before", "original order", row["envelope_original"]),
                                ("after", "Cuthill-McKee order", row["envelope_cm"])):
            panels.append(f"set title '{title}: envelope {env} entries'\n"
                          f"plot '{prefix}-{tag}.dat' using 1:2 with points pt 5 ps 0.25 lc rgb '#1f4e9c' notitle, "
                          f"'{prefix}-sky-{tag}.dat' using 2:1 with steps lw 1.5 lc rgb '#d62728' title 'skyline (envelope edge)'")
        body = (f"set multiplot layout 1,2 title 'Fig. 5: {scene}, largest island (n = {n}, {row['nonzeros']} non-zeros)'\n"
                f"set size ratio -1\nset xrange [-0.5:{n - 0.5}]\nset yrange [{n - 0.5}:-0.5]\nset xlabel 'column'\n"
                f"set ylabel 'row'\nset key bottom left font ',8'\n" + "\n".join(panels))
        run_gnuplot(charts, f"fig5-{scene}", body)
        drawn.append(row)
    return drawn


def chart_fig7(charts, bench, regime):
    body = [f"set multiplot layout 2,3 title 'Fig. 7: solve time per frame, {gq(dict(REGIMES)[regime])}'",
            "set logscale y", "set xlabel 'step'", "set ylabel 'solve time (ms)'", "set key top right font ',8'"]
    for scene in SCENES:
        frames = frames_of(bench.get(f"{scene}-{regime}", {}))
        plots = []
        for m in TABLE3_METHODS:
            rows = [(frame, frames[frame][m]["time_us"] / 1000) for frame in sorted(frames) if m in frames[frame]]
            if rows:
                path = write_dat(charts, f"fig7-{scene}-{regime}-{m}.dat", rows)
                plots.append(f"'{path}' using 1:2 with lines lw 1.5 title '{m}'")
        body.append(panel(scene, plots, "set logscale y"))
    run_gnuplot(charts, f"fig7-{regime}", "\n".join(body))


def panel(title, plots, scale=""):
    """One multiplot panel, or an empty one saying 'no data' (gnuplot stops on a plot without
    points); scale: the chart's logscale command, restored after an empty panel."""
    if plots:
        return f"set title '{gq(title)}'\nplot " + ", ".join(plots)
    return f"set title '{gq(title)}: no data'\nunset logscale\nplot [0:1] [0:1] NaN notitle\n{scale}"


def chart_fig3(charts, out_dir):
    body = ["set multiplot layout 1,2 title 'Fig. 3: tight rows (% of all rows) over time, bpp'",
            "set xlabel 'time (s)'", "set ylabel 'tight (%)'", "set key top right font ',8'"]
    for regime, label in REGIMES:
        plots = []
        for scene in SCENES:
            rows = load_tight_fraction(out_dir, scene, regime)
            if rows:
                path = write_dat(charts, f"fig3-{scene}-{regime}.dat", rows)
                plots.append(f"'{path}' using 1:2 with lines lw 1.5 title '{scene}'")
        body.append(panel(label, plots))
    run_gnuplot(charts, "fig3", "\n".join(body))


def chart_fig4(charts, out_dir):
    path = os.path.join(out_dir, "bench_fig4.csv")
    if not os.path.exists(path):
        return False
    with open(path) as handle:
        text = handle.read()
    start = text.find("name,")  # Google Benchmark writes the context first
    series = defaultdict(list)
    for row in csv.DictReader(text[start:].splitlines()):
        parts = row["name"].strip('"').split("/")
        if len(parts) >= 3 and parts[0] == "BM_Fig4" and row.get("speedup_vs_refactor"):
            series[int(parts[1])].append((int(parts[2]), num(row["speedup_vs_refactor"]), num(row.get("speedup_vs_eigen"))))
    if not series:
        return False
    plots = []
    for m, rows in sorted(series.items()):
        dat = write_dat(charts, f"fig4-{m}.dat", sorted(rows))
        plots.append(f"'{dat}' using 1:2 with linespoints lw 2 title 'm = {m}'")
    body = "set title 'Fig. 4: speed-up of row deletion over refactoring'\nset xlabel 'tight (%)'\nset ylabel 'speed-up'\n" \
           "set logscale y\nset key top right\nplot " + ", ".join(plots) + ", 1 with lines dt 2 notitle"
    run_gnuplot(charts, "fig4", body)
    return True


# ------------------------------------------------------------------------------------------


def factor_target(lines, bench, missed):
    lines.append("### Factor error within the paper's Table 4\n")
    lines.append("bpp's largest factor error per scene (Table 4: its downdated factor against a fresh one, both in "
                 "double) against the largest of the paper's Table 4 (with skyline) for that scene. Beside it, the "
                 "precision floor, over the same islands: how far each of the two factors is from the exact factor "
                 "(taken in long double), largest per scene, and the median over the islands of the downdated "
                 "factor's distance over the fresh one's (docs/benchmarks.md, \"Table 4 at the precision floor\").\n")
    lines.append("| scene-regime | islands with tight rows | bpp max | downdated vs exact, max | fresh vs exact, max "
                 "| downdated / fresh, median | paper max | verdict |")
    lines.append("|---|---|---|---|---|---|---|---|")
    for regime, _ in REGIMES:
        for scene in SCENES:
            group = f"{scene}-{regime}"
            rows = [i["bpp"] for i in bench.get(group, {}).values() if "bpp" in i and int(i["bpp"]["tight"] or 0) > 0]
            errors = finite([num(r["factor_error"]) for r in rows])
            fresh = finite([num(r.get("fresh_factor_error", "nan")) for r in rows])
            deleted = finite([num(r.get("deleted_factor_error", "nan")) for r in rows])
            ratios = finite([num(r.get("deleted_factor_error", "nan")) / num(r["fresh_factor_error"]) for r in rows
                             if num(r.get("fresh_factor_error", "nan")) > 0])
            paper = PAPER_T4[scene][1][1]
            if not errors:
                lines.append(f"| {group} | 0 | – | – | – | – | {fmt_e(paper)} | n/a |")
                continue
            fresh_max = max(fresh) if fresh else float("nan")
            deleted_max = max(deleted) if deleted else float("nan")
            ratio = f"{statistics.median(ratios):.2f}" if ratios else "–"
            ok = max(errors) <= paper
            if not ok:
                missed.append(f"{group}: bpp's max factor error {fmt_e(max(errors))} above the paper's {fmt_e(paper)} "
                              f"(from the exact factor: downdated up to {fmt_e(deleted_max)}, fresh up to "
                              f"{fmt_e(fresh_max)})")
            lines.append(f"| {group} | {len(errors)} | {fmt_e(max(errors))} | {fmt_e(deleted_max)} | {fmt_e(fresh_max)} "
                         f"| {ratio} | {fmt_e(paper)} | {verdict(ok)} |")
    lines.append("")


def section(lines, failures, name, function, *args):
    """Runs one part of the report; if it breaks (missing or malformed inputs), the report says so
    at that place and in its list of failures, and the other parts still come out."""
    try:
        return function(*args)
    except Exception as error:  # noqa: BLE001 -- any failure of one section is reported, not fatal
        lines.append(f"\n**{name}: not produced** ({type(error).__name__}: {error}).\n")
        failures.append(f"report section '{name}': {type(error).__name__}: {error}")
        return None


def read_failures(out_dir):
    path = os.path.join(out_dir, "failures.txt")
    if not os.path.exists(path):
        return []
    with open(path) as handle:
        return [line.strip() for line in handle if line.strip()]


def charts_section(lines, failures, charts, out_dir, bench):
    lines.append("## Charts\n")
    for regime, label in REGIMES:
        section(lines, failures, f"work-precision {regime}", chart_work_precision, charts, bench, regime)
        section(lines, failures, f"Fig. 7 {regime}", chart_fig7, charts, bench, regime)
        lines.append(f"- {label}: work–precision ![](charts/work-precision-{regime}.png), Fig. 7 ![](charts/fig7-{regime}.png)")
    section(lines, failures, "Fig. 3", chart_fig3, charts, out_dir)
    lines.append("- Fig. 3 (tight % over time): ![](charts/fig3.png)")
    if section(lines, failures, "Fig. 4", chart_fig4, charts, out_dir):
        lines.append("- Fig. 4 (bench_fig4, random SPD matrices): ![](charts/fig4.png)")
    else:
        lines.append("- Fig. 4: not run (needs bench/bench_fig4 built; see the failures)")
    drawn = section(lines, failures, "Fig. 5", chart_fig5, charts, out_dir) or []
    if drawn:
        lines.append("- Fig. 5 (largest island per scene at CFM 1e-10, before and after Cuthill-McKee, with the skyline; "
                     "envelope = stored entries of the lower skyline factor):\n")
        lines.append("| scene | n | non-zeros | envelope original | envelope CM | envelope RCM | bandwidth original | bandwidth CM | chart |")
        lines.append("|---|---|---|---|---|---|---|---|---|")
        for row in drawn:
            lines.append(f"| {row['scene']} | {row['n']} | {row['nonzeros']} | {row['envelope_original']} | {row['envelope_cm']} | "
                         f"{row['envelope_rcm']} | {row['bandwidth_original']} | {row['bandwidth_cm']} | "
                         f"![](charts/fig5-{row['scene']}.png) |")
    else:
        lines.append("- Fig. 5: not drawn (bench_fig5 did not run; see the failures)")
    lines.append("")


def main():
    out_dir, mode = sys.argv[1], sys.argv[2] if len(sys.argv) > 2 else "full"
    charts = os.path.join(out_dir, "charts")
    os.makedirs(os.path.join(charts, "data"), exist_ok=True)
    failures = read_failures(out_dir)
    bench_path = os.path.join(out_dir, "bench.csv")
    bench = load_bench(bench_path) if os.path.exists(bench_path) else {}
    if not bench:
        failures.append("bench.csv missing or empty: no table or chart from the corpus")
    files = sum(len(v) for v in bench.values())
    lines = ["# ode-bpp benchmark report\n",
             f"Mode: **{mode}**. Corpus: {files} captured islands in {len(bench)} scene/regime groups "
             "(ode-bpp-demo with bpp, `--capture-every`), solved by bench_corpus in one process, methods interleaved "
             "per file after a warm-up, median of the repetitions. Times are wall-clock on a shared, noisy machine: "
             "compare ratios within this run, not absolute values across runs. Every time includes what the call "
             "does besides solving: for ode_bpp's methods the residuals solve() reports, for the peers their copies "
             "of A and the bounds into their own layout.\n",
             "bpp's *limit* is bpp re-solved from its own final index set with one pivot step "
             "(Start::states, max_pivots = 1): ordering + factoring A + taking T's rows out + one solve, "
             "an upper bound of the ideal one Cholesky of A_FF plus one solve. Where that re-solve does not certify the "
             "set in its one step (status max-iterations, counted below), its time is that of the one-step budget, not of a certified answer.\n"]
    meta = os.path.join(out_dir, "meta.txt")
    if os.path.exists(meta):
        with open(meta) as handle:
            lines.extend(f"- {line.strip()}" for line in handle if line.strip())
        lines.append("")
    body = []
    section(body, failures, "headline", headline, body, bench)
    missed = section(body, failures, "targets", targets, body, bench) or []
    section(body, failures, "accuracy", accuracy, body, bench, missed)
    section(body, failures, "factor error target", factor_target, body, bench, missed)
    world = []
    section(world, failures, "sparse world step", world_report.section, world, out_dir, bench, missed, failures)
    section(world, failures, "hard contact", contact_report.section, world, out_dir, bench, missed, failures)
    body.append("### Missed targets\n")
    body.extend([f"- {m}" for m in missed] or ["- none"])
    body.append("")
    body.extend(world)
    section(body, failures, "peers", peers_table, body, bench)
    body.append("## Tables\n")
    for regime, _ in REGIMES:
        section(body, failures, f"Table 3 {regime}", table3, body, bench, regime)
    for regime, _ in REGIMES:
        section(body, failures, f"Table 4 {regime}", table4, body, bench, regime)
    section(body, failures, "convergence", convergence, body, bench)
    section(body, failures, "whole step", whole_step, body, out_dir)
    section(body, failures, "callgrind", callgrind, body, out_dir)
    charts_section(body, failures, charts, out_dir, bench)
    lines.append("## Failures during the run\n")
    lines.extend([f"- {f}" for f in failures] or ["- none: every step ran"])
    lines.append("")
    with open(os.path.join(out_dir, "report.md"), "w") as handle:
        handle.write("\n".join(lines + body))
    print(f"make_report: {os.path.join(out_dir, 'report.md')}; {len(missed)} target(s) missed, {len(failures)} failure(s)")


if __name__ == "__main__":
    main()
