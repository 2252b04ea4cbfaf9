#!/usr/bin/env bash
# Runs a long build command with its output appended to a log, and prints a progress line every
# INTERVAL seconds: the time so far and how many compile commands the log shows.
# Usage: run-with-progress.sh LABEL LOG INTERVAL CMD [ARGS...]
# Exit status: CMD's. The progress lines go to stdout, prefixed with [LABEL].
set -uo pipefail
label=${1:?usage: run-with-progress.sh LABEL LOG INTERVAL CMD...}
log=${2:?usage: run-with-progress.sh LABEL LOG INTERVAL CMD...}
interval=${3:?usage: run-with-progress.sh LABEL LOG INTERVAL CMD...}
shift 3
(( $# )) || { echo "usage: run-with-progress.sh LABEL LOG INTERVAL CMD..." >&2; exit 2; }

# compile commands as make echoes them, libtool's ("libtool: compile:  g++ ... -c") included
compiled() { grep -cE "(^|libtool: compile: +)(gcc|g\+\+|cc|c\+\+|clang|clang\+\+) .* -c " "$log" 2>/dev/null || true; }

"$@" >>"$log" 2>&1 &
pid=$!
trap 'kill "$pid" 2>/dev/null' INT TERM
start=$SECONDS
next=$interval
while kill -0 "$pid" 2>/dev/null; do
    sleep 1
    if (( SECONDS - start >= next )) && kill -0 "$pid" 2>/dev/null; then
        elapsed=$(( SECONDS - start ))
        printf '[%s] %d min %02d s: %d files compiled so far\n' "$label" $(( elapsed / 60 )) $(( elapsed % 60 )) "$(compiled)"
        next=$(( next + interval ))
    fi
done
wait "$pid"
