#!/usr/bin/env bash
# libode_bpp.so is built with hidden visibility: what it exports in namespace ode_bpp is exactly
# what include/ode_bpp/*.h declares (marked ODE_BPP_API) and the launcher's interface
# (src/ode/summary.h); the pivoting, linear algebra, ordering and io internals stay inside.
set -euo pipefail
: "${ODE_BPP_BINARY_DIR:?set by ctest}"
here=$(cd "$(dirname "$0")" && pwd)
src=$here/../../ode_bpp
lib=$ODE_BPP_BINARY_DIR/ode_bpp/libode_bpp.so
[ -e "$lib" ] || { echo "missing $lib" >&2; exit 1; }

# qualified names of the exported functions of ours, without arguments and ABI tags
exported=$(nm -DC --defined-only "$lib" | awk '$2 ~ /^[TW]$/' | cut -d' ' -f3- |
           grep -E '^(ode_bpp::|ode_bpp_)' | sed -E 's/\[abi:[a-z0-9]+\]//g; s/\(.*$//' | sort -u)
count=$(printf '%s\n' "$exported" | grep -c . || true)
if (( count < 20 )); then
  echo "only $count exported functions: the public API (solve, validate, read_mlcp, ...) is missing" >&2
  exit 1
fi
status=0
while IFS= read -r name; do
  leaf=${name##*::}
  headers=$src/include/ode_bpp/*.h
  [[ $name == ode_bpp::summary::* ]] && headers=$src/src/ode/summary.h
  if [[ $name == ode_bpp::*::* && $name != ode_bpp::summary::* && $name != ode_bpp::Metadata::* &&
        $name != ode_bpp::MlcpFile::* ]]; then
    echo "internal symbol exported: $name" >&2; status=1; continue
  fi
  # shellcheck disable=SC2086
  if ! grep -qwF -- "$leaf" $headers; then
    echo "exported but declared in no public header: $name" >&2; status=1
  fi
done <<< "$exported"
# the check itself can fail: the library does hold internals, just not exported ones
internal=$(nm -C "$lib" | grep -c 'ode_bpp::pivoting::' || true)
if (( internal == 0 )); then
  echo "self-check failed: libode_bpp.so should contain (hidden) ode_bpp::pivoting:: code" >&2
  exit 1
fi
(( status == 0 )) && echo "libode_bpp.so exports $count functions, all public"
exit $status
