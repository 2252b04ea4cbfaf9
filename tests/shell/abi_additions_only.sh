#!/usr/bin/env bash
# The patched libode stays ABI-compatible with Debian's libode8: same soname, and abidiff
# (Debian's abigail-tools) reports additions only for everything ODE's headers declare.
# ELF-only symbols (no debug info: inlined C++ template destructors) differ between Debian's
# build and any rebuild with today's toolchain, with or without our patches; for those we
# check that no C symbol (the public API) is missing.
set -euo pipefail
ours=${ODE_ROOT:?}/lib/libode.so.8
debian=$(ls /usr/lib/*/libode.so.8 2>/dev/null | head -1)
[ -n "$debian" ] || { echo "FAIL: Debian's libode8 is not installed (scripts/install-deps.sh installs it)"; exit 1; }

soname() { readelf -d "$1" | sed -n 's/.*(SONAME).*\[\(.*\)\]/\1/p'; }
[ "$(soname "$ours")" = "$(soname "$debian")" ] || { echo "FAIL: soname $(soname "$ours") != $(soname "$debian")"; exit 1; }

report=$(abidiff "$debian" "$ours" || true)
head -4 <<<"$report"
grep -q "^Functions changes summary: 0 Removed, 0 Changed" <<<"$report" || { echo "FAIL: functions removed or changed"; echo "$report"; exit 1; }
grep -q "^Variables changes summary: 0 Removed, 0 Changed" <<<"$report" || { echo "FAIL: variables removed or changed"; echo "$report"; exit 1; }

# every exported C (unmangled) symbol of Debian's library is still exported
c_symbols() { nm -D --defined-only "$1" | awk '{print $3}' | grep -v '^_Z' | sort -u; }
missing=$(comm -23 <(c_symbols "$debian") <(c_symbols "$ours"))
[ -z "$missing" ] || { echo "FAIL: C symbols missing: $missing"; exit 1; }
# and the new public API is there
exported=$(c_symbols "$ours")
for s in dRegisterMLCPSolver dWorldSetMLCPSolver dWorldGetMLCPStats dWorldSetMLCPObserver dSolveMLCPDantzig; do
  grep -qx "$s" <<<"$exported" || { echo "FAIL: $s not exported"; exit 1; }
done
echo "PASS: additions only ($(c_symbols "$ours" | wc -l) C symbols, $(comm -13 <(c_symbols "$debian") <(c_symbols "$ours") | wc -l) added)"
