#!/usr/bin/env bash
# ode-bpp installs as a package: an existing ODE program links with find_package(ode_bpp) +
# target_link_libraries(app ode_bpp::ode_bpp), or with pkg-config, and steps with bpp.
set -euo pipefail
B=${ODE_BPP_BINARY_DIR:?} S=${ODE_BPP_SOURCE_DIR:?}
stage=$B/test-install/prefix app=$B/test-install/app
rm -rf "$B/test-install"
cmake --install "$B" --prefix "$stage" >/dev/null
cmake -S "$S/tests/link_example" -B "$app" -DCMAKE_PREFIX_PATH="$stage" >/dev/null
cmake --build "$app" >/dev/null
out=$("$app/hello_ode" bpp)
echo "cmake package: $out"
grep -q "solver=bpp" <<<"$out" || { echo "FAIL: not solved by bpp"; exit 1; }
# the app runs against the staged libode, not Debian's
# a here-string, not a pipe: grep -q closing early would SIGPIPE ldd and fail under pipefail
grep -qF "$stage/lib/libode.so.8" <<<"$(ldd "$app/hello_ode")" || { echo "FAIL: wrong libode"; ldd "$app/hello_ode"; exit 1; }

# a program that calls no ode-bpp function, linked the same way with --as-needed (which drops
# libode_bpp from it): ODE_LCP_SOLVER still reaches bpp, the plug-in beside the patched libode
cmake -S "$S/tests/link_example" -B "$app-as-needed" -DCMAKE_PREFIX_PATH="$stage" \
      -DCMAKE_EXE_LINKER_FLAGS=-Wl,--as-needed >/dev/null
cmake --build "$app-as-needed" --target plain_ode >/dev/null
out=$(ODE_LCP_SOLVER=bpp "$app-as-needed/plain_ode" 2>&1)
echo "no ode-bpp call, --as-needed: $out"
grep -q "solver=bpp islands=[1-9]" <<<"$out" || { echo "FAIL: ODE_LCP_SOLVER=bpp did not reach bpp"; exit 1; }
# and with a plug-in that cannot be loaded, the warning names the file and the reason
out=$(ODE_LCP_SOLVER=bpp ODE_LCP_PLUGIN=/nonexistent/libode_bpp.so "$app-as-needed/plain_ode" 2>&1 || true)
grep -q "ODE_LCP_PLUGIN='/nonexistent/libode_bpp.so' could not be loaded: .*No such file" <<<"$out" \
    || { echo "FAIL: no reason given for a plug-in that cannot be loaded: $out"; exit 1; }

export PKG_CONFIG_PATH=$stage/lib/pkgconfig
g++ -std=c++17 "$S/tests/link_example/hello_ode.cpp" -o "$B/test-install/hello_pc" $(pkg-config --cflags --libs ode_bpp)
out=$("$B/test-install/hello_pc" bpp-sky)
echo "pkg-config:    $out"
grep -q "solver=bpp-sky" <<<"$out" || { echo "FAIL: pkg-config build not solved by bpp-sky"; exit 1; }
# pkg-config keeps libode_bpp linked even under --as-needed (the plug-in is then loaded at start)
g++ -std=c++17 -Wl,--as-needed "$S/tests/link_example/plain_ode.cpp" -o "$B/test-install/plain_pc" \
    $(pkg-config --cflags --libs ode_bpp)
grep -qF "libode_bpp.so" <<<"$(readelf -d "$B/test-install/plain_pc")" \
    || { echo "FAIL: pkg-config's flags let --as-needed drop libode_bpp"; exit 1; }
echo PASS
