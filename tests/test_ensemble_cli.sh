#!/usr/bin/env bash
# CLI of random surfaces and ensembles: scene keys and their errors, the ensemble and
# realisations outputs, the same bytes for 1 and 2 threads and either split, --realisations
# parts merged back into the same bytes (and merge's refusals), a single realisation's e and
# profile. With MPIRUN given: mpirun -n 1, 2, 3 (oversubscribed) write the same bytes.
# Usage: test_ensemble_cli.sh CANTACT SOURCE_DIR [MPIRUN]
source "$(dirname "${BASH_SOURCE[0]}")/preamble.sh"
ct=$1
mpirun=${3:-}

cat >"$tmp/r.ini" <<INI
[surface]
type = random_cantor
fx = 1.5
fz = 1.3
H = 10
depth = 9
distribution = lognormal
fx_spread = 0.15
fz_spread = 0.05
seed = 11
[material]
E = 500
[impact]
V_star = 1e-4:1e-2:7:log
impacts = 2
[ensemble]
realisations = 23
INI

expect 0 "ensemble run" -- "$ct" run "$tmp/r.ini" -o "$tmp/ens.csv"
grep -q "standard error of mean e" "$tmp/err" && ok || bad "standard error not printed: $(cat "$tmp/err")"
grep -q "ratios clipped into the valid ranges: fx [0-9]* of 23506 draws" "$tmp/err" && ok || bad "clipping not reported: $(cat "$tmp/err")"
hdr="impact,V_star,realisations,e_mean,e_sd,e_sem,e_q05,e_q50,e_q95,u_max_over_h0_mean,u_max_over_h0_sd,u_max_over_h0_sem,u_max_over_h0_q05,u_max_over_h0_q50,u_max_over_h0_q95,V_star_crit_mean,V_star_crit_sd,V_star_crit_sem,V_star_crit_q05,V_star_crit_q50,V_star_crit_q95,e_deterministic"
[ "$(head -1 "$tmp/ens.csv")" = "$hdr" ] && ok || bad "ensemble header: $(head -1 "$tmp/ens.csv")"
[ "$(wc -l <"$tmp/ens.csv")" -eq 15 ] && ok || bad "one row per speed and impact"
# 23 samples each; q05 <= q50 <= q95 within (0, 1]; the mean inside [q05, q95]; sem = sd / sqrt(23)
awk -F, 'NR > 1 { if ($3 != 23 || !($7 <= $8 && $8 <= $9 && $7 > 0 && $9 <= 1)) exit 1
    if (!($4 >= $7 && $4 <= $9)) exit 1
    d = $6 - $5 / sqrt(23); if (d < 0) d = -d; if (d > 1e-15) exit 1
    if ($22 == "" || $22 <= 0 || $22 > 1) exit 1 }' "$tmp/ens.csv" && ok || bad "ensemble rows: $(sed -n 2,3p "$tmp/ens.csv")"

# an ensemble under a curved body: every realisation struck by it, each sample the bits of that
# realisation's own run under the body (surface.realisation = k), from the scene or --set; the
# identity line of its parts names the body (parts of another body are another run)
sed '/^\[ensemble\]/,$d' "$tmp/r.ini" >"$tmp/r1.ini"
for how in scene set; do
    if [ $how = scene ]; then
        printf '[body]\nshape = cylinder\nradius = 10\n[surface]\nperiodic = true\n' |
            cat "$tmp/r.ini" - | sed 's/^realisations = 23/realisations = 4/' >"$tmp/rb.ini"
        args=("$tmp/rb.ini")
    else
        args=("$tmp/r.ini" --set ensemble.realisations=4 --set body.shape=cylinder
            --set body.radius=10 --set surface.periodic=true)
    fi
    expect 0 "ensemble under a cylinder ($how)" -- "$ct" run -q "${args[@]}" \
        --set output.what=realisations -o "$tmp/body_ens.csv"
    head -1 "$tmp/body_ens.csv" | grep -q "; under a cylinder of R = 10, its apex at the middle" &&
        ok || bad "the parts' identity line does not name the body: $(head -1 "$tmp/body_ens.csv")"
    for k in 0 1 2 3; do
        "$ct" run -q "$tmp/r1.ini" --set surface.realisation=$k --set body.shape=cylinder \
            --set body.radius=10 --set surface.periodic=true -o "$tmp/one_$k.csv" ||
            bad "realisation $k under the cylinder exited $?"
        # e of realisation k in the ensemble's samples (column 5) against its own run's (column 4)
        diff <(awk -F, -v k=$k 'NR > 2 && $1 == k { print $2, $3, $5 }' "$tmp/body_ens.csv") \
            <(awk -F, 'NR > 1 { print $1, $2, $4 }' "$tmp/one_$k.csv") >/dev/null && ok ||
            bad "ensemble under a cylinder ($how): realisation $k differs from its own run"
    done
