#!/usr/bin/env bash
# Every subcommand x every kind of surface x every output, walked from the registry
# (`cantact kinds --csv`): what a kind gives must work (exit 0, a header and rows, nothing
# half-written), what it does not give must be refused in one line on stderr that says why
# (the registry's reason), with exit 2 and no output file. A new kind or output joins the walk
# by itself; a kind needs its example scene, examples/scenes/KIND.ini (docs/cli.md).
# Usage: test_matrix.sh CANTACT SOURCE_DIR
source "$(dirname "${BASH_SOURCE[0]}")/preamble.sh"
ct=$1
src=$(cd "$2" && pwd)

"$ct" kinds --csv >"$tmp/kinds.csv" || bad "cantact kinds --csv exited $?"
kinds=$(awk -F, 'NR > 1 { print $1 }' "$tmp/kinds.csv" | uniq)
outputs=$(awk -F, 'NR > 1 { print $2 }' "$tmp/kinds.csv" | awk '!seen[$0]++')
[ -n "$kinds" ] && [ -n "$outputs" ] || bad "no kinds or outputs in cantact kinds --csv"

# given KIND OUTPUT -> 1 or 0; why KIND OUTPUT -> the registry's reason
given() { awk -F, -v k="$1" -v o="$2" 'NR > 1 && $1 == k && $2 == o { print $3 }' "$tmp/kinds.csv"; }
why() {
    awk -F, -v k="$1" -v o="$2" 'NR > 1 && $1 == k && $2 == o {
        sub(/^[^,]*,[^,]*,[^,]*,"/, ""); sub(/"$/, ""); print }' "$tmp/kinds.csv"
}

# check KIND OUTPUT OUTFILE -- command...: given -> exit 0 and OUTFILE (or stdout when "-")
# has a header and a row; refused -> exit 2, one line holding the reason, no OUTFILE
check() {
    local kind=$1 output=$2 file=$3
    shift 4
    rm -f "$file"
    "$@" >"$tmp/stdout" 2>"$tmp/stderr"
    local rc=$? g
    g=$(given "$kind" "$output")
    [ "$file" = - ] && file=$tmp/stdout
    if [ "$g" = 1 ]; then
        if [ $rc -ne 0 ]; then
            bad "$kind x $output: exit $rc, expected 0: $(head -c 400 "$tmp/stderr")"
        elif [ ! -s "$file" ] || [ "$(grep -vc '^#' "$file")" -lt 2 ]; then
            bad "$kind x $output: no header and rows in $file"
        elif [ "$output" != geometry ] && ! grep -v '^#' "$file" |
            awk -F, 'NR == 1 { n = NF } NF != n { exit 1 }'; then
            bad "$kind x $output: rows with another field count than the header in $file"
        elif grep -qiw nan "$file"; then
            bad "$kind x $output: NaN written in $file"
        else
            ok
        fi
    else
        local reason
        reason=$(why "$kind" "$output")
        if [ $rc -ne 2 ]; then
            bad "$kind x $output: refused with exit $rc, expected 2"
        elif [ "$(wc -l <"$tmp/stderr")" -ne 1 ]; then
            bad "$kind x $output: expected one line on stderr, got: $(cat "$tmp/stderr")"
        elif ! grep -qF -- "$reason" "$tmp/stderr"; then
            bad "$kind x $output: the reason '$reason' is not in: $(cat "$tmp/stderr")"
        elif [ "$file" != "$tmp/stdout" ] && [ -e "$file" ]; then
            bad "$kind x $output: refused, yet $file was written"
        else
            ok
        fi
    fi
}

