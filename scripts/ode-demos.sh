#!/usr/bin/env bash
# Runs ODE's own demo programs (ode/demo of Debian's ODE source, built by scripts/build-ode.sh),
# unchanged, headless under Xvfb, once with ODE's Dantzig and once with ode-bpp, through
# ode-bpp-run, for a fixed number of frames (DS_MAX_FRAMES, patches/0002). Records what the
# solver did (the summary line ode-bpp prints at exit) and keeps a PNG of each demo's last frame.
#
# Usage: ode-demos.sh BUILD_DIR OUT_DIR
#   BUILD_DIR  the directory given to build-ode.sh (holds ode-work/ode/demo); the launcher is
#              BUILD_DIR/cmake/bin/ode-bpp-run unless ODE_BPP_RUN names another one
#   OUT_DIR    receives ode-demos.csv, ode-demos.md, png/DEMO.png and logs/DEMO.SOLVER.log
# Environment: ODE_DEMOS_FRAMES (default 600), ODE_DEMOS_TIMEOUT seconds per run (default 300),
#   ODE_DEMOS_SOLVERS (default "dantzig bpp"), ODE_DEMOS_ONLY (space-separated demo names).
set -euo pipefail

BUILD=$(realpath "${1:?usage: ode-demos.sh BUILD_DIR OUT_DIR}")
OUT=$(realpath -m "${2:?usage: ode-demos.sh BUILD_DIR OUT_DIR}")
FRAMES=${ODE_DEMOS_FRAMES:-600}
TIMEOUT=${ODE_DEMOS_TIMEOUT:-300}
read -ra SOLVERS <<<"${ODE_DEMOS_SOLVERS:-dantzig bpp}"
LAUNCHER=${ODE_BPP_RUN:-$BUILD/cmake/bin/ode-bpp-run}
DEMO_DIR=$BUILD/ode-work/ode/demo
SCREEN=1024x768x24

say() { echo "[ode-demos] $*"; }
die() { echo "[ode-demos] error: $*" >&2; exit 1; }

[[ -d "$DEMO_DIR" ]] || die "no ODE demos in $DEMO_DIR (build ODE with scripts/build-ode.sh $BUILD patches)"
grep -q DS_MAX_FRAMES "$BUILD/ode-work/drawstuff/src/x11.cpp" \
    || die "drawstuff in $BUILD/ode-work has no frame limit: rebuild ODE with patches/0002-drawstuff-frame-limit.patch"
[[ -x "$LAUNCHER" ]] || die "no launcher at $LAUNCHER (build ode-bpp, or set ODE_BPP_RUN)"
for tool in xvfb-run convert timeout; do command -v "$tool" >/dev/null || die "$tool is not installed"; done
[[ "$FRAMES" =~ ^[1-9][0-9]*$ ]] || die "ODE_DEMOS_FRAMES must be a positive number"

# --- what a demo is, from its source -------------------------------------------------------

# The source file of a demo (ode/demo/demo_X.cpp or .c)
demo_source() { ls "$DEMO_DIR/$1".c "$DEMO_DIR/$1".cpp 2>/dev/null | head -1; }

# The code of a source file without // comments and without lines inside /* */ blocks
code_of() { sed -e 's://.*$::' "$1" | awk '/\/\*/ { c = 1 } !c { print } /\*\// { c = 0 }'; }

# Why a demo makes no world step with constraints on ode-bpp, judged from its source
reason_not_exercised() {
    local src code
    src=$(demo_source "$1")
    [[ -n "$src" ]] || { echo "no source found"; return; }
    code=$(code_of "$src")
    if ! grep -q dsSimulationLoop <<<"$code"; then
        echo "not a drawstuff demo (a test program without a window)"
    elif grep -qE 'dWorldStep|[.>]step *\(' <<<"$code"; then
        if grep -qE 'dWorldQuickStep|quickStep' <<<"$code"; then
            echo "dWorldStep only on a key press (dWorldQuickStep by default)"
        else
            echo "dWorldStep without constraints in the frames run, or only after user input"
        fi
    elif grep -qE 'dWorldQuickStep|quickStep' <<<"$code"; then
        echo "uses only dWorldQuickStep (the iterative solver; ode-bpp replaces the LCP of dWorldStep)"
    else
        echo "no dynamics stepped (collision or geometry only)"
    fi
}

# The demo's ELF program: libtool keeps it in .libs/ behind a wrapper script
demo_program() {
    local name=$1
    if [[ -x "$DEMO_DIR/.libs/$name" ]]; then echo "$DEMO_DIR/.libs/$name"
    elif [[ -x "$DEMO_DIR/.libs/lt-$name" ]]; then echo "$DEMO_DIR/.libs/lt-$name"
    else echo "$DEMO_DIR/$name"; fi
}

