#!/usr/bin/env bash
# bench-report.sh BUILD_DIR OUT_DIR [--quick] [--no-peers]
#
# Speed against accuracy on one corpus, in one run (docs/benchmarks.md):
#   1. corpus: every paper scene stepped with bpp, its islands' MLCPs captured every K-th step,
#      at ODE's default CFM 1e-10 and at the paper's compliance 1e-8
#      -> OUT_DIR/corpus/<scene>-<regime>/*.mlcp (regenerated each run; never commit it)
#   2. whole steps: each scene stepped with dantzig and with bpp, without capture, at CFM 1e-10
#      (the paper's six at compliance 1e-8 too), in 5 runs (--quick: 2)
#      -> OUT_DIR/steps/<scene>[-comp1e-8]-step[-r<run>].csv;
#      the contact scenes the corpus leaves out (boxstack, pyramid, bin, rock pile) with bpp alone,
#      for their fallbacks -> OUT_DIR/steps/<scene>-cfm1e-10-bpp.csv
#   3. one bench_corpus process over the whole corpus, every method (and the peers, when built
#      with them) interleaved per file -> OUT_DIR/bench.csv
#   4. Fig. 4 of the paper from bench_fig4 (--quick: 0.02 s per benchmark)
#   5. Fig. 5: bench_fig5 on each scene's largest captured island
#   6. callgrind instruction counts of bpp, dantzig and bpp-chol on a few frames (if valgrind is there)
#   7. the whole world step, method against method: chain scaling, the scenes against QuickStep,
#      small islands, the physical limit inside ODE, the crane's instructions per step, long chains
#      (scripts/bench-world.sh) -> OUT_DIR/world/
#   8. tables, targets and charts -> OUT_DIR/report.md, OUT_DIR/charts/*.png|svg
# A step that fails (a scene's capture, one tool) is written to OUT_DIR/failures.txt and reported
# in report.md; the run goes on with the rest. The exit status is 1 when anything failed.
# --quick: 5 s per scene, 3 repetitions, peers on every 4th captured frame (a few minutes);
# default: the paper's 20 s per scene, 5 repetitions, peers on every 8th captured frame.
# --no-peers: leave the peer solvers out even when bench_corpus was built with them.
set -uo pipefail

usage() { echo "usage: $0 BUILD_DIR OUT_DIR [--quick] [--no-peers]" >&2; exit 2; }
[[ $# -ge 2 ]] || usage
BUILD_DIR=$(realpath "$1")
OUT_DIR=$2
shift 2
QUICK=0
PEERS=1
for arg in "$@"; do
  case $arg in
    --quick) QUICK=1 ;;
    --no-peers) PEERS=0 ;;
    *) usage ;;
  esac
done

HERE=$(cd "$(dirname "$0")/.." && pwd)
DEMO=$BUILD_DIR/demos/ode-bpp-demo
HARNESS=$BUILD_DIR/bench/report/bench_corpus
FIG4=$BUILD_DIR/bench/bench_fig4
FIG5=$BUILD_DIR/bench/report/bench_fig5
for tool in "$DEMO" "$HARNESS"; do
  [[ -x $tool ]] || { echo "bench-report: $tool not built (configure with -DODE_BPP_BUILD_BENCH=ON and build it)" >&2; exit 1; }
done
command -v python3 >/dev/null || { echo "bench-report: python3 is needed for the report" >&2; exit 1; }
command -v gnuplot >/dev/null || { echo "bench-report: gnuplot is needed for the charts" >&2; exit 1; }

PAPER_SCENES=(crane winch parkour offshore forklift forwarder)
SCENES=("${PAPER_SCENES[@]}" cannon stack)
EVERY=5
PGS_SWEEPS=10,35,100,300,1000
PEER_SWEEPS=10,35,100,300
# peers run on frames whose step number is a multiple of PEER_EVERY (every PEER_EVERY/EVERY-th capture)
if [[ $QUICK == 1 ]]; then SECONDS_PER_SCENE=5; REPEAT=3; STEP_RUNS=2; PEER_EVERY=20; PEER_REPEAT=1; MODE=quick
  CONTACT_RUNS=("boxstack 5" "pyramid 2" "bin 2" "rockpile 1")
