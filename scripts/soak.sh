#!/usr/bin/env bash
# Soak: each of the paper's scenes and each pile, stepped for 100,000 steps (about 28 minutes of
# simulated time) with bpp, one process per scene, watching what must not drift: every body stays
# finite, no island goes to ODE's Dantzig after the baseline step (10,000), and the process's
# resident memory (RSS) at the last step is within 1 % of its RSS at the baseline step.
#
# Usage: scripts/soak.sh BUILD_DIR OUT_DIR [--steps N] [--baseline STEP] [--every K] [--solver NAME]
#                        [--scenes "crane winch ..."]
# Writes OUT_DIR/soak.csv (a row per scene every K steps: RSS, its peak, fallbacks, largest island,
# wall time), OUT_DIR/logs/SCENE.txt and OUT_DIR/report.md. Progress lines go to the terminal.
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
  echo "fallback count at the last step equals the count at step $BASELINE, and RSS at the last step is"
  echo "within 1 % of RSS at step $BASELINE."
  echo
  echo "| scene | steps | fallbacks at $BASELINE | fallbacks at end | RSS at $BASELINE [kB] | RSS at end [kB] | change | peak RSS [kB] | largest island | wall [s] | verdict |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|"
  awk -F, -v baseline="$BASELINE" '
    NR == 1 { next }
    { scene = $1; last[scene] = $0; if ($3 == baseline) base[scene] = $0; if ($8 > rows[scene]) rows[scene] = $8
      if (!(scene in order)) { order[scene] = ++n; names[n] = scene } }
    END {
      for (k = 1; k <= n; ++k) {
        s = names[k]; split(last[s], e, ","); split(base[s], b, ",")
        change = (b[5] > 0) ? 100 * (e[5] - b[5]) / b[5] : 0
        ok = (e[11] == 0 && b[9] == e[9] && change <= 1 && change >= -1 && (s in base))
        printf "| %s | %s | %s | %s | %s | %s | %+.2f %% | %s | %s | %.0f | %s |\n", s, e[3], b[9], e[9], b[5], e[5], change, e[6], rows[s], e[13], ok ? "pass" : "FAIL"
      }
    }' "$CSV"
  echo
  echo "Verdicts as printed by the tool:"
  echo
  sed 's/^/    /' "$VERDICTS"
} > "$OUT_DIR/report.md"
say "report: $OUT_DIR/report.md"
exit $status
