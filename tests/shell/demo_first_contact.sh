#!/usr/bin/env bash
# ode-bpp-demo as a newcomer meets it:
#   --capture into a path that cannot be created -> status 3 and a message (no abort);
#   --capture into a directory -> reports the files and bytes it wrote, as they are on disk;
#   a run shorter than the scene's criterion -> "not evaluated", status 0 (n/a in --compare);
#   --compare -> a speed-up column against the first solver, units, a legend and the scene's
#     Table 2 line;
#   ODE's "LCP internal error" messages -> followed once by a line that explains them, and
#     counted per run.
set -euo pipefail
source "$(dirname "$0")/../launcher/common.bash"
demo=$ODE_BPP_BINARY_DIR/demos/ode-bpp-demo
[[ -x "$demo" ]] || fail "no $demo"

# --- capture
touch "$WORK/a-file"
capture bad_capture "$demo" crane --seconds 0.1 --quiet --capture "$WORK/a-file/sub"
(( STATUS == 3 )) || { show bad_capture; fail "--capture under a file: status $STATUS, expected 3"; }
grep -q "^ode-bpp-demo: --capture $WORK/a-file/sub: cannot create the directory" "$WORK/bad_capture.err" \
    || { show bad_capture; fail "--capture under a file: no message naming the path and the reason"; }

capture good_capture "$demo" crane --seconds 0.25 --quiet --capture "$WORK/corpus" --capture-every 5
(( STATUS == 0 )) || { show good_capture; fail "--capture: status $STATUS"; }
files=$(find "$WORK/corpus" -name '*.mlcp' | wc -l)
bytes=$(find "$WORK/corpus" -name '*.mlcp' -printf '%s\n' | awk '{ s += $1 } END { print s + 0 }')
(( files > 0 )) || fail "--capture wrote no file"
grep -q "^capture: $files files, $bytes bytes (.* MB) in $WORK/corpus$" "$WORK/good_capture.out" \
    || { show good_capture; fail "--capture does not report what is on disk ($files files, $bytes bytes)"; }
note "capture: $(grep '^capture:' "$WORK/good_capture.out")"

# --capture-failures: only the islands whose solve did not end dMLCPSolved, with why in the file;
# a pivot budget of 1 makes boxstack's islands fail, the default budget does not
capture failures "$demo" boxstack --seconds 1 --quiet --cond-every 0 --max-pivots 1 --capture "$WORK/failures" --capture-failures
(( STATUS == 0 )) || { show failures; fail "--capture-failures: status $STATUS"; }
failed=$(find "$WORK/failures" -name '*.mlcp' | wc -l)
(( failed > 0 )) || { show failures; fail "--capture-failures with --max-pivots 1 wrote no file"; }
unmarked=$(grep -aL -E 'status=(failed|solved-by-fallback)' "$WORK"/failures/*.mlcp | wc -l)
(( unmarked == 0 )) || fail "--capture-failures: $unmarked of $failed files do not say how the solve ended"
capture no_failures "$demo" boxstack --seconds 1 --quiet --cond-every 0 --capture "$WORK/none" --capture-failures
(( STATUS == 0 )) || { show no_failures; fail "--capture-failures (default budget): status $STATUS"; }
(( $(find "$WORK/none" -name '*.mlcp' | wc -l) == 0 )) || fail "--capture-failures wrote islands that were solved"
capture failures_every "$demo" boxstack --seconds 0.1 --quiet --capture "$WORK/x" --capture-failures --capture-every 2
(( STATUS == 2 )) || { show failures_every; fail "--capture-failures with --capture-every: status $STATUS, expected 2"; }
note "capture-failures: $failed islands of boxstack at --max-pivots 1"

# --- a run shorter than the criterion
capture short "$demo" crane --seconds 1 --quiet --cond-every 0
(( STATUS == 0 )) || { show short; fail "crane --seconds 1: status $STATUS, expected 0 (criterion not evaluated)"; }
grep -q "success: not evaluated (the criterion is judged after the scene's 20 s; this run: 1.00 s)" "$WORK/short.out" \
    || { show short; fail "crane --seconds 1: does not say that the criterion was not evaluated"; }

# --- the comparison table
capture compare "$demo" crane --compare dantzig,bpp --seconds 0.5 --quiet --cond-every 0
(( STATUS == 0 )) || { show compare; fail "--compare: status $STATUS"; }
out=$WORK/compare.out
grep -qE '^scene +solver +solve ms/step +speed-up ' "$out" || { show compare; fail "--compare: no speed-up column or units"; }
grep -qE '^crane +dantzig +[0-9.]+ +[0-9.]+ +1\.00x ' "$out" || { show compare; fail "--compare: the baseline is not 1.00x"; }
grep -qE '^crane +bpp +[0-9.]+ +[0-9.]+ +[0-9.]+x .* n/a ' "$out" || { show compare; fail "--compare: bpp's row lacks its speed-up or n/a"; }
grep -qE '^  Table 2 \(crane\): measured mass ratio [0-9]+:1, rows [0-9]+, .* \| paper ' "$out" \
    || { show compare; fail "--compare: no Table 2 line for the scene"; }
for legend in 'lower is better' "speed-up: dantzig's median / this solver's" 'fallbacks: ' 'Frozen' "Dantzig's semantics"; do
    grep -qF "$legend" "$out" || { show compare; fail "--compare: the legend does not say '$legend'"; }
done
note "compare: $(grep -c . "$out") lines"

# --- ODE's Dantzig's "LCP internal error": the first run of these that prints it is checked
explained=0
for run in "forklift 2" "winch 20"; do
    read -r scene seconds <<<"$run"
    capture lcp "$demo" "$scene" --solver dantzig --seconds "$seconds" --quiet --cond-every 0
    messages=$(grep -c '^ODE Message 3: LCP internal error' "$WORK/lcp.err" || true)
    (( messages > 0 )) || continue
    awk '/^ODE Message 3: LCP internal error/ { m = 1; next } m && /^ode-bpp-demo: this comes from ODE.s Dantzig/ { ok = 1 } { m = 0 }
         END { exit !ok }' <(grep -v '^$' "$WORK/lcp.err") || { show lcp; fail "$scene: ODE's message is not followed by the explanation"; }
    [[ $(grep -c '^ode-bpp-demo: this comes from' "$WORK/lcp.err") -eq 1 ]] || { show lcp; fail "$scene: the explanation is repeated"; }
    grep -q "ODE's Dantzig printed 'LCP internal error' $messages times" "$WORK/lcp.out" \
        || { show lcp; fail "$scene: the run does not count its $messages messages"; }
    explained=1
    note "LCP messages: $scene, $messages explained and counted"
    break
done
(( explained )) || fail "no run printed ODE's 'LCP internal error' (forklift 2 s, winch 20 s with dantzig did): find another"
note PASS