done
# and the flat strip's samples are not the cylinder's: the body is not dropped
expect 0 "flat body with an ensemble" -- "$ct" run -q "$tmp/r.ini" --set body.shape=flat \
    --set ensemble.realisations=4 --set output.what=realisations -o "$tmp/flat_ens.csv"
[ "$(awk -F, 'NR > 2 { print $5 }' "$tmp/flat_ens.csv")" != \
    "$(awk -F, 'NR > 2 { print $5 }' "$tmp/body_ens.csv")" ] && ok ||
    bad "the ensemble under a cylinder gave the flat strip's e"

# the same bytes for 1 and 2 threads and either split
OMP_NUM_THREADS=1 "$ct" run -q "$tmp/r.ini" -o "$tmp/t1.csv" || bad "1 thread"
"$ct" run -q "$tmp/r.ini" --set solver.threads=2 --set ensemble.split=rods -o "$tmp/rods.csv" || bad "split rods"
cmp -s "$tmp/t1.csv" "$tmp/ens.csv" && ok || bad "1 and 2 threads differ"
cmp -s "$tmp/rods.csv" "$tmp/ens.csv" && ok || bad "split = rods differs"

# job arrays: parts merged into the same bytes, in any order, both outputs
expect 0 "all realisations" -- "$ct" run -q "$tmp/r.ini" --set output.what=ensemble,realisations -o "$tmp/both.csv"
cmp -s "$tmp/both.csv" "$tmp/ens.csv" && ok || bad "ensemble with realisations differs"
[ "$(sed -n 2p "$tmp/both_realisations.csv")" = "realisation,impact,V_star,u_max_over_h0,e,V_star_crit,fx_clipped,fz_clipped" ] && ok || bad "realisations header"
head -1 "$tmp/both_realisations.csv" | grep -q "^# realisations of surface = random_cantor: fx = 1.5.*seed .*; impacts 2; solver.on_error = stop$" &&
    ok || bad "realisations identity line: $(head -1 "$tmp/both_realisations.csv")"
[ "$(wc -l <"$tmp/both_realisations.csv")" -eq $((23 * 14 + 2)) ] && ok || bad "one realisations row per sample"
expect 0 "part 0:5" -- "$ct" run -q "$tmp/r.ini" --realisations 0:5 -o "$tmp/p0.csv"
expect 0 "part 5:17" -- "$ct" run -q "$tmp/r.ini" --realisations 5:17 -o "$tmp/p1.csv"
expect 0 "part 17:23" -- "$ct" run -q "$tmp/r.ini" --realisations 17:23 -o "$tmp/p2.csv"
expect 0 "merge" -- "$ct" merge "$tmp/r.ini" "$tmp/p2.csv" "$tmp/p0.csv" "$tmp/p1.csv" --set output.what=ensemble,realisations -o "$tmp/m.csv"
cmp -s "$tmp/m.csv" "$tmp/ens.csv" && ok || bad "merged ensemble differs from one run"
cmp -s "$tmp/m_realisations.csv" "$tmp/both_realisations.csv" && ok || bad "merged realisations differ"
expect 2 "merge: a realisation missing" -- "$ct" merge "$tmp/r.ini" "$tmp/p0.csv" "$tmp/p2.csv" -o "$tmp/x.csv"
grep -q "the parts hold 154 rows, 11 realisations of 14 rows; the scene has ensemble.realisations = 23" "$tmp/err" && ok || bad "missing message: $(cat "$tmp/err")"
[ ! -e "$tmp/x.csv" ] && ok || bad "a failed merge left its output"
expect 2 "merge: a realisation twice" -- "$ct" merge "$tmp/r.ini" "$tmp/p0.csv" "$tmp/p0.csv" "$tmp/p1.csv" "$tmp/p2.csv" -o "$tmp/x.csv"
expect 2 "merge: parts of another scene" -- "$ct" merge "$tmp/r.ini" "$tmp/p0.csv" "$tmp/p1.csv" "$tmp/p2.csv" --set impact.V_star=1e-3 -o "$tmp/x.csv"
expect 2 "merge: not a realisations file" -- "$ct" merge "$tmp/r.ini" "$tmp/ens.csv" -o "$tmp/x.csv"
expect 2 "merge: no parts" -- "$ct" merge "$tmp/r.ini"
expect 0 "merge --help" -- "$ct" merge --help
expect 2 "--realisations out of range" -- "$ct" run "$tmp/r.ini" --realisations 5:24
expect 2 "--realisations malformed" -- "$ct" run "$tmp/r.ini" --realisations 5-7
expect 2 "--realisations empty" -- "$ct" run "$tmp/r.ini" --realisations 7:7