else SECONDS_PER_SCENE=20; REPEAT=5; STEP_RUNS=5; PEER_EVERY=40; PEER_REPEAT=3; MODE=full
  CONTACT_RUNS=("boxstack 20" "pyramid 10" "bin 10" "rockpile 5"); fi
# regime name -> ode-bpp-demo option
declare -A REGIMES=([cfm1e-10]="--cfm 1e-10" [comp1e-8]="--compliance 1e-8")

mkdir -p "$OUT_DIR"
OUT_DIR=$(realpath "$OUT_DIR")
rm -rf "$OUT_DIR/corpus" "$OUT_DIR/steps" "$OUT_DIR/charts" "$OUT_DIR/callgrind" "$OUT_DIR/fig5"
rm -f "$OUT_DIR"/{failures.txt,bench.csv,bench_fig4.csv,callgrind.csv,fig5.csv,report.md}
mkdir -p "$OUT_DIR/corpus" "$OUT_DIR/steps" "$OUT_DIR/charts" "$OUT_DIR/logs"
FAILURES=$OUT_DIR/failures.txt
START=$(date +%s)
say() { echo "[bench-report $(( $(date +%s) - START ))s] $*"; }
# A failed step: one line in failures.txt (report.md lists them), and the run goes on.
failed() { echo "$*" >> "$FAILURES"; say "FAILED: $*"; }
# ode-bpp-demo exits 1 when a scene misses its success criterion (short runs often do): that is
# reported by the demo itself, not a failure of the benchmark; 2 (bad arguments), 3 (capture
# failed) or a crash are.
# Its output goes to logs/WHAT.txt.
demo() {
  local what=$1 status=0
  shift
  "$DEMO" "$@" > "$OUT_DIR/logs/$what.txt" 2>&1 || status=$?
  [[ $status -le 1 ]] || failed "$what: ode-bpp-demo exited with status $status (log: logs/$what.txt)"
}

PEER_ARGS=()
PEER_LIST=none
if [[ $PEERS == 1 ]] && grep -qv '^none' <<<"$("$HARNESS" --list-peers)"; then
  PEER_LIST=$("$HARNESS" --list-peers | sed 's/-10$/-<k>/' | sort -u | paste -sd' ')
  PEER_ARGS=(--peers all --peer-iterations "$PEER_SWEEPS" --peer-every "$PEER_EVERY" --peer-repeat "$PEER_REPEAT")
fi

{
  echo "date: $(date -u '+%Y-%m-%d %H:%M UTC')"
  echo "source: $(git -C "$HERE" rev-parse --short HEAD 2>/dev/null || echo unknown)$(git -C "$HERE" diff --quiet HEAD 2>/dev/null || echo ' + uncommitted changes')"
  echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//'), load at start $(cut -d' ' -f1-3 /proc/loadavg)"
  echo "peers: $PEER_LIST$([[ ${#PEER_ARGS[@]} -gt 0 ]] && echo " (sweeps $PEER_SWEEPS; on frames whose step is a multiple of $PEER_EVERY; $PEER_REPEAT timed repetitions)")"
} > "$OUT_DIR/meta.txt"
say "mode $MODE: ${SECONDS_PER_SCENE} s per scene, every ${EVERY}th step captured, $REPEAT repetitions per solve, $STEP_RUNS whole-step runs; peers: $PEER_LIST"

for scene in "${SCENES[@]}"; do
  for regime in cfm1e-10 comp1e-8; do
    dir=$OUT_DIR/corpus/$scene-$regime
    mkdir -p "$dir"
    # shellcheck disable=SC2086  # the regime option is two words
    demo "corpus-$scene-$regime" "$scene" --solver bpp --seconds "$SECONDS_PER_SCENE" ${REGIMES[$regime]} --cond-every 0 \
      --capture "$dir" --capture-every "$EVERY" --csv "$OUT_DIR/steps/$scene-$regime-bpp.csv" --quiet
    files=$(find "$dir" -name '*.mlcp' | wc -l)
    [[ $files -gt 0 ]] || failed "corpus-$scene-$regime: no island captured"
    say "corpus $scene-$regime: $files files"
  done
done

