#!/usr/bin/env bash
# Prints the lead table of docs/benchmarks.md: each stage's goal benchmark and the whole
# engine, measured now, on one core, as Markdown.
#
#   tools/bench-summary.sh [--build-dir DIR] [--repetitions N]
#
# Build first (tools/setup.sh build, Release). Each Google Benchmark gives the median of N
# repetitions (default 5) of its CPU time; the engine is `imagepro-cli bench --frames 100`,
# three runs. Pinned to the second core with taskset when there is one. Takes a few minutes.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${BUILD_DIR:-$root/build}"
repetitions=5
while (($#)); do
  case "$1" in
    --build-dir) build_dir="$2"; shift ;;
    --repetitions) repetitions="$2"; shift ;;
    -h|--help) sed -n '2,9p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "bench-summary: unknown option $1" >&2; exit 2 ;;
  esac
  shift
done
bench="$build_dir/tests/bench"
cli="$build_dir/src/cli/imagepro-cli"
for p in "$bench/bench_segmentation" "$bench/bench_edges" "$bench/bench_ellipse" "$bench/bench_reconstruction" "$cli"; do
  [ -x "$p" ] || { echo "bench-summary: $p is not built (tools/setup.sh build)" >&2; exit 2; }
done
pin=()
if command -v taskset >/dev/null && [ "$(nproc)" -ge 2 ]; then pin=(taskset -c 1); fi

# median CPU time of one benchmark, in its own unit: median BENCH FILTER -> "value unit"
median() {
  "${pin[@]}" "$1" --benchmark_filter="^$2\$" --benchmark_repetitions="$repetitions" \
    --benchmark_report_aggregates_only=true --benchmark_format=csv 2>/dev/null |
    awk -F, -v name="\"$2_median\"" '$1 == name { printf "%.3g %s\n", $4, $5 }'
}
# "value unit" in microseconds, or milliseconds from 1000 us on
shown() {
  awk '{ v = $1; u = $2; if (u == "ns") v /= 1000; else if (u == "ms") v *= 1000;
         if (v >= 1000) printf "%.3g ms", v / 1000; else printf "%.3g µs", v }' <<<"$1"
}
row() {  # row LABEL GOAL BENCH FILTER...
  local label="$1" goal="$2" program="$3"; shift 3
  local cells="" names=""
  for f in "$@"; do
    echo "bench-summary: $(basename "$program") $f ..." >&2
    cells+="${cells:+ / }$(shown "$(median "$program" "$f")")"
    names+="${names:+, }\`$f\`"
  done
  printf '| %s | `%s` %s | %s | %s |\n' "$label" "$(basename "$program")" "$names" "$cells" "$goal"
}

echo "Measured $(date -u +%Y-%m-%d) at $(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo '?'), $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), medians of $repetitions repetitions, one core:"
echo
echo "| stage, per 640x480 frame | benchmark | measured | goal |"
echo "| --- | --- | ---: | ---: |"
row "histogram + AT-Mod" "150 µs" "$bench/bench_segmentation" HistogramAtMod
row "Laplace edges, densest frame" "300 µs" "$bench/bench_edges" "Laplace/frame:8"
row "CN1, densest frame / average" "100 µs" "$bench/bench_edges" "CN1/frame:8" "CN1/frame:-1"
row "ellipse stage with the fit, worst frame" "50 µs" "$bench/bench_ellipse" "DirectFitStage/frame:9"
row "Bennett stage, worst frame" "20 ms" "$bench/bench_ellipse" "BennettStage/frame:9"
row "crop to pose, default mode, 400 / 800 / 1200 mm" "50 µs" "$bench/bench_reconstruction" \
  "BM_CropToPose/mm:400/mode:4/rethreshold:1" "BM_CropToPose/mm:800/mode:4/rethreshold:1" \
  "BM_CropToPose/mm:1200/mode:4/rethreshold:1"
echo
echo "| engine, 640x480, one core (\`imagepro-cli bench --frames 100\`, 3 runs) | frames/s | goal |"
echo "| --- | ---: | ---: |"
runs=()
for i in 1 2 3; do
  echo "bench-summary: imagepro-cli bench, run $i ..." >&2
  runs+=("$("${pin[@]}" "$cli" bench --frames 100 --format json 2>/dev/null | head -1)")
done
engine() {  # engine LABEL KEY GOAL
  local values=""
  for r in "${runs[@]}"; do
    values+="${values:+, }$(grep -o "\"$2\": [0-9.]*" <<<"$r" | head -1 | awk '{ printf "%d", $2 }')"
  done
  printf '| %s | %s | %s |\n' "$1" "$values" "$3"
}
engine "real scenes, full frame" real_full_frame_hz "1,000"
engine "real scenes, tracked" real_tracked_hz "10,000"
engine "virtual bench, full frame" full_frame_hz ""
engine "virtual bench, tracked" tracked_hz ""
