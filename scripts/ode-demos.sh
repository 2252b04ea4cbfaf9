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
#   ODE_DEMOS_SOLVERS (default "dantzig bpp"), ODE_DEMOS_ONLY (space-separated demo names),
#   ODE_DEMOS_QUICKSTEP (default 1: the demos that step only with dWorldQuickStep run too, their
#   quick steps routed to the exact step with each solver, ode-bpp-run --quickstep; 0: not run),
#   ODE_DEMOS_MEMORY_MB (default 8192: the address space of a run, so that a demo whose island
#   outgrows it fails on an allocation instead of being killed by the kernel),
#   ODE_DEMOS_ALL=1 also runs the demos whose source never calls dWorldStep.
set -euo pipefail

BUILD=$(realpath "${1:?usage: ode-demos.sh BUILD_DIR OUT_DIR}")
OUT=$(realpath -m "${2:?usage: ode-demos.sh BUILD_DIR OUT_DIR}")
FRAMES=${ODE_DEMOS_FRAMES:-600}
TIMEOUT=${ODE_DEMOS_TIMEOUT:-300}
read -ra SOLVERS <<<"${ODE_DEMOS_SOLVERS:-dantzig bpp}"
QUICKSTEP=${ODE_DEMOS_QUICKSTEP:-1}
MEMORY_MB=${ODE_DEMOS_MEMORY_MB:-8192}
LAUNCHER=${ODE_BPP_RUN:-$BUILD/cmake/bin/ode-bpp-run}
DEMO_DIR=$BUILD/ode-work/ode/demo
SCREEN=1024x768x24

# Keys typed before the first frame (DS_KEYS), where a demo's default mode would not show the
# solver: demo_crash steps with dWorldQuickStep until 'f' and fires its cannon on 'x';
# demo_buggy stands still until 'a' (faster); demo_trimesh and demo_boxstack drop objects on b, s,
# c, x (boxes, spheres, capsules or cylinders, composites; demo_boxstack starts empty).
declare -A KEYS=([demo_crash]=fx [demo_buggy]=aa [demo_trimesh]=bscxbscxbs [demo_boxstack]=bbbbbsssssccccxx)

say() { echo "[ode-demos] $*"; }
die() { echo "[ode-demos] error: $*" >&2; exit 1; }

[[ -d "$DEMO_DIR" ]] || die "no ODE demos in $DEMO_DIR (build ODE with scripts/build-ode.sh $BUILD patches)"
grep -q DS_KEYS "$BUILD/ode-work/drawstuff/src/x11.cpp" \
    || die "drawstuff in $BUILD/ode-work has no frame limit: rebuild ODE with patches/0002-drawstuff-frame-limit.patch"
