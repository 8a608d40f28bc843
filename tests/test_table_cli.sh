#!/usr/bin/env bash
# cantact table: the output's header and rows, the [table] keys' one-line errors naming
# file:line, exit 1 and no file when the tolerance cannot be met, a random surface, a table of
# an ensemble's statistics (its mean at a node the ensemble's own), the table's first node,
# V*_c and end against cantact run.
# Usage: test_table_cli.sh CANTACT SOURCE_DIR
source "$(dirname "${BASH_SOURCE[0]}")/preamble.sh"
ct=$1
src=$2

cat >"$tmp/s.ini" <<INI
[surface]
fx = 1.5
fz = 1.3
H = 10
[material]
E = 500
[impact]
V_star = 1e-5, 1e-3, 1e-2
[table]
tolerance = 1e-5
INI

expect 0 "table --help" -- "$ct" table --help
has out "Usage: cantact table" "table --help"
expect 0 "main help lists table" -- "$ct" --help
has out "  table SCENE" "main help"
expect 0 "table to a file" -- "$ct" table "$tmp/s.ini" -o "$tmp/t.csv"
has err "worst |e_table - e| = " "summary on stderr"
for key in "interpolation = monotone_cubic" "V_star_crit = " "tolerance = 1.0000000000000001e-05" \
    "worst_error = " "scene = $tmp/s.ini" "units: V_star = sqrt(m v^2 / (2 l0 E h0))"; do
    grep -q "^# $key" "$tmp/t.csv" && ok || bad "header line '# $key'"
done
grep -q "^V_star,e,de_dlnV_star$" "$tmp/t.csv" && ok || bad "column header"
grep -q v_per_V_star "$tmp/t.csv" && bad "v_per_V_star without mass" || ok
# the claim: worst error <= tolerance; nodes increasing; e in [0, 1]; ends are the range
awk -F' = ' '/^# worst_error =/ { if (!($2 + 0 <= 1e-5)) exit 1 }' "$tmp/t.csv" && ok || bad "worst error above the tolerance"
awk -F, '/^[0-9]/ { if (n && !($1 > p)) exit 1; if (!($2 >= 0 && $2 <= 1)) exit 1; p = $1; n++; first = first ? first : $1; last = $1 }
         END { if (n < 10 || first != 1.0000000000000001e-05 || last != 0.01) exit 1 }' "$tmp/t.csv" && ok ||
    bad "rows: increasing, e in [0, 1], ends 1e-5 and 1e-2"
# V*_c is a node, with e = 1, and the run's V*_c
vc=$(awk -F' = ' '/^# V_star_crit/ { print $2 }' "$tmp/t.csv")
grep -q "^$vc,1,0$" "$tmp/t.csv" && ok || bad "V*_c = $vc is a node with e = 1"
"$ct" run -q "$tmp/s.ini" -o "$tmp/run.csv"
[ "$(awk -F, 'NR == 2 { print $7 }' "$tmp/run.csv")" = "$vc" ] && ok || bad "V*_c as cantact run's"
# e at the last node as the run's e at V* = 1e-2 (same depth: auto from the smallest speed)
[ "$(awk -F, '/^0.01,/ { print $2 }' "$tmp/t.csv")" = "$(awk -F, 'NR == 4 { print $4 }' "$tmp/run.csv")" ] &&
    ok || bad "e at V* = 1e-2 as cantact run's"
# linear needs more nodes than the cubic for the same tolerance
expect 0 "linear" -- "$ct" table -q "$tmp/s.ini" --set table.interpolation=linear -o "$tmp/lin.csv"
[ "$(grep -c '^[0-9]' "$tmp/lin.csv")" -gt "$(grep -c '^[0-9]' "$tmp/t.csv")" ] && ok || bad "linear has more nodes"
has lin.csv "^# interpolation = linear" "linear header"
# stdout
expect 0 "table to stdout" -- "$ct" table -q "$tmp/s.ini"
grep -q "^V_star,e,de_dlnV_star$" "$tmp/out" && ok || bad "stdout table"

# progress: on a terminal (script gives the program one) the exact impacts computed of those
# planned so far, up to the summary's count; off a terminal nothing but the summary; the table
# the same bytes either way
command -v script >/dev/null || fail "script (util-linux) is needed for the terminal checks"
script -qec "'$ct' table '$tmp/s.ini' --set table.tolerance=1e-8 -o '$tmp/tty.csv'" /dev/null \
    >"$tmp/tty" && ok || bad "table on a terminal"
n=$(sed -n 's/.*; \([0-9]*\) exact impacts, .*/\1/p' "$tmp/tty")
tr '\r' '\n' <"$tmp/tty" | grep -q "^$n of $n exact impacts (more while intervals fail)" && ok ||
    bad "table: no progress on a terminal: $(cat -v "$tmp/tty" | head -c 300)"
expect 0 "table off a terminal" -- "$ct" table "$tmp/s.ini" --set table.tolerance=1e-8 -o "$tmp/pipe.csv"
[ "$(wc -l <"$tmp/err")" -eq 1 ] && ! grep -q "exact impacts (more" "$tmp/err" && ok ||
    bad "table: progress off a terminal: $(cat -v "$tmp/err")"
cmp -s "$tmp/tty.csv" "$tmp/pipe.csv" && ok || bad "the table differs with progress shown"

