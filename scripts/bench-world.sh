#!/usr/bin/env bash
# bench-world.sh BUILD_DIR OUT_DIR [--quick]
#
# The whole world step, method against method (docs/benchmarks.md, "The sparse world step"),
# into OUT_DIR/world/; part of `make bench` (scripts/bench-report.sh runs it), or on its own:
#   1. chain scaling: the sweeps' hanging chain, N links, mass ratio 1000, CFM 1e-10, h = 1/60,
#      bpp, QuickStep-20 and (up to about 1,200 rows) dantzig, one process per configuration
#      (its peak memory is that configuration's)                              -> chain.csv
#      and the joint error against a reference beyond dantzig's reach: the dense bpp-down
#      (up to 9,003 rows) and bpp-sky, over a few steps                       -> chain-accuracy.csv
#   2. the paper's six scenes: bpp, QuickStep at 20 and 100 iterations, QuickStep routed to bpp,
#      stepped in turn in one process                                         -> scenes.csv
#   3. small islands: the classic demos and the tiny-island scene, bpp vs dantzig -> classic.csv
#   4. time per island against island size, 1 to ~500 rows, bpp vs dantzig    -> islands.csv
#   5. bpp's distance to the physical limit inside ODE, per island             -> limit.csv
#   6. callgrind: instructions per dWorldStep on the crane (bpp, QuickStep-20) -> callgrind.csv
#   7. long chains: joint gap against the solve's accuracy and the time step   -> conditioning.csv,
#      and the same tear with dantzig on a shorter, heavier chain              -> tension.csv
# A failed step is appended to OUT_DIR/failures.txt and the rest goes on; exit status 1 then.
# --quick: fewer steps and seconds everywhere (about a minute and a half).
set -uo pipefail

