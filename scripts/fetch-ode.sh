#!/usr/bin/env bash
# Fetches ODE 0.16.2 from Debian's `ode` source package into $1 (a directory in the build tree),
# adding a deb-src entry if the machine has none. Skips the download when the source is already there.
set -euo pipefail
DEST=${1:?usage: fetch-ode.sh DEST}
WANT_VERSION=0.16.2
mkdir -p "$DEST"
if [ -f "$DEST/.fetched" ]; then
  echo "[ode] source already fetched: $(cat "$DEST/.fetched")"; exit 0
fi

have_deb_src() { grep -rqsE '^(Types:.*deb-src|deb-src )' /etc/apt/sources.list /etc/apt/sources.list.d/; }
if ! have_deb_src; then
  [ "$(id -u)" -eq 0 ] || { echo "[ode] error: no deb-src entry and not root to add one" >&2; exit 1; }
  uri=$(awk '/^URIs:/ {print $2; exit}' /etc/apt/sources.list.d/debian.sources 2>/dev/null || true)
  [ -n "$uri" ] || uri=$(awk '/^deb / {print $2; exit}' /etc/apt/sources.list 2>/dev/null || true)
  [ -n "$uri" ] || uri=http://deb.debian.org/debian
  echo "[ode] adding deb-src entry for $uri"
  cat > /etc/apt/sources.list.d/ode-bpp-src.sources <<SRC
Types: deb-src
URIs: $uri
Suites: bookworm
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
SRC
  apt-get update -qq
fi

work=$(mktemp -d "$(dirname "$DEST")/ode-fetch.XXXXXX")
trap 'rm -rf "$work"' EXIT
echo "[ode] apt-get source ode"
if ! (cd "$work" && apt-get source -qq ode >"$work/log" 2>&1); then
  if ! grep -qs ode "$(ls /var/lib/apt/lists/*Sources 2>/dev/null | head -1)"; then apt-get update -qq; fi
  (cd "$work" && apt-get source -qq ode >"$work/log" 2>&1) || {
    cat "$work/log" >&2; echo "[ode] error: could not fetch Debian source package 'ode'" >&2; exit 1; }
fi
srcdir=$(find "$work" -mindepth 1 -maxdepth 1 -type d -name 'ode-*' | head -1)
[ -n "$srcdir" ] || { echo "[ode] error: apt-get source produced no ode-* directory" >&2; exit 1; }
ver=$(sed -n 's/^AC_INIT(\[ODE\],\[\([^]]*\)\].*/\1/p' "$srcdir/configure.ac" | head -1)
if [ "$ver" != "$WANT_VERSION" ]; then
  echo "[ode] error: Debian's ode source is version '$ver'; ode-bpp's patches are for $WANT_VERSION" >&2; exit 1
fi
rm -rf "$DEST"; mv "$srcdir" "$DEST"
dsc=$(ls "$work"/*.dsc | head -1); echo "$(basename "$dsc") ODE $ver" > "$DEST/.fetched"
echo "[ode] fetched $(cat "$DEST/.fetched")"
