#!/usr/bin/env bash
# The summary line also when a program ends by SIGINT (Ctrl-C) or SIGTERM (timeout, kill), and
# the signal keeps its outcome: the caller sees status 128 + n (130, 143).
#   ode-bpp-run PROGRAM (the launcher becomes the program), SIGINT and SIGTERM;
#   `timeout -s TERM` around the launcher, as a user would write it;
#   a script under the launcher (it runs as the launcher's child): Ctrl-C (SIGINT to the whole
#   process group), SIGTERM to the launcher alone (passed on to the script), timeout.
# The program is box_stack --until-signal (tests/launcher/stack_scene.h), built against Debian's
# libode-dev: it steps until a signal ends it.
set -euo pipefail
source "$(dirname "$0")/../launcher/common.bash"

prog=$WORK/box_stack
g++ -O2 "$PROGRAMS/box_stack.cpp" -lode -o "$prog" || fail "cannot build box_stack.cpp against Debian's libode-dev"

# wait_for_stepping NAME PID: until the run printed "stepping" (its stack rests on contacts)
wait_for_stepping() {
    local name=$1 pid=$2 tries
    for (( tries = 0; tries < 200; ++tries )); do
        grep -q '^stepping' "$WORK/$name.out" 2>/dev/null && return 0
        kill -0 "$pid" 2>/dev/null || { show "$name"; fail "$name: ended before it printed 'stepping'"; }
        sleep 0.05
    done
    show "$name"; fail "$name: no 'stepping' within 10 s"
}

# signalled NAME SIGNAL CMD...: starts CMD in the background (SIGINT at its default, as in a
# terminal), sends SIGNAL once it steps a resting stack and sets STATUS
signalled() {
    local name=$1 signal=$2 pid; shift 2
    ( trap - INT QUIT; exec "$@" ) >"$WORK/$name.out" 2>"$WORK/$name.err" &
    pid=$!
    wait_for_stepping "$name" "$pid"
    kill -s "$signal" "$pid"
    STATUS=0
    wait "$pid" || STATUS=$?
}

# check_ended NAME SIGNAL STATUS: the expected status and one summary line that says so
check_ended() {
    local name=$1 signal=$2 want=$3 line
    (( STATUS == want )) || { show "$name"; fail "$name: status $STATUS, expected $want (killed by SIG$signal)"; }
    line=$(summary_lines "$name")
    [[ $(grep -c . <<<"$line") -eq 1 ]] || { show "$name"; fail "$name: expected one summary line after SIG$signal"; }
    grep -q "^ode-bpp: solver=bpp steps=[1-9].* (ended by SIG$signal)" <<<"$line" \
        || { show "$name"; fail "$name: the summary does not show bpp's steps ended by SIG$signal"; }
    note "$name: status $STATUS; $line"
}

signalled int INT "$RUN" "$prog" --until-signal
check_ended int INT 130
signalled term TERM "$RUN" "$prog" --until-signal
check_ended term TERM 143

# timeout signals the launcher's process (by then the program) and its process group
capture timeout timeout -s TERM 1 "$RUN" "$prog" --until-signal
(( STATUS == 124 )) || { show timeout; fail "timeout: status $STATUS, expected 124 (timed out)"; }
grep -q '^ode-bpp: solver=bpp steps=[1-9].* (ended by SIGTERM)' "$WORK/timeout.err" \
    || { show timeout; fail "timeout: no summary ended by SIGTERM"; }
note "timeout: $(summary_lines timeout)"
# --- a script: the launcher waits for it, notes what it saw, and ends by the same signal
printf '#!/bin/sh\n"%s" --until-signal\n' "$prog" >"$WORK/script.sh"
printf '#!/bin/sh\nexec "%s" --until-signal\n' "$prog" >"$WORK/exec_script.sh"
chmod +x "$WORK/script.sh" "$WORK/exec_script.sh"

# Ctrl-C: the terminal signals the foreground process group; setsid makes the launcher lead one
( trap - INT QUIT; exec setsid "$RUN" "$WORK/script.sh" ) >"$WORK/script_int.out" 2>"$WORK/script_int.err" &
pid=$!
wait_for_stepping script_int "$pid"
kill -s INT -- "-$pid"
STATUS=0
wait "$pid" || STATUS=$?
check_ended script_int INT 130

# SIGTERM to the launcher alone reaches the script it runs
signalled script_term TERM "$RUN" "$WORK/exec_script.sh"
check_ended script_term TERM 143

capture script_timeout timeout -s TERM 1 "$RUN" "$WORK/script.sh"
(( STATUS == 124 )) || { show script_timeout; fail "script under timeout: status $STATUS, expected 124"; }
grep -q '^ode-bpp: solver=bpp steps=[1-9].* (ended by SIGTERM)' "$WORK/script_timeout.err" \
    || { show script_timeout; fail "script under timeout: no summary ended by SIGTERM"; }
! grep -q "no process of" "$WORK/script_timeout.err" || { show script_timeout; fail "script under timeout: a false note"; }
note "script under timeout: $(summary_lines script_timeout)"
note PASS
