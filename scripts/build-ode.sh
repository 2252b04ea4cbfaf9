#!/usr/bin/env bash
# Builds ODE 0.16.2 from Debian's source package with patches/*.patch applied, in double precision
# against the system libccd, and installs it inside the build tree (never into /usr).
# Usage: build-ode.sh BUILD_DIR PATCH_DIR
#   BUILD_DIR/ode-src      pristine Debian source (fetched once)
#   BUILD_DIR/ode-work     patched copy that is configured and compiled
#   BUILD_DIR/ode-install  the install prefix ode-bpp links against
# A second run with unchanged patches does nothing.
set -euo pipefail
BUILD=$(realpath -m "${1:?usage: build-ode.sh BUILD_DIR PATCH_DIR}")
PATCHES=$(realpath "${2:?usage: build-ode.sh BUILD_DIR PATCH_DIR}")
HERE=$(dirname "$(realpath "$0")")
SRC=$BUILD/ode-src WORK=$BUILD/ode-work PREFIX=$BUILD/ode-install

"$HERE/fetch-ode.sh" "$SRC"

shopt -s nullglob
patches=("$PATCHES"/*.patch)
stamp=$( { echo "ode-bpp-odebuild-v3"; cat "$SRC/.fetched"; for p in "${patches[@]}"; do sha256sum "$p" | cut -d' ' -f1; done; } | sha256sum | cut -d' ' -f1)
if [ -f "$PREFIX/.stamp" ] && [ "$(cat "$PREFIX/.stamp")" = "$stamp" ]; then
  echo "[ode] up to date in $PREFIX"; exit 0
fi

version=$(cut -d' ' -f3 "$SRC/.fetched")
echo "[ode] preparing patched copy of ODE $version"
rm -rf "$WORK"
cp -a "$SRC" "$WORK"
for p in "${patches[@]}"; do
  if ! patch -d "$WORK" -p1 --dry-run --quiet < "$p" >/dev/null 2>&1; then
    echo "[ode] error: patch $(basename "$p") does not apply to ODE $version (from $(cut -d' ' -f1 "$SRC/.fetched"))" >&2
    patch -d "$WORK" -p1 --dry-run < "$p" >&2 || true
    exit 1
  fi
  patch -d "$WORK" -p1 --quiet < "$p"
  echo "[ode] applied $(basename "$p")"
done

log=$BUILD/ode-build.log
echo "[ode] configuring (double precision, system libccd, drawstuff X11); log: $log"
cd "$WORK"
# Debian's own compiler and linker flags (debian/rules: hardening=+all), so that the library
# matches libode8 symbol for symbol apart from our additions.
flags() { DEB_BUILD_MAINT_OPTIONS=hardening=+all dpkg-buildflags --get "$1" | sed 's/-ffile-prefix-map=[^ ]*//'; }
# -DdIDEDOUBLE: the tarball's include/ode/precision.h defaults to single precision and is found
# before the generated one, which would give a single-precision library behind a double header.
if ! ./configure --prefix="$PREFIX" --enable-double-precision --with-libccd=system --enable-libccd \
      --enable-shared --disable-static --with-drawstuff=X11 \
      CPPFLAGS="$(flags CPPFLAGS) -DdIDEDOUBLE" CFLAGS="$(flags CFLAGS)" CXXFLAGS="$(flags CXXFLAGS)" \
      LDFLAGS="$(flags LDFLAGS)" >"$log" 2>&1; then
  tail -n 30 "$log" >&2; echo "[ode] error: configure failed (see $log)" >&2; exit 1
fi
echo "[ode] compiling with $(nproc) jobs (a few minutes on 2 cores: the library and its demos)"
if ! "$HERE/run-with-progress.sh" ode "$log" 20 make -j"$(nproc)"; then
  grep -m 20 -E "error|Error" "$log" >&2 || tail -n 30 "$log" >&2
  echo "[ode] error: build failed (see $log)" >&2; exit 1
fi
# install into a staging copy and swap it in at the end, so that a rebuild never leaves
# programs that use the previous install without a library
stage=$BUILD/ode-stage
rm -rf "$stage"
make install DESTDIR="$stage" >>"$log" 2>&1 || { tail -n 20 "$log" >&2; echo "[ode] error: install failed" >&2; exit 1; }
new=$stage$PREFIX
# drawstuff is not installed by ODE's Makefiles; keep it beside the library for the viewer
mkdir -p "$new/include/drawstuff" "$new/share/drawstuff"
cp include/drawstuff/*.h "$new/include/drawstuff/"
cp drawstuff/src/.libs/libdrawstuff.a "$new/lib/"
cp drawstuff/textures/*.ppm "$new/share/drawstuff/"
grep -q '^#define dDOUBLE' "$new/include/ode/precision.h" || { echo "[ode] error: installed precision.h is not double" >&2; exit 1; }
echo "$stamp" > "$new/.stamp"
rm -rf "$PREFIX.old"
[ -d "$PREFIX" ] && mv "$PREFIX" "$PREFIX.old"
mv "$new" "$PREFIX"
rm -rf "$PREFIX.old" "$stage"
echo "[ode] installed ODE $version (double) in $PREFIX"
