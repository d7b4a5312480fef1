#!/usr/bin/env bash
# The Python reader of docs/streaming.md: the page shows tools/stream_reader.py as it is,
# and the reader receives every frame of an imagepro-cli run on the loopback address.
#   stream_reader_test.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
root="$1"
build_dir="$2"
tmp="$(mktemp -d)"
reader=""
trap '[[ -n "$reader" ]] && kill "$reader" 2>/dev/null; rm -rf "$tmp"' EXIT

# The listing: the page's python block against the file.
awk '/^```python$/{on=1; next} /^```$/{on=0} on' "$root/docs/streaming.md" > "$tmp/listing.py"
diff -u "$root/tools/stream_reader.py" "$tmp/listing.py"

port="$(python3 -c 'import socket; s=socket.socket(socket.AF_INET, socket.SOCK_DGRAM); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')"
python3 "$root/tools/stream_reader.py" "$port" > "$tmp/received.csv" &
reader=$!
for _ in $(seq 100); do [[ -s "$tmp/received.csv" ]] && break; sleep 0.1; done
"$build_dir/src/cli/imagepro-cli" reconstruct --virtual --frames 20 --no-pace \
  --data-out "$tmp/dataout.csv" --stream "udp://127.0.0.1:$port" > /dev/null 2> "$tmp/summary.txt"
wait "$reader"
reader=""
# One line a frame, in order, with the data-out file's status and Tz (Python prints the
# number shortest, the file with six decimals).
got="$(awk -F, 'NR > 1 { printf "%s,%s,%s\n", $1, $3, ($9 == "" ? "" : sprintf("%.6f", $9)) }' "$tmp/received.csv")"
want="$(tail -n +2 "$tmp/dataout.csv" | cut -d, -f1,2,8)"
if [[ "$got" != "$want" ]]; then
  echo "the reader got:"; echo "$got"; echo "the data-out file has:"; echo "$want"; exit 1
fi
echo "the reader received all $(echo "$got" | wc -l) frames"
