#!/usr/bin/env bash
# What the build prints on the way to `make demo` and `make test`:
#   scripts/quiet-build.awk (make build): compiler messages pass, per-file lines become one
#     progress line per 10 %, make's directory lines and CMake's bookkeeping lines disappear;
#   scripts/run-with-progress.sh (the ODE build, minutes of silence before): a progress line per
#     interval with the compile commands seen so far, the command's output in the log only, and
#     the command's exit status;
#   the Makefile keeps make's directory lines out of the builds it runs.
set -euo pipefail
: "${ODE_BPP_SOURCE_DIR:?set by ctest (tests/CMakeLists.txt)}"
S=$ODE_BPP_SOURCE_DIR
fail() { echo "build_output: FAIL: $*" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# --- quiet-build.awk on a build's output
{
    echo "gmake[1]: Entering directory '/b'"
    echo "gmake[3]: Leaving directory '/b'"
    echo "Consolidate compiler generated dependencies of target ode_bpp"
    for p in 1 3 8 11 14 35 36 77 99; do echo "[ $p%] Building CXX object f$p.o"; done
    echo "/src/a.cpp:3:1: warning: unused variable 'x'"
    echo "[100%] Linking CXX executable app"
    echo "[100%] Built target app"
} >"$work/build.txt"
awk -f "$S/scripts/quiet-build.awk" "$work/build.txt" >"$work/quiet.txt"
cat "$work/quiet.txt"
! grep -qE 'Entering|Leaving|Consolidate|Built target|Building CXX' "$work/quiet.txt" || fail "noise lines passed"
grep -qF "/src/a.cpp:3:1: warning: unused variable 'x'" "$work/quiet.txt" || fail "a compiler message was dropped"
[[ "$(grep -c '^\[build\] *[0-9]* %$' "$work/quiet.txt")" == 6 ]] || fail "expected 6 progress lines (1, 11, 35, 77, 99, 100 %)"
tail -1 "$work/quiet.txt" | grep -qx '\[build\] done' || fail "no closing line"
echo "[100%] Built target app" | awk -f "$S/scripts/quiet-build.awk" | grep -qx '\[build\] up to date' \
    || fail "an up-to-date build does not say so"

# --- run-with-progress.sh on a command that compiles for 3 s and fails
status=0
"$S/scripts/run-with-progress.sh" t "$work/run.log" 1 bash -c '
    for i in 1 2 3; do echo "libtool: compile:  g++ -O2 -c x$i.cpp"; sleep 1; done; exit 3' >"$work/progress.txt" || status=$?
cat "$work/progress.txt"
(( status == 3 )) || fail "run-with-progress.sh returned $status, not the command's 3"
(( $(grep -c '^\[t\] 0 min 0[0-9] s: [0-9]* files compiled so far$' "$work/progress.txt") >= 2 )) || fail "fewer than 2 progress lines in 3 s"
grep -q 'files compiled so far' <<<"$(tail -1 "$work/progress.txt")" && [[ "$(tail -1 "$work/progress.txt" | awk '{print $6}')" -ge 2 ]] \
    || fail "the progress lines do not count the compile commands"
! grep -q 'libtool' "$work/progress.txt" || fail "the command's output reached the terminal"
[[ "$(grep -c 'libtool: compile' "$work/run.log")" == 3 ]] || fail "the command's output is not in the log"

# --- the Makefile passes --no-print-directory on to the builds it runs
grep -qE '^MAKEFLAGS *\+= *--no-print-directory' "$S/Makefile" || fail "the Makefile does not set --no-print-directory"
echo "build_output: PASS"
