#!/usr/bin/env bash
# bench-report.sh BUILD_DIR OUT_DIR [--quick]
#
# Speed against accuracy on one corpus, in one run:
#   1. corpus: every paper scene stepped with bpp, its islands' MLCPs captured every K-th step,
#      at ODE's default CFM 1e-10 and at the paper's compliance 1e-8
#      -> OUT_DIR/corpus/<scene>-<regime>/*.mlcp (regenerated each run; never commit it)
#   2. whole steps: each scene stepped with dantzig and with bpp, without capture
#      -> OUT_DIR/steps/<scene>-step.csv
#   3. one bench_corpus process over the whole corpus, methods interleaved per file
#      -> OUT_DIR/bench.csv
#   4. Fig. 4 of the paper from bench_fig4, if it is built (--quick: 0.02 s per benchmark)
#   5. callgrind instruction counts of bpp, dantzig and bpp-chol on a few frames (if valgrind is there)
#   6. tables, targets and charts -> OUT_DIR/report.md, OUT_DIR/charts/*.png|svg
# --quick: 5 s per scene, every 5th step, 3 repetitions (about 3 minutes in all);
# default: the paper's 20 s per scene, every 5th step, 5 repetitions.
set -euo pipefail

usage() { echo "usage: $0 BUILD_DIR OUT_DIR [--quick]" >&2; exit 2; }
[[ $# -ge 2 ]] || usage
BUILD_DIR=$(realpath "$1")
OUT_DIR=$2
QUICK=0
[[ "${3:-}" == "--quick" ]] && QUICK=1
[[ $# -le 3 ]] || usage

HERE=$(cd "$(dirname "$0")/.." && pwd)
DEMO=$BUILD_DIR/demos/ode-bpp-demo
HARNESS=$BUILD_DIR/bench/report/bench_corpus
FIG4=$BUILD_DIR/bench/bench_fig4
for tool in "$DEMO" "$HARNESS"; do
  [[ -x $tool ]] || { echo "bench-report: $tool not built (configure with -DODE_BPP_BUILD_BENCH=ON and build it)" >&2; exit 1; }
done
command -v python3 >/dev/null || { echo "bench-report: python3 is needed for the report" >&2; exit 1; }
command -v gnuplot >/dev/null || { echo "bench-report: gnuplot is needed for the charts" >&2; exit 1; }

SCENES=(crane winch parkour offshore forklift forwarder)
if [[ $QUICK == 1 ]]; then SECONDS_PER_SCENE=5; EVERY=5; REPEAT=3; MODE=quick
else SECONDS_PER_SCENE=20; EVERY=5; REPEAT=5; MODE=full; fi
# regime name -> ode-bpp-demo option
declare -A REGIMES=([cfm1e-10]="--cfm 1e-10" [comp1e-8]="--compliance 1e-8")

mkdir -p "$OUT_DIR"
OUT_DIR=$(realpath "$OUT_DIR")
rm -rf "$OUT_DIR/corpus" "$OUT_DIR/steps" "$OUT_DIR/charts"
mkdir -p "$OUT_DIR/corpus" "$OUT_DIR/steps" "$OUT_DIR/charts"
START=$(date +%s)
say() { echo "[bench-report $(( $(date +%s) - START ))s] $*"; }
# ode-bpp-demo exits 1 when a scene misses its success criterion (short runs often do): that is
# reported, not fatal; 2 (bad arguments) and 3 (capture failed) stop the run.
demo() {
  local status=0
  "$DEMO" "$@" || status=$?
  if [[ $status -gt 1 ]]; then echo "bench-report: ode-bpp-demo $* failed with status $status" >&2; exit 1; fi
  return 0
}

{
  echo "date: $(date -u '+%Y-%m-%d %H:%M UTC')"
  echo "source: $(git -C "$HERE" rev-parse --short HEAD 2>/dev/null || echo unknown)$(git -C "$HERE" diff --quiet HEAD 2>/dev/null || echo ' + uncommitted changes')"
  echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//'), load at start $(cut -d' ' -f1-3 /proc/loadavg)"
} > "$OUT_DIR/meta.txt"
say "mode $MODE: ${SECONDS_PER_SCENE} s per scene, every ${EVERY}th step captured, $REPEAT repetitions per solve"
for scene in "${SCENES[@]}"; do
  for regime in cfm1e-10 comp1e-8; do
    dir=$OUT_DIR/corpus/$scene-$regime
    mkdir -p "$dir"
    # shellcheck disable=SC2086  # the regime option is two words
    demo "$scene" --solver bpp --seconds "$SECONDS_PER_SCENE" ${REGIMES[$regime]} --cond-every 0 \
      --capture "$dir" --capture-every "$EVERY" --csv "$OUT_DIR/steps/$scene-$regime-bpp.csv" --quiet \
      > "$OUT_DIR/steps/$scene-$regime-bpp.txt"
    say "corpus $scene-$regime: $(find "$dir" -name '*.mlcp' | wc -l) files"
  done
done

for scene in "${SCENES[@]}"; do
  demo "$scene" --compare dantzig,bpp --seconds "$SECONDS_PER_SCENE" --cond-every 0 \
    --csv "$OUT_DIR/steps/$scene-step.csv" --quiet > "$OUT_DIR/steps/$scene-step.txt"
  say "whole steps $scene: dantzig and bpp, CFM 1e-10"
done

FILES=$(find "$OUT_DIR/corpus" -name '*.mlcp' | wc -l)
say "harness: $FILES files x (bpp-chol bpp-down bpp-sky bpp dantzig pgs x5 bpp-consistent), $REPEAT repetitions, interleaved"
# bench_corpus exits 1 when some file could not be read (named on stderr); the others are in the CSV
harness_status=0
"$HARNESS" --methods bpp-chol,bpp-down,bpp-sky,bpp,dantzig,pgs --pgs-iterations 10,35,100,300,1000 \
  --repeat "$REPEAT" --factor-error --limit --cond --consistent --csv "$OUT_DIR/bench.csv" "$OUT_DIR/corpus" ||
  harness_status=$?
[[ $harness_status -le 1 ]] || { echo "bench-report: bench_corpus failed with status $harness_status" >&2; exit 1; }
[[ $harness_status -eq 0 ]] || say "warning: bench_corpus could not read some files (see above); the report covers the rest"

if [[ -x $FIG4 ]]; then
  say "Fig. 4: bench_fig4 (random SPD matrices, deletion vs refactoring)"
  FIG4_ARGS=()
  [[ $QUICK == 1 ]] && FIG4_ARGS=(--benchmark_min_time=0.02)
  "$FIG4" "${FIG4_ARGS[@]}" --benchmark_out="$OUT_DIR/bench_fig4.csv" --benchmark_out_format=csv > "$OUT_DIR/bench_fig4.txt"
else
  say "Fig. 4: skipped, $FIG4 not built"
fi

# Instruction counts inside ode_bpp::solve (callgrind), bpp against dantzig, on one frame with
# tight rows per scene: noise-free, unlike the wall-clock times.
if command -v valgrind >/dev/null; then
  mapfile -t CG_FILES < <(awk -F, 'NR > 1 && $9 == "bpp-chol" && $15 > 0 { print $1 "/" $5 }' "$OUT_DIR/bench.csv" |
    awk -F/ '{ split($1, part, "-"); if (seen[part[1]]++ < 1) print "'"$OUT_DIR"'/corpus/" $0 }')
  if [[ ${#CG_FILES[@]} -gt 0 ]]; then
    mkdir -p "$OUT_DIR/callgrind"
    echo "method,files,solves,instructions" > "$OUT_DIR/callgrind.csv"
    for method in bpp dantzig bpp-chol; do
      valgrind --tool=callgrind --callgrind-out-file="$OUT_DIR/callgrind/$method.out" \
        '--toggle-collect=ode_bpp::solve(ode_bpp::Problem const&, ode_bpp::Options const&, ode_bpp::Strided)' \
        "$HARNESS" --methods "$method" --repeat 1 --warmup 1 --csv /dev/null "${CG_FILES[@]}" \
        > "$OUT_DIR/callgrind/$method.log" 2>&1
      # every file is solved twice (untimed + 1 repetition), the first once more as warm-up
      echo "$method,${#CG_FILES[@]},$(( 2 * ${#CG_FILES[@]} + 1 )),$(awk '/^totals:/ { print $2 }' "$OUT_DIR/callgrind/$method.out")" \
        >> "$OUT_DIR/callgrind.csv"
    done
    say "callgrind: ${#CG_FILES[@]} islands with tight rows, bpp / dantzig / bpp-chol -> callgrind.csv"
  fi
else
  say "callgrind: skipped, valgrind not installed"
fi

say "report and charts"
python3 "$HERE/bench/report/make_report.py" "$OUT_DIR" "$MODE"
say "done: $OUT_DIR/report.md, charts in $OUT_DIR/charts/"
