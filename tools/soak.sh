#!/usr/bin/env bash
# Soak of the command-line engine: imagepro-cli reconstruct on the Virtual source with
# tracking (the settings' default), as fast as it goes, writing data out, while its
# resident memory is sampled every second. Afterwards: the memory's slope (least squares
# over the samples after the warm-up: the first 30 s or the first tenth, the longer), and the frames the CLI counted
# against the data-out rows. Fails when they disagree or memory grows by more than
# MAX_SLOPE_KB_PER_MIN (default 64).
#
#   tools/soak.sh [FRAMES]      (default 20000; 1000000 took 14 min at about 1,000 frames/s)
#
# Environment: BUILD_DIR (default: build, already built), SOAK_DIR (default: a fresh
# folder under the build), MAX_SLOPE_KB_PER_MIN.
# The application's soak is the app_soak test program (tests/app/soak).
set -euo pipefail

frames="${1:-20000}"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${BUILD_DIR:-$root/build}"
cli="$build_dir/src/cli/imagepro-cli"
max_slope="${MAX_SLOPE_KB_PER_MIN:-64}"
[ -x "$cli" ] || { echo "error: $cli is not built (tools/setup.sh build)" >&2; exit 2; }
dir="${SOAK_DIR:-$build_dir/soak}"
rm -rf "$dir"
mkdir -p "$dir"

echo "== soak: imagepro-cli reconstruct --virtual --frames $frames --no-pace --data-out $dir/dataout.csv"
"$cli" reconstruct --virtual --frames "$frames" --no-pace --data-out "$dir/dataout.csv" >/dev/null 2>"$dir/stderr.txt" &
pid=$!
start=$(date +%s.%N)
: >"$dir/rss.txt"
while kill -0 "$pid" 2>/dev/null; do
  rss=$(awk '/^VmRSS:/ {print $2}' "/proc/$pid/status" 2>/dev/null || true)
  [ -n "$rss" ] && awk -v now="$(date +%s.%N)" -v s="$start" -v r="$rss" 'BEGIN { printf "%.2f %d\n", now - s, r }' >>"$dir/rss.txt"
  sleep 1
done
status=0
wait "$pid" || status=$?
((status == 0)) || { echo "error: imagepro-cli exited $status:" >&2; cat "$dir/stderr.txt" >&2; exit 1; }

counted=$(sed -n 's/^\([0-9]*\) frames, .*/\1/p' "$dir/stderr.txt" | tail -1)
rows=$(($(wc -l <"$dir/dataout.csv") - 1))
# Slope of RSS (KB) against time (min) after the warm-up, and the first and last RSS.
read -r slope first last minutes < <(awk '{t[NR]=$1; r[NR]=$2} END {
  w = t[NR] / 10; if (w < 30) w = 30; s = 1; while (s < NR && t[s] < w) ++s; n = 0; st = 0; sr = 0; stt = 0; str = 0
  for (i = s; i <= NR; ++i) { x = t[i] / 60; n++; st += x; sr += r[i]; stt += x * x; str += x * r[i] }
  d = n * stt - st * st
  printf "%.1f %d %d %.1f\n", (n > 2 && d > 0) ? (n * str - st * sr) / d : 0, r[s], r[NR], t[NR] / 60 }' "$dir/rss.txt")
echo "frames counted $counted, data-out rows $rows"
echo "resident memory ${first} KB after warm-up, ${last} KB at the end, slope ${slope} KB/min over ${minutes} min"
fail=0
[ "$counted" = "$rows" ] || { echo "error: the frame counter and the data-out rows disagree" >&2; fail=1; }
awk -v s="$slope" -v m="$max_slope" 'BEGIN { exit !(s > m) }' && { echo "error: memory grows by more than $max_slope KB/min" >&2; fail=1; }
exit "$fail"
