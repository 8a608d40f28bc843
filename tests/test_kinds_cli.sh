#!/usr/bin/env bash
# Every kind through the CLI against closed forms (docs/model.md §3, §11): one elastic-plastic
# rod of a measured profile and of a user's rod set, in time and in a bounce sequence, and the
# outputs only some kinds give (a profile's table, a rod set's profile).
#
# The rod: top 0, length L = H* = 1 m, area s = 1 m per unit depth, E = 100 Pa, sigma_y = 1 Pa
# (eps_y = 0.01, k = E s / L = 100 N/m^2, first yield at u = 0.01 m, plateau force 1 N/m), a
# body of 1 kg per metre. The profile x = 0, 1, 2 m, z = 0, -0.9, -0.9 m (no levelling) has it
# as its highest sample; its other two rods (tops 0.9 m) are never touched. Its scales:
# l0 = 3 m (three samples, 1 m each), h0 = Rt = 0.9 m, P_Y = sigma_y l0 = 3 N/m.
# Usage: test_kinds_cli.sh CANTACT SOURCE_DIR
source "$(dirname "${BASH_SOURCE[0]}")/preamble.sh"
ct=$1
src=$(cd "$2" && pwd)
# near WHAT GOT WANT [REL]: |got - want| <= rel |want| (default 1e-12)
near() {
    awk -v g="$2" -v w="$3" -v r="${4:-1e-12}" 'BEGIN { d = g - w; if (d < 0) d = -d;
        a = w < 0 ? -w : w; exit !(g != "" && d <= r * a) }' && ok ||
        bad "$1: got '$2', want $3"
}
# col FILE NAME ROW: the value of column NAME in data row ROW (1 = first after the header)
col() {
    awk -F, -v n="$2" -v r="$3" 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
        NR == r + 1 { print $(c[n]) }' "$1"
}

printf '0 0\n1 -0.9\n2 -0.9\n' >"$tmp/p3.txt"
cat >"$tmp/profile.ini" <<INI
[surface]
type = profile
file = p3.txt
unit = m
detrend = none
Hstar = 1
[material]
E = 100
sigma_y = 1
[impact]
mass = 1
velocity = 0.05
INI
cat >"$tmp/rods.ini" <<INI
[surface]
type = rods
rods = 0:1
unit = m
Hstar = 1
[material]
E = 100
sigma_y = 1
[impact]
mass = 1
velocity = 0.05
INI

# --- the impact in time, elastic: W = 1/2 m v^2 = 1.25e-3 J/m below the yield energy
# E s L eps_y^2 / 2 = 5e-3: u_max = v sqrt(m/k) = 0.005 m, P_peak = k u_max = 0.5 N/m,
# t_contact = pi sqrt(m/k) = pi/10 s
for kind in profile rods; do
    "$ct" run -q "$tmp/$kind.ini" --set output.what=time -o "$tmp/$kind.time.csv" ||
        bad "$kind: what = time exited $?"
    f=$tmp/$kind.time.csv
    near "$kind P_peak_N_per_m" "$(col "$f" P_peak_N_per_m 1)" 0.5
    near "$kind t_contact_s" "$(col "$f" t_contact_s 1)" 0.31415926535897932
    near "$kind e" "$(col "$f" e 1)" 1
done
# in the surface's own units: P / P_Y with P_Y = sigma_y l0 (3 N/m for the profile, 1 for the
# rod set: l0 = its area), u / h0 (h0 = 0.9 m; the rod set's tops are all 0: h0 = H* = 1 m)
near "profile P_peak_over_PY" "$(col "$tmp/profile.time.csv" P_peak_over_PY 1)" \
    0.16666666666666667
near "rods P_peak_over_PY" "$(col "$tmp/rods.time.csv" P_peak_over_PY 1)" 0.5
near "profile u_max_over_h0" "$(col "$tmp/profile.time.csv" u_max_over_h0 1)" \
    0.0055555555555555556
near "rods u_max_over_h0" "$(col "$tmp/rods.time.csv" u_max_over_h0 1)" 0.005

