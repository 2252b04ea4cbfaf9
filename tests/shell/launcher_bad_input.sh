#!/usr/bin/env bash
# ode-bpp-run on programs it must not (or cannot) switch to ode-bpp:
#   a program without ODE (/bin/true, /bin/false)    -> says so, runs it unchanged, its status;
#   a program NEEDing libode.so.6                     -> refuses (125), the program does not run;
#   a program or script whose libode.so.8 is single precision -> refuses (125);
#   a private libode.so.8 reached through DT_RPATH    -> refuses (125); through RUNPATH -> runs on bpp;
#   ODE linked statically                             -> refuses (125);
#   a setuid program                                  -> refuses (125);
#   an unknown --solver                               -> refuses (125) listing the valid names;
#   a missing program                                 -> 127;
#   a script reads the caller's stdin (a closed one is no error).
set -euo pipefail
source "$(dirname "$0")/../launcher/common.bash"

# expect_refusal NAME PATTERN: the run exited 125, said PATTERN, and the program did not run
expect_refusal() {
    local name=$1 pattern=$2
    (( STATUS == 125 )) || { show "$name"; fail "$name: exit status $STATUS, expected 125 (refused)"; }
    grep -qiE "$pattern" "$WORK/$name.err" || { show "$name"; fail "$name: the message does not say /$pattern/"; }
    [[ ! -s "$WORK/$name.out" ]] || { show "$name"; fail "$name: the program ran although refused"; }
    ! grep -q '^ode-bpp: solver=' "$WORK/$name.err" || { show "$name"; fail "$name: a summary although refused"; }
    note "$name: refused: $(grep -m1 refusing "$WORK/$name.err")"
}

# --- not ODE: runs unchanged, with its own exit status
capture true_prog "$RUN" /bin/true
(( STATUS == 0 )) || { show true_prog; fail "/bin/true under the launcher: status $STATUS"; }
grep -q "does not use ODE" "$WORK/true_prog.err" || { show true_prog; fail "/bin/true: no 'does not use ODE' message"; }
[[ -z "$(summary_lines true_prog)" ]] || { show true_prog; fail "/bin/true: got an ode-bpp summary"; }
capture false_prog "$RUN" false
(( STATUS == 1 )) || { show false_prog; fail "false under the launcher: status $STATUS, expected its own 1"; }
note "non-ODE programs run unchanged with their own status"

# --- a script runs as the launcher's child: it reads the caller's stdin; a closed stdin is no error
capture stdin_script bash -c "echo hello | '$RUN' bash -c 'read -r line; echo \"got \$line\"'"
[[ "$(cat "$WORK/stdin_script.out")" == "got hello" ]] || { show stdin_script; fail "a script under the launcher did not read the caller's stdin"; }
capture closed_stdin bash -c "'$RUN' /bin/sh -c 'echo ran' <&-"
(( STATUS == 0 )) && [[ "$(cat "$WORK/closed_stdin.out")" == ran ]] && ! grep -q 'Bad file descriptor' "$WORK/closed_stdin.err" \
    || { show closed_stdin; fail "a script under the launcher with stdin closed"; }
note "scripts get the caller's stdin"

capture missing "$RUN" "$WORK/no-such-program"
(( STATUS == 127 )) || { show missing; fail "missing program: status $STATUS, expected 127"; }

# --- other libodes, built from fake_ode.c with the soname and precision marker to be refused
build_fake() {  # build_fake DIR SONAME PRECISION
    mkdir -p "$1"
    gcc -shared -fPIC -DFAKE_PRECISION="$3" -Wl,-soname,"$2" "$PROGRAMS/fake_ode.c" -o "$1/$2"
    ln -sf "$2" "$1/libode.so"
}
link_user() {  # link_user OUT DIR [linker flags]: uses_fake_ode linked against DIR/libode.so
    local out=$1 dir=$2; shift 2
    gcc "$PROGRAMS/uses_fake_ode.c" -L"$dir" -lode "$@" -o "$out"
}