# a failed impact: stop names the lowest realisation; skip keeps rows and leaves them out
expect 2 "crushing speed stops the ensemble" -- "$ct" run -q "$tmp/r.ini" --set "impact.V_star=1e-3, 50" -o "$tmp/x.csv"
grep -q "realisation 0, V\* = 50, impact 1: .*crushed" "$tmp/err" && ok || bad "crush message: $(cat "$tmp/err")"
[ ! -e "$tmp/x.csv" ] && ok || bad "a stopped ensemble left its output"
expect 0 "crushing speed skipped" -- "$ct" run -q "$tmp/r.ini" --set "impact.V_star=1e-3, 50" --set solver.on_error=skip -o "$tmp/skip.csv"
awk -F, 'NR > 1 && $2 == 50 { n++; if ($3 != 0 || $4 != "") exit 1 } NR > 1 && $2 != 50 { m++; if ($3 != 23) exit 1 }
    END { exit !(n == 2 && m == 2) }' "$tmp/skip.csv" && ok || bad "skipped rows: $(cat "$tmp/skip.csv")"
"$ct" run -q "$tmp/r.ini" --set "impact.V_star=1e-3, 50" --set solver.on_error=skip --realisations 0:9 -o "$tmp/s0.csv" &&
    "$ct" run -q "$tmp/r.ini" --set "impact.V_star=1e-3, 50" --set solver.on_error=skip --realisations 9:23 -o "$tmp/s1.csv" &&
    "$ct" merge -q "$tmp/r.ini" "$tmp/s0.csv" "$tmp/s1.csv" --set "impact.V_star=1e-3, 50" --set solver.on_error=skip -o "$tmp/sm.csv" || bad "skip parts"
cmp -s "$tmp/sm.csv" "$tmp/skip.csv" && ok || bad "merged parts with failed rows differ"

# scene keys: each type's keys only with it, ranges, outputs
expect 2 "seed with type = cantor" -- "$ct" run "$tmp/r.ini" --set surface.type=cantor
grep -q "r.ini:7: surface.distribution = lognormal: only for surface.type = random_cantor" "$tmp/err" && ok || bad "seed message: $(cat "$tmp/err")"
expect 2 "representation with random_cantor" -- "$ct" run "$tmp/r.ini" --set surface.representation=segments
grep -q "surface.representation = segments: only for surface.type = cantor (not random_cantor)" "$tmp/err" && ok || bad "representation message: $(cat "$tmp/err")"
expect 2 "depth auto" -- "$ct" run "$tmp/r.ini" --set surface.depth=auto
grep -q "surface.depth = auto: not an integer (type = random_cantor needs an integer 0 <= depth <= 30)" "$tmp/err" && ok || bad "depth message: $(cat "$tmp/err")"
expect 2 "uniform spread >= 1" -- "$ct" run "$tmp/r.ini" --set surface.distribution=uniform --set surface.fx_spread=1
grep -q "surface.fx_spread = 1: must satisfy 0 <= spread < 1" "$tmp/err" && ok || bad "spread message: $(cat "$tmp/err")"
expect 2 "negative spread" -- "$ct" run "$tmp/r.ini" --set surface.fz_spread=-0.1
expect 2 "unknown distribution" -- "$ct" run "$tmp/r.ini" --set surface.distribution=gamma
expect 2 "negative seed" -- "$ct" run "$tmp/r.ini" --set surface.seed=-1
expect 2 "realisations 0" -- "$ct" run "$tmp/r.ini" --set ensemble.realisations=0
expect 2 "what = e with an ensemble" -- "$ct" run "$tmp/r.ini" --set output.what=e
expect 2 "ensemble and realisations to stdout" -- "$ct" run "$tmp/r.ini" --set output.what=ensemble,realisations
expect 2 "realisation with [ensemble]" -- "$ct" run "$tmp/r.ini" --set surface.realisation=3
expect 2 "bad split" -- "$ct" run "$tmp/r.ini" --set ensemble.split=threads

