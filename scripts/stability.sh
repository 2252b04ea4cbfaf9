#!/usr/bin/env bash
# Stability where methods fail (issue 6): runs the sweeps of bench/stability/stability_sweep
# (mass ratio x CFM in three heavy-on-light patterns, time step, closed loops, chain length,
# coupled friction; every method: dantzig, bpp, bpp-sky, bpp-down, bpp-chol, pgs, quickstep),
# then draws the maps and writes the report (bench/stability/make_stability_report.py).
#
# Usage: stability.sh BUILD_DIR OUT_DIR [--quick]
#   BUILD_DIR  a CMake build of this repository (the target stability_sweep is built if needed)
#   OUT_DIR    receives csv/*.csv, charts/*.png and *.svg, report.md, sweep.log
#   --quick    shorter runs on a coarser grid (seconds instead of about 3 minutes; docs/stability.md)
# Progress: one line per run on stdout (also kept in OUT_DIR/sweep.log).
set -euo pipefail

usage() { echo "usage: stability.sh BUILD_DIR OUT_DIR [--quick]" >&2; exit 2; }
[[ $# -ge 2 && $# -le 3 ]] || usage
BUILD=$(realpath "$1")
OUT=$(realpath -m "$2")
QUICK=()
if [[ $# -eq 3 ]]; then
  [[ $3 == --quick ]] || usage
  QUICK=(--quick)
fi
HERE=$(cd "$(dirname "$0")/.." && pwd)
SWEEP=$BUILD/bench/stability/stability_sweep

echo "[stability] building stability_sweep in $BUILD"
cmake --build "$BUILD" --target stability_sweep -j"$(nproc)" >/dev/null
[[ -x $SWEEP ]] || { echo "stability.sh: $SWEEP was not built" >&2; exit 1; }
if ! command -v gnuplot >/dev/null; then
  echo "stability.sh: gnuplot is needed for the charts (apt-get install gnuplot-nox)" >&2
  exit 1
fi

mkdir -p "$OUT/csv" "$OUT/charts"
echo "[stability] sweeps (${QUICK[*]:-full}):"
"$SWEEP" --list "${QUICK[@]}" | sed 's/^/  /'
start=$(date +%s)
"$SWEEP" --out "$OUT/csv" "${QUICK[@]}" | tee "$OUT/sweep.log"
echo "[stability] sweeps done in $(( $(date +%s) - start )) s"

python3 "$HERE/bench/stability/make_stability_report.py" "$OUT/csv" "$OUT" ${QUICK[@]:+--quick}
echo "[stability] report: $OUT/report.md"
