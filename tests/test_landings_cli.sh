#!/usr/bin/env bash
# Landings (body.landings): a curved body struck at apex positions drawn where its face stays on
# the surface. Each landing is bit for bit the one run with body.position at its apex; the
# apexes are uniform over the region, whose bounds are computed here from the geometry; the
# statistics are those of the landings' rows (recomputed here); the same bytes for 1 and 2
# threads, for split runs merged back and (MPIRUN given) for 2 MPI ranks; a landing is a
# function of (seed, k) alone; what merge, run and the scene refuse, in one line each.
# Usage: test_landings_cli.sh CANTACT SOURCE_DIR [MPIRUN]
source "$(dirname "${BASH_SOURCE[0]}")/preamble.sh"
ct=$1
src=$2
mpirun=${3:-}

# 201 point rods on a line at x = 0 .. 200, tops in [0, 1], bottoms at H* = 2: a cylinder of
# R = 100 reaches rho = sqrt(H* (2 R - H*)) = sqrt(396) from its apex before the layer crushes,
# so the apexes are drawn over [rho, 200 - rho]
awk 'BEGIN { print "top,area,x"; for (k = 0; k <= 200; k++) printf "%.17g,1,%d\n", 0.5 * (1 + sin(k * 1.7)), k }' >"$tmp/rods.csv"
cat >"$tmp/c.ini" <<INI
[surface]
type = rods
file = rods.csv
Hstar = 2
[body]
shape = cylinder
radius = 100
landings = 400
seed = 5
[material]
E = 500
[impact]
V_star = 1e-3, 1e-2
impacts = 2
INI

expect 0 "landings of a cylinder" -- "$ct" run "$tmp/c.ini" --set output.what=e,landings -o "$tmp/c.csv"
has err "landings drawn over x 19.8997 .. 180.1" "the region"
head -1 "$tmp/c_landings.csv" | grep -q "^# landings on surface = rods: .*under a cylinder of R = 100.*; seed 5$" && ok ||
    bad "identity line: $(head -1 "$tmp/c_landings.csv")"
[ "$(sed -n 2p "$tmp/c_landings.csv")" = "landing,x,impact,V_star,u_max_over_h0,e,V_star_crit" ] && ok ||
    bad "landings header: $(sed -n 2p "$tmp/c_landings.csv")"
[ "$(wc -l <"$tmp/c_landings.csv")" -eq $((2 + 400 * 4)) ] && ok || bad "one row per landing, speed and impact"
# uniform over [rho, 200 - rho]: every apex inside; mean and variance of 400 draws within 4
# standard errors of the uniform law's (width w: mean w/2, variance w^2/12)
awk -F, 'NR > 2 && $3 == 1 && $4 == 0.001 { x = $2 - sqrt(396); w = 200 - 2 * sqrt(396)
        if (x < 0 || x > w) exit 1; n++; s += x; q += x * x }
    END { m = s / n; v = q / n - m * m
        if (n != 400) exit 1
        if ((m - w / 2) ^ 2 > 16 * w * w / 12 / n) exit 1
        if ((v - w * w / 12) ^ 2 > 16 * w ^ 4 / 180 / n) exit 1 }' "$tmp/c_landings.csv" && ok ||
    bad "the apexes are not uniform over [rho, 200 - rho]"
# the statistics of e over the landings, recomputed from the rows: n, mean, sd and the order
awk -F, 'NR == FNR { if (FNR > 2) { k = $3 "," $4; n[k]++; s[k] += $6; q[k] += $6 * $6 } next }
    FNR > 1 { k = $1 "," $2; m = s[k] / n[k]; sd = sqrt((q[k] - n[k] * m * m) / (n[k] - 1))
        if ($3 != 400 || n[k] != 400) exit 1
        if ((($4 - m) ^ 2) > 1e-28 || (($5 - sd) ^ 2) > 1e-20) exit 1
        if (!($7 <= $8 && $8 <= $9)) exit 1 }' "$tmp/c_landings.csv" "$tmp/c.csv" && ok ||
    bad "the statistics are not those of the landings' rows"
# landing k is the run with the apex at its x, to the bit (every impact and speed)
for k in 0 17 399; do
    x=$(awk -F, -v k=$k 'NR > 2 && $1 == k { print $2; exit }' "$tmp/c_landings.csv")
    expect 0 "the run at landing $k's apex" -- "$ct" run -q "$tmp/c.ini" --set body.landings=0 \
        --set body.position="$x" -o "$tmp/one.csv"
    diff <(awk -F, -v k=$k 'NR > 2 && $1 == k { print $3 "," $4 "," $5 "," $6 }' "$tmp/c_landings.csv") \
        <(awk -F, 'NR > 1 { print $1 "," $2 "," $3 "," $4 }' "$tmp/one.csv") >/dev/null && ok ||
        bad "landing $k differs from the run with body.position = $x"
