#!/usr/bin/env bash
# The installed header and the library agree on double precision (scripts/build-ode.sh: the precision trap).
set -euo pipefail
grep -q '^#define dDOUBLE' "${ODE_ROOT:?}/include/ode/precision.h" || { echo "FAIL: precision.h is not double"; exit 1; }
text=$(strings "$ODE_ROOT/lib/libode.so.8")
grep -q 'ODE_double_precision' <<<"$text" || { echo "FAIL: library not configured for double"; exit 1; }
grep -q 'ODE_single_precision' <<<"$text" && { echo "FAIL: library reports single precision"; exit 1; }
echo PASS
