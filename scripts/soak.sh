#!/usr/bin/env bash
# Soak: each of the paper's scenes and each pile, stepped for 100,000 steps (about 28 minutes of
# simulated time) with bpp, one process per scene, watching what must not drift: every body stays
# finite, no island goes to ODE's Dantzig after the baseline step (10,000), and the process's memory
# shows no steady growth from the baseline step to the last: the live heap's floor gains at most
# 1 % beyond its two largest rises, RSS at most 5 % (demos/ode-bpp-soak.cpp and docs/soak.md).
#
# Usage: scripts/soak.sh BUILD_DIR OUT_DIR [--steps N] [--baseline STEP] [--every K] [--solver NAME]
#                        [--scenes "crane winch ..."]
# Writes OUT_DIR/soak.csv (a row per scene every K steps: live heap, RSS, its peak, fallbacks,
# largest island, wall time), OUT_DIR/logs/SCENE.txt and OUT_DIR/report.md. Progress lines go to the terminal.
# Exit status: 0 when every scene passed, 1 when one did not, 2 on bad usage.
set -euo pipefail

usage() { echo "usage: $0 BUILD_DIR OUT_DIR [--steps N] [--baseline STEP] [--every K] [--solver NAME] [--scenes LIST]" >&2; exit 2; }
[[ $# -ge 2 ]] || usage
BUILD_DIR=$1
OUT_DIR=$2
shift 2
STEPS=100000
BASELINE=10000
EVERY=1000
SOLVER=bpp
SCENES="crane winch parkour offshore forklift forwarder pyramid stack bin rockpile"
while [[ $# -gt 0 ]]; do
  case $1 in
    --steps) STEPS=${2:?}; shift 2 ;;
    --baseline) BASELINE=${2:?}; shift 2 ;;
    --every) EVERY=${2:?}; shift 2 ;;
    --solver) SOLVER=${2:?}; shift 2 ;;
    --scenes) SCENES=${2:?}; shift 2 ;;
    *) usage ;;
  esac
done
SOAK=$BUILD_DIR/demos/ode-bpp-soak
[[ -x $SOAK ]] || { echo "soak: $SOAK not built (make build)" >&2; exit 2; }

mkdir -p "$OUT_DIR/logs"
CSV=$OUT_DIR/soak.csv
VERDICTS=$OUT_DIR/verdicts.txt
: > "$VERDICTS"
rm -f "$CSV"
START=$(date +%s)
say() { echo "[soak $(( $(date +%s) - START ))s] $*"; }
say "$SOLVER, $STEPS steps per scene (baseline step $BASELINE, a row every $EVERY): $SCENES"

status=0
for scene in $SCENES; do
  say "$scene: starting"
  part=$OUT_DIR/logs/$scene.csv
  # progress (stderr) to the terminal and the log; the verdict (stdout) to verdicts.txt
  if ! "$SOAK" "$scene" --solver "$SOLVER" --steps "$STEPS" --baseline "$BASELINE" --every "$EVERY" --csv "$part" \
      2> >(tee "$OUT_DIR/logs/$scene.txt" >&2) >> "$VERDICTS"; then
    status=1
  fi
  if [[ -f $CSV ]]; then tail -n +2 "$part" >> "$CSV"; else cp "$part" "$CSV"; fi
  say "$(tail -n 1 "$VERDICTS")"
done

# report.md: per scene the baseline row and the last row of the CSV
{
  echo "# Soak: $SOLVER, $STEPS steps per scene"
  echo
  echo "date: $(date -u '+%Y-%m-%d %H:%M UTC'); source: $(git -C "$(dirname "$0")/.." rev-parse --short HEAD 2>/dev/null || echo unknown);" \
       "machine: $(nproc) cores; wall time $(( $(date +%s) - START )) s"
  echo
  echo "Each scene runs in its own process (\`ode-bpp-soak\`). Passes when every body stays finite, the"
  echo "fallback count at the last step equals the count at step $BASELINE, and memory shows no steady"
  echo "growth: over ten windows of steps from step $BASELINE on, the live heap's floor (its smallest"
  echo "sample in a window) gains at most 1 % beyond its two largest rises between windows (the"
  echo "high-water marks of kept buffers), and RSS at the last step is at most 5 % above step"
  echo "$BASELINE's (docs/soak.md says why). Verdicts and heap floors are the tool's own."
  echo
  echo "| scene | steps | fallbacks at $BASELINE | fallbacks at end | heap floor [kB] | change | beyond 2 largest rises | RSS at $BASELINE [kB] | RSS at end [kB] | change | peak RSS [kB] | largest island | wall [s] | verdict |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
  awk -F, -v baseline="$BASELINE" -v solver="$SOLVER" '
    function change(from, to) { return from > 0 ? 100 * (to - from) / from : 0 }
    FILENAME != ARGV[1] {
      split($0, words, ": "); key = words[1]; verdict[key] = words[2]
      if (match($0, /heap floor [0-9]+ -> [0-9]+ kB \([^;]*; beyond its [0-9]+ largest rises [^%]*%/)) {
        split(substr($0, RSTART + 11, RLENGTH - 11), t, " "); sub(/^\(/, "", t[5])
        floor[key] = t[1] " -> " t[3]; floor_change[key] = t[5] " %"; steady[key] = t[12] " %"
      }
      next
    }
    FNR == 1 { next }
    { scene = $1; last[scene] = $0; if ($3 == baseline) base[scene] = $0; if ($8 > rows[scene]) rows[scene] = $8
      if (!(scene in order)) { order[scene] = ++n; names[n] = scene } }
    END {
      for (k = 1; k <= n; ++k) {
        s = names[k]; split(last[s], e, ","); split(base[s], b, ","); key = s "/" solver
        v = (key in verdict) ? verdict[key] : "no verdict"
        printf "| %s | %s | %s | %s | %s | %s | %s | %s | %s | %+.2f %% | %s | %s | %.0f | %s |\n", s, e[3], b[9], e[9],
               (key in floor) ? floor[key] : "–", (key in floor) ? floor_change[key] : "–", (key in floor) ? steady[key] : "–",
               b[5], e[5], change(b[5], e[5]), e[6], rows[s], e[13], v
      }
    }' "$CSV" "$VERDICTS"
  echo
  echo "Verdicts as printed by the tool:"
  echo
  sed 's/^/    /' "$VERDICTS"
} > "$OUT_DIR/report.md"
say "report: $OUT_DIR/report.md"
exit $status
