#!/usr/bin/env bash
# An unchanged program built against Debian's libode-dev with plain `g++ box_stack.cpp -lode`
# (it loads /usr/lib/.../libode.so.8) runs on ode-bpp through ode-bpp-run:
#   as it is:                      Debian's libode (Dantzig only), no ode-bpp summary;
#   ode-bpp-run --solver dantzig:  the patched libode's Dantzig, summary solver=dantzig;
#   ode-bpp-run (default bpp):     summary solver=bpp with steps, islands, no failures.
# Oracles: the stack of cubes ends resting on the ground (box i's centre at height (i + 1/2)
# edges) in every run, and the ode-bpp runs end where Debian's Dantzig run ends.
set -euo pipefail
source "$(dirname "$0")/../launcher/common.bash"

side=0.5                       # cube edge in box_stack.cpp
rest_tolerance=0.05            # of an edge: contact softness (ERP/CFM) lets cubes sink a little
agree_tolerance=0.01           # of an edge: both solvers answer the same MLCPs to their tolerance

[[ -e /usr/include/ode/ode.h ]] || fail "Debian's libode-dev is not installed (scripts/install-deps.sh installs it)"
prog=$WORK/box_stack
(cd "$WORK" && g++ -O2 "$PROGRAMS/box_stack.cpp" -lode -o "$prog") \
    || fail "cannot build box_stack.cpp against Debian's libode-dev"
debian=$(debian_libode)
[[ -n "$debian" && "$(resolved_libode "$prog")" == "$debian" ]] \
    || { ldd "$prog"; fail "box_stack does not load Debian's libode.so.8 ($debian)"; }
note "built box_stack against $debian"

# positions NAME: checks the run's box lines are a stack resting on the ground
check_rest() {
    local name=$1
    awk -v side="$side" -v tol="$rest_tolerance" '
        $1 == "box" { n++; want = ($2 + 0.5) * side
                      if (!($5 == $5 + 0) || ($5 - want > tol * side) || (want - $5 > tol * side)) {
                          printf "box %d at height %s, expected %.3f +- %.3f\n", $2, $5, want, tol * side; bad = 1 } }
        END { if (n != 4) { print "expected 4 box lines, got " n; bad = 1 } exit bad }' "$WORK/$name.out" \
        || { show "$name"; fail "$name: the stack is not resting on the ground"; }
}

# agree A B: every coordinate of run A within agree_tolerance edges of run B
agree() {
    paste "$WORK/$1.out" "$WORK/$2.out" | awk -v side="$side" -v tol="$agree_tolerance" '
        { for (k = 3; k <= 5; ++k) { d = $k - $(k + 5); if (d < 0) d = -d
              if (d > worst) worst = d
              if (!(d <= tol * side)) { printf "box %s coordinate %d: %s vs %s\n", $2, k - 2, $k, $(k + 5); bad = 1 } } }
        END { printf "largest difference %.2e m (allowed %.2e m)\n", worst, tol * side; exit bad }' \
        || { show "$1"; show "$2"; fail "$1 does not end where $2 ends"; }
}

# one_summary NAME SOLVER: exactly one summary line naming SOLVER, with steps, islands, no failures
check_summary() {
    local name=$1 solver=$2 line
    line=$(summary_lines "$name")
    [[ $(grep -c . <<<"$line") -eq 1 ]] || { show "$name"; fail "$name: expected one ode-bpp summary line"; }
    note "$name: $line"
    [[ "$(field "$line" solver)" == "$solver" ]] || fail "$name: summary names solver '$(field "$line" solver)', not $solver"
    (( $(field "$line" steps) > 0 )) || fail "$name: no world step counted"
    (( $(field "$line" islands) > 0 )) || fail "$name: no island counted"
    (( $(field "$line" failures) == 0 )) || fail "$name: $(field "$line" failures) failed solves"
    ! grep -qiE 'internal error|error:' "$WORK/$name.err" || { show "$name"; fail "$name: error messages on stderr"; }
}

capture plain "$prog"
(( STATUS == 0 )) || { show plain; fail "box_stack failed on its own (status $STATUS)"; }
[[ -z "$(summary_lines plain)" ]] || { show plain; fail "an ode-bpp summary without the launcher"; }
check_rest plain

capture dantzig "$RUN" --solver dantzig "$prog"
(( STATUS == 0 )) || { show dantzig; fail "box_stack under ode-bpp-run --solver dantzig: status $STATUS"; }
check_summary dantzig dantzig
check_rest dantzig
agree dantzig plain

capture bpp "$RUN" "$prog"
(( STATUS == 0 )) || { show bpp; fail "box_stack under ode-bpp-run: status $STATUS"; }
check_summary bpp bpp
check_rest bpp
agree bpp plain

# ODE_BPP_SUMMARY_FILE gets the same line
capture bpp_file env ODE_BPP_SUMMARY_FILE="$WORK/summary.txt" "$RUN" --solver bpp-sky "$prog"
(( STATUS == 0 )) || { show bpp_file; fail "box_stack under ode-bpp-run --solver bpp-sky: status $STATUS"; }
grep -q '^ode-bpp: solver=bpp-sky steps=[1-9]' "$WORK/summary.txt" 2>/dev/null \
    || { show bpp_file; fail "no bpp-sky summary line in ODE_BPP_SUMMARY_FILE"; }
note PASS