[[ -x "$LAUNCHER" ]] || die "no launcher at $LAUNCHER (build ode-bpp, or set ODE_BPP_RUN)"
for tool in xvfb-run convert timeout; do command -v "$tool" >/dev/null || die "$tool is not installed"; done
[[ "$FRAMES" =~ ^[1-9][0-9]*$ ]] || die "ODE_DEMOS_FRAMES must be a positive number"
[[ "$MEMORY_MB" =~ ^[1-9][0-9]*$ ]] || die "ODE_DEMOS_MEMORY_MB must be a positive number"
(( ${#SOLVERS[@]} >= 1 )) || die "ODE_DEMOS_SOLVERS is empty"

# --- what a demo is, from its source ---------------------------------------------------------

demo_source() {
    local f
    for f in "$DEMO_DIR/$1".c "$DEMO_DIR/$1".cpp; do [[ -f "$f" ]] && { echo "$f"; return; }; done
    return 0
}

# A source file without // comments and without the lines of /* */ blocks
code_of() { sed -e 's://.*$::' "$1" | awk '/\/\*/ { c = 1 } !c { print } /\*\// { c = 0 }'; }

# Why a demo cannot exercise ode-bpp, judged from its source; empty if it calls dWorldStep
reason_not_run() {
    local src code
    src=$(demo_source "$1")
    [[ -n "$src" ]] || { echo "no source found"; return; }
    code=$(code_of "$src")
    if grep -qE 'dWorldStep *\(|[.>]step *\(' <<<"$code"; then
        return
    elif ! grep -q dsSimulationLoop <<<"$code"; then
        echo "not a simulation (a test of ODE's internals without a world step or window)"
    elif grep -qE 'dWorldQuickStep|quickStep' <<<"$code"; then
        echo "$QUICK_ONLY"
    else
        echo "steps no dynamics (collision or geometry only)"
    fi
}

# reason_not_run's words for a demo that steps only with dWorldQuickStep (routed when QUICKSTEP=1)
QUICK_ONLY="uses only dWorldQuickStep (the iterative solver; ode-bpp replaces the LCP of dWorldStep)"
# Quick-step demos not routed, and why (no commas: the reason is a CSV field)
declare -A NOT_ROUTED=([demo_space_stress]="drops 10000 overlapping spheres at once: islands of millions of rows, beyond any exact step; bpp answers them by PGS on J without forming A, about 12 s a frame (docs/modelling.md), too slow for this run, and Dantzig cannot form its dense A; under the address-space limit ODE's own collision (the SAP space's pair array) crashes first")

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

# Messages of ODE, of a solver or of the launcher in a log (not the demo's own output, not the
# summary), counted, with the values in parentheses dropped so that repeats merge:
# "107x ODE Message 3: LCP internal error s <= 0 (...);1x ..."
solver_messages() {
    { grep -E 'ODE (Message|INTERNAL ERROR|Error)|LCP|ode-bpp-run:|^ode-bpp: (warning|error)|Segmentation|Aborted' "$1" || true; } \
        | sed -E 's/\([^)]*\)/(...)/g' | sort | uniq -c | sort -rn | awk 'NR <= 3' \
        | awk '{ $1 = $1 "x"; print }' | paste -sd ';' | tr -d ',|'
}

# The line of a log that says why a run ended badly: the first error, else the last line
exit_reason() {
    { grep -m1 -E 'X Error|Segmentation fault|Aborted|INTERNAL ERROR|[Aa]ssert|Killed|terminate called|dsError' "$1" \
        || grep -v '^ode-bpp' "$1" | grep . | tail -1; } \
        | tr -d ',|' | cut -c1-120
}

# run_demo NAME SOLVER [QUICK]: sets RUN_STATUS, RUN_SECONDS, RUN_SUMMARY, RUN_SHOT, RUN_MESSAGES;
# QUICK=1 routes the demo's quick steps to the exact step with SOLVER (--quickstep)
run_demo() {
    local name=$1 solver=$2 quick=${3:-0} program log summary start end
    program=$(demo_program "$name")
    log=$OUT/logs/$name.$solver.log
    summary=$WORK/$name.$solver.summary
    RUN_SHOT=$WORK/$name.$solver.ppm
    rm -f "$summary" "$RUN_SHOT"
    start=$(date +%s.%N)
    RUN_STATUS=0
    # in WORK, so that files some demos write (state.dif) stay out of the way
    local route=(--solver "$solver")
    (( quick )) && route+=(--quickstep "$solver")
    (cd "$WORK" && ulimit -v $((MEMORY_MB * 1024)) && DS_MAX_FRAMES=$FRAMES DS_SCREENSHOT=$RUN_SHOT DS_KEYS=${KEYS[$name]:-} \
        ODE_BPP_SUMMARY_FILE=$summary \
        timeout --kill-after=10 "$TIMEOUT" xvfb-run -a -s "-screen 0 $SCREEN" \
        "$LAUNCHER" "${route[@]}" "$program" </dev/null >"$log" 2>&1) || RUN_STATUS=$?
    end=$(date +%s.%N)
    RUN_SECONDS=$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.1f", b - a }')
    RUN_SUMMARY=$(grep -m1 '^ode-bpp: solver=' "$summary" 2>/dev/null || true)
    RUN_MESSAGES=$(solver_messages "$log")
}

field() { tr ' ' '\n' <<<"$1" | sed -n "s/^$2=//p"; }
ratio() { awk -v a="$1" -v b="$2" -v s="${3:-1}" -v f="$4" 'BEGIN { if (b > 0) printf f, s * a / b }'; }

# --- all demos -------------------------------------------------------------------------------

mkdir -p "$OUT/png" "$OUT/logs"
WORK=$(mktemp -d "${TMPDIR:-/tmp}/ode-demos.XXXXXX")
trap 'rm -rf "$WORK"' EXIT
csv=$OUT/ode-demos.csv
md=$OUT/ode-demos.md

mapfile -t demos < <(list_demos)
(( ${#demos[@]} )) || die "no demo programs in $DEMO_DIR"
say "${#demos[@]} demos, $FRAMES frames each, solvers: ${SOLVERS[*]}; launcher $LAUNCHER; output in $OUT"

echo "demo,stepper,solver,keys,status,exit_code,wall_seconds,steps,islands,rows,pivots,fallbacks,failures,solve_seconds,us_per_step,islands_per_step,rows_per_island,messages,screenshot,note" >"$csv"

declare -A result       # result[DEMO.SOLVER.KEY]
declare -A skipped      # skipped[DEMO] = reason it was not run
declare -A stepper      # stepper[DEMO] = dWorldStep, or dWorldQuickStep for a demo whose quick steps are routed
i=0
for name in "${demos[@]}"; do
    i=$((i + 1))
    reason=$(reason_not_run "$name")
    quick=0
    stepper[$name]=dWorldStep
    if [[ "$reason" == "$QUICK_ONLY" && -n "${NOT_ROUTED[$name]:-}" ]]; then
        reason="$QUICK_ONLY; not routed: ${NOT_ROUTED[$name]}"
    elif [[ "$reason" == "$QUICK_ONLY" && "$QUICKSTEP" == 1 ]]; then
        quick=1
        stepper[$name]=dWorldQuickStep
        reason=""
    fi
    if [[ -n "$reason" && "${ODE_DEMOS_ALL:-0}" != 1 ]]; then
        skipped[$name]=$reason
        echo "$name,,,,not-run,,,,,,,,,,,,,,,$reason" >>"$csv"
        say "($i/${#demos[@]}) $name: not run: $reason"
        continue
    fi
    for solver in "${SOLVERS[@]}"; do
        run_demo "$name" "$solver" "$quick"
        steps=$(field "$RUN_SUMMARY" steps); steps=${steps:-0}
        islands=$(field "$RUN_SUMMARY" islands); islands=${islands:-0}
        rows=$(field "$RUN_SUMMARY" rows); pivots=$(field "$RUN_SUMMARY" pivots)
        fallbacks=$(field "$RUN_SUMMARY" fallbacks); failures=$(field "$RUN_SUMMARY" failures)
        seconds=$(field "$RUN_SUMMARY" solve_seconds)
        # ok: the solver was exercised (a demo may still end badly afterwards: exit_code, note)
        if (( steps > 0 && islands > 0 )); then status=ok
        elif (( RUN_STATUS == 124 || RUN_STATUS == 137 )); then status=timeout
        elif (( RUN_STATUS != 0 )); then status=failed
        elif [[ -z "$RUN_SUMMARY" ]]; then status=no-summary
        else status=not-exercised; fi
        us=$(ratio "${seconds:-0}" "$steps" 1e6 %.1f)
        ips=$(ratio "$islands" "$steps" 1 %.2f)
        rpi=$(ratio "${rows:-0}" "$islands" 1 %.1f)
        png=""
        # one screenshot per demo: the last solver's (bpp by default) replaces the earlier ones
        if [[ -s "$RUN_SHOT" ]] && convert "$RUN_SHOT" "$OUT/png/$name.png"; then png=png/$name.png; fi
        note=""
        if (( RUN_STATUS != 0 )); then
            note="exit $RUN_STATUS: $(exit_reason "$OUT/logs/$name.$solver.log")"
            [[ "$solver" != "${SOLVERS[0]}" && "${result[$name.${SOLVERS[0]}.exit]:-}" == "$RUN_STATUS" ]] \
                && note="$note (the same with ${SOLVERS[0]}: the demo or ODE, not the solver)"
        elif [[ "$status" == not-exercised ]]; then
            note=$(reason_not_run "$name")
            [[ -n "$note" ]] || note="no world step with constraints in $FRAMES frames"
            (( steps > 0 )) && note="dWorldStep on bodies without joints or contacts: no MLCP to solve"
        fi
        keys=${KEYS[$name]:-}
        echo "$name,${stepper[$name]},$solver,$keys,$status,$RUN_STATUS,$RUN_SECONDS,$steps,$islands,${rows:-},${pivots:-},${fallbacks:-},${failures:-},${seconds:-},$us,$ips,$rpi,$RUN_MESSAGES,$png,$note" >>"$csv"
        for key in status steps islands rows pivots failures us ips rpi png note keys; do
            result[$name.$solver.$key]=${!key}
        done
        result[$name.$solver.exit]=$RUN_STATUS
        result[$name.$solver.messages]=$RUN_MESSAGES
        say "($i/${#demos[@]}) $name ${solver}$( (( quick )) && echo " (quick steps routed)")${keys:+ (keys $keys)}: $status, ${RUN_SECONDS}s, $steps steps${us:+, $us us/step}${failures:+, $failures failures}${RUN_MESSAGES:+, messages: $RUN_MESSAGES}${note:+; $note}"
    done
done

# --- the markdown report -----------------------------------------------------------------------

ref=${SOLVERS[0]} alt=${SOLVERS[-1]}
# table STEPPER: the rows of the exercised demos that step with STEPPER
table() {
    local name steps pps msgs solver notes shot
    echo "| demo | keys | steps | islands/step | rows/island | $ref µs/step | $alt µs/step | $alt pivots/step | failures $ref/$alt | messages | notes | screenshot |"
    echo "|---|---|---:|---:|---:|---:|---:|---:|---|---|---|---|"
    for name in "${demos[@]}"; do
        exercised "$name" && [[ "${stepper[$name]}" == "$1" ]] || continue
        steps=${result[$name.$alt.steps]}
        pps=$(ratio "${result[$name.$alt.pivots]:-0}" "$steps" 1 %.1f)
        msgs=""
        for solver in "$ref" "$alt"; do
            [[ -n "${result[$name.$solver.messages]}" ]] && msgs+="${msgs:+ }$solver: ${result[$name.$solver.messages]}"
        done
        notes=${result[$name.$alt.note]:-${result[$name.$ref.note]}}
        shot=${result[$name.$alt.png]:-${result[$name.$ref.png]}}
        echo "| $name | ${result[$name.$alt.keys]} | $steps | ${result[$name.$alt.ips]} | ${result[$name.$alt.rpi]} | ${result[$name.$ref.us]} | ${result[$name.$alt.us]} | $pps | ${result[$name.$ref.failures]:-?}/${result[$name.$alt.failures]:-?} | ${msgs:-none} | $notes | ${shot:+[png]($shot)} |"
    done
}
exercised() { [[ "${result[$1.$alt.status]:-}" == ok || "${result[$1.$ref.status]:-}" == ok ]]; }
{
    echo "# ODE's demos on ode-bpp"
    echo
    echo "ODE $(cut -d' ' -f3 "$BUILD/ode-src/.fetched" 2>/dev/null || echo 0.16.2)'s demos (Debian's source, ode/demo), unchanged, each run headless under"
    echo "Xvfb for $FRAMES frames through \`ode-bpp-run --solver $ref\` and \`--solver $alt\`."
    echo "µs/step: wall time inside the MLCP solver per world step (solve_seconds / steps of the"
    echo "summary line); rows/island: mean island size; failures: solves the world step handed to"
    echo "ODE's Dantzig; messages: ODE's and the solvers' messages on stderr."
    echo
    table dWorldStep
    if [[ "$QUICKSTEP" == 1 ]]; then
        echo
        echo "## Demos that step with dWorldQuickStep, routed to the exact step"
        echo
        echo "Run through \`ode-bpp-run --solver S --quickstep S\`: every quick step is the exact world step"
        echo "with that solver instead of QuickStep's iterations (the program is unchanged). Each run"
        echo "may map ${MEMORY_MB} MB, so that an island whose matrix outgrows it fails on an allocation."
        echo
        table dWorldQuickStep
    fi
    echo
    echo "## Demos that do not exercise ode-bpp"
    echo
    echo "| demo | outcome | reason |"
    echo "|---|---|---|"
    for name in "${demos[@]}"; do
        exercised "$name" && continue
        if [[ -n "${skipped[$name]:-}" ]]; then
            echo "| $name | not run | ${skipped[$name]} |"
        else
            echo "| $name | ${result[$name.$alt.status]} | ${result[$name.$alt.note]} |"
        fi
    done
} >"$md"

ok=0
for name in "${demos[@]}"; do [[ "${result[$name.$alt.status]:-}" == ok ]] && ok=$((ok + 1)); done
say "done: $ok of ${#demos[@]} demos stepped with constraints on $alt; table in $md, data in $csv"
