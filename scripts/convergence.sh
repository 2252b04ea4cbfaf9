#!/usr/bin/env bash
# Measures how often bpp converges inside ODE's world step (issue 3, item 4): the six paper scenes
# at ODE's default CFM 1e-10 and at the paper's compliance c = 1e-6, 1e-8, 1e-10 (CFM = c/h), with
# Frozen friction against Dantzig in the same run (for the timings), then bpp with Consistent
# friction, and optionally a baseline build's bpp ("before"). Writes one CSV per run and a
# markdown report (bench/convergence/summarize.py): frames converged per scene and regime,
# pivots per frame, fallbacks, and the median solve time of bpp and Dantzig.
#
# Usage: convergence.sh BUILD_DIR OUT_DIR [--baseline BUILD_DIR] [--seconds S] [--only KINDS]
#   BUILD_DIR   a CMake build of this repository (holds demos/ode-bpp-demo)
#   OUT_DIR     receives frozen-*.csv, consistent-*.csv, before-*.csv, convergence.md, logs/
#   --baseline  another build (e.g. of an older commit) whose bpp is measured as "before"
#   --seconds   simulated seconds per scene (default: each scene's own, 20 s)
#   --only      comma-separated subset of frozen,consistent,before to (re)run; the CSVs of the
#               other kinds already in OUT_DIR are kept and enter the report
# Progress: one line per run on stderr, and the demo's own progress line every 5 s.
set -euo pipefail

usage() { echo "usage: convergence.sh BUILD_DIR OUT_DIR [--baseline BUILD_DIR] [--seconds S] [--only KINDS]" >&2; exit 2; }
[[ $# -ge 2 ]] || usage
BUILD=$(realpath "$1")
OUT=$(realpath -m "$2")
shift 2
BASELINE=""
SECONDS_ARG=()
ONLY="frozen,consistent,before"
while [[ $# -gt 0 ]]; do
  case "$1" in
    --baseline) BASELINE=$(realpath "${2:?--baseline needs a directory}"); shift 2 ;;
    --seconds) SECONDS_ARG=(--seconds "${2:?--seconds needs a value}"); shift 2 ;;
    --only) ONLY=${2:?--only needs a list}; shift 2 ;;
    *) usage ;;
  esac
done
HERE=$(cd "$(dirname "$0")/.." && pwd)
DEMO=$BUILD/demos/ode-bpp-demo
[[ -x $DEMO ]] || { echo "convergence.sh: $DEMO not found (build the target ode-bpp-demo)" >&2; exit 1; }
if [[ -n $BASELINE && ! -x $BASELINE/demos/ode-bpp-demo ]]; then
  echo "convergence.sh: $BASELINE/demos/ode-bpp-demo not found" >&2
  exit 1
fi
mkdir -p "$OUT/logs"
wanted() { [[ ",$ONLY," == *",$1,"* ]]; }

# name and demo flag of each regime
REGIMES=("cfm-1e-10:--cfm 1e-10" "compliance-1e-6:--compliance 1e-6" "compliance-1e-8:--compliance 1e-8"
         "compliance-1e-10:--compliance 1e-10")
RUNS=()
for kind in frozen consistent before; do
  wanted $kind || continue
  [[ $kind != before || -n $BASELINE ]] || continue
  rm -f "$OUT/$kind"-*.csv
  for regime in "${REGIMES[@]}"; do RUNS+=("$kind:$regime"); done
done

# The demo exits 1 when a scene misses its physical success criterion (the softest compliance
# lets loads sag); that is not a convergence failure, so only exit codes >= 2 stop the script.
run_demo() {
  local demo=$1 log=$2
  shift 2
  local status=0
  "$demo" "$@" 2> >(tee "$log" >&2) >>"$log.summary" || status=$?
  if [[ $status -ge 2 ]]; then
    echo "convergence.sh: $demo $* failed with status $status (see $log)" >&2
    exit 1
  fi
}

count=0
for run in "${RUNS[@]}"; do
  count=$((count + 1))
  kind=${run%%:*}
  rest=${run#*:}
  regime=${rest%%:*}
  read -ra flags <<<"${rest#*:}"
  csv=$OUT/$kind-$regime.csv
  log=$OUT/logs/$kind-$regime.log
  echo "[convergence ${count}/${#RUNS[@]}] $kind friction, $regime" >&2
  rm -f "$log.summary"
  case $kind in
    frozen) run_demo "$DEMO" "$log" paper --compare dantzig,bpp --cond-every 0 "${flags[@]}" "${SECONDS_ARG[@]}" --csv "$csv" ;;
    consistent) run_demo "$DEMO" "$log" paper --solver bpp --friction consistent --cond-every 0 "${flags[@]}" "${SECONDS_ARG[@]}" --csv "$csv" ;;
    before) run_demo "$BASELINE/demos/ode-bpp-demo" "$log" paper --solver bpp --cond-every 0 "${flags[@]}" "${SECONDS_ARG[@]}" --csv "$csv" ;;
  esac
done

python3 "$HERE/bench/convergence/summarize.py" "$OUT" >"$OUT/convergence.md"
echo "[convergence] report: $OUT/convergence.md" >&2
