#!/usr/bin/env bash
# ode_bpp_core needs no ODE: the archive has no undefined ODE symbol (ODE's API is d + capital,
# its internals dx...), and the core's standalone test executable needs no libode.
set -euo pipefail
: "${ODE_BPP_BINARY_DIR:?set by ctest}"
archive=$ODE_BPP_BINARY_DIR/ode_bpp/libode_bpp_core.a
exe=$ODE_BPP_BINARY_DIR/tests/core_test_standalone
for f in "$archive" "$exe"; do [ -e "$f" ] || { echo "missing $f" >&2; exit 1; }; done
ode_symbols=$(nm -u "$archive" | awk '{print $NF}' | grep -E '^(d[A-Z]|_?Z.*dx)' | sort -u || true)
if [ -n "$ode_symbols" ]; then
  echo "ode_bpp_core refers to ODE symbols:" >&2
  echo "$ode_symbols" >&2
  exit 1
fi
if readelf -d "$exe" | grep -E 'NEEDED.*(libode|libode_bpp)' >&2; then
  echo "core_test_standalone needs a library of ODE's or the ODE glue" >&2
  exit 1
fi
# the check itself can fail: the glue does refer to ODE
if ! nm -u "$ODE_BPP_BINARY_DIR/ode_bpp/libode_bpp.so" --dynamic | grep -q ' dSolveMLCPDantzig'; then
  echo "self-check failed: libode_bpp.so should need ODE's dSolveMLCPDantzig" >&2
  exit 1
fi
echo "ode_bpp_core: no ODE symbol; core_test_standalone: no libode"
