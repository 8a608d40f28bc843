#!/bin/sh
# The two forms for a LAMMPS you build yourself (README.md, "A self-built LAMMPS"), end to end:
#   1. drop-in: copies the style (and cantact_table.h) into LAMMPS_SRC/src/GRANULAR and builds
#      LAMMPS with cmake (GRANULAR, PLUGIN, shared library, serial: no MPI, no OpenMP);
#   2. plugin: compiles cantact_plugin.cpp + the style against that tree into cantactplugin.so;
#   then runs collide_test.py's checks with the new lmp, the style built in and then loaded
#   with `plugin load` (which overrides the built-in one, with a warning).
#
#   dem/lammps/selfbuilt.sh LAMMPS_SRC BUILD_DIR [PATH/TO/cantact]     (run from the repo root)
#
# LAMMPS_SRC: a LAMMPS source tree (tested: Debian's `apt-get source lammps`, 29 Sep 2021 Update
# 2; other versions need the style's base class, PairGranHookeHistory, unchanged). It is
# modified (two files and cantact_table.h added to src/GRANULAR). Needs cmake, g++; 9 to 11
# minutes of building on 2 cores.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../.." && pwd)
src=$(cd "$1" && pwd)
mkdir -p "$2"
build=$(cd "$2" && pwd)
cantact=${3:-$(cd "$(dirname "$0")/../.." && pwd)/build/cantact}
cd "$repo"

cp "$here/pair_gran_hooke_history_cantact.h" "$here/pair_gran_hooke_history_cantact.cpp" \
    "$repo/include/cantact_table.h" "$src/src/GRANULAR/"
t=$(date +%s)
cmake -S "$src/cmake" -B "$build/lammps" -DCMAKE_BUILD_TYPE=Release -DBUILD_MPI=no -DBUILD_OMP=no \
    -DPKG_GRANULAR=yes -DPKG_PLUGIN=yes -DBUILD_SHARED_LIBS=yes >"$build/cmake.log"
make -C "$build/lammps" -j"$(nproc)" >"$build/make.log" 2>&1 || { tail -20 "$build/make.log"; exit 1; }
echo "selfbuilt.sh: LAMMPS built in $(( $(date +%s) - t )) s: $build/lammps/lmp"
"$build/lammps/lmp" -h | grep -q "gran/hooke/history/cantact" || { echo "selfbuilt.sh: style not built in" >&2; exit 1; }

# the plugin: the same compiler flags as the LAMMPS build (serial: the STUBS mpi.h)
g++ -std=c++11 -O2 -fPIC -shared -DLAMMPS_SMALLBIG -I"$src/src" -I"$src/src/GRANULAR" \
    -I"$src/src/STUBS" -I"$repo/include" -o "$build/cantactplugin.so" \
    "$here/cantact_plugin.cpp" "$here/pair_gran_hooke_history_cantact.cpp"
echo "selfbuilt.sh: plugin built: $build/cantactplugin.so"

"$cantact" table scripts/scenes/dem_table.ini -o "$build/e_table.csv"
cc -O2 -I"$repo/include" "$here/e_of_speed.c" -o "$build/e_of_speed" -lm
status=0
echo "selfbuilt.sh: the style built in (drop-in):"
python3 "$here/collide_test.py" --lmp "$build/lammps/lmp" --builtin --no-mpi --table "$build/e_table.csv" \
    --e-of-speed "$build/e_of_speed" --work "$build/runs-builtin" >"$build/builtin.txt" || status=1
sed -n '/^worst/,$p' "$build/builtin.txt"
echo "selfbuilt.sh: the style loaded as a plugin:"
python3 "$here/collide_test.py" --lmp "$build/lammps/lmp" --plugin "$build/cantactplugin.so" --no-mpi \
    --table "$build/e_table.csv" --e-of-speed "$build/e_of_speed" --work "$build/runs-plugin" \
    >"$build/plugin.txt" || status=1
sed -n '/^worst/,$p' "$build/plugin.txt"
exit "$status"
