#!/usr/bin/env bash
# Runs each libFuzzer target for a bounded time and keeps what it finds.
#
# Usage: tests/fuzz/run-fuzz.sh BUILD_DIR SECONDS [LIBFUZZER_FLAG...]
#   BUILD_DIR  a build configured with -DODE_BPP_FUZZ=ON and clang (see tests/fuzz/CMakeLists.txt),
#              with the targets fuzz_read_mlcp and fuzz_solve built
#   SECONDS    fuzzing time per target
#   flags      passed on to libFuzzer, e.g. -fork=1 -ignore_crashes=1 to go on after a crash
#              (every crash is then saved, duplicates included)
#
# The seed corpus is every sample in tests/data and tests/data/captured plus the recorded regressions; the working
# corpus lives in BUILD_DIR/fuzz-work and grows across runs. Every crash, leak, timeout or
# out-of-memory input is copied to tests/data/fuzz-regressions/<target>-<kind>-<hash>, where
# the unit test test_io_regressions and the fuzz replay tests run it from then on.
# Exit status: 0 when nothing was found, 1 when something was, 2 on bad usage.
set -euo pipefail

if [ $# -lt 2 ] || ! [[ $2 =~ ^[0-9]+$ ]] || [ "$2" -lt 1 ] || [ ! -d "$1" ]; then
  echo "usage: $0 BUILD_DIR SECONDS [LIBFUZZER_FLAG...]" >&2
  exit 2
fi
build=$(cd "$1" && pwd)
seconds=$2
shift 2
extra_flags=("$@")
source_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
data=$source_dir/tests/data
regressions=$data/fuzz-regressions
work=$build/fuzz-work
mkdir -p "$regressions"

found=0
for target in fuzz_read_mlcp fuzz_solve; do
  exe=$build/tests/fuzz/$target
  if [ ! -x "$exe" ]; then
    echo "[fuzz] $exe missing: build it with cmake --build $build --target $target" >&2
    exit 2
  fi
  corpus=$work/$target/corpus
  artifacts=$work/$target/artifacts
  rm -rf "$artifacts"
  mkdir -p "$corpus" "$artifacts"
  cp "$data"/*.mlcp "$data"/captured/*.mlcp "$corpus"/
  find "$regressions" -maxdepth 1 -type f ! -name '*.md' -exec cp {} "$corpus"/ \;

  echo "[fuzz] $target for ${seconds}s (corpus: $(ls "$corpus" | wc -l) files)"
  status=0
  # -timeout: one input taking seconds is a bug (the budgets in fuzz_solve are small);
  # -rss_limit_mb/-malloc_limit_mb: a file must never make the reader allocate gigabytes
  "$exe" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=1024 \
         -max_len=16384 -print_final_stats=1 -artifact_prefix="$artifacts/" "${extra_flags[@]}" "$corpus" \
         > "$work/$target.log" 2>&1 || status=$?
  tail -n 12 "$work/$target.log"

  saved=0
  for artifact in "$artifacts"/*; do
    [ -e "$artifact" ] || continue
    kind=$(basename "$artifact" | cut -d- -f1)
    hash=$(sha1sum "$artifact" | cut -c1-40)
    known=$(find "$regressions" -maxdepth 1 -type f -exec sha1sum {} + | awk -v h="$hash" '$1 == h {print $2; exit}')
    if [ -n "$known" ]; then
      echo "[fuzz] $target: $kind on a known regression, $(basename "$known")"
    else
      name=$target-$kind-${hash:0:16}
      cp "$artifact" "$regressions/$name"
      echo "[fuzz] $target: $kind input saved as tests/data/fuzz-regressions/$name"
      # where it happened, last: CI keeps only the tail of the output
      echo "[fuzz] $target: the project's frames of the first report:"
      awk '/ERROR: libFuzzer|ERROR: AddressSanitizer|runtime error/ {on = 1} on && / #[0-9]+ .* in (ode_bpp::|LLVMFuzzer)/ {print; if (++k == 12) exit}' \
          "$work/$target.log" | sed -e 's/(.*) \//  \//' -e 's/^ */[fuzz]   /' | cut -c1-200
    fi
    saved=$((saved + 1))
    found=1
  done
  if [ "$status" -ne 0 ] && [ "$saved" -eq 0 ]; then
    echo "[fuzz] $target exited with $status without an artifact; see $work/$target.log" >&2
    found=1
  fi
done
exit $found
