#!/usr/bin/env bash
# tools/regenerate-docs.sh on a repository of its own making (the script and a docs/ folder
# in a scratch folder): a generated block is filled in from its command, --check passes on
# it and fails on a changed line with the diff, and a block that is no plain command or
# has no end line is refused with the doc left as it was.
# usage: regenerate_docs_test.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
source_dir="$1" build_dir="$2"
repo="$(mktemp -d)"
trap 'rm -rf "$repo"' EXIT
mkdir "$repo/tools" "$repo/docs"
cp "$source_dir/tools/regenerate-docs.sh" "$repo/tools/"
script=("bash" "$repo/tools/regenerate-docs.sh" --build-dir "$build_dir" --only blocks)
fail() { echo "FAILED: $*" >&2; exit 1; }

doc="$repo/docs/page.md"
printf '%s\n' "Prose before." "<!-- generated code: imagepro-cli settings -->" "stale" "<!-- end generated -->" \
  "Prose after." >"$doc"
"${script[@]}" --check >"$repo/out" 2>&1 && fail "--check passed a stale block"
grep -q '^-stale$' "$repo/out" || fail "--check printed no diff: $(cat "$repo/out")"
grep -q '^stale$' "$doc" || fail "--check changed the doc"

"${script[@]}" 2>/dev/null || fail "regenerating the block"
expected="$("$build_dir/src/cli/imagepro-cli" settings)"
[ "$(sed -n '1,4p' "$doc")" = $'Prose before.\n<!-- generated code: imagepro-cli settings -->\n\n```' ] ||
  fail "the marker and a blank line do not open the block: $(head -4 "$doc")"
[ "$(sed -n '/^```$/,/^```$/p' "$doc" | sed '1d;$d')" = "$expected" ] || fail "the block is not the command's output"
[ "$(tail -3 "$doc")" = $'\n<!-- end generated -->\nProse after.' ] || fail "the block's end: $(tail -3 "$doc")"
"${script[@]}" --check 2>/dev/null || fail "--check failed on a block just regenerated"

cp "$doc" "$repo/regenerated.md"
sed -i 's/^  "pipeline": {$/  "pipeline": {"changed": 1,/' "$doc"
"${script[@]}" --check >"$repo/out" 2>&1 && fail "--check passed a changed line"
grep -q '^-  "pipeline": {"changed": 1,$' "$repo/out" || fail "--check printed no diff: $(cat "$repo/out")"

for bad in "<!-- generated: imagepro-cli settings; touch $repo/ran -->" "<!-- generated: ls -->"; do
  printf '%s\n' "$bad" "<!-- end generated -->" >"$doc"
  "${script[@]}" 2>/dev/null && fail "ran the block \"$bad\""
  [ ! -e "$repo/ran" ] || fail "ran a shell command"
  [ "$(cat "$doc")" = "$bad"$'\n<!-- end generated -->' ] || fail "changed the doc of a refused block"
done
printf '%s\n' "<!-- generated: imagepro-cli settings -->" "no end line" >"$doc"
"${script[@]}" 2>/dev/null && fail "filled a block without its end line"
[ "$(cat "$doc")" = $'<!-- generated: imagepro-cli settings -->\nno end line' ] || fail "changed a doc without end line"
echo "regenerate-docs: blocks filled, checked and refused as they should be"
