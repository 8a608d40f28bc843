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
[ $failn -eq 0 ] && echo "docs: consistent" && exit 0
exit 1
