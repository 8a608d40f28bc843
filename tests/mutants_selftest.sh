#!/usr/bin/env bash
# The mutation check cannot hide a survivor (issue: the fast check): scripts/mutants on the
# rules of tests/mutants/selftest must fail the run, report the rule killed only by a suite
# it does not name as mislabelled, the rule no test catches as a survivor, and the rule whose
# old text is gone as stale, naming its file. A malformed rule is refused before any build.
# Usage: tests/mutants_selftest.sh   (from anywhere; takes about a minute)
source "$(dirname "${BASH_SOURCE[0]}")/preamble.sh"
root=$(cd "$(dirname "$0")/.." && pwd)
dir=$root/tests/mutants/selftest

# malformed rules: refused at once (exit 2), naming the file and what is missing
sed '/^suites:/d' "$dir/mislabelled.mut" >"$tmp/nosuites.mut"
/usr/bin/python3 "$root/scripts/mutants.py" --check "$tmp/nosuites.mut" >"$tmp/out" 2>&1
rc=$?
[ $rc -eq 2 ] && grep -q "nosuites.mut: no \"suites:\" line" "$tmp/out" ||
    bad "a rule without suites: exit $rc: $(cat "$tmp/out")"
sed 's/^suites: rod$/suites: rod, nosuchsuite/' "$dir/mislabelled.mut" >"$tmp/unknown.mut"
/usr/bin/python3 "$root/scripts/mutants.py" --check "$tmp/unknown.mut" >"$tmp/out" 2>&1
rc=$?
[ $rc -eq 2 ] && grep -q "unknown suite nosuchsuite" "$tmp/out" ||
    bad "a rule naming an unknown suite: exit $rc: $(cat "$tmp/out")"
/usr/bin/python3 "$root/scripts/mutants.py" --check "$dir/stale.mut" >"$tmp/out" 2>&1
rc=$?
[ $rc -eq 1 ] && grep -q "stale: stale: its old text occurs 0 times in src/surface/cantor.c" "$tmp/out" ||
    bad "--check of a stale rule: exit $rc: $(cat "$tmp/out")"

# the three cases in one run: it must fail, and say why for each
# (within the suites the rules name and the one that kills the mislabelled rule: the survivor
# walks every test there is, which need not be all of them to show the verdict)
/usr/bin/python3 "$root/scripts/mutants.py" --jobs 2 --within rod,cantor,laws "$dir/mislabelled.mut" \
    "$dir/survivor.mut" "$dir/stale.mut" >"$tmp/out" 2>&1
rc=$?
cat "$tmp/out"
[ $rc -eq 1 ] || bad "the run exited $rc, expected 1"
grep -q "^mislabelled: mislabelled: killed, but not by its suites (rod): by " "$tmp/out" ||
    bad "the mislabelled rule is not reported as killed by another suite"
grep -q "^survivor: survivor: " "$tmp/out" || bad "the surviving rule is not reported"
grep -q "^stale: stale: its old text occurs 0 times in src/surface/cantor.c" "$tmp/out" ||
    bad "the stale rule is not reported with its file"
grep -q "^killed 1 of 3" "$tmp/out" || bad "the count is not 'killed 1 of 3'"
[ $failn -eq 0 ] && echo "ok: mislabelled, surviving and stale rules fail the run" && exit 0
exit 1
