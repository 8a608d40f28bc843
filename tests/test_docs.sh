#!/usr/bin/env bash
# The docs in the repository stay true to the code: docs/scene-keys.md is what `cantact keys
# --markdown` prints from the key tables, every "docs/model.md §N" the sources cite is a
# section of docs/model.md, and every docs/ page the README and docs link to exists.
# Usage: test_docs.sh CANTACT SOURCE_DIR
source "$(dirname "${BASH_SOURCE[0]}")/preamble.sh"
ct=$1
src=$(cd "$2" && pwd)
if ! "$ct" keys --markdown | cmp -s - "$src/docs/scene-keys.md"; then
    bad "docs/scene-keys.md is not what cantact keys --markdown prints (regenerate it:" \
        "build/cantact keys --markdown > docs/scene-keys.md)"
fi
sections=$(sed -n 's/^## \([0-9][0-9]*\)\. .*/\1/p' "$src/docs/model.md")
cited=$(cd "$src" && grep -rhoE "docs/model\.md §[0-9]+(-[0-9]+)?" src include tests tools bench \
    python scripts examples 2>/dev/null | sed 's/.*§//' | tr '-' '\n' | sort -un)
for n in $cited; do
    echo "$sections" | grep -qx "$n" || bad "docs/model.md §$n is cited but docs/model.md has no section $n"
done
[ -n "$cited" ] || bad "no docs/model.md citations found (the grep is broken)"
grep -q "MODEL.md" -r "$src/src" "$src/include" && bad "a source still cites MODEL.md (not in the repository)"
for page in $(cd "$src" && grep -ohE "docs/[a-z_-]+\.md" README.md docs/*.md | sort -u); do
    [ -f "$src/$page" ] || bad "$page is linked but does not exist"
done
# a rod file's separators and comments are said where the rods kind is described (its key's doc,
# so scene-keys.md and cantact keys; docs/cli.md's table of kinds), and are what the reader takes
"$ct" keys | grep "^surface.file (rods)" >"$tmp/rods_key" || bad "cantact keys: no surface.file (rods)"
for said in "separated by commas, semicolons or blanks" "lines starting with # or ; are comments"; do
    grep -q "$said" "$tmp/rods_key" || bad "surface.file (rods): its doc does not say '$said'"
done
grep "^| \`rods\` |" "$src/docs/cli.md" | grep -q "fields separated by commas, semicolons or blanks, none empty; \`#\` or \`;\` comment lines" ||
    bad "docs/cli.md: the rods kind's row does not give a rod file's separators and comments"
printf '# a comment\n; another\ntop area\n0 1\n0.5;1\n0.75,1\n' >"$tmp/rods.txt"
printf '[surface]\ntype = rods\nfile = rods.txt\nHstar = 2\n[material]\nE = 10\n[impact]\nV_star = 0.3\n' >"$tmp/rods.ini"
"$ct" run -q "$tmp/rods.ini" -o "$tmp/rods.csv" || bad "a rod file with both comments and every separator is refused"
[ $failn -eq 0 ] && echo "docs: consistent" && exit 0
exit 1
