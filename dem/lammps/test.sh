#!/bin/sh
# The LAMMPS test of gran/hooke/history/cantact (README.md): installs Debian 12's LAMMPS and the
# build tools when missing, builds the add-on, writes the e(V*) table with the project's CLI,
# and runs head-on collisions of 2 mm steel spheres in the stock lmp (collide_test.py says what
# it checks); oblique impacts of unequal spheres against an ODE of the same spring-dashpot
# (oblique_test.py); and two particle types with a table per type pair, written by
# dem/pair_tables.py for each pair's reduced radius and mass (pairs_test.py); and scatter, e drawn
# per contact from a table of samples, checked by Kolmogorov-Smirnov (scatter_test.py). Exit 0
# only when every check passes.
#
#   dem/lammps/test.sh [PATH/TO/cantact]     (default build/cantact of this checkout)
#
# KEEP=1 keeps the work directory (inputs, dumps) and prints its name.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../.." && pwd)
cantact=${1:-$repo/build/cantact}
cd "$repo"
t_all=$(date +%s.%N)
elapsed() { awk -v a="$1" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }'; }

# ---- install what is missing ----
pkgs="lammps liblammps-dev python3-lammps libopenmpi-dev openmpi-bin g++ gcc pkg-config librandom123-dev python3 python3-numpy python3-scipy"
missing=""
for p in $pkgs; do
    s=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
    [ "$s" = "install ok installed" ] || missing="$missing $p"
done
if [ -n "$missing" ]; then
    sudo=""
    [ "$(id -u)" -eq 0 ] || sudo=sudo
    echo "test.sh: installing:$missing"
    t=$(date +%s.%N)
    # shellcheck disable=SC2086
    if ! $sudo apt-get install -y --no-install-recommends $missing; then
        $sudo apt-get update
        # shellcheck disable=SC2086
        $sudo apt-get install -y --no-install-recommends $missing
    fi
    echo "test.sh: install: $(elapsed "$t") s"
else
    echo "test.sh: lammps, liblammps-dev, python3-lammps, MPI and compilers already installed"
fi
t_start=$(date +%s.%N)
[ -x "$cantact" ] || { echo "test.sh: $cantact: not an executable (build the project: meson compile -C build)" >&2; exit 1; }

work=$(mktemp -d "${TMPDIR:-/tmp}/cantact-lammps.XXXXXX")
if [ "${KEEP:-0}" = 1 ]; then
    echo "test.sh: work directory $work (kept)"
else
    trap 'rm -rf "$work"' EXIT
fi

status=0

# ---- build ----
t=$(date +%s.%N)
"$here/build.sh" "$work/build"
echo "test.sh: build: $(elapsed "$t") s"
# the same style with its own copy of the e <-> zeta relations (used when cantact_table.h lacks
# ct_tab_zeta_of_e): checked too, at dt only
EXTRA_CXXFLAGS=-DCANTACT_LOCAL_ZETA "$here/build.sh" "$work/build-local" >/dev/null
cc -O2 -Wall -I"$repo/include" "$here/e_of_speed.c" -o "$work/e_of_speed" -lm

# ---- the table (SI units, the [impact] mass gives v_per_V_star) ----
t=$(date +%s.%N)
"$cantact" table scripts/scenes/dem_table.ini -o "$work/e_table.csv"
echo "test.sh: table: $(elapsed "$t") s"

# ---- the example, from another directory: found, its log where asked, nothing left behind ----
t=$(date +%s.%N)
mkdir "$work/elsewhere"
had_log=0
[ ! -e "$repo/log.lammps" ] || had_log=1
ratio() { sed -n 's/^rebound ratio (v2 - v1) \/ v = //p' "$1"; }
(cd "$work/elsewhere" && "$here/two_spheres.sh" ../e_table.csv --lib "$work/build/libcantact_lammps.so" \
    --log "$work/two.log" >"$work/two.out" 2>&1) || { echo "test.sh: FAIL: two_spheres.sh from another directory" >&2; status=1; }
lmp -nocite -log none -in dem/lammps/in.two_spheres -var table "$work/e_table.csv" \
    -var lib "$work/build/libcantact_lammps.so" >"$work/root.out" 2>&1
r1=$(ratio "$work/two.out") r2=$(ratio "$work/root.out") r3=$(ratio "$work/two.log")
if [ -n "$r1" ] && [ "$r1" = "$r2" ] && [ "$r1" = "$r3" ] && [ -z "$(ls -A "$work/elsewhere")" ] &&
    { [ "$had_log" = 1 ] || [ ! -e "$repo/log.lammps" ]; }; then
    echo "test.sh: the example from another directory: rebound ratio $r1 as from the root, its log where asked, no log.lammps left"
else
    echo "test.sh: FAIL: the example from another directory: ratios '$r1' '$r2' (root) '$r3' (log); left: $(ls -A "$work/elsewhere")" >&2
    status=1
fi
# lmp itself from elsewhere: the missing file named, not lmp's bare "Could not open Python file"
(cd "$work/elsewhere" && lmp -nocite -log none -in "$here/in.two_spheres" -var table ../e_table.csv \
    -var lib "$work/build/libcantact_lammps.so" >"$work/bare.out" 2>&1) || true
if grep -q "in.two_spheres: dem/lammps/cantact_load.py not found" "$work/bare.out" &&
    ! grep -q "Could not open Python file" "$work/bare.out"; then
    echo "test.sh: lmp -in in.two_spheres from elsewhere names the loader it cannot find"
else
    echo "test.sh: FAIL: lmp from elsewhere: $(tail -n 3 "$work/bare.out")" >&2
    status=1