# the thread count changes no byte
OMP_NUM_THREADS=1 "$ct" table -q "$tmp/s.ini" -o "$tmp/t1.csv"
OMP_NUM_THREADS=2 "$ct" table -q "$tmp/s.ini" --set solver.threads=2 -o "$tmp/t2.csv"
sed -i 's|^# scene = .*||' "$tmp/t1.csv" "$tmp/t2.csv"
cmp -s "$tmp/t1.csv" "$tmp/t2.csv" && ok || bad "tables differ between 1 and 2 threads"

# the tolerance cannot be met: exit 1, no file
expect 1 "max_nodes too small" -- "$ct" table "$tmp/s.ini" --set table.max_nodes=20 -o "$tmp/none.csv"
has err "max_nodes = 20" "max_nodes message"
[ -e "$tmp/none.csv" ] && bad "a failed table left a file" || ok
# a range that crushes the layer: exit 2
expect 2 "crushed layer" -- "$ct" table "$tmp/s.ini" --set table.V_star=1e-3:1 -o "$tmp/none.csv"
has err "crushed" "crushed message"

# [table] keys: one line naming file:line, the key and the range
i=0
while IFS='|' read -r line message; do
    i=$((i + 1))
    sed "s/^tolerance = 1e-5$/$line/" "$tmp/s.ini" >"$tmp/b$i.ini"
    expect 2 "bad key $line" -- "$ct" table "$tmp/b$i.ini"
    has err "b$i.ini:10: table.$message" "bad key $line"
done <<'BAD'
tolerance = 0|tolerance = 0: must satisfy 1e-13 <= tolerance < 0.5
tolerance = 1e-5x|tolerance = 1e-5x: not a finite number
tolerance = nan|tolerance = nan: not a finite number
V_star = 1e-3|V_star = 1e-3: expected from:to
V_star = 1e-2:1e-3|V_star = 1e-2:1e-3: expected from:to with 0 < from < to
V_star = 0:1e-3|V_star = 0:1e-3: expected from:to with 0 < from < to
V_star = a:1|V_star = a:1: not a finite number
V_star = 1:2:3|V_star = 1:2:3: expected from:to
interpolation = cubic|interpolation = cubic: must be monotone_cubic or linear
max_nodes = 1|max_nodes = 1: must satisfy 2 <= max_nodes
max_nodes = 1.5|max_nodes = 1.5: not an integer
check_points = 0|check_points = 0: must satisfy 1 <= check_points <= 1000
frob = 1|frob: unknown key
BAD
printf '[tabel]\nx = 1\n' >>"$tmp/b1.ini"
expect 2 "unknown section" -- "$ct" table "$tmp/b1.ini"
has err "unknown section (did you mean \[table\]?) (known: surface, body, material, impact, solver, output, ensemble, table, fit)" "section list"
# one speed in [impact] and no table.V_star: no range
sed 's/^V_star = .*/V_star = 1e-3/' "$tmp/s.ini" >"$tmp/one.ini"
expect 2 "no range" -- "$ct" table "$tmp/one.ini"
has err "table: V\* range" "no range message"

# a random surface (one realisation) tabulates; an ensemble is refused
cat >"$tmp/r.ini" <<INI
[surface]
type = random_cantor
fx = 1.5
fz = 1.3
H = 10
depth = 8
fx_spread = 0.1
seed = 3
[material]
E = 500
[impact]
V_star = 1e-4:1e-2:3:log
[table]
tolerance = 1e-4
INI
expect 0 "random surface" -- "$ct" table -q "$tmp/r.ini" -o "$tmp/r.csv"
has r.csv "^# surface = random_cantor" "random header"
printf '[ensemble]\nrealisations = 4\n' >>"$tmp/r.ini"
expect 0 "a table of the ensemble" -- "$ct" table "$tmp/r.ini" --set table.tolerance=1e-2 \
    --set table.grid=2000 -o "$tmp/re.csv"
has err "table of the mean and 21 quantiles of e over ensemble.realisations = 4" "ensemble summary"
has re.csv "^# quantiles = 21 " "ensemble table's quantiles"
# a node's mean e is the ensemble's mean at that speed (cantact run's statistics)
nodes=$(sed -n 's/^# nodes = \([0-9]*\).*/\1/p' "$tmp/re.csv")
row=$(awk -F, -v m=$((nodes / 2)) '/^V_star,/ { h = 1; next } h && ++k == m' "$tmp/re.csv")
expect 0 "the ensemble at the middle node" -- "$ct" run -q "$tmp/r.ini" --set impact.V_star="${row%%,*}" \
    --set impact.impacts=1 -o "$tmp/rm.csv"
awk -F, -v row="$row" 'NR == 2 { split(row, r, ","); d = r[2] - $4; exit !(d * d < 1e-26) }' "$tmp/rm.csv" &&
    ok || bad "the middle node: mean e $(echo "$row" | cut -d, -f2) is not the ensemble's $(sed -n 2p "$tmp/rm.csv" | cut -d, -f4)"
# a tolerance the grid cannot resolve: refused (every interval keeps a point to check), no file
expect 1 "tolerance beyond the grid" -- "$ct" table "$tmp/r.ini" --set table.tolerance=1e-9 \
    --set table.grid=50 -o "$tmp/fine.csv"
has err "not met at the grid's resolution" "tolerance beyond the grid"
[ ! -e "$tmp/fine.csv" ] && ok || bad "a table that missed its tolerance was written"
expect 2 "quantiles above 1" -- "$ct" table "$tmp/r.ini" --set table.quantiles=0.5,1.5 -o "$tmp/no.csv"
has err "must be probabilities in (0, 1]" "quantiles above 1"

finish