done
# a landing is a function of (seed, k): the first 10 of 400 are the 10 of a run of 10; another
# seed draws others
expect 0 "10 landings" -- "$ct" run -q "$tmp/c.ini" --set body.landings=10 --set output.what=landings -o "$tmp/ten.csv"
cmp -s <(sed 1d "$tmp/ten.csv") <(sed 1d "$tmp/c_landings.csv" | head -41) && ok ||
    bad "landings 0 .. 9 depend on body.landings"
expect 0 "another seed" -- "$ct" run -q "$tmp/c.ini" --set body.landings=10 --set body.seed=6 --set output.what=landings -o "$tmp/ten6.csv"
cmp -s <(sed 1,2d "$tmp/ten.csv") <(sed 1,2d "$tmp/ten6.csv") && bad "body.seed changes nothing" || ok

# the same bytes for 1 and 2 threads, either split, parts merged back, and MPI ranks
expect 0 "one thread" -- "$ct" run -q "$tmp/c.ini" --set solver.threads=1 --set output.what=e,landings -o "$tmp/t1.csv"
cmp -s "$tmp/t1.csv" "$tmp/c.csv" && cmp -s "$tmp/t1_landings.csv" "$tmp/c_landings.csv" && ok ||
    bad "1 thread differs from 2"
expect 0 "split by rods" -- "$ct" run -q "$tmp/c.ini" --set ensemble.split=rods --set output.what=e,landings -o "$tmp/sr.csv"
cmp -s "$tmp/sr.csv" "$tmp/c.csv" && cmp -s "$tmp/sr_landings.csv" "$tmp/c_landings.csv" && ok ||
    bad "split by rods differs from split by landings"
expect 0 "part 0:150" -- "$ct" run -q "$tmp/c.ini" --landings 0:150 -o "$tmp/p1.csv"
expect 0 "part 150:400" -- "$ct" run -q "$tmp/c.ini" --landings 150:400 -o "$tmp/p2.csv"
expect 0 "merge" -- "$ct" merge -q "$tmp/c.ini" "$tmp/p2.csv" "$tmp/p1.csv" --set output.what=e,landings -o "$tmp/m.csv"
cmp -s "$tmp/m.csv" "$tmp/c.csv" && cmp -s "$tmp/m_landings.csv" "$tmp/c_landings.csv" && ok ||
    bad "the merged parts differ from one run"
sed '3s/^0,[0-9.e+-]*,/0,100,/' "$tmp/p1.csv" >"$tmp/moved.csv"
expect 2 "merge of a part with a moved apex" -- "$ct" merge -q "$tmp/c.ini" "$tmp/moved.csv" "$tmp/p2.csv" -o "$tmp/mm.csv"
has err "landing 0 at x = 100: this scene draws it at x = " "a moved apex"
expect 2 "merge under another seed" -- "$ct" merge -q "$tmp/c.ini" "$tmp/p1.csv" "$tmp/p2.csv" --set body.seed=9 -o "$tmp/mm.csv"
has err "not a part of this scene" "another seed"
expect 2 "merge of one part" -- "$ct" merge -q "$tmp/c.ini" "$tmp/p1.csv" -o "$tmp/mm.csv"
has err "the parts hold 600 rows, 150 landings of 4 rows; the scene has body.landings = 400" "a missing part"
[ ! -e "$tmp/mm.csv" ] && ok || bad "a refused merge left an output"
if [ -n "$mpirun" ]; then
    mpiopts=(--oversubscribe)
    [ "$(id -u)" -eq 0 ] && mpiopts+=(--allow-run-as-root)
    OMP_NUM_THREADS=1 "$mpirun" "${mpiopts[@]}" -n 2 "$ct" run -q "$tmp/c.ini" --set output.what=e,landings \
        -o "$tmp/mpi.csv" >"$tmp/mpi.out" 2>&1 || bad "mpirun -n 2: $(cat "$tmp/mpi.out")"
    cmp -s "$tmp/mpi.csv" "$tmp/c.csv" && cmp -s "$tmp/mpi_landings.csv" "$tmp/c_landings.csv" && ok ||
        bad "mpirun -n 2 differs from one process"
fi

