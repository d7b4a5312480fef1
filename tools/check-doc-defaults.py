#!/usr/bin/env python3
"""Checks that every setting's default quoted in docs/*.md is the default the program has.

A default is quoted as the key in backticks followed by the value in parentheses:
`trace_inlier_px` (1 px ...) or `pipeline.calibration.min_matches` (20 ...), a share also
as a percentage (5 %). The key is a
setting's full path or, when no other setting ends so, its last part. The defaults are
read from `imagepro-cli settings` (the effective settings without a file).

usage: tools/check-doc-defaults.py IMAGEPRO_CLI DOCS_DIR
Exits 1, listing file:line, key, quoted and real value, when a quoted default is stale.
"""
import json
import pathlib
import re
import subprocess
import sys


def leaves(node, path=""):
    """Every scalar setting as (full path, value)."""
    if isinstance(node, dict):
        for key, value in node.items():
            yield from leaves(value, f"{path}.{key}" if path else key)
    elif not isinstance(node, list):
        yield path, node


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    cli, docs = sys.argv[1], pathlib.Path(sys.argv[2])
    defaults = dict(leaves(json.loads(subprocess.run([cli, "settings"], check=True, capture_output=True, text=True).stdout)))
    by_last = {}
    for path in defaults:
        by_last.setdefault(path.rsplit(".", 1)[-1], []).append(path)
    quoted = re.compile(r"`([a-z_][a-z0-9_.]*)` \((-?[0-9]+(?:\.[0-9]+)?)( ?%)?")
    stale, checked = [], 0
    for page in sorted(docs.glob("*.md")):
        for number, line in enumerate(page.read_text(encoding="utf-8").splitlines(), 1):
            for key, value, percent in quoted.findall(line):
                paths = [key] if key in defaults else by_last.get(key, [])
                if len(paths) != 1 or isinstance(defaults[paths[0]], (bool, str)):
                    continue  # not a setting, or one a last part cannot name alone
                checked += 1
                real = defaults[paths[0]]
                said = float(value) / 100.0 if percent else float(value)  # "5 %" of a share 0.05
                if abs(said - float(real)) > 1e-9 * max(1.0, abs(float(real))):
                    stale.append(f"{page.name}:{number}: `{key}` quoted as {value}, its default is {real} ({paths[0]})")
    for problem in stale:
        print(problem)
    print(f"{checked} quoted defaults checked, {len(stale)} stale")
    sys.exit(1 if stale else 0)


if __name__ == "__main__":
    main()
