# What every shell test shares, sourced first: bash's -u, a temporary directory $tmp removed at
# exit, the counting of checks and the assertions the tests make. With CT_FAIL_FAST set (by
# scripts/mutants) a test stops at its first failed check; scripts/test and meson read only the
# exit status: 0 when every check passed.
#     source "$(dirname "${BASH_SOURCE[0]}")/preamble.sh"
set -u
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

pass=0
failn=0
# ok: a passed check
ok() { pass=$((pass + 1)); }
# bad MESSAGE: a failed check, said in one line
bad() {
    failn=$((failn + 1))
    echo "FAIL: $*"
    [ -z "${CT_FAIL_FAST:-}" ] || exit 1
}
# fail MESSAGE: a failure after which the test cannot go on
fail() {
    echo "FAIL: $*"
    exit 1
}
# finish [NAME]: "NAME: N passed, M failed", and the test's exit status (its last command)
finish() {
    echo "${1:+$1: }$pass passed, $failn failed"
    [ "$failn" -eq 0 ]
}

# expect CODE DESCRIPTION -- command...: the exit code, and one line on stderr on failure
# (stdout in $tmp/out, stderr in $tmp/err)
expect() {
    local code=$1 what=$2
    shift 3
    "$@" >"$tmp/out" 2>"$tmp/err"
    local rc=$?
    if [ "$rc" -ne "$code" ]; then
        bad "$what: exit $rc, expected $code; stderr: $(cat "$tmp/err")"
        return
    fi
    if [ "$code" -ne 0 ] && [ "$(wc -l <"$tmp/err")" -ne 1 ]; then
        bad "$what: expected one line on stderr, got: $(cat "$tmp/err")"
        return
    fi
    ok
}
# has FILE TEXT DESCRIPTION: $tmp/FILE holds TEXT
has() { grep -q -- "$2" "$tmp/$1" && ok || bad "$3: expected '$2' in $(cat "$tmp/$1")"; }
