#!/usr/bin/env bash
# Installs the Debian packages ode-bpp needs, skipping those already present.
# Usage: install-deps.sh [extra-package ...]
# Stops with a message naming the package when one cannot be had.
set -euo pipefail

PACKAGES=(
  build-essential cmake pkg-config dpkg-dev patch quilt
  autoconf automake libtool
  libeigen3-dev libccd-dev
  googletest libgtest-dev libbenchmark-dev
  clang libclang-rt-14-dev
  abigail-tools libode8 libode-dev python3
  libx11-dev libgl-dev libglu1-mesa-dev libpng-dev xvfb xauth x11-apps imagemagick
  gnuplot-nox valgrind
)
PACKAGES+=("$@")

missing=()
for p in "${PACKAGES[@]}"; do
  if ! grep -q "install ok installed" <<<"$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null)"; then
    missing+=("$p")
  fi
done
[ ${#missing[@]} -eq 0 ] && { echo "[deps] all ${#PACKAGES[@]} Debian packages present"; exit 0; }

if [ "$(id -u)" -ne 0 ]; then
  echo "[deps] error: missing packages (${missing[*]}) and not root; install them with apt-get" >&2
  exit 1
fi
echo "[deps] installing: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
stamp=/var/lib/apt/periodic/ode-bpp-update-stamp
if [ ! -f "$stamp" ] || [ -n "$(find "$stamp" -mmin +360 2>/dev/null)" ]; then
  apt-get update -qq || { echo "[deps] error: apt-get update failed" >&2; exit 1; }
  mkdir -p "$(dirname "$stamp")" && touch "$stamp"
fi
for p in "${missing[@]}"; do
  if ! apt-cache show "$p" >/dev/null 2>&1; then
    echo "[deps] error: Debian package '$p' cannot be found in the configured apt sources" >&2
    exit 1
  fi
done
if ! apt-get install -y -qq --no-install-recommends "${missing[@]}" >/tmp/ode-bpp-apt.log 2>&1; then
  tail -n 20 /tmp/ode-bpp-apt.log >&2
  echo "[deps] error: apt-get could not install: ${missing[*]} (log: /tmp/ode-bpp-apt.log)" >&2
  exit 1
fi
echo "[deps] installed ${#missing[@]} package(s)"
