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
# every word list docs/cli.md's scenes give a key ("check = auto ; auto | all | none: ...") is the
# key's own list of words (cantact keys), none left out
"$ct" keys >"$tmp/keys"
awk '/^```ini/ { f = 1; next } /^```/ { f = 0 } f' "$src/docs/cli.md" | sed 's/^; \{0,1\}//' |
    awk '/^\[[a-z]+\]/ { sec = substr($1, 2, length($1) - 2); next }
         match($0, /^[a-z_]+ += [^;]*; [a-z_]+( \| [a-z_]+)+/) {
             key = $1; list = substr($0, index($0, ";") + 2)
             sub(/[^a-z_| ].*$/, "", list); gsub(/ /, "", list); print sec "." key, list }' >"$tmp/doc_words"
[ -s "$tmp/doc_words" ] || bad "docs/cli.md: no word list of a key found (the parser is broken)"
while read -r key doc; do
    have=$(grep -m1 "^$key[ :]" "$tmp/keys" | sed 's/^[^:]*: //; s/;.*//; s/, /|/g; s/ or /|/')
    [ "$doc" = "$have" ] || bad "docs/cli.md: $key lists $doc, the key takes $have"
done <"$tmp/doc_words"

# the outputs that start with '#' lines say, where they are described, how pandas reads them
# (comment='#': without it the '#' lines are rows); each is checked to start so first
printf '[surface]\nfx = 1.5\nfz = 1.3\nH = 10\n[material]\nE = 500\n[impact]\nV_star = 1e-3, 1e-2\n' >"$tmp/c.ini"
printf '[surface]\ntype = random_cantor\nfx = 1.5\nfz = 1.3\nH = 10\ndepth = 4\n[material]\nE = 500\n[impact]\nV_star = 1e-3\n[ensemble]\nrealisations = 2\n' >"$tmp/r.ini"
printf '[surface]\ntype = profile\nfile = %s\nH = 10\n[material]\nE = 2e11\nsigma_y = 4e8\n[impact]\nV_star = 1e-3\n' \
    "$src/tests/data/dektak-1.csv" >"$tmp/p.ini"
"$ct" table -q "$tmp/c.ini" -o "$tmp/o_table.csv" && "$ct" geometry "$tmp/c.ini" -o "$tmp/o_geometry.csv" &&
    "$ct" fit "$src/tests/data/dektak-1.csv" -o "$tmp/o_fit.csv" &&
    "$ct" run -q "$tmp/p.ini" --set output.what=e,bearing -o "$tmp/o.csv" && mv "$tmp/o_bearing.csv" "$tmp/o_bearing2.csv" &&
    "$ct" run -q "$tmp/r.ini" --set output.what=realisations -o "$tmp/o_realisations.csv" ||
    bad "the outputs with '#' lines: a run failed"
for out in table geometry fit bearing2 realisations; do
    [ "$(head -c 1 "$tmp/o_$out.csv")" = "#" ] || bad "$out: its output does not start with a '#' line (update this test)"
done
para() { awk -v RS= -v a="$2" 'index($0, a) { print; exit }' "$src/docs/$1"; }
for where in "dem.md|The CSV: \`# key = value\` lines" "cli.md|cantact geometry SCENE.ini" "cli.md|**The fit**" \
    "cli.md|| \`bearing\` |" "cli.md|| \`realisations\` |"; do
    para "${where%%|*}" "${where#*|}" | grep -q "comment='#'" ||
        bad "docs/${where%%|*}: where '${where#*|}' is described, pandas' comment='#' is not said"
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
