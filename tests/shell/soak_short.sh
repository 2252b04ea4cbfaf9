#!/usr/bin/env bash
# A short soak (make soak runs 100,000 steps per scene): the winch, whose chain's contacts on the
# drum change every step, and the forklift, stepped with bpp past the point where their largest
# islands and the hook's bounded caches have been met (step 4,000), then 2,000 steps more: every
# body stays finite, no island goes to ODE's Dantzig, and memory shows no steady growth: the live
# heap's floor gains at most 1 % beyond its two largest rises (a leak of 32 bytes a step reads
# +1.7 to +2.5 % here and fails), RSS at most 5 % (docs/soak.md).
# Also: the tool refuses bad arguments with status 2.
set -euo pipefail
soak=${ODE_BPP_BINARY_DIR:?}/demos/ode-bpp-soak
[ -x "$soak" ] || { echo "FAIL: no $soak (configure with ODE_BPP_BUILD_DEMOS=ON)"; exit 1; }

out=$("$soak" winch forklift --steps 6000 --baseline 4000 --every 100 2>/dev/null) || { echo "FAIL: $out"; exit 1; }
echo "$out"
[ "$(grep -c ': PASS: ' <<<"$out")" -eq 2 ] || { echo "FAIL: expected two PASS verdicts"; exit 1; }

for args in "" "no-such-scene" "winch --steps 0" "winch --steps 1000 --baseline 1000" "winch --solver nope"; do
  status=0
  # shellcheck disable=SC2086  # the arguments are words
  "$soak" $args > /dev/null 2>&1 || status=$?
  [ "$status" -eq 2 ] || { echo "FAIL: 'ode-bpp-soak $args' exited $status, not 2"; exit 1; }
done
echo "PASS: bad arguments refused"