# a sphere on a periodic map: x and y, anywhere in one period (the 128 x 128 map at 1 um, its
# grid from -0.5 um), each landing the run at its apex
cp "$src/examples/data/map128.x3p" "$tmp/"
cat >"$tmp/s.ini" <<INI
[surface]
type = profile
file = map128.x3p
H = 10
periodic = true
[body]
shape = sphere
radius = 2.5e-3
landings = 6
seed = 1
[material]
E = 2e11
sigma_y = 4e8
[impact]
mass = 5.14e-4
velocity = 1e-3, 0.1
INI
expect 0 "landings of a sphere" -- "$ct" run "$tmp/s.ini" --set output.what=landings -o "$tmp/s.csv"
[ "$(sed -n 2p "$tmp/s.csv")" = "landing,x,y,impact,V_star,u_max_over_h0,e,V_star_crit" ] && ok ||
    bad "sphere landings header: $(sed -n 2p "$tmp/s.csv")"
awk -F, 'NR > 2 { if ($2 < -5e-7 || $2 >= 1.275e-4 || $3 < -5e-7 || $3 >= 1.275e-4) exit 1 }' "$tmp/s.csv" && ok ||
    bad "an apex outside the map's period"
xy=$(awk -F, 'NR > 2 && $1 == 4 { print $2 ", " $3; exit }' "$tmp/s.csv")
expect 0 "the run at landing 4's apex" -- "$ct" run -q "$tmp/s.ini" --set body.landings=0 --set body.position="$xy" -o "$tmp/s4.csv"
diff <(awk -F, 'NR > 2 && $1 == 4 { print $5 "," $6 "," $7 }' "$tmp/s.csv") \
    <(awk -F, 'NR > 1 { print $2 "," $3 "," $4 }' "$tmp/s4.csv") >/dev/null && ok ||
    bad "sphere landing 4 differs from the run with body.position = $xy"

# a table of the landings' statistics: the mean and e at each p per node; at a node (a grid
# speed) they are the landings' own mean and type-7 quantiles, recomputed here from the rows of
# a run at that speed; the C reader evaluates it between the columns, non-decreasing in p
expect 0 "a table of landings" -- "$ct" table "$tmp/c.ini" --set impact.impacts=1 \
    --set impact.V_star=1e-3,1e-2 --set table.tolerance=1e-3 --set body.landings=100 -o "$tmp/lt.csv"
has err "table of the mean and 21 quantiles of e over body.landings = 100" "the table's summary"
grep -q "^# quantiles = 21 " "$tmp/lt.csv" && ok || bad "no # quantiles line"
for node in 40 300; do
    row=$(awk -F, '/^V_star,/ { h = 1; next } h && ++k == n' n=$node "$tmp/lt.csv")
    V=${row%%,*}
    expect 0 "the landings at node $node's speed" -- "$ct" run -q "$tmp/c.ini" --set impact.impacts=1 \
        --set impact.V_star="$V" --set body.landings=100 --set output.what=landings -o "$tmp/lv.csv"
    awk -F, 'NR > 2 { print $6 }' "$tmp/lv.csv" | sort -g >"$tmp/lv.sorted"
    awk -v row="$row" '{ e[n++] = $1; s += $1 }
        function q(p,   h, f) { h = (n - 1) * p; f = int(h); return f + 1 < n ? e[f] + (h - f) * (e[f + 1] - e[f]) : e[n - 1] }
        END { split(row, r, ","); d = r[2] - s / n; if (d * d > 1e-24) exit 1
            # columns: e_p0.01 is field 4, e_p0.05 field 6, ..., e_p0.5 field 24, e_p0.99 field 44
            if ((r[4] - q(0.01)) ^ 2 > 1e-24 || (r[24] - q(0.5)) ^ 2 > 1e-24 || (r[44] - q(0.99)) ^ 2 > 1e-24) exit 1 }' \
        "$tmp/lv.sorted" && ok || bad "node $node: the table's mean or quantiles are not the landings' own at V* = $V"
done

# with a mass, the statistics end with the impact speed in m/s: the e table's own
expect 0 "the ball's landings' statistics" -- "$ct" run -q "$tmp/s.ini" --set body.landings=3 -o "$tmp/ss.csv"
expect 0 "the ball's e table" -- "$ct" run -q "$tmp/s.ini" --set body.landings=0 -o "$tmp/se.csv"
head -1 "$tmp/ss.csv" | grep -q ',e_at_position,v_impact_m_per_s$' && ok || bad "no v_impact_m_per_s last: $(head -1 "$tmp/ss.csv")"
paste -d, <(awk -F, 'NR > 1 { print $NF }' "$tmp/ss.csv") \
    <(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "v_impact_m_per_s") c = i; next } { print $c }' "$tmp/se.csv") |
    awk -F, '{ n++; d = ($1 - $2) / $2; if (d * d > 1e-24 || $2 == "") exit 1 } END { exit n != 2 }' &&
    ok || bad "the statistics' speeds are not the e table's (to 1e-12)"