# one realisation, no [ensemble]: the e and profile outputs of any surface
sed '/^\[ensemble\]/,$d' "$tmp/r.ini" >"$tmp/one.ini"
expect 0 "one realisation" -- "$ct" run "$tmp/one.ini" --set surface.realisation=4 --set output.what=e,profile -o "$tmp/one.csv"
grep -q "random cantor rods, depth 9 (given), 1023 rods" "$tmp/err" && ok || bad "summary: $(cat "$tmp/err")"
[ "$(tail -n +2 "$tmp/one_profile.csv" | wc -l)" -eq 1023 ] && ok || bad "profile: one row per piece"
# realisation 4's first impacts are the ensemble's samples of realisation 4
awk -F, 'NR == FNR && NR > 1 && $1 == 1 { e[$2] = $4; next }
    FNR > 1 && $1 == 4 && $2 == 1 { n++; if (e[$3] != $5) exit 1 } END { exit n != 7 }' \
    "$tmp/one.csv" "$tmp/both_realisations.csv" && ok || bad "realisation 4 alone differs from its samples"
expect 2 "compare with random_cantor" -- "$ct" run "$tmp/one.ini" --set output.what=compare
expect 2 "--realisations without [ensemble]" -- "$ct" run "$tmp/one.ini" --realisations 0:1
printf '[surface]\nfx = 1.5\nfz = 1.3\nH = 10\n[material]\nE = 500\n[impact]\nV_star = 1e-3\n[ensemble]\nrealisations = 3\n' >"$tmp/c.ini"
expect 2 "[ensemble] with type = cantor" -- "$ct" run "$tmp/c.ini"
grep -q "c.ini:10: ensemble.realisations = 3: ensembles are of random surfaces: surface.type = random_cantor" "$tmp/err" && ok || bad "ensemble message: $(cat "$tmp/err")"

# started by a launcher (its environment) with no MPI module to load: one line, exit 1, no
# output (never every rank writing the whole file); MPI is loaded only under a launcher
expect 1 "launcher without the MPI module" -- env OMPI_COMM_WORLD_SIZE=2 \
    CANTACT_MPI_MODULE=/nonexistent/cantact-mpi.so "$ct" run -q "$tmp/r.ini" -o "$tmp/nompi.csv"
grep -q "started by an MPI launcher" "$tmp/err" && [ ! -e "$tmp/nompi.csv" ] && ok ||
    bad "launcher without the module: $(cat "$tmp/err")"
if [ -n "$mpirun" ]; then
    mpiopts=(--oversubscribe)
    [ "$(id -u)" -eq 0 ] && mpiopts+=(--allow-run-as-root)
    for n in 1 2 3; do
        OMP_NUM_THREADS=1 "$mpirun" "${mpiopts[@]}" -n $n "$ct" run -q "$tmp/r.ini" -o "$tmp/mpi$n.csv" >"$tmp/mpi.out" 2>&1 ||
            bad "mpirun -n $n: $(cat "$tmp/mpi.out")"
        cmp -s "$tmp/mpi$n.csv" "$tmp/ens.csv" && ok || bad "mpirun -n $n differs from one process"
    done
    OMP_NUM_THREADS=1 "$mpirun" "${mpiopts[@]}" -n 3 "$ct" run -q "$tmp/r.ini" --set output.what=ensemble,realisations -o "$tmp/mpib.csv" >"$tmp/mpi.out" 2>&1 ||
        bad "mpirun -n 3, both outputs: $(cat "$tmp/mpi.out")"
    cmp -s "$tmp/mpib_realisations.csv" "$tmp/both_realisations.csv" && ok || bad "mpirun -n 3: the samples are not in realisation order"
    OMP_NUM_THREADS=1 "$mpirun" "${mpiopts[@]}" -n 2 "$ct" run -q "$tmp/r.ini" --realisations 5:17 -o "$tmp/mpip1.csv" >"$tmp/mpi.out" 2>&1 ||
        bad "mpirun -n 2 --realisations: $(cat "$tmp/mpi.out")"
    cmp -s "$tmp/mpip1.csv" "$tmp/p1.csv" && ok || bad "mpirun -n 2 --realisations 5:17 differs"
    OMP_NUM_THREADS=1 "$mpirun" "${mpiopts[@]}" -n 3 "$ct" run -q "$tmp/r.ini" --set "impact.V_star=1e-3, 50" -o "$tmp/x.csv" >"$tmp/mpi.out" 2>&1
    [ $? -ne 0 ] && grep -q "realisation 0, V\* = 50" "$tmp/mpi.out" && [ ! -e "$tmp/x.csv" ] && ok ||
        bad "mpirun -n 3 with a crushing speed: $(cat "$tmp/mpi.out")"
fi

finish
