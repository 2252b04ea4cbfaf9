#!/usr/bin/env bash
# Programs that step only with dWorldQuickStep (most games on ODE do), built against Debian's
# libode-dev (quickstep_stack.cpp: the box stack of box_stack.cpp, stepped by dWorldQuickStep):
#   ode-bpp-run PROGRAM                     -> says before the run that it uses QuickStep only, that
#                                              ode-bpp changes nothing there and which option does;
#                                              the summary says QuickStep solved its steps;
#   ode-bpp-run --quickstep bpp PROGRAM     -> bpp solves its islands; the run is the exact step's:
#   ODE_QUICKSTEP_SOLVER=bpp ode-bpp-run       the same output as box_stack (dWorldStep) on bpp;
#   a script whose child uses QuickStep only -> the launcher says so afterwards (no false claim
#                                              that it does not use ODE);
#   --quickstep with an unknown name        -> refused (125), the valid names listed.
set -euo pipefail
source "$(dirname "$0")/../launcher/common.bash"

quick=$WORK/quickstep_stack exact=$WORK/box_stack
g++ -O2 "$PROGRAMS/quickstep_stack.cpp" -lode -o "$quick" || fail "cannot build quickstep_stack.cpp against Debian's libode-dev"
g++ -O2 "$PROGRAMS/box_stack.cpp" -lode -o "$exact" || fail "cannot build box_stack.cpp against Debian's libode-dev"
readelf --dyn-syms -W "$quick" | grep -q ' UND dWorldQuickStep' || fail "quickstep_stack does not import dWorldQuickStep"
! readelf --dyn-syms -W "$quick" | grep -q ' UND dWorldStep' || fail "quickstep_stack imports dWorldStep"

# one_summary NAME: the run's only summary line
one_summary() {
    local line
    line=$(summary_lines "$1")
    [[ $(grep -c . <<<"$line") -eq 1 ]] || { show "$1"; fail "$1: expected one ode-bpp summary line"; }
    echo "$line"
}

# --- unrouted: said before the run, and in the summary
capture plain "$RUN" "$quick"
(( STATUS == 0 )) || { show plain; fail "quickstep_stack under ode-bpp-run: status $STATUS"; }
grep -q "steps its worlds with dWorldQuickStep only" "$WORK/plain.err" || { show plain; fail "no note that the program uses QuickStep only"; }
grep -q "nothing changes" "$WORK/plain.err" || { show plain; fail "the note does not say that nothing changes"; }
grep -q -- "--quickstep bpp" "$WORK/plain.err" || { show plain; fail "the note does not name --quickstep"; }
line=$(one_summary plain)
[[ "$(field "$line" solver)" == quickstep && "$(field "$line" quickstep_steps)" == 300 && "$(field "$line" islands)" == 0 ]] \
    || { show plain; fail "the summary does not say that QuickStep solved the 300 steps: $line"; }
note "unrouted: $line"

# --- routed to bpp, by option and by environment: bpp's islands, the exact step's trajectory
capture exact_bpp "$RUN" "$exact"
(( STATUS == 0 )) || { show exact_bpp; fail "box_stack under ode-bpp-run: status $STATUS"; }
for how in option environment; do
    if [[ $how == option ]]; then capture "routed_$how" "$RUN" --quickstep bpp "$quick"
    else capture "routed_$how" env ODE_QUICKSTEP_SOLVER=bpp "$RUN" "$quick"; fi
    (( STATUS == 0 )) || { show "routed_$how"; fail "routed by $how: status $STATUS"; }
    ! grep -q "dWorldQuickStep only" "$WORK/routed_$how.err" || { show "routed_$how"; fail "routed by $how: still told that nothing changes"; }
    line=$(one_summary "routed_$how")
    [[ "$(field "$line" solver)" == bpp ]] && (( $(field "$line" steps) == 300 && $(field "$line" islands) > 0 )) \
        && (( $(field "$line" failures) == 0 )) && [[ -z "$(field "$line" quickstep_steps)" ]] \
        || { show "routed_$how"; fail "routed by $how: the summary does not show bpp solving the 300 steps: $line"; }
    cmp -s "$WORK/routed_$how.out" "$WORK/exact_bpp.out" \
        || { show "routed_$how"; show exact_bpp; fail "routed by $how: not the trajectory of dWorldStep on bpp"; }
    note "routed by $how: $line"
done

# --- a script whose child uses only QuickStep
printf '#!/bin/sh\n"%s" >/dev/null\n' "$quick" >"$WORK/script.sh"
chmod +x "$WORK/script.sh"
capture script "$RUN" "$WORK/script.sh"
(( STATUS == 0 )) || { show script; fail "script under ode-bpp-run: status $STATUS"; }
grep -q "stepped its worlds with dWorldQuickStep only" "$WORK/script.err" || { show script; fail "script: no note that its child used QuickStep only"; }
! grep -qiE "does not use ODE|no ode-bpp summary" "$WORK/script.err" || { show script; fail "script: a false claim that it does not use ODE"; }
note "script: $(grep '^ode-bpp-run:' "$WORK/script.err")"

# --- an unknown name
capture unknown "$RUN" --quickstep nosuch "$quick"
(( STATUS == 125 )) || { show unknown; fail "--quickstep nosuch: status $STATUS, expected 125"; }
grep -q "unknown dWorldQuickStep solver 'nosuch'; valid names: dantzig, .*bpp" "$WORK/unknown.err" \
    || { show unknown; fail "--quickstep nosuch: the valid names are not listed"; }
[[ ! -s "$WORK/unknown.out" ]] || fail "--quickstep nosuch: the program ran"
note PASS