list_demos() {
    local f name
    for f in "$DEMO_DIR"/demo_*; do
        name=$(basename "$f")
        [[ -f "$f" && -x "$f" && "$name" != *.* ]] || continue
        if [[ -n "${ODE_DEMOS_ONLY:-}" ]] && ! grep -qw -- "$name" <<<"$ODE_DEMOS_ONLY"; then continue; fi
        echo "$name"
    done
}

# --- one run -----------------------------------------------------------------------------------

# Lines on stderr that are messages of ODE or of a solver (not drawstuff's banner, not the summary)
solver_messages() {
    grep -E 'ODE (Message|INTERNAL ERROR|Error)|LCP|ode-bpp-run:|^ode-bpp: (warning|error)|Segmentation|Aborted' "$1" \
        | grep -v '^ode-bpp: solver=' | sort | uniq -c | sort -rn | head -3 \
        | awk '{ $1 = $1 "x"; print }' | paste -sd ';' | tr -d ',|' || true
}

# run_demo NAME SOLVER: runs it, sets RUN_STATUS, RUN_SECONDS and RUN_SUMMARY (the summary line)
run_demo() {
    local name=$1 solver=$2 program log summary shot start end
    program=$(demo_program "$name")
    log=$OUT/logs/$name.$solver.log
    summary=$WORK/$name.$solver.summary
    shot=$WORK/$name.$solver.ppm
    rm -f "$summary" "$shot"
    start=$(date +%s.%N)
    RUN_STATUS=0
    # the demos look for textures relative to nothing (their path is compiled in); run in WORK so
    # that files some demos write (state.dif) stay out of the way
    (cd "$WORK" && DS_MAX_FRAMES=$FRAMES DS_SCREENSHOT=$shot ODE_BPP_SUMMARY_FILE=$summary \
        timeout --kill-after=10 "$TIMEOUT" xvfb-run -a -s "-screen 0 $SCREEN" \
        "$LAUNCHER" --solver "$solver" "$program" </dev/null >"$log" 2>&1) || RUN_STATUS=$?
    end=$(date +%s.%N)
    RUN_SECONDS=$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.1f", b - a }')
    RUN_SUMMARY=$(grep -m1 '^ode-bpp: solver=' "$summary" 2>/dev/null || true)
    RUN_SHOT=$shot
    RUN_MESSAGES=$(solver_messages "$log")
}

field() { tr ' ' '\n' <<<"$1" | sed -n "s/^$2=//p"; }

# The line of a log that says why the demo ended badly: the first error, else the last line
exit_reason() {
    { grep -m1 -E 'Error|error|Segmentation|Aborted|assert|Killed' "$1" || grep -v '^ode-bpp' "$1" | grep . | tail -1; } \
        | tr -d ',|' | cut -c1-120
}

# --- all demos -------------------------------------------------------------------------------

mkdir -p "$OUT/png" "$OUT/logs"
WORK=$(mktemp -d "${TMPDIR:-/tmp}/ode-demos.XXXXXX")
trap 'rm -rf "$WORK"' EXIT
csv=$OUT/ode-demos.csv
md=$OUT/ode-demos.md

