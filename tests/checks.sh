# The shell tests' counting (sourced): ok counts a passed check, bad reports a failed one (and,
# with CT_FAIL_FAST set by the mutation check, stops at the first).
pass=0
failn=0
ok() { pass=$((pass + 1)); }
bad() {
    failn=$((failn + 1))
    echo "FAIL: $*"
    [ -z "${CT_FAIL_FAST:-}" ] || exit 1
}
