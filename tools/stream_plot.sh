#!/usr/bin/env bash
# docs/streaming-live-run.png: tools/stream_reader.py listens while imagepro-cli
# reconstruct streams a live Virtual pendulum (paced at its 25 frames/s, 10 s) to it;
# what the reader printed is plotted with matplotlib.
#
#   tools/stream_plot.sh [BUILD_DIR] [PORT]     (defaults: build, 5005)
#
# The plot needs a Python with matplotlib: $PYTHON, else python3 or /usr/bin/python3,
# whichever has it.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${1:-$root/build}"
port="${2:-5005}"
cli="$build_dir/src/cli/imagepro-cli"
[[ -x "$cli" ]] || { echo "no $cli: build it first (tools/setup.sh build)" >&2; exit 1; }
plotter=""
for p in ${PYTHON:-} python3 /usr/bin/python3; do
  if "$p" -c 'import matplotlib' 2>/dev/null; then plotter="$p"; break; fi
done
[[ -n "$plotter" ]] || { echo "no Python with matplotlib (set PYTHON)" >&2; exit 1; }
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

echo '{"virtual": {"motion": {"kind": "pendulum"}}}' > "$tmp/pendulum.json"
python3 "$root/tools/stream_reader.py" "$port" > "$tmp/received.csv" &
reader=$!
until [[ -s "$tmp/received.csv" ]]; do sleep 0.1; done  # its header: the port is bound
"$cli" reconstruct --config "$tmp/pendulum.json" --virtual --frames 250 \
  --stream "udp://127.0.0.1:$port" > /dev/null
wait "$reader"  # it ends 5 s after the last datagram

"$plotter" - "$tmp/received.csv" "$root/docs/streaming-live-run.png" <<'PY'
import csv, sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

rows = list(csv.DictReader(open(sys.argv[1])))
t = [float(r["timestamp_s"]) for r in rows if r["status"] == "ok"]
fig, (ax1, ax2) = plt.subplots(2, 1, sharex=True, figsize=(7, 4.5), dpi=100)
ax1.plot(t, [float(r["Tx_mm"]) for r in rows if r["status"] == "ok"], ".-", ms=3, lw=0.8)
ax1.set_ylabel("Tx (mm)")
ax2.plot(t, [float(r["Rz_deg"]) for r in rows if r["status"] == "ok"], ".-", ms=3, lw=0.8, color="C1")
ax2.set_ylabel("Rz (deg)")
ax2.set_xlabel("frame time (s)")
lost = len(rows) - len(t)
ax1.set_title(f"Virtual pendulum streamed live: {len(rows)} frames received, {lost} without a pose")
fig.tight_layout()
fig.savefig(sys.argv[2])
PY
echo "wrote $root/docs/streaming-live-run.png from $(($(wc -l < "$tmp/received.csv") - 1)) datagrams" >&2