build_fake "$WORK/old" libode.so.6 ODE_double_precision
link_user "$WORK/needs_so6" "$WORK/old" -Wl,-rpath,"$WORK/old"
"$WORK/needs_so6" | grep ran >/dev/null || fail "the libode.so.6 program does not run on its own"
capture so6 "$RUN" "$WORK/needs_so6"
expect_refusal so6 "libode\.so\.6"

build_fake "$WORK/single" libode.so.8 ODE_single_precision
link_user "$WORK/needs_single" "$WORK/single" -Wl,-rpath,"$WORK/single"
"$WORK/needs_single" | grep ran >/dev/null || fail "the single-precision program does not run on its own"
capture single "$RUN" "$WORK/needs_single"
expect_refusal single "single.precision"
# a script, whose libode.so.8 (found through LD_LIBRARY_PATH without us) is single precision
printf '#!/bin/sh\necho script ran\n' >"$WORK/script.sh"
chmod +x "$WORK/script.sh"
capture single_script env LD_LIBRARY_PATH="$WORK/single" "$RUN" "$WORK/script.sh"
expect_refusal single_script "single.precision"

# --- a private copy of Debian's libode.so.8: DT_RPATH wins over LD_LIBRARY_PATH, RUNPATH does not
mkdir -p "$WORK/private"
cp "$(debian_libode)" "$WORK/private/libode.so.8"
ln -s libode.so.8 "$WORK/private/libode.so"
g++ -O2 "$PROGRAMS/box_stack.cpp" -L"$WORK/private" -lode -Wl,--disable-new-dtags,-rpath,"$WORK/private" -o "$WORK/rpath_prog"
readelf -d "$WORK/rpath_prog" | grep '(RPATH)' >/dev/null || fail "could not build a DT_RPATH program"
capture rpath "$RUN" "$WORK/rpath_prog"
expect_refusal rpath "RPATH"
g++ -O2 "$PROGRAMS/box_stack.cpp" -L"$WORK/private" -lode -Wl,--enable-new-dtags,-rpath,"$WORK/private" -o "$WORK/runpath_prog"
readelf -d "$WORK/runpath_prog" | grep '(RUNPATH)' >/dev/null || fail "could not build a RUNPATH program"
capture runpath "$RUN" "$WORK/runpath_prog"
(( STATUS == 0 )) || { show runpath; fail "RUNPATH program under the launcher: status $STATUS"; }
grep -q '^ode-bpp: solver=bpp steps=[1-9]' "$WORK/runpath.err" || { show runpath; fail "RUNPATH program not stepped by bpp"; }
note "RUNPATH'd private copy: overridden, stepped by bpp"

# --- ODE linked statically (Debian's libode.a)
if [[ -e "$(dirname "$(debian_libode)")/libode.a" ]]; then
    g++ -O2 "$PROGRAMS/box_stack.cpp" -Wl,-Bstatic -lode -Wl,-Bdynamic -lccd -lpthread -o "$WORK/static_prog"
    capture static "$RUN" "$WORK/static_prog"
    expect_refusal static "statically"
else
    note "Debian's libode.a not installed: static case skipped"
fi

# --- setuid: the loader ignores LD_* for it
cp "$WORK/runpath_prog" "$WORK/setuid_prog"
chmod u+s "$WORK/setuid_prog"
capture setuid "$RUN" "$WORK/setuid_prog"
expect_refusal setuid "setuid"

# --- solver names
capture unknown "$RUN" --solver no-such-solver /bin/true
(( STATUS == 125 )) || { show unknown; fail "unknown solver: status $STATUS, expected 125"; }
for name in dantzig bpp bpp-sky bpp-down bpp-chol pgs; do
    grep -qw -- "$name" "$WORK/unknown.err" || { show unknown; fail "unknown solver: valid name $name not listed"; }
done
capture list "$RUN" --list
(( STATUS == 0 )) || { show list; fail "--list: status $STATUS"; }
for name in dantzig bpp bpp-sky bpp-down bpp-chol pgs; do
    grep -qw -- "$name" "$WORK/list.out" || { show list; fail "--list does not name $name"; }
done
note "--list: $(cat "$WORK/list.out")"
note PASS
