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

export PKG_CONFIG_PATH=$stage/lib/pkgconfig
g++ -std=c++17 "$S/tests/link_example/hello_ode.cpp" -o "$B/test-install/hello_pc" $(pkg-config --cflags --libs ode_bpp)
out=$("$B/test-install/hello_pc" bpp-sky)
echo "pkg-config:    $out"
grep -q "solver=bpp-sky" <<<"$out" || { echo "FAIL: pkg-config build not solved by bpp-sky"; exit 1; }
echo PASS