# --- a bounce from 0.2 m/s: W = 0.02 > 5e-3, the rod yields to eps = (W/(E s L) + eps_y^2/2)
# / eps_y = 0.025 (u_max = 0.025 m), e = sqrt(5e-3 / W) = 0.5, v_out = 0.1 m/s; contact time:
# elastic to u = 0.01 (pi/60 s), the plateau at 1 N/m from 0.2 cos(pi/6) m/s to rest
# (0.1 sqrt(3) s), and a quarter period back (pi/20 s). The rebound's energy is the rod's
# elastic capacity: every later impact is elastic, e = 1, pi/10 s on the unloading line.
t1=$(awk 'BEGIN { pi = atan2(0, -1); printf "%.17g", pi / 60 + 0.1 * sqrt(3) + pi / 20 }')
for kind in profile rods; do
    f=$tmp/$kind.bounce.csv
    "$ct" run -q "$tmp/$kind.ini" --set impact.sequence=bounce --set impact.velocity=0.2 \
        --set impact.impacts=3 --set output.what=bounce -o "$f" || bad "$kind: bounce exited $?"
    near "$kind bounce 1 v_in" "$(col "$f" v_in_m_per_s 1)" 0.2
    near "$kind bounce 1 e" "$(col "$f" e 1)" 0.5
    near "$kind bounce 1 v_out" "$(col "$f" v_out_m_per_s 1)" 0.1
    near "$kind bounce 1 t_contact" "$(col "$f" t_contact_s 1)" "$t1"
    near "$kind bounce 1 P_peak" "$(col "$f" P_peak_N_per_m 1)" 1
    near "$kind bounce 2 v_in" "$(col "$f" v_in_m_per_s 2)" "$(col "$f" v_out_m_per_s 1)" 0
    near "$kind bounce 2 e" "$(col "$f" e 2)" 1 1e-9
    near "$kind bounce 2 t_contact" "$(col "$f" t_contact_s 2)" 0.31415926535897932 1e-9
    near "$kind bounce 1 height" "$(col "$f" height_m 1)" "$(awk 'BEGIN { printf "%.17g", 0.01 / 2 / 9.81 }')"
done
near "profile u_max_over_h0 in a bounce" "$(col "$tmp/profile.bounce.csv" u_max_over_h0 1)" \
    0.027777777777777778

# --- a profile's table: its nodes are exact impacts, the same bits as cantact run at them
"$ct" table -q "$tmp/profile.ini" --set impact.velocity=0.01:0.5:2:log --set table.tolerance=1e-4 \
    -o "$tmp/table.csv" || bad "profile table exited $?"
grep -q "^# surface = profile: p3.txt (text), 3 rods" "$tmp/table.csv" && ok ||
    bad "profile table: no surface line: $(grep surface "$tmp/table.csv")"
V=$(awk -F, '/^[0-9]/ { printf "%s%s", s, $1; s = "," }' "$tmp/table.csv")
grep -v "^mass\|^velocity" "$tmp/profile.ini" >"$tmp/profile_v.ini"
"$ct" run -q "$tmp/profile_v.ini" --set "impact.V_star=$V" -o "$tmp/at_nodes.csv" ||
    bad "run at the table's nodes exited $?"
paste -d, <(awk -F, '/^[0-9]/ { print $2 }' "$tmp/table.csv") \
    <(awk -F, 'NR > 1 { print $4 }' "$tmp/at_nodes.csv") |
    awk -F, '$1 != $2 { exit 1 } END { exit NR < 3 }' && ok ||
    bad "profile table: e at the nodes differs from cantact run"

# --- a rod set's profile: every rod, its top and the top after the impacts (residual)
"$ct" run -q "$tmp/rods.ini" --set impact.velocity=0.2 --set output.what=e,profile \
    -o "$tmp/r.csv" || bad "rods profile exited $?"
head -1 "$tmp/r_profile.csv" | grep -q "^rod,top_over_h0,area_over_l0,length_over_h0,residual_top_over_h0$" &&
    ok || bad "rods profile header: $(head -1 "$tmp/r_profile.csv")"
# the plastic strain eps - eps_y = 0.015 of L = 1 m: the top now at 0.015 m (h0 = 1 m)
near "rods residual top" "$(col "$tmp/r_profile.csv" residual_top_over_h0 1)" 0.015