# a force on a plane is in N (l0 an area), on a line in N per metre of depth
expect 0 "the ball's time columns" -- "$ct" run -q "$tmp/s.ini" --set body.landings=0 --set output.what=e,time -o "$tmp/st.csv"
head -1 "$tmp/st.csv" | tr ',' '\n' | grep -qx P_peak_N && ok || bad "a ball's peak force not in N: $(head -1 "$tmp/st.csv")"
expect 0 "the ball's bounces" -- "$ct" run -q "$tmp/s.ini" --set body.landings=0 --set impact.sequence=bounce \
    --set impact.velocity=0.1 --set impact.impacts=2 -o "$tmp/sb.csv"
head -1 "$tmp/sb.csv" | tr ',' '\n' | grep -qx P_peak_N && ok || bad "a ball's bounces: peak force not in N: $(head -1 "$tmp/sb.csv")"
expect 0 "a strip's time columns" -- "$ct" run -q "$src/examples/scenes/cantor.ini" --set impact.V_star= \
    --set impact.mass=1 --set impact.velocity=0.01 --set output.what=e,time -o "$tmp/ct.csv"
head -1 "$tmp/ct.csv" | tr ',' '\n' | grep -qx P_peak_N_per_m && ok || bad "a strip's peak force not in N/m: $(head -1 "$tmp/ct.csv")"

# with a mass the plain e table carries the contact time and the peak force in the scene's units:
# the time columns' own values (what = e,time), N for a ball
for col in t_contact_s P_peak_N; do
    diff <(awk -F, -v n=$col 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == n) c = i; next } { print c ? $c : "none" }' "$tmp/se.csv") \
        <(awk -F, -v n=$col 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == n) c = i; next } { print c ? $c : "none" }' "$tmp/st.csv") >/dev/null &&
        ! grep -q none <(awk -F, -v n=$col 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == n) c = i; next } { print c ? $c : "none" }' "$tmp/se.csv") &&
        ok || bad "the e table's $col is not the time columns'"
done
expect 0 "a strip's e table" -- "$ct" run -q "$src/examples/scenes/cantor.ini" --set impact.V_star= \
    --set impact.mass=1 --set impact.velocity=0.01 -o "$tmp/ce.csv"
head -1 "$tmp/ce.csv" | grep -q ',v_rebound_m_per_s,t_contact_s,P_peak_N_per_m$' && ok ||
    bad "a strip's e table: $(head -1 "$tmp/ce.csv")"

# refusals, one line each, nothing written
expect 2 "landings of the flat strip" -- "$ct" run -q "$tmp/c.ini" --set body.shape=flat -o "$tmp/no.csv"
has err "landings need a curved body" "flat strip"
expect 2 "landings with time" -- "$ct" run -q "$tmp/c.ini" --set output.what=e,time -o "$tmp/no.csv"
has err "with body.landings each item must be e" "time"
expect 2 "landings output without landings" -- "$ct" run -q "$tmp/c.ini" --set body.landings=0 --set output.what=landings -o "$tmp/no.csv"
has err "landings needs body.landings" "no landings"
expect 2 "--landings beyond body.landings" -- "$ct" run -q "$tmp/c.ini" --landings 0:401 -o "$tmp/no.csv"
has err "must satisfy 0 <= a < b <= body.landings = 400" "range"
expect 2 "--realisations on landings" -- "$ct" run -q "$tmp/c.ini" --realisations 0:2 -o "$tmp/no.csv"
expect 2 "no room to land" -- "$ct" run -q "$tmp/c.ini" --set body.radius=1e4 -o "$tmp/no.csv"
has err "no apex keeps its face on the surface" "no room"
expect 2 "landings on random realisations" -- "$ct" run -q "$src/scripts/scenes/default.ini" \
    --set surface.type=random_cantor --set body.shape=cylinder --set body.radius=10 \
    --set body.landings=3 -o "$tmp/no.csv"
[ ! -e "$tmp/no.csv" ] && ok || bad "a refused run left an output"
finish landings-cli
