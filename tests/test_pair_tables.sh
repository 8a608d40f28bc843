#!/usr/bin/env bash
# dem/pair_tables.py (docs/dem.md, "e(v) for a pair of particles"): one table per pair of
# particle types, from scripts/scenes/dem_pair_table.ini (a sphere on an areal map), for the
# pair's reduced radius R1 R2/(R1 + R2) and reduced mass m1 m2/(m1 + m2). Two types of different
# radius and density (a coarse table: this checks what the tables are for, not their nodes):
# the three files I <= J and no other; each table's sphere is the pair's reduced radius (its
# header), and its v_per_V_star the pair's reduced mass: V* = sqrt(m v^2 / (2 l0 E h0)) on one
# surface, so v_per_V_star^2 m is the same for every pair and for the scene at its own mass
# (computed here by awk from R and rho, not by the script); bad input refused in one line.
# The DEM engines' runs on such tables are in dem/lammps/test.sh and dem/yade/test.sh.
# Usage: test_pair_tables.sh CANTACT SOURCE_ROOT PYTHON
source "$(dirname "${BASH_SOURCE[0]}")/preamble.sh"
set -o pipefail
ct=$1 src=$2 py=$3
pt=("$py" "$src/dem/pair_tables.py")
scene=$src/scripts/scenes/dem_pair_table.ini
coarse=(--set table.tolerance=1e-2 --set impact.velocity=0.01:0.03:2)
header() { sed -n "s/^# $1 = \\([^ ]*\\).*/\\1/p" "$2"; }

# the scene at its own mass: the reference v_per_V_star^2 m
"$ct" table -q "$scene" "${coarse[@]}" -o "$tmp/scene.csv" || fail "cantact table $scene"
m_scene=$(sed -n 's/^mass *= *\([^ ;]*\).*/\1/p' "$scene")
k_scene=$(awk -v v="$(header v_per_V_star "$tmp/scene.csv")" -v m="$m_scene" 'BEGIN { printf "%.17g", v * v * m }')

# two types: 2 mm steel, 3 mm at 1200 kg/m^3
expect 0 "pair_tables.py, two types" -- "${pt[@]}" "$scene" --type 2e-3:7850 --type 3e-3:1200 \
    --cantact "$ct" "${coarse[@]}" -o "$tmp/t"
cp "$tmp/out" "$tmp/said"
got=$(cd "$tmp/t" && ls | tr '\n' ' ')
[ "$got" = "e_1_1.csv e_1_2.csv e_2_2.csv " ] && ok || bad "tables written: '$got', expected e_1_1 e_1_2 e_2_2"
for p in "1 1" "1 2" "2 2"; do
    set -- $p
    f=$tmp/t/e_$1_$2.csv
    [ -s "$f" ] || { bad "e_$1_$2.csv: not written"; continue; }
    # R and rho of each type; the pair's reduced radius and mass, here
    read -r r_red m_red <<<"$(awk -v i="$1" -v j="$2" 'BEGIN {
        r[1] = 2e-3; d[1] = 7850; r[2] = 3e-3; d[2] = 1200; pi = atan2(0, -1)
        mi = d[i] * 4 / 3 * pi * r[i] ^ 3; mj = d[j] * 4 / 3 * pi * r[j] ^ 3
        printf "%.17g %.17g", r[i] * r[j] / (r[i] + r[j]), mi * mj / (mi + mj) }')"
    r_tab=$(sed -n 's/^# surface = .*under a sphere of R = \([^,]*\),.*/\1/p' "$f")
    awk -v a="$r_tab" -v b="$r_red" 'BEGIN { exit !(a != "" && (a - b) ^ 2 <= (1e-14 * b) ^ 2) }' &&
        ok || bad "e_$1_$2.csv: the sphere's R '$r_tab', the pair's reduced radius is $r_red"
    k=$(awk -v v="$(header v_per_V_star "$f")" -v m="$m_red" 'BEGIN { printf "%.17g", v * v * m }')
    awk -v a="$k" -v b="$k_scene" 'BEGIN { exit !((a - b) ^ 2 <= (1e-12 * b) ^ 2) }' &&
        ok || bad "e_$1_$2.csv: v_per_V_star^2 m_red = $k, the scene's v_per_V_star^2 m = $k_scene: not the pair's reduced mass ($m_red kg)"
    grep -q "^types $1 $2: R_red $(printf '%.6g' "$r_red") m, m_red $(printf '%.6g' "$m_red") kg: " "$tmp/said" &&
        ok || bad "types $1 $2: its line, R_red and m_red: $(cat "$tmp/said")"
done
echo "ok: pair_tables.py: e_1_1, e_1_2, e_2_2, each for its pair's reduced radius and mass"

# the scene's own pair (2 mm and 3 mm steel): its 1-2 table is the scene's (-q: nothing said)
expect 0 "pair_tables.py, the scene's pair" -- "${pt[@]}" "$scene" --type 2e-3:7850 \
    --type 3e-3:7850 --cantact "$ct" "${coarse[@]}" -q -o "$tmp/steel"
[ ! -s "$tmp/out" ] && ok || bad "-q: stdout '$(cat "$tmp/out")'"
awk -F, -v f="$tmp/scene.csv" 'BEGIN { while ((getline l < f) > 0) if (l !~ /^#/) { n++; split(l, c, ","); e[n] = c[2] } }
    !/^#/ { k++; d = $2 - e[k]; if (d < 0) d = -d; if (d > w) w = d }
    END { exit !(k == n && k > 2 && w <= 1e-12) }' "$tmp/steel/e_1_2.csv" && ok ||
    bad "the 1-2 table of 2 mm and 3 mm steel differs from scripts/scenes/dem_pair_table.ini's"

# bad input: one line, exit 2 (arguments) or 1 (cantact's refusal, named with the pair)
expect 2 "no --type" -- "${pt[@]}" "$scene" --cantact "$ct" -o "$tmp/x"
expect 2 "--type without a density" -- "${pt[@]}" "$scene" --type 2e-3 --cantact "$ct" -o "$tmp/x"
has err "give RADIUS:DENSITY" "--type 2e-3"
expect 2 "--type of a zero density" -- "${pt[@]}" "$scene" --type 2e-3:0 --cantact "$ct" -o "$tmp/x"
expect 2 "--type of words" -- "${pt[@]}" "$scene" --type a:b --cantact "$ct" -o "$tmp/x"
expect 2 "--type nan" -- "${pt[@]}" "$scene" --type nan:7850 --cantact "$ct" -o "$tmp/x"
expect 2 "--set of a key it sets" -- "${pt[@]}" "$scene" --type 2e-3:7850 --cantact "$ct" \
    --set impact.mass=1 -o "$tmp/x"
has err "sets impact.mass itself" "--set impact.mass"
expect 2 "no scene" -- "${pt[@]}" "$tmp/none.ini" --type 2e-3:7850 --cantact "$ct" -o "$tmp/x"
expect 2 "no cantact" -- "${pt[@]}" "$scene" --type 2e-3:7850 --cantact "$tmp/none" -o "$tmp/x"
expect 1 "a line surface" -- "${pt[@]}" "$src/scripts/scenes/dem_table.ini" --type 2e-3:7850 \
    --cantact "$ct" -o "$tmp/x"
has err "types 1 1 (R 0.001 m, m 0.000131528 kg): cantact table exit 2: cantact: body.shape = sphere" \
    "a line surface: cantact's refusal named with the pair"
expect 0 "--help" -- "${pt[@]}" --help
has out "reduced mass m_IJ = m_I m_J" "--help"
finish test_pair_tables
