#!/usr/bin/env python3
"""Reads ImagePro's live pose stream (format json) and prints one CSV line a frame."""
import json, socket, sys

port = int(sys.argv[1]) if len(sys.argv) > 1 else 5005
sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
sock.bind(("127.0.0.1", port))
sock.settimeout(5.0)  # ends 5 s after the last datagram
names = ["Rx_deg", "Ry_deg", "Rz_deg", "Tx_mm", "Ty_mm", "Tz_mm"]
print(",".join(["frame", "timestamp_s", "status", *names]), flush=True)
try:
    while True:
        d = json.loads(sock.recv(65536))
        pose = ["" if d[k] is None else d[k] for k in names]  # null: no pose this frame
        print(",".join(str(v) for v in [d["frame"], d["timestamp_s"], d["status"], *pose]), flush=True)
except socket.timeout:
    pass