# Whole steps, STEP_RUNS runs of each comparison in turn: run r writes <name>-step.csv (r = 1) or
# <name>-step-r<r>.csv, dantzig first in odd runs and bpp first in even ones, so that a change in
# the shared machine's load during a run does not always fall on the same method. The report takes
# each ratio's median over the runs (contact_report.py).
whole_steps() {  # NAME SCENE LABEL [ode-bpp-demo options...]
  local name=$1 scene=$2 label=$3 r order suffix
  shift 3
  for ((r = 1; r <= STEP_RUNS; ++r)); do
    order=$([[ $((r % 2)) == 1 ]] && echo dantzig,bpp || echo bpp,dantzig)
    suffix=$([[ $r == 1 ]] && echo "" || echo "-r$r")
    demo "steps-$name$suffix" "$scene" --compare "$order" --seconds "$SECONDS_PER_SCENE" --cond-every 0 \
      --csv "$OUT_DIR/steps/$name-step$suffix.csv" --quiet "$@"
  done
  say "whole steps $scene: dantzig and bpp, $label, $STEP_RUNS runs"
}
for scene in "${SCENES[@]}"; do whole_steps "$scene" "$scene" "CFM 1e-10"; done
# the paper's compliance too, for the hard-contact targets (contact_report.py: both regimes)
for scene in "${PAPER_SCENES[@]}"; do whole_steps "$scene-comp1e-8" "$scene" "compliance 1e-8" --compliance 1e-8; done
# The contact scenes the corpus does not capture, stepped with bpp alone: their fallbacks inside
# ODE (the cannon's and the stack's come from the corpus runs above). Simulated seconds per scene,
# the rock pile's about 4 s of wall time per simulated second.
for entry in "${CONTACT_RUNS[@]}"; do
  read -r scene seconds <<< "$entry"
  demo "fallbacks-$scene" "$scene" --solver bpp --seconds "$seconds" --cond-every 0 \
    --csv "$OUT_DIR/steps/$scene-cfm1e-10-bpp.csv" --quiet
  say "contact scene $scene: bpp inside ODE, $seconds s simulated, for its fallbacks"
done

