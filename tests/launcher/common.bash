# shellcheck shell=bash disable=SC2034  # RUN, PROGRAMS, STATUS are for the sourcing tests
# Shared by tests/shell/launcher_*.sh: the launcher under test, a scratch directory, and helpers
# to run a command capturing its stdout, stderr and exit status.
: "${ODE_BPP_BINARY_DIR:?set by ctest (tests/CMakeLists.txt)}"
: "${ODE_BPP_SOURCE_DIR:?set by ctest (tests/CMakeLists.txt)}"
RUN=$ODE_BPP_BINARY_DIR/bin/ode-bpp-run
PROGRAMS=$ODE_BPP_SOURCE_DIR/tests/launcher
TEST_NAME=$(basename "$0" .sh)

fail() { echo "$TEST_NAME: FAIL: $*" >&2; exit 1; }
note() { echo "$TEST_NAME: $*"; }

[[ -x "$RUN" ]] || fail "no launcher at $RUN"
WORK=$(mktemp -d "${TMPDIR:-/tmp}/$TEST_NAME.XXXXXX")
trap 'rm -rf "$WORK"' EXIT

# capture NAME CMD...: runs CMD with stdout in $WORK/NAME.out, stderr in $WORK/NAME.err and
# sets STATUS; never fails itself.
capture() {
    local name=$1; shift
    STATUS=0
    "$@" >"$WORK/$name.out" 2>"$WORK/$name.err" || STATUS=$?
}

show() { local name=$1; echo "--- $name stdout"; cat "$WORK/$name.out"; echo "--- $name stderr"; cat "$WORK/$name.err"; }

# summary_lines NAME: the ode-bpp summary lines a captured run printed on stderr
summary_lines() { grep '^ode-bpp: solver=' "$WORK/$1.err" || true; }

# stepping_lines NAME: the summary lines of processes that made world steps with constraints
# (under ode-bpp-run every process of a script prints a line, those without ODE with steps=0)
stepping_lines() { grep -E '^ode-bpp: solver=[^ ]+ steps=[1-9]' "$WORK/$1.err" || true; }

# field LINE KEY: the value of KEY=VALUE in a summary line
field() { tr ' ' '\n' <<<"$1" | sed -n "s/^$2=//p"; }

# Debian's libode.so.8 as the loader resolves it for a program, symlinks followed
debian_libode() { readlink -f "$(ls /usr/lib/*/libode.so.8 2>/dev/null | head -1)"; }
resolved_libode() { ldd "$1" | awk '$1 == "libode.so.8" { print $3 }' | xargs -r readlink -f; }
