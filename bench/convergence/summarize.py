#!/usr/bin/env python3
"""Summarizes the CSVs of scripts/convergence.sh into a markdown report.

A frame is one world step that solved at least one island. For the solver under test (bpp) a
frame has converged when every island of it returned dMLCPSolved (status 0): the solver's own
pivoting certified the answer within its budget. Status 1 (dMLCPSolvedByFallback: the solver's
regularize-on-breakdown or Dantzig fallback, or consistent friction whose rounds ran out) and
status 2 (dMLCPFailed: ODE's Dantzig answered instead) are counted separately.
Pivots and times are per frame, summed over the frame's islands; medians and 95th percentiles.

Usage: summarize.py OUT_DIR   (reads OUT_DIR/*.csv, writes the report to stdout)
File names: <kind>-<regime>.csv, kind in {frozen, consistent, before}; regime e.g. cfm-1e-10.
"""
import csv
import glob
import os
import sys
from collections import OrderedDict, defaultdict

SCENES = ["crane", "winch", "parkour", "offshore", "forklift", "forwarder"]
REGIME_ORDER = ["cfm-1e-10", "compliance-1e-6", "compliance-1e-8", "compliance-1e-10"]
TARGET = 0.99


def percentile(values, q):
    if not values:
        return float("nan")
    ordered = sorted(values)
    return ordered[int(q * (len(ordered) - 1) + 0.5)]


class Frames:
    """Per (scene, solver): frame -> summed pivots, summed ms, worst island status."""

    def __init__(self):
        self.pivots = defaultdict(int)
        self.ms = defaultdict(float)
        self.status = defaultdict(int)

    def add(self, row):
        step = int(row["step"])
        self.pivots[step] += int(row["pivots"])
        self.ms[step] += float(row["solve_ms"])
        self.status[step] = max(self.status[step], int(row["status"]))

    def count(self):
        return len(self.status)

    def with_status(self, status):
        return sum(1 for s in self.status.values() if s == status)

    def rate(self):
        return self.with_status(0) / self.count() if self.count() else float("nan")


def read(path):
    """(scene, solver) -> Frames."""
    runs = defaultdict(Frames)
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            runs[(row["scene"], row["solver"])].add(row)
    return runs


def regime_label(regime):
    kind, value = regime.split("-", 1)
    if kind == "cfm":
        return f"ODE CFM {value}"
    return f"compliance {value} (CFM = c/h)"


def rate_text(frames):
    if frames is None or frames.count() == 0:
        return "-"
    mark = "" if frames.rate() >= TARGET else " **below 99 %**"
    return f"{frames.with_status(0)}/{frames.count()} ({100 * frames.rate():.2f} %){mark}"


def detail_table(regime, runs, before):
    lines = [
        f"### {regime_label(regime)}",
        "",
        "| scene | frames | converged (after) | converged (before) | pivots/frame median | p95 "
        "| fallback frames | frames handed to Dantzig | bpp ms median | dantzig ms median | speed-up |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for scene in SCENES:
        bpp = runs.get((scene, "bpp"))
        if bpp is None:
            continue
        dz = runs.get((scene, "dantzig"))
        old = before.get((scene, "bpp")) if before else None
        pivots = list(bpp.pivots.values())
        bpp_ms = percentile(list(bpp.ms.values()), 0.5)
        dz_ms = percentile(list(dz.ms.values()), 0.5) if dz else float("nan")
        speedup = f"{dz_ms / bpp_ms:.1f}x" if dz and bpp_ms > 0 else "-"
        lines.append(
            f"| {scene} | {bpp.count()} | {rate_text(bpp)} | {rate_text(old)} "
            f"| {percentile(pivots, 0.5):.0f} | {percentile(pivots, 0.95):.0f} "
            f"| {bpp.with_status(1)} | {bpp.with_status(2)} "
            f"| {bpp_ms:.3f} | {dz_ms:.3f} | {speedup} |"
        )
    lines.append("")
    return lines


def consistent_table(regime, runs):
    lines = [
        f"### {regime_label(regime)}, consistent friction",
        "",
        "| scene | frames | converged | pivots/frame median | p95 | fallback frames "
        "| frames handed to Dantzig | bpp ms median |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for scene in SCENES:
        bpp = runs.get((scene, "bpp"))
        if bpp is None:
            continue
        pivots = list(bpp.pivots.values())
        lines.append(
            f"| {scene} | {bpp.count()} | {rate_text(bpp)} | {percentile(pivots, 0.5):.0f} "
            f"| {percentile(pivots, 0.95):.0f} | {bpp.with_status(1)} | {bpp.with_status(2)} "
            f"| {percentile(list(bpp.ms.values()), 0.5):.3f} |"
        )
    lines.append("")
    return lines


def overview(kind_runs, kind, regimes):
    lines = [
        "| scene | " + " | ".join(regime_label(r) for r in regimes) + " |",
        "|---|" + "---|" * len(regimes),
    ]
    for scene in SCENES:
        cells = []
        for regime in regimes:
            frames = kind_runs.get((kind, regime), {}).get((scene, "bpp"))
            cells.append(f"{100 * frames.rate():.2f} %" if frames and frames.count() else "-")
        lines.append(f"| {scene} | " + " | ".join(cells) + " |")
    lines.append("")
    return lines


def ordered_regimes(kind_runs, kind):
    present = {r for k, r in kind_runs if k == kind}
    return [r for r in REGIME_ORDER if r in present] + sorted(present - set(REGIME_ORDER))


def main():
    out = sys.argv[1]
    kind_runs = OrderedDict()
    for path in sorted(glob.glob(os.path.join(out, "*.csv"))):
        kind, regime = os.path.basename(path)[:-4].split("-", 1)
        kind_runs[(kind, regime)] = read(path)
    regimes = ordered_regimes(kind_runs, "frozen")
    report = [
        "# bpp convergence inside ODE",
        "",
        "Frames converged: every island of the step was answered by bpp's own pivoting within its "
        "budget (dMLCPSolved). Target: >= 99 % on every scene and regime. Times are the solver's "
        "wall time per frame from the same run (`ode-bpp-demo --compare dantzig,bpp`).",
        "",
        "## Frozen friction (default), frames converged",
        "",
    ]
    report += overview(kind_runs, "frozen", regimes)
    if any(k == "before" for k, _ in kind_runs):
        report += ["Before (baseline build):", ""] + overview(kind_runs, "before", regimes)
    cons_regimes = ordered_regimes(kind_runs, "consistent")
    if cons_regimes:
        report += ["## Consistent friction, frames converged", ""] + overview(kind_runs, "consistent", cons_regimes)
    report += ["## Details", ""]
    for regime in regimes:
        report += detail_table(regime, kind_runs[("frozen", regime)], kind_runs.get(("before", regime)))
    for regime in cons_regimes:
        report += consistent_table(regime, kind_runs[("consistent", regime)])
    print("\n".join(report))


if __name__ == "__main__":
    main()
