#!/usr/bin/env bash
# In a setgid (or setuid) program the environment must not steer what the patched libode loads or
# what ode-bpp writes: ODE_LCP_PLUGIN (a library to dlopen), ODE_LCP_SOLVER and ODE_BPP_SUMMARY_FILE
# (a file to append to) are read with secure_getenv, which returns nothing in secure execution.
# The same binary without the setgid bit is the control: there the variables act, so the test can
# fail. Needs root (to give the binary another group); CI runs as root.
set -euo pipefail
: "${ODE_ROOT:?}" "${ODE_BPP_SOURCE_DIR:?}" "${ODE_BPP_BINARY_DIR:?}"
fail() { echo "setgid_environment: FAIL: $*" >&2; exit 1; }
[[ $(id -u) -eq 0 ]] || fail "must run as root to make a setgid binary of another group"
group=$(getent group nogroup | cut -d: -f1) || fail "no group 'nogroup' to make the binary setgid to"

work=$(mktemp -d /tmp/ode-bpp-setgid.XXXXXX)
trap 'rm -rf "$work"' EXIT
chmod 755 "$work"
src=$ODE_BPP_SOURCE_DIR/tests/setgid
bpp_dir=$(dirname "$(find "$ODE_BPP_BINARY_DIR/ode_bpp" -maxdepth 1 -name 'libode_bpp.so' | head -1)")
[[ -e "$bpp_dir/libode_bpp.so" ]] || fail "no libode_bpp.so under $ODE_BPP_BINARY_DIR/ode_bpp"

cc -shared -fPIC -DMARK_PATH="\"$work/plugin-loaded\"" -o "$work/marker_plugin.so" "$src/marker_plugin.c"
# the patched libode and libode_bpp by absolute RUNPATH: the loader honours it in secure execution
cc -DdIDEDOUBLE -I"$ODE_ROOT/include" -o "$work/probe" "$src/probe.c" \
   -L"$ODE_ROOT/lib" -L"$bpp_dir" -Wl,--no-as-needed -lode -lode_bpp -Wl,-rpath,"$ODE_ROOT/lib:$bpp_dir"

run() {  # run NAME: the probe with every variable set; output in $work/NAME.{out,err}
    rm -f "$work/plugin-loaded" "$work/summary"
    env ODE_LCP_PLUGIN="$work/marker_plugin.so" ODE_LCP_SOLVER=bpp \
        ODE_BPP_SUMMARY=1 ODE_BPP_SUMMARY_FILE="$work/summary" \
        "$work/probe" >"$work/$1.out" 2>"$work/$1.err" || fail "$1 run: exit $?: $(cat "$work/$1.err")"
}

# control: an ordinary process obeys the variables
run plain
grep -qx "secure=0" "$work/plain.out" || fail "the plain run is in secure execution"
grep -qx "solver=bpp" "$work/plain.out" || fail "plain run: ODE_LCP_SOLVER=bpp not followed: $(cat "$work/plain.out")"
[[ -e "$work/plugin-loaded" ]] || fail "plain run: ODE_LCP_PLUGIN was not loaded for an unknown solver name"
[[ -s "$work/summary" ]] || fail "plain run: no summary appended to ODE_BPP_SUMMARY_FILE"

# setgid: the same binary must ignore all of them
chgrp "$group" "$work/probe"
chmod g+s "$work/probe"
run setgid
grep -qx "secure=1" "$work/setgid.out" \
    || fail "the setgid run is not in secure execution (a nosuid file system?): nothing was tested"
[[ ! -e "$work/plugin-loaded" ]] || fail "setgid run: ODE_LCP_PLUGIN named a library and it was loaded"
grep -qx "solver=dantzig" "$work/setgid.out" || fail "setgid run: ODE_LCP_SOLVER was followed: $(cat "$work/setgid.out")"
[[ ! -e "$work/summary" ]] || fail "setgid run: ode-bpp appended to the file named by ODE_BPP_SUMMARY_FILE"
echo "setgid_environment: PASS (plain run obeys ODE_LCP_PLUGIN, ODE_LCP_SOLVER, ODE_BPP_SUMMARY_FILE; setgid run ignores them)"