# a kind with a depth key runs at depth 10, so that every output can be written (a profile of
# the pieces of a deep prefractal is refused for its size, not its kind)
"$ct" keys >"$tmp/keys.txt" || bad "cantact keys exited $?"
for kind in $kinds; do
    scene=$src/examples/scenes/$kind.ini
    if [ ! -f "$scene" ]; then
        bad "kind $kind has no example scene examples/scenes/$kind.ini"
        continue
    fi
    quick="--set impact.velocity=0.01:1:4:log"
    grep -q "^surface.depth ($kind)" "$tmp/keys.txt" && quick="$quick --set surface.depth=10"
    for output in $outputs; do
        out=$tmp/$kind.$output.csv
        case $output in
        e | time | curve | history | profile | compare | bearing)
            check "$kind" "$output" "$out" -- "$ct" run -q "$scene" $quick \
                --set "output.what=$output" -o "$out"
            ;;
        bounce)
            check "$kind" "$output" "$out" -- "$ct" run -q "$scene" --set impact.velocity=0.1 \
                --set impact.sequence=bounce --set impact.impacts=3 --set output.what=bounce \
                -o "$out"
            ;;
        ensemble | realisations)
            check "$kind" "$output" "$out" -- "$ct" run -q "$scene" $quick \
                --set ensemble.realisations=3 --set "output.what=$output" -o "$out"
            ;;
        landings)
            # a curved body's landings: walked with the bodies below where the kind gives them
            # (a kind's example may have no footprints to land on); refused here where not
            [ "$(given "$kind" landings)" = 1 ] ||
                check "$kind" "$output" "$out" -- "$ct" run -q "$scene" $quick \
                    --set body.shape=cylinder --set body.radius=10 --set body.landings=3 \
                    --set output.what=landings -o "$out"
            ;;
        table)
            check "$kind" "$output" "$out" -- "$ct" table -q "$scene" $quick \
                --set table.tolerance=1e-3 -o "$out"
            ;;
        geometry)
            check "$kind" "$output" - -- "$ct" geometry "$scene" $quick
            ;;
        fit)
            check "$kind" "$output" "$out" -- "$ct" fit "$scene" -o "$out"
            ;;
        merge)
            # parts of an ensemble run in two jobs, merged
            args=("$scene" $quick --set ensemble.realisations=3 --set output.what=ensemble)
            if [ "$(given "$kind" merge)" = 1 ]; then
                "$ct" run -q "${args[@]}" --realisations 0:2 -o "$tmp/p0.csv" &&
                    "$ct" run -q "${args[@]}" --realisations 2:3 -o "$tmp/p1.csv" ||
                    bad "$kind x merge: the parts did not run"
            else
                printf 'realisation\n' >"$tmp/p0.csv"
                cp "$tmp/p0.csv" "$tmp/p1.csv"
                args=("$scene")
            fi
            check "$kind" "$output" "$out" -- "$ct" merge -q "${args[@]}" "$tmp/p0.csv" \
                "$tmp/p1.csv" -o "$out"
            ;;
        *)
            bad "output $output: the matrix does not know how to ask for it (add it here)"
            ;;
        esac
    done
done

