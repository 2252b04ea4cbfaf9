#!/usr/bin/env bash
# A Python program that loads libode.so.8 with ctypes (tests/launcher/pendulum_ctypes.py) runs
# on ode-bpp through ode-bpp-run, started as `python3 script` and as an executable script:
# the summary names the solver with steps, islands and no failures, and the joints still hold
# (every link of the swinging chain keeps its length). Loading Debian's libode by absolute path
# bypasses the launcher (a second libode in the process), which then says so after the run.
set -euo pipefail
source "$(dirname "$0")/../launcher/common.bash"

length=0.4                 # link length in pendulum_ctypes.py
drift_tolerance=0.05       # of a link: ODE's joint error correction (ERP) lets links stretch a little

# Debian's python3 (scripts/install-deps.sh installs it); the executable-script run below goes
# through the script's own `#!/usr/bin/env python3`, whichever python3 is first on PATH
python=/usr/bin/python3
[[ -x "$python" ]] || python=$(command -v python3) || fail "python3 is not installed (scripts/install-deps.sh installs it)"
script=$WORK/pendulum_ctypes.py
cp "$PROGRAMS/pendulum_ctypes.py" "$script"
chmod +x "$script"

check_links() {
    awk -v L="$length" -v tol="$drift_tolerance" '
        $1 == "link" { n++; d = $3 - L; if (d < 0) d = -d
                       if (!(d <= tol * L)) { printf "link %d has length %s, expected %s\n", $2, $3, L; bad = 1 } }
        END { if (n != 5) { print "expected 5 link lines, got " n; bad = 1 } exit bad }' "$WORK/$1.out" \
        || { show "$1"; fail "$1: the chain's joints do not hold"; }
}

check_summary() {
    local name=$1 solver=$2 line
    (( STATUS == 0 )) || { show "$name"; fail "$name: status $STATUS"; }
    line=$(stepping_lines "$name")
    [[ $(grep -c . <<<"$line") -eq 1 ]] || { show "$name"; fail "$name: expected one process with world steps in the summaries"; }
    note "$name: $line"
    [[ "$(field "$line" solver)" == "$solver" ]] || fail "$name: solver '$(field "$line" solver)', expected $solver"
    (( $(field "$line" steps) > 0 )) || fail "$name: no world step counted"
    (( $(field "$line" islands) > 0 )) || fail "$name: no island counted"
    (( $(field "$line" failures) == 0 )) || fail "$name: $(field "$line" failures) failed solves"
    ! grep -q "^ode-bpp-run: note" "$WORK/$name.err" || { show "$name"; fail "$name: launcher says ODE was not used"; }
    check_links "$name"
}

capture plain "$python" "$script"
(( STATUS == 0 )) || { show plain; fail "the script fails on its own (status $STATUS)"; }
[[ -z "$(summary_lines plain)" ]] || { show plain; fail "a summary without the launcher"; }
check_links plain

capture interpreter "$RUN" "$python" "$script"
check_summary interpreter bpp
capture executable "$RUN" --solver dantzig "$script"
check_summary executable dantzig
capture chol "$RUN" --solver=bpp-chol "$python" "$script"
check_summary chol bpp-chol

# Python keeps Ctrl-C as KeyboardInterrupt under the launcher: CPython installs that handler only
# where SIGINT is at its default when it starts, so the summary's SIGINT handler must wait
capture keyboard_interrupt "$RUN" "$python" -c 'import signal; print(signal.getsignal(signal.SIGINT) is signal.default_int_handler)'
[[ "$(cat "$WORK/keyboard_interrupt.out")" == True ]] \
    || { show keyboard_interrupt; fail "under the launcher, Python's SIGINT is no longer KeyboardInterrupt"; }

# by absolute path: Debian's copy is loaded beside the patched one, the launcher cannot switch it
capture absolute "$RUN" "$python" "$script" "$(debian_libode)"
(( STATUS == 0 )) || { show absolute; fail "absolute-path run: status $STATUS"; }
# (which of the two messages depends on how the second copy's internal calls bind)
grep -qE "^ode-bpp-run: (note|warning): .*absolute path" "$WORK/absolute.err" \
    || { show absolute; fail "absolute-path load: the launcher did not say that ode-bpp was not used"; }
check_links absolute
note "absolute path: $(grep -E '^ode-bpp-run: (note|warning)' "$WORK/absolute.err")"
note PASS