FILES=$(find "$OUT_DIR/corpus" -name '*.mlcp' | wc -l)
METHODS=bpp-chol,bpp-down,bpp-sky,bpp,dantzig,pgs
run_harness() {
  "$HARNESS" --methods "$METHODS" --pgs-iterations "$PGS_SWEEPS" --repeat "$REPEAT" --factor-error --limit --cond \
    --consistent "$@" --csv "$OUT_DIR/bench.csv" "$OUT_DIR/corpus" > "$OUT_DIR/logs/harness-stdout.txt"
}
if [[ $FILES -gt 0 ]]; then
  say "harness: $FILES files x ($METHODS (pgs: $PGS_SWEEPS sweeps), bpp-consistent${PEER_ARGS:+, peers}), $REPEAT repetitions, interleaved"
  harness_status=0
  run_harness "${PEER_ARGS[@]}" || harness_status=$?
  # 1: some file could not be read (named above; the rest is in the CSV). More: a crash, maybe
  # inside a peer's library; the corpus is then timed again without the peers.
  if [[ $harness_status -eq 1 ]]; then
    failed "bench_corpus: some corpus files could not be read (see the log above); the report covers the rest"
  elif [[ $harness_status -gt 1 && ${#PEER_ARGS[@]} -gt 0 ]]; then
    failed "bench_corpus with peers stopped with status $harness_status; timed again without peers"
    harness_status=0
    run_harness || harness_status=$?
  fi
  [[ $harness_status -le 1 ]] || failed "bench_corpus stopped with status $harness_status; bench.csv holds the files done before"
else
  failed "harness: no corpus file to time"
fi

if [[ -x $FIG4 ]]; then
  say "Fig. 4: bench_fig4 (random SPD matrices, deletion vs refactoring)"
  FIG4_ARGS=()
  [[ $QUICK == 1 ]] && FIG4_ARGS=(--benchmark_min_time=0.02)
  "$FIG4" "${FIG4_ARGS[@]}" --benchmark_out="$OUT_DIR/bench_fig4.csv" --benchmark_out_format=csv \
    > "$OUT_DIR/logs/bench_fig4.txt" 2>&1 || failed "Fig. 4: bench_fig4 exited with status $? (log: logs/bench_fig4.txt)"
else
  failed "Fig. 4: $FIG4 not built"
fi

# Fig. 5: the largest island captured at CFM 1e-10 of each scene (largest file = largest n).
if [[ -x $FIG5 ]]; then
  mkdir -p "$OUT_DIR/fig5"
  echo "scene,file,n,nonzeros,envelope_original,envelope_cm,envelope_rcm,bandwidth_original,bandwidth_cm" > "$OUT_DIR/fig5.csv"
  for scene in "${SCENES[@]}"; do
    largest=$(ls -S "$OUT_DIR/corpus/$scene-cfm1e-10" 2>/dev/null | head -n 1)
    [[ -n $largest ]] || { failed "Fig. 5 $scene: no captured island"; continue; }
    if line=$("$FIG5" "$OUT_DIR/corpus/$scene-cfm1e-10/$largest" "$OUT_DIR/fig5/$scene"); then
      echo "$scene,$largest,$line" >> "$OUT_DIR/fig5.csv"
    else
      failed "Fig. 5 $scene: bench_fig5 failed on $largest"
    fi
  done
  say "Fig. 5: sparsity before and after Cuthill-McKee, largest island per scene"
else
  failed "Fig. 5: $FIG5 not built"
fi

# Instruction counts inside ode_bpp::solve (callgrind), bpp against dantzig, on one frame with
# tight rows per scene: noise-free, unlike the wall-clock times.
if ! command -v valgrind >/dev/null; then
  failed "callgrind: valgrind not installed"
elif [[ -s $OUT_DIR/bench.csv ]]; then
  mapfile -t CG_FILES < <(awk -F, 'NR > 1 && $9 == "bpp-chol" && $15 > 0 { print $1 "/" $5 }' "$OUT_DIR/bench.csv" |
    awk -F/ '{ split($1, part, "-"); if (seen[part[1]]++ < 1) print "'"$OUT_DIR"'/corpus/" $0 }')
  if [[ ${#CG_FILES[@]} -gt 0 ]]; then
    mkdir -p "$OUT_DIR/callgrind"
    echo "method,files,solves,instructions" > "$OUT_DIR/callgrind.csv"
    for method in bpp dantzig bpp-chol; do
      if valgrind --tool=callgrind --callgrind-out-file="$OUT_DIR/callgrind/$method.out" \
        '--toggle-collect=ode_bpp::solve(ode_bpp::Problem const&, ode_bpp::Options const&, ode_bpp::Strided, ode_bpp::Start const&, ode_bpp::Workspace&)' \
        "$HARNESS" --methods "$method" --repeat 1 --warmup 1 --csv /dev/null "${CG_FILES[@]}" \
        > "$OUT_DIR/callgrind/$method.log" 2>&1; then
        # every file is solved twice (untimed + 1 repetition), the first once more as warm-up
        echo "$method,${#CG_FILES[@]},$(( 2 * ${#CG_FILES[@]} + 1 )),$(awk '/^totals:/ { print $2 }' "$OUT_DIR/callgrind/$method.out")" \
          >> "$OUT_DIR/callgrind.csv"
      else
        failed "callgrind $method: valgrind failed (log: callgrind/$method.log)"
      fi
    done
    say "callgrind: ${#CG_FILES[@]} islands with tight rows, bpp / dantzig / bpp-chol -> callgrind.csv"
  else
    failed "callgrind: no island with tight rows in bench.csv"
  fi
fi

say "whole world step: chain scaling, scenes against QuickStep, small islands, physical limit (scripts/bench-world.sh)"
WORLD_ARGS=()
[[ $QUICK == 1 ]] && WORLD_ARGS=(--quick)
bash "$HERE/scripts/bench-world.sh" "$BUILD_DIR" "$OUT_DIR" "${WORLD_ARGS[@]}" ||
  say "whole world step: some runs failed (listed in failures.txt)"

say "report and charts"
if ! python3 "$HERE/bench/report/make_report.py" "$OUT_DIR" "$MODE"; then
  echo "bench-report: make_report.py failed; the raw results are in $OUT_DIR" >&2
  exit 1
fi
if [[ -s $FAILURES ]]; then
  say "done with $(wc -l < "$FAILURES") failed step(s) (listed in report.md): $OUT_DIR/report.md"
  exit 1
fi
say "done: $OUT_DIR/report.md, charts in $OUT_DIR/charts/"
