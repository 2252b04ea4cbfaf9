#!/usr/bin/env bash
# The installed ode-bpp-run finds libode_bpp.so and the patched libode.so.8 relative to itself
# (PREFIX/bin -> PREFIX/<libdir>), also when started through a symlink, and never the build tree:
# a prefix made by `cmake --install` (the launcher in bin/; the patched libode, libode_bpp.so,
# the preload libode_bpp_run.so and the helper ode-bpp/ode-bpp-run-solvers in the relative lib
# dir baked into it) runs a Debian-built program on bpp.
set -euo pipefail
source "$(dirname "$0")/../launcher/common.bash"

prefix=$WORK/prefix
cmake --install "$ODE_BPP_BINARY_DIR" --prefix "$prefix" >/dev/null || fail "cmake --install into $prefix failed"
rel=$(sed -n 's/^readonly LIB_DIRS_SPEC="\(.*\)"$/\1/p' "$prefix/bin/ode-bpp-run")
[[ -n "$rel" && "$rel" != /* ]] || fail "the installed launcher does not look in a relative lib dir (got '$rel')"
for f in libode.so.8 libode_bpp.so libode_bpp_run.so ode-bpp/ode-bpp-run-solvers; do
    [[ -e "$prefix/bin/$rel/$f" ]] || fail "not installed beside the libraries: $f"
done
ln -s "$prefix/bin/ode-bpp-run" "$WORK/launcher-link"

g++ -O2 "$PROGRAMS/box_stack.cpp" -lode -o "$WORK/box_stack" || fail "cannot build box_stack.cpp against Debian's libode-dev"

for launcher in "$prefix/bin/ode-bpp-run" "$WORK/launcher-link"; do
    capture installed "$launcher" "$WORK/box_stack"
    (( STATUS == 0 )) || { show installed; fail "$launcher: status $STATUS"; }
    grep -q '^ode-bpp: solver=bpp steps=[1-9]' "$WORK/installed.err" || { show installed; fail "$launcher: not stepped by bpp"; }
    # the program loaded the prefix's libraries, not the build tree's
    capture maps "$launcher" bash -c 'cat /proc/$$/maps'
    grep -q "$(readlink -f "$prefix/bin/$rel")/libode_bpp.so" "$WORK/maps.out" \
        || { show maps; fail "$launcher: libode_bpp.so not loaded from the prefix"; }
    ! grep -q "$ODE_BPP_BINARY_DIR/ode_bpp/libode_bpp" "$WORK/maps.out" \
        || fail "$launcher: loaded the build tree's libode_bpp.so"
    note "$launcher: OK ($(grep '^ode-bpp:' "$WORK/installed.err"))"
done
note PASS