usage() { echo "usage: $0 BUILD_DIR OUT_DIR [--quick]" >&2; exit 2; }
[[ $# -ge 2 ]] || usage
BUILD_DIR=$(realpath "$1")
OUT_DIR=$2
QUICK=0
[[ ${3:-} == --quick ]] && QUICK=1
[[ $# -le 3 && ( $# -eq 2 || $QUICK == 1 ) ]] || usage

STEP=$BUILD_DIR/bench/world/bench_world_step
CONDITIONING=$BUILD_DIR/bench/world/chain_conditioning
for tool in "$STEP" "$CONDITIONING"; do
  [[ -x $tool ]] || { echo "bench-world: $tool not built (make bench builds it)" >&2; exit 1; }
done

mkdir -p "$OUT_DIR"
OUT_DIR=$(realpath "$OUT_DIR")
WORLD=$OUT_DIR/world
rm -rf "$WORLD"
mkdir -p "$WORLD/logs"
FAILURES=$OUT_DIR/failures.txt
START=$(date +%s)
say() { echo "[bench-world $(( $(date +%s) - START ))s] $*"; }
failed() { echo "$*" >> "$FAILURES"; say "FAILED: $*"; }
STATUS=0
# run LOG COMMAND...: the command's stderr (progress) into logs/LOG.txt; a failure is recorded.
run() {
  local log=$1 status=0
  shift
  "$@" 2> "$WORLD/logs/$log.txt" > /dev/null || status=$?
  if [[ $status -ne 0 ]]; then
    failed "world $log: exited with status $status (log: world/logs/$log.txt)"
    STATUS=1
  fi
}

PAPER_SCENES=(crane winch parkour offshore forklift forwarder)
CLASSIC_SCENES=(motors chain buggy boxstack cannon islands)
CHAIN_LINKS=(100 300 1000 3000 10000)
CHAIN_RATIO=1000      # light links under a 100 kg load; sound at h = 1/60 up to 10,000 links (docs/benchmarks.md)
DANTZIG_MAX_LINKS=400 # dantzig's dense step up to about 1,200 rows
# island families: KIND:SIZE:COPIES (rows per island: contact 1, marble 3, chain 3 (size + 1),
# stack about 12 (size + 1)); copies keep every world at a few thousand rows
FAMILIES=(contact:1:200 marble:1:200 chain:1:150 chain:3:100 chain:7:60 chain:15:40 chain:31:20 chain:63:10
          chain:127:5 chain:165:4 stack:1:60 stack:3:30 stack:7:12 stack:15:6)
# joint-error references beyond dantzig's reach: LINKS:METHOD (bpp runs beside each, as many steps)
if [[ $QUICK == 1 ]]; then
  ACCURACY=(1000:bpp-down 10000:bpp-sky); ACCURACY_STEPS=5
  CHAIN_STEPS=60; SCENE_SECONDS=5; CLASSIC_SECONDS=(--seconds 3); FAMILY_STEPS=30; LIMIT_SECONDS=3
  CALLGRIND_SECONDS=2; CONDITIONING_SECONDS=2
else
  ACCURACY=(1000:bpp-down 3000:bpp-down 3000:bpp-sky 10000:bpp-sky); ACCURACY_STEPS=10
  CHAIN_STEPS=300; SCENE_SECONDS=20; CLASSIC_SECONDS=(); FAMILY_STEPS=120; LIMIT_SECONDS=20
  CALLGRIND_SECONDS=20; CONDITIONING_SECONDS=3
fi

say "1. chain scaling: ${CHAIN_LINKS[*]} links, $CHAIN_STEPS steps, one process per configuration"
for links in "${CHAIN_LINKS[@]}"; do
  methods=(bpp quickstep-20)
  [[ $links -le $DANTZIG_MAX_LINKS ]] && methods+=(dantzig)
  for method in "${methods[@]}"; do
    run "chain-$links-$method" "$STEP" chain --links "$links" --method "$method" --ratio "$CHAIN_RATIO" \
      --steps "$CHAIN_STEPS" --csv "$WORLD/chain.csv"
    say "   chain of $links links ($(( 3 * (links + 1) )) rows): $method"
  done
done

say "   joint error against references: ${ACCURACY[*]}, $ACCURACY_STEPS steps each"
for spec in "${ACCURACY[@]}"; do
  IFS=: read -r links reference <<< "$spec"
  for method in bpp "$reference"; do
    grep -q "^$links,[0-9]*,$method," "$WORLD/chain-accuracy.csv" 2>/dev/null && continue  # bpp once per length
    # the reference exact whatever its factor's size (a dense one past max_factor_entries would be PGS's)
    exact=(); [[ "$method" != bpp ]] && exact=(--exact)
    run "accuracy-$links-$method" "$STEP" chain --links "$links" --method "$method" --ratio "$CHAIN_RATIO" \
      --steps "$ACCURACY_STEPS" "${exact[@]}" --csv "$WORLD/chain-accuracy.csv"
    say "   chain of $links links: $method"
  done
done

say "2. paper scenes, ${SCENE_SECONDS} s each: bpp, quickstep-20, quickstep-100, quickstep-bpp in turn"
for scene in "${PAPER_SCENES[@]}"; do
  run "scene-$scene" "$STEP" scene --scene "$scene" --methods bpp,quickstep-20,quickstep-100,quickstep-bpp \
    --seconds "$SCENE_SECONDS" --csv "$WORLD/scenes.csv"
  say "   $scene"
done

say "3. small islands: ${CLASSIC_SCENES[*]}, bpp and dantzig in turn"
for scene in "${CLASSIC_SCENES[@]}"; do
  run "classic-$scene" "$STEP" scene --scene "$scene" --methods bpp,dantzig "${CLASSIC_SECONDS[@]}" --csv "$WORLD/classic.csv"
  say "   $scene"
done

say "4. time per island against its size: ${#FAMILIES[@]} families, $FAMILY_STEPS steps, bpp and dantzig in turn"
for family in "${FAMILIES[@]}"; do
  IFS=: read -r kind size copies <<< "$family"
  run "islands-$kind-$size" "$STEP" islands --kind "$kind" --size "$size" --copies "$copies" --methods bpp,dantzig \
    --steps "$FAMILY_STEPS" --csv "$WORLD/islands.csv"
  say "   $copies x $kind $size"
done

say "5. distance to the physical limit inside ODE, ${LIMIT_SECONDS} s per scene"
for scene in "${PAPER_SCENES[@]}"; do
  run "limit-$scene" "$STEP" limit --scene "$scene" --seconds "$LIMIT_SECONDS" --csv "$WORLD/limit.csv"
  say "   $scene"
done

if command -v valgrind > /dev/null; then
  say "6. callgrind: instructions per dWorldStep on the crane, ${CALLGRIND_SECONDS} s (bpp, quickstep-20)"
  echo "scene,method,steps,instructions,per_step" > "$WORLD/callgrind.csv"
  for method in bpp quickstep-20; do
    out=$WORLD/callgrind-crane-$method.out
    if valgrind --tool=callgrind --callgrind-out-file="$out" --toggle-collect=dWorldStep --toggle-collect=dWorldQuickStep \
        "$STEP" scene --scene crane --methods "$method" --seconds "$CALLGRIND_SECONDS" --csv "$WORLD/logs/callgrind-$method.csv" \
        > "$WORLD/logs/callgrind-$method.txt" 2>&1; then
      steps=$(awk -F, 'NR == 2 { print $4 }' "$WORLD/logs/callgrind-$method.csv")  # completed steps
      total=$(awk '/^totals:/ { print $2 }' "$out")
      echo "crane,$method,$steps,$total,$(( total / steps ))" >> "$WORLD/callgrind.csv"
      callgrind_annotate --inclusive=yes "$out" 2> /dev/null | head -n 90 > "$WORLD/callgrind-crane-$method.txt"
      say "   $method: $(( total / steps )) instructions per step"
    else
      failed "world callgrind $method: valgrind failed (log: world/logs/callgrind-$method.txt)"
      STATUS=1
    fi
  done
else
  failed "world callgrind: valgrind not installed"
  STATUS=1
fi

say "7. long chains at mass ratio 40: joint gap against the solve's accuracy and the time step"
# 2,000 links (6,003 rows) hold at h = 1/60; 2,500 (7,503 rows) tear, whichever way A x = b is
# solved; at h = 1/120 they hold again
for run_spec in 2000:bpp:0.0166666667 2500:bpp:0.0166666667 2500:refined:0.0166666667 2500:longdouble:0.0166666667 \
                2500:bpp:0.0083333333; do
  IFS=: read -r links variant h <<< "$run_spec"
  run "conditioning-$links-$variant-$h" "$CONDITIONING" --links "$links" --ratio 40 --seconds "$CONDITIONING_SECONDS" \
    --step "$h" --variant "$variant" --summary "$WORLD/conditioning.csv"
  say "   $links links, $variant, h = $h"
done

# the same tear with dantzig, where its dense step can run: mass ratio 3 (top tension 34 kN at 100
# links, 99 kN at 300)
for run_spec in 100:bpp 300:bpp 300:dantzig; do
  IFS=: read -r links method <<< "$run_spec"
  run "tension-$links-$method" "$STEP" chain --links "$links" --method "$method" --ratio 3 --steps 120 \
    --csv "$WORLD/tension.csv"
  say "   $links links at mass ratio 3, $method"
done

say "done: $WORLD"
exit $STATUS