# --- rods with lengths, the second below the first's bottom: rod 1 (0:1:1) crushes at H* = 1 m
# before rod 2 (top 2 m) could be reached, so every impact is rod 1's alone (the bounce's first
# impact above: e = 0.5, P_peak = 1 N/m, the same contact time) and rod 2 stays untouched
sed 's|^rods = 0:1$|rods = 0:1:1, 2:1:10|; /^Hstar/d' "$tmp/rods.ini" >"$tmp/deep.ini"
"$ct" run -q "$tmp/deep.ini" --set impact.velocity=0.2 --set output.what=e,time,profile \
    -o "$tmp/deep.csv" || bad "rods below the crushed limit: exited $?"
near "deep rods e" "$(col "$tmp/deep.csv" e 1)" 0.5
near "deep rods P_peak_N_per_m" "$(col "$tmp/deep.csv" P_peak_N_per_m 1)" 1
near "deep rods t_contact_s" "$(col "$tmp/deep.csv" t_contact_s 1)" "$t1"
# h0 = the deepest top, 2 m: rod 1's plastic strain 0.015 of L = 1 m leaves its top at 0.0075 h0
near "deep rods residual top 1" "$(col "$tmp/deep_profile.csv" residual_top_over_h0 1)" 0.0075
near "deep rods residual top 2" "$(col "$tmp/deep_profile.csv" residual_top_over_h0 2)" 1
# a speed that crushes rod 1 is refused as outside the model: one line, exit 2, no file
"$ct" run -q "$tmp/deep.ini" --set impact.velocity=1.42 -o "$tmp/crushed.csv" 2>"$tmp/err"
[ $? -eq 2 ] && [ ! -e "$tmp/crushed.csv" ] && [ "$(wc -l <"$tmp/err")" -eq 1 ] &&
    grep -q "u_max >= H\* = 1" "$tmp/err" && ok || bad "deep rods crushed: $(cat "$tmp/err")"

# --- a rod file beside the scene, a header naming its columns
printf 'top,area\n0,1\n0.9,1\n0.9,1\n' >"$tmp/rods.csv"
sed 's|rods = 0:1|file = rods.csv|' "$tmp/rods.ini" >"$tmp/rodfile.ini"
"$ct" run -q "$tmp/rodfile.ini" --set output.what=time -o "$tmp/rf.csv" ||
    bad "rod file exited $?"
near "rod file P_peak_N_per_m" "$(col "$tmp/rf.csv" P_peak_N_per_m 1)" 0.5
near "rod file P_peak_over_PY (l0 = 3 m)" "$(col "$tmp/rf.csv" P_peak_over_PY 1)" \
    0.16666666666666667

# --- with a mass and a speed the e table carries the speeds: v_impact is the velocity given
# (0.05 m/s), v_rebound is e times it; a plastic impact (1.2 m/s, e < 1) checks the product
"$ct" run -q "$tmp/rods.ini" --set impact.velocity=0.05,1.2 -o "$tmp/speeds.csv" ||
    bad "speeds exited $?"
near "v_impact_m_per_s" "$(col "$tmp/speeds.csv" v_impact_m_per_s 1)" 0.05
near "v_rebound_m_per_s (elastic)" "$(col "$tmp/speeds.csv" v_rebound_m_per_s 1)" 0.05
near "v_impact_m_per_s" "$(col "$tmp/speeds.csv" v_impact_m_per_s 2)" 1.2
e2=$(col "$tmp/speeds.csv" e 2)
awk -v e="$e2" 'BEGIN { exit !(e > 0 && e < 0.999) }' || bad "the second impact is not plastic: e = $e2"
near "v_rebound_m_per_s = e v_impact" "$(col "$tmp/speeds.csv" v_rebound_m_per_s 2)" \
    "$(awk -v e="$e2" 'BEGIN { printf "%.17g", 1.2 * e }')"
# given V* alone there is no mass: no speeds in the scene's units
sed '/^mass/d; s/^velocity = .*/V_star = 0.01/' "$tmp/rods.ini" >"$tmp/vstar.ini"
"$ct" run -q "$tmp/vstar.ini" -o "$tmp/nospeed.csv" || bad "V* scene exited $?"
head -1 "$tmp/nospeed.csv" | grep -q "elastic$" && ok ||
    bad "a scene given in V* has other columns: $(head -1 "$tmp/nospeed.csv")"

finish kinds-cli
