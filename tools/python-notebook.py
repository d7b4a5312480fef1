#!/usr/bin/env python3
"""Runs a Python script written as cells and writes it out as a Markdown page.

    python3 tools/python-notebook.py SCRIPT --out PAGE.md

The script is in the "percent" cell format that editors open as a notebook: a line
"# %% [markdown]" starts a text cell (its lines are comments, "# " taken off), a line
"# %%" starts a code cell. The page has each text cell as it is and each code cell in a
python block, followed by what it printed. Cells run in order, in one namespace, from the
current folder. docs/python.md is made this way from docs/python-walkthrough.py
(tools/regenerate-docs.sh --only python).
"""
import argparse
import contextlib
import io
import sys


def cells(text):
    """(kind, lines) of each cell, kind "markdown" or "code"."""
    kind, lines, out = None, [], []
    for line in text.splitlines():
        if line.startswith("# %%"):
            if kind:
                out.append((kind, lines))
            kind, lines = ("markdown" if "[markdown]" in line else "code"), []
        elif kind == "markdown":
            lines.append(line[2:] if line.startswith("# ") else line.lstrip("#"))
        elif kind == "code":
            lines.append(line)
    if kind:
        out.append((kind, lines))
    return [(k, trimmed(l)) for k, l in out]


def trimmed(lines):
    while lines and not lines[0].strip():
        lines = lines[1:]
    while lines and not lines[-1].strip():
        lines = lines[:-1]
    return lines


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("script")
    parser.add_argument("--out", required=True)
    args = parser.parse_args()
    with open(args.script, encoding="utf-8") as f:
        source = f.read()
    namespace = {"__name__": "__main__"}
    page = [f"<!-- Made by tools/python-notebook.py from {args.script}: edit that script, not this page. -->", ""]
    for kind, lines in cells(source):
        if not lines:
            continue
        if kind == "markdown":
            page += lines + [""]
            continue
        printed = io.StringIO()
        with contextlib.redirect_stdout(printed):
            exec(compile("\n".join(lines) + "\n", args.script, "exec"), namespace)
        page += ["```python"] + lines + ["```", ""]
        if printed.getvalue().strip():
            page += ["```"] + printed.getvalue().rstrip("\n").splitlines() + ["```", ""]
    with open(args.out, "w", encoding="utf-8") as f:
        f.write("\n".join(page).rstrip("\n") + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
