#!/usr/bin/env bash
# The closed-form check at run time (issue 26): with the default solver.check = auto, runs that
# sample the check (a 2000-speed sweep of the Dektak profile, 9600 rods; an ensemble of random
# surfaces) and runs that check every speed must succeed, and say what they checked. This
# script asserts nothing about the numbers themselves: the mutants of the curve and impact
# code labelled with its suite (`check`) are killed only when the check itself turns their
# wrong e into a failed row (exit 1), which is what the default check promises.
# Usage: test_check_cli.sh CANTACT SOURCE_DIR
source "$(dirname "${BASH_SOURCE[0]}")/preamble.sh"
ct=$1
src=$(cd "$2" && pwd)

# runs NAME -- command...: exit 0, stderr kept in $tmp/NAME.err
runs() {
    local name=$1
    shift 2
    if "$@" >"$tmp/$name.out" 2>"$tmp/$name.err"; then ok; else bad "$name: exit $?: $(tail -c 400 "$tmp/$name.err")"; fi
}
# the default scene: 758 rods x 31 speeds, every row checked (no sample note)
runs default -- "$ct" run "$src/scripts/scenes/default.ini" --set impact.V_star=1e-5:3e-2:31:log \
    --set impact.impacts=3
grep -q "closed-form check" "$tmp/default.err" && bad "default: sampled, though small" || ok
awk -F, 'NR > 1 && $5 == "" { n++ } END { exit n > 0 }' "$tmp/default.out" && ok ||
    bad "default: rows without e_closed_form"
# the Dektak profile at 2000 speeds: a sample of the speeds, every impact of each
runs dektak -- "$ct" run "$src/scripts/scenes/dektak.ini" --set impact.velocity=0.001:3:2000:log \
    --set output.what=e --set impact.impacts=2
grep -q "closed-form check: every impact of [0-9]* of 2000 speeds, a sample" "$tmp/dektak.err" && ok ||
    bad "dektak: no note of the sampled check: $(cat "$tmp/dektak.err")"
# the sample holds plastic speeds of both impacts (rows with e_closed_form and e < 1)
awk -F, 'NR > 1 && $5 != "" && $4 < 1 { n[$1]++ } END { exit !(n[1] >= 8 && n[2] >= 8) }' \
    "$tmp/dektak.out" && ok || bad "dektak: fewer than 8 checked plastic rows per impact"
# the speeds on either side of V*_c are in the sample (where the first rods yield)
awk -F, 'NR > 1 && $1 == 1 { if ($2 > $7 && (a == "" || $2 < a)) { a = $2; ea = $5 }
    if ($2 <= $7 && (b == "" || $2 > b)) { b = $2; eb = $5 } }
    END { exit !(a != "" && ea != "" && (b == "" || eb != "")) }' "$tmp/dektak.out" && ok ||
    bad "dektak: the speeds around V*_c are not checked"
# the curve path's general branch (impacts below an earlier maximum: the state carried)
runs cantor -- "$ct" run "$src/examples/scenes/cantor.ini" --set impact.velocity=0.01:1:400:log \
    --set impact.impacts=4 --set surface.depth=18 --set surface.representation=segments
# an ensemble of random surfaces: realisations 0 and 8 of 0 .. 9 checked, each on its sweep's
# sample of the speeds, and the run says so
runs ensemble -- "$ct" run "$src/examples/scenes/random_cantor.ini" --set surface.depth=12 \
    --set ensemble.realisations=10 --set output.what=ensemble --set impact.velocity=0.01:1:600:log
grep -q "closed-form check of 2 of 10 realisations (those whose index is a multiple of 8" \
    "$tmp/ensemble.err" && ok || bad "ensemble: no note of the checked realisations: $(cat "$tmp/ensemble.err")"
# a part of the ensemble with no multiple of 8 in it: nothing checked, and the run says so
runs part -- "$ct" run "$src/examples/scenes/random_cantor.ini" --set surface.depth=10 \
    --set ensemble.realisations=20 --set output.what=ensemble --set impact.velocity=0.01:1:20:log \
    --realisations 1:7
grep -q "closed-form check of none of realisations 1 .. 6" "$tmp/part.err" && ok ||
    bad "part: no note that nothing was checked: $(cat "$tmp/part.err")"
finish check-cli