# every kind x every body (from the key table's body.shape) x the outputs of a run: works (exit
# 0, a header and rows, no NaN) or is refused in one line (exit 1 or 2, no file). A curved
# body needs footprints: a Cantor surface runs with one rod per piece, its own refusal of stage
# rods checked too; the surface repeats (surface.periodic) so that the face stays on it.
bodies=$(sed -n 's/^body\.shape: \([^;]*\);.*/\1/p' "$tmp/keys.txt" | sed 's/ or /, /g; s/,//g')
[ -n "$bodies" ] || bad "no body.shape row in cantact keys"
body_check() {
    local what=$1 file=$2
    shift 2
    rm -f "$file"
    "$@" >"$tmp/stdout" 2>"$tmp/stderr"
    local rc=$?
    if [ $rc -eq 0 ]; then
        if [ ! -s "$file" ] || [ "$(grep -vc '^#' "$file")" -lt 2 ]; then
            bad "$what: exit 0 and no header and rows in $file"
        elif grep -qiw nan "$file"; then
            bad "$what: NaN written in $file"
        else
            ok
        fi
    elif [ $rc -ne 1 ] && [ $rc -ne 2 ]; then
        bad "$what: exit $rc: $(head -c 300 "$tmp/stderr")"
    elif [ "$(wc -l <"$tmp/stderr")" -ne 1 ]; then
        bad "$what: refused in more than one line: $(cat "$tmp/stderr")"
    elif [ -e "$file" ]; then
        bad "$what: refused, yet $file was written"
    else
        ok
    fi
}
worked=0
landed=0
for kind in $kinds; do
    scene=$src/examples/scenes/$kind.ini
    [ -f "$scene" ] || continue
    extra=(--set impact.velocity=0.01:1:4:log)
    grep -q "^surface.depth ($kind)" "$tmp/keys.txt" && extra+=(--set surface.depth=8)
    if grep -q "^surface.representation ($kind)" "$tmp/keys.txt"; then
        # stage rods stand nowhere: a curved body refuses them in one line
        body_check "$kind x stage rods x cylinder" "$tmp/stages.csv" "$ct" run -q "$scene" \
            "${extra[@]}" --set body.shape=cylinder --set body.radius=10 -o "$tmp/stages.csv"
        grep -q "representation = segments" "$tmp/stderr" ||
            bad "$kind x stage rods: not refused naming the representation: $(cat "$tmp/stderr")"
        extra+=(--set surface.representation=segments)
    fi
    for body in $bodies; do
        args=("${extra[@]}" --set "body.shape=$body")
        [ "$body" = flat ] || args+=(--set body.radius=10 --set surface.periodic=true)
        for output in e time curve history profile compare; do
            [ "$(given "$kind" "$output")" = 1 ] || continue
            out=$tmp/$kind.$body.$output.csv
            body_check "$kind x $body x $output" "$out" "$ct" run -q "$scene" "${args[@]}" \
                --set "output.what=$output" -o "$out"
            [ "$output" = e ] && [ -s "$out" ] && [ "$body" != flat ] && worked=$((worked + 1))
        done
        out=$tmp/$kind.$body.bounce.csv
        body_check "$kind x $body x bounce" "$out" "$ct" run -q "$scene" "${args[@]}" \
            --set impact.velocity=0.1 --set impact.sequence=bounce --set impact.impacts=3 \
            --set output.what=bounce -o "$out"
        if [ "$(given "$kind" ensemble)" = 1 ]; then
            out=$tmp/$kind.$body.ensemble.csv
            body_check "$kind x $body x ensemble" "$out" "$ct" run -q "$scene" "${args[@]}" \
                --set ensemble.realisations=3 --set output.what=ensemble -o "$out"
        fi
        if [ "$(given "$kind" landings)" = 1 ] && [ "$body" != flat ]; then
            out=$tmp/$kind.$body.landings.csv
            body_check "$kind x $body x landings" "$out" "$ct" run -q "$scene" "${args[@]}" \
                --set body.landings=3 --set output.what=e,landings -o "$out"
            [ -s "${out%.csv}_landings.csv" ] && landed=$((landed + 1))
        fi
        out=$tmp/$kind.$body.table.csv
        body_check "$kind x $body x table" "$out" "$ct" table -q "$scene" "${args[@]}" \
            --set table.tolerance=1e-3 -o "$out"
    done
done
# compare puts the flat strip's laws beside e: not beside a curved body's
body_check "cantor x cylinder x compare" "$tmp/cmp.csv" "$ct" run -q \
    "$src/examples/scenes/cantor.ini" --set surface.representation=segments --set surface.depth=8 \
    --set body.shape=cylinder --set body.radius=10 --set output.what=compare -o "$tmp/cmp.csv"
grep -q "compare: the paper's laws and a fitted Cantor surface are the flat strip's" \
    "$tmp/stderr" && ok || bad "compare under a cylinder: not refused: $(cat "$tmp/stderr")"
# a curved body is not refused everywhere: at least a cylinder and a sphere ran somewhere
[ $worked -ge 2 ] && ok || bad "curved bodies ran on only $worked kind(s)"
[ $landed -ge 2 ] && ok || bad "landings ran on only $landed kind x body pair(s)"

finish matrix
