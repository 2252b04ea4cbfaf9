#!/usr/bin/env bash
# Every tool answers --help on stdout with status 0 and documents its exit statuses there, and an
# unknown name (scene, solver, method) is refused with the valid names listed:
#   ode-bpp-demo, ode-bpp-viewer, ode-bpp-solve, ode-bpp-run.
set -euo pipefail
source "$(dirname "$0")/../launcher/common.bash"
B=$ODE_BPP_BINARY_DIR
demo=$B/demos/ode-bpp-demo viewer=$B/demos/viewer/ode-bpp-viewer solve=$B/ode_bpp/ode-bpp-solve

# helps NAME TOOL: --help exits 0 with a usage that documents the exit statuses
helps() {
    local name=$1 tool=$2
    [[ -x "$tool" ]] || fail "no $tool"
    capture "$name" "$tool" --help
    (( STATUS == 0 )) || { show "$name"; fail "$name --help: status $STATUS"; }
    grep -qi '^usage: ' "$WORK/$name.out" || { show "$name"; fail "$name --help: no usage on stdout"; }
    grep -qiE '^ *exit status' "$WORK/$name.out" || { show "$name"; fail "$name --help: the exit statuses are not documented"; }
    note "$name --help: OK"
}

# refuses NAME STATUS PATTERN TOOL ARGS...: the status, and PATTERN (the valid names) on stderr
refuses() {
    local name=$1 want=$2 pattern=$3; shift 3
    capture "$name" "$@"
    (( STATUS == want )) || { show "$name"; fail "$name: status $STATUS, expected $want"; }
    grep -qE "$pattern" "$WORK/$name.err" || { show "$name"; fail "$name: the message does not list the valid names (/$pattern/)"; }
    note "$name: $(head -1 "$WORK/$name.err")"
}

helps demo "$demo"
helps viewer "$viewer"
helps solve "$solve"
helps run "$RUN"

valid_solvers='valid(: | names: )dantzig, .*bpp'
refuses demo_scene 2 "unknown scene 'nosuch'; valid: paper, crane, .*boxstack" "$demo" nosuch
refuses demo_solver 2 "unknown solver 'nosuch'; $valid_solvers" "$demo" crane --solver nosuch
refuses demo_compare 2 "unknown solver 'nosuch'; $valid_solvers" "$demo" crane --compare dantzig,nosuch
refuses viewer_scene 2 "unknown scene 'nosuch'; valid: crane, " "$viewer" nosuch
refuses viewer_solver 2 "unknown solver 'nosuch'; valid: dantzig, " "$viewer" crane --solver nosuch
refuses solve_method 2 "unknown method 'nosuch'; valid: .*bpp.*dantzig" "$solve" --methods bpp,nosuch "$WORK"
refuses run_solver 125 "unknown dWorldStep solver 'nosuch'; $valid_solvers" "$RUN" --solver nosuch /bin/true
note PASS
