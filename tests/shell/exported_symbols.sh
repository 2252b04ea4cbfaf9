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

# the exported functions of ours, one line per overload (with its arguments), without ABI tags
signatures=$(nm -DC --defined-only "$lib" | awk '$2 ~ /^[TW]$/' | cut -d' ' -f3- |
             grep -E '^(ode_bpp::|ode_bpp_)' | sed -E 's/\[abi:[a-z0-9]+\]//g' | sort -u)
# their qualified names, without arguments
exported=$(sed -E 's/\(.*$//' <<< "$signatures" | sort -u)
# the public headers' code: comments out, so that a name in a comment declares nothing
declared=$(cat "$src"/include/ode_bpp/*.h | sed -E 's|//.*$||')
count=$(printf '%s\n' "$exported" | grep -c . || true)
if (( count < 20 )); then
  echo "only $count exported functions: the public API (solve, validate, read_mlcp, ...) is missing" >&2
  exit 1
fi
status=0
while IFS= read -r name; do
  leaf=${name##*::}
  if [[ $name == ode_bpp::summary::* ]]; then
    grep -qwF -- "$leaf" "$src/src/ode/summary.h" || { echo "exported but not in summary.h: $name" >&2; status=1; }
    continue
  fi
  if [[ $name == ode_bpp::*::* ]]; then
    # a member function: its class must be an exported class of a public header
    scope=${name#ode_bpp::}; scope=${scope%%::*}
    if ! grep -qE "(class|struct) ODE_BPP_API $scope\b" "$src"/include/ode_bpp/*.h; then
      echo "internal symbol exported: $name" >&2; status=1
    fi
    continue
  fi
  # every exported overload has its own ODE_BPP_API declaration: an internal overload of a
  # public name (say residual_vectors on linalg::SymmetricRows) would outnumber them
  overloads=$(grep -cE "^${name}\(" <<< "$signatures" || true)
  declarations=$(grep -E 'ODE_BPP_API' <<< "$declared" | { grep -oE "\b${leaf}[[:space:]]*\(" || true; } | wc -l)
  if (( declarations == 0 )); then
    echo "exported but declared in no public header: $name" >&2; status=1
  elif (( overloads > declarations )); then
    echo "$name: $overloads overloads exported, $declarations declared ODE_BPP_API in the public headers:" >&2
    grep -E "^${name}\(" <<< "$signatures" >&2; status=1
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
