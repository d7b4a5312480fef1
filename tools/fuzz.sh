#!/usr/bin/env bash
# Runs each libFuzzer target of tests/fuzz for SECONDS (default 60), one after the other,
# after building them (tools/setup.sh fuzz). Each starts from its seed corpus in
# tests/fuzz/corpus/<target> and grows a working corpus in the build folder; an input
# that crashes, leaks, hangs or trips a sanitizer is kept in build-fuzz/crashes/<target>/.
#
#   tools/fuzz.sh [SECONDS] [TARGET...]     TARGET: image settings calibration pose_csv
#
# FUZZ_RUNS=N stops each target after N inputs if that comes first (the long runs of
# docs/reliability.md: FUZZ_RUNS=1000000).
# Prints one line per target (inputs run, seconds, crashes) and exits 1 if any crashed.
# Replay a kept input with the same program: build-fuzz/tests/fuzz/fuzz_<target> FILE.
set -euo pipefail

seconds="${1:-60}"
runs_limit=()
[ -n "${FUZZ_RUNS:-}" ] && runs_limit=(-runs="$FUZZ_RUNS")
shift || true
targets=("$@")
((${#targets[@]})) || targets=(image settings calibration pose_csv)
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${BUILD_DIR:-$root/build-fuzz}"

BUILD_DIR="$build_dir" "$root/tools/setup.sh" fuzz

failed=0
summary=()
for t in "${targets[@]}"; do
  program="$build_dir/tests/fuzz/fuzz_$t"
  [ -x "$program" ] || { echo "error: no fuzz target $t ($program)" >&2; exit 2; }
  work="$build_dir/corpus/$t" crashes="$build_dir/crashes/$t" log="$build_dir/fuzz-$t.log"
  mkdir -p "$work" "$crashes"
  touch "$crashes/.start"  # what an earlier run kept is not counted again
  echo "== fuzzing $t for $seconds s (log: $log)"
  # Inputs past 64 KiB only slow the run: the seeds are far smaller. A 2 GiB memory
  # cap and a 30 s limit per input turn a runaway allocation or a hang into a finding.
  # OpenCV's decoders refuse images over 512x512 pixels before allocating them (their
  # own limit, 1 Gpixel by default): 64 KiB of PNG, BMP or TIFF can unpack to 64
  # Mpixels, which took 0.9 s an input, and the image target uses only a corner.
  status=0 started=$(date +%s)
  OPENCV_IO_MAX_IMAGE_PIXELS=262144 ASAN_OPTIONS="detect_leaks=1:abort_on_error=1" UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1" \
    "$program" "$work" "$root/tests/fuzz/corpus/$t" -max_total_time="$seconds" "${runs_limit[@]}" -max_len=65536 \
    -rss_limit_mb=2048 -timeout=30 -print_final_stats=1 -artifact_prefix="$crashes/" >"$log" 2>&1 || status=$?
  runs="$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)"
  # libFuzzer also keeps inputs over its 10 s slow-input mark (slow-unit-*): on a loaded
  # machine those are not findings, so only crashes, leaks, time-outs and memory count.
  found="$(find "$crashes" -type f -newer "$crashes/.start" \( -name 'crash-*' -o -name 'leak-*' -o -name 'timeout-*' -o -name 'oom-*' \) | wc -l)"
  slow="$(find "$crashes" -type f -newer "$crashes/.start" -name 'slow-unit-*' | wc -l)"
  line="$t: ${runs:-?} inputs in $(($(date +%s) - started)) s, $found crashing, $slow slow (kept)"
  if ((status != 0)) || ((found > 0)); then
    failed=1
    line+=" (exit $status; see $log)"
    grep -m 20 -E "ERROR|SUMMARY|invariant broken|runtime error" "$log" >&2 || true
  fi
  summary+=("$line")
done
echo "== fuzz summary"
printf '%s\n' "${summary[@]}"
exit "$failed"