fi
echo "test.sh: the example: $(elapsed "$t") s"

# ---- the collisions ----
t=$(date +%s.%N)
python3 "$here/collide_test.py" --lmp lmp --lib "$work/build/libcantact_lammps.so" \
    --loader "$here/cantact_load.py" --table "$work/e_table.csv" \
    --e-of-speed "$work/e_of_speed" --work "$work/runs" || status=$?
echo
echo "test.sh: again with the style's local e <-> zeta relations (-DCANTACT_LOCAL_ZETA), dt 1e-8 only:"
python3 "$here/collide_test.py" --quick --lmp lmp --lib "$work/build-local/libcantact_lammps.so" \
    --loader "$here/cantact_load.py" --table "$work/e_table.csv" \
    --e-of-speed "$work/e_of_speed" --work "$work/runs-local" >"$work/local.txt" 2>&1 || status=$?
sed -n '/^worst/,$p' "$work/local.txt"
echo
echo "test.sh: a measured surface's table (the Dektak profile, scripts/scenes/dem_profile_table.ini), dt 1e-8 only:"
"$cantact" table -q scripts/scenes/dem_profile_table.ini -o "$work/e_profile.csv"
python3 "$here/collide_test.py" --quick --lmp lmp --lib "$work/build/libcantact_lammps.so" \
    --loader "$here/cantact_load.py" --table "$work/e_profile.csv" \
    --e-of-speed "$work/e_of_speed" --work "$work/runs-profile" >"$work/profile.txt" 2>&1 || status=$?
sed -n '/^worst/,$p' "$work/profile.txt"
echo "test.sh: collisions: $(elapsed "$t") s"

# ---- oblique impacts: the normal rebound ratio against e_table and against an ODE ----
# (Debian's Python: its python3-numpy and python3-scipy, whatever python3 comes first on PATH)
py=/usr/bin/python3
t=$(date +%s.%N)
echo
echo "test.sh: oblique impacts at 30 degrees (oblique_test.py; docs/dem.md, \"Oblique impacts\"):"
"$py" "$here/oblique_test.py" --lmp lmp --lib "$work/build/libcantact_lammps.so" \
    --loader "$here/cantact_load.py" --table "$work/e_table.csv" \
    --e-of-speed "$work/e_of_speed" --work "$work/runs-oblique" >"$work/oblique.txt" 2>&1 || status=$?
sed -n '/^oblique impacts/,/^head-on pairs/p;/^FAILED/,/^$/p;/^oblique: /p' "$work/oblique.txt"
[ -n "$(sed -n '/^oblique: /p' "$work/oblique.txt")" ] || { tail -n 5 "$work/oblique.txt"; status=1; }
echo "test.sh: oblique: $(elapsed "$t") s"

# ---- a table per pair of particle types: pair_coeff I J table FILE ----
t=$(date +%s.%N)
echo
echo "test.sh: two particle types, a table per type pair (pair_tables.py, pairs_test.py; docs/dem.md, \"e(v) for a pair of particles\"):"
types="--type 2e-3:7850 --type 3e-3:7850"
# shellcheck disable=SC2086
if "$py" "$repo/dem/pair_tables.py" scripts/scenes/dem_pair_table.ini $types --cantact "$cantact" \
    -o "$work/pairs"; then
    # shellcheck disable=SC2086
    "$py" "$here/pairs_test.py" --lmp lmp --lib "$work/build/libcantact_lammps.so" \
        --loader "$here/cantact_load.py" --e-of-speed "$work/e_of_speed" --work "$work/runs-pairs" \
        $types --tables "$work/pairs" >"$work/pairs.txt" 2>&1 || status=$?
    sed -n '/^tables:/,/^negative control/p;/^FAILED/,/^$/p;/^pairs: /p' "$work/pairs.txt"
    [ -n "$(sed -n '/^pairs: /p' "$work/pairs.txt")" ] || { tail -n 5 "$work/pairs.txt"; status=1; }
else
    echo "test.sh: FAIL: dem/pair_tables.py" >&2
    status=1
fi
echo "test.sh: pairs: $(elapsed "$t") s"

# ---- scatter: e at a quantile drawn per contact from a table of samples ----
t=$(date +%s.%N)
echo
echo "test.sh: scatter, e of each contact at a drawn probability (scatter_test.py; docs/dem.md, \"Scatter: a table of samples\"):"
"$cantact" table -q scripts/scenes/random_ensemble.ini --set table.tolerance=1e-2 -o "$work/e_samples.csv"
lib="$(dirname "$cantact")/libcantact.so.0"
[ -f "$lib" ] || lib=""
"$py" "$here/scatter_test.py" --lmp lmp --lib "$work/build/libcantact_lammps.so" \
    --loader "$here/cantact_load.py" --table "$work/e_samples.csv" --plain-table "$work/e_table.csv" \
    ${lib:+--cantact-library "$lib"} --cantact-python "$repo/python" \
    --work "$work/runs-scatter" >"$work/scatter.txt" 2>&1 || status=$?
sed -n '/^table /,/^refused: scatter with a table/p;/^FAILED/,/^$/p;/^scatter: [0-9]/p' "$work/scatter.txt"
[ -n "$(sed -n '/^scatter: [0-9]/p' "$work/scatter.txt")" ] || { tail -n 5 "$work/scatter.txt"; status=1; }
echo "test.sh: scatter: $(elapsed "$t") s"
echo "test.sh: after the install: $(elapsed "$t_start") s; with it: $(elapsed "$t_all") s"
[ "$status" -eq 0 ] && echo "test.sh: PASS" || echo "test.sh: FAIL"
exit "$status"