mapfile -t demos < <(list_demos)
(( ${#demos[@]} )) || die "no demo programs in $DEMO_DIR"
say "${#demos[@]} demos, $FRAMES frames each, solvers: ${SOLVERS[*]}; launcher $LAUNCHER; output in $OUT"

echo "demo,solver,status,exit_code,wall_seconds,steps,islands,rows,pivots,fallbacks,failures,solve_seconds,us_per_step,islands_per_step,rows_per_island,messages,screenshot,note" >"$csv"

declare -A result       # result[demo.solver.key]
i=0
for name in "${demos[@]}"; do
    i=$((i + 1))
    for solver in "${SOLVERS[@]}"; do
        run_demo "$name" "$solver"
        steps=$(field "$RUN_SUMMARY" steps); steps=${steps:-0}
        islands=$(field "$RUN_SUMMARY" islands); rows=$(field "$RUN_SUMMARY" rows)
        pivots=$(field "$RUN_SUMMARY" pivots); fallbacks=$(field "$RUN_SUMMARY" fallbacks)
        failures=$(field "$RUN_SUMMARY" failures); seconds=$(field "$RUN_SUMMARY" solve_seconds)
        # ok: the solver was exercised (a demo may still exit badly afterwards: see exit_code, note)
        if (( steps > 0 && ${islands:-0} > 0 )); then status=ok
        elif (( RUN_STATUS == 124 || RUN_STATUS == 137 )); then status=timeout
        elif (( RUN_STATUS != 0 )); then status=failed
        elif [[ -z "$RUN_SUMMARY" ]]; then status=no-summary
        else status=not-exercised; fi
        us=""; ips=""; rpi=""
        if (( steps > 0 )); then
            us=$(awk -v s="$seconds" -v n="$steps" 'BEGIN { printf "%.1f", 1e6 * s / n }')
            ips=$(awk -v i="$islands" -v n="$steps" 'BEGIN { printf "%.2f", i / n }')
            rpi=$(awk -v r="$rows" -v i="$islands" 'BEGIN { printf "%.1f", (i > 0 ? r / i : 0) }')
        fi
        png=""
        if [[ -s "$RUN_SHOT" ]]; then
            # one screenshot per demo: the last solver's (bpp by default) replaces the earlier ones
            convert "$RUN_SHOT" "$OUT/png/$name.png" && png=png/$name.png
        fi
        note=""
        if (( RUN_STATUS != 0 )); then
            note="exit $RUN_STATUS: $(exit_reason "$OUT/logs/$name.$solver.log")"
            [[ "$solver" != "${SOLVERS[0]}" && "${result[$name.${SOLVERS[0]}.exit]}" == "$RUN_STATUS" ]] \
                && note="$note (the same with ${SOLVERS[0]}: a problem of the demo or of ODE, not of the solver)"
        elif [[ "$status" != ok ]]; then
            note=$(reason_not_exercised "$name")
            (( steps > 0 )) && note="dWorldStep on bodies without joints or contacts: no MLCP to solve"
        fi
        echo "$name,$solver,$status,$RUN_STATUS,$RUN_SECONDS,$steps,${islands:-},${rows:-},${pivots:-},${fallbacks:-},${failures:-},${seconds:-},$us,$ips,$rpi,$RUN_MESSAGES,$png,$note" >>"$csv"
        for key in status steps islands rows pivots failures us ips rpi png note; do
            result[$name.$solver.$key]=${!key}
        done
        result[$name.$solver.exit]=$RUN_STATUS
        result[$name.$solver.messages]=$RUN_MESSAGES
        say "($i/${#demos[@]}) $name $solver: $status, ${RUN_SECONDS}s, $steps steps${us:+, $us us/step}${failures:+, $failures failures}${RUN_MESSAGES:+, messages: $RUN_MESSAGES}"
    done
done

# --- the markdown report -----------------------------------------------------------------------

ref=${SOLVERS[0]} alt=${SOLVERS[-1]}
{
    echo "# ODE's demos on ode-bpp"
    echo
    echo "Each demo of ODE $(cut -d' ' -f3 "$BUILD/ode-src/.fetched" 2>/dev/null || echo 0.16.2) (Debian's source, ode/demo), unchanged, run headless"
    echo "under Xvfb for $FRAMES frames through \`ode-bpp-run --solver $ref\` and \`--solver $alt\`."
    echo "Solve time is the wall time inside the MLCP solver per world step with constraints"
    echo "(solve_seconds / steps of the ode-bpp summary line); pivots per step for $alt."
    echo
    echo "| demo | steps | islands/step | rows/island | $ref µs/step | $alt µs/step | $alt pivots/step | failures ($ref/$alt) | messages | notes | screenshot |"
    echo "|---|---:|---:|---:|---:|---:|---:|---|---|---|---|"
    for name in "${demos[@]}"; do
        [[ "${result[$name.$alt.status]}" == ok || "${result[$name.$ref.status]}" == ok ]] || continue
        steps=${result[$name.$alt.steps]}
        pps=$(awk -v p="${result[$name.$alt.pivots]:-0}" -v n="$steps" 'BEGIN { if (n > 0) printf "%.1f", p / n }')
        msgs="${result[$name.$ref.messages]}${result[$name.$ref.messages]:+ ($ref)}${result[$name.$alt.messages]:+ }${result[$name.$alt.messages]}${result[$name.$alt.messages]:+ ($alt)}"
        shot=${result[$name.$alt.png]:-${result[$name.$ref.png]}}
        notes=${result[$name.$alt.note]:-${result[$name.$ref.note]}}
        echo "| $name | $steps | ${result[$name.$alt.ips]} | ${result[$name.$alt.rpi]} | ${result[$name.$ref.us]} | ${result[$name.$alt.us]} | $pps | ${result[$name.$ref.failures]:-?}/${result[$name.$alt.failures]:-?} | ${msgs:-none} | ${notes} | ${shot:+[png]($shot)} |"
    done
    echo
    echo "## Demos that do not exercise ode-bpp"
    echo
    echo "| demo | outcome | reason |"
    echo "|---|---|---|"
    for name in "${demos[@]}"; do
        [[ "${result[$name.$alt.status]}" == ok || "${result[$name.$ref.status]}" == ok ]] && continue
        echo "| $name | ${result[$name.$alt.status]} | ${result[$name.$alt.note]} |"
    done
} >"$md"

ok=0; for name in "${demos[@]}"; do [[ "${result[$name.$alt.status]}" == ok ]] && ok=$((ok + 1)); done
say "done: $ok of ${#demos[@]} demos stepped with constraints on $alt; table in $md, data in $csv"
