#!/bin/sh
# Builds libcantact_lammps.so, the pair style gran/hooke/history/cantact as an add-on for
# Debian 12's packaged LAMMPS (lammps, liblammps-dev: 29 Sep 2021 - Update 2), in one command:
#
#   dem/lammps/build.sh [OUTDIR]        (default OUTDIR: dem/lammps/build)
#
# Extra compiler flags: EXTRA_CXXFLAGS (e.g. -DCANTACT_LOCAL_ZETA: the style's own e <-> zeta
# relations instead of cantact_table.h's).
# Needs: liblammps-dev, libopenmpi-dev (mpicxx), g++, librandom123-dev (Random123's Philox, for
# the scatter keyword); and include/cantact_table.h of this repo.
# The headers liblammps-dev lacks are in lammps-headers/ (copied from that LAMMPS version's
# source): the class layouts must be the binary's, so any other LAMMPS version is refused.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../.." && pwd)
out=${1:-$here/build}
CXX=${CXX:-mpicxx}

want=20210929
have=$(pkg-config --modversion liblammps 2>/dev/null || true)
if [ "$have" != "$want" ]; then
    echo "build.sh: needs Debian 12's liblammps-dev (pkg-config liblammps version $want), found '${have:-none}'" >&2
    echo "build.sh: for another LAMMPS build it as a plugin or in its source tree (README.md)" >&2
    exit 1
fi
command -v "$CXX" >/dev/null 2>&1 || { echo "build.sh: $CXX not found (apt-get install libopenmpi-dev g++)" >&2; exit 1; }
[ -f "$repo/include/cantact_table.h" ] || { echo "build.sh: $repo/include/cantact_table.h missing" >&2; exit 1; }
printf '#include <Random123/philox.h>\n' | "$CXX" -std=c++11 -x c++ -fsyntax-only - 2>/dev/null ||
    { echo "build.sh: Random123/philox.h not found (apt-get install librandom123-dev)" >&2; exit 1; }

mkdir -p "$out"
# -ffp-contract=off and no -march: no fused multiply-adds, the arithmetic of Debian's build
# (baseline x86-64), so that the style equals stock gran/hooke/history to the bit.
# shellcheck disable=SC2046,SC2086
"$CXX" -std=c++11 -O2 -DOMPI_SKIP_MPICXX -DMPICH_SKIP_MPICXX -fPIC -shared -ffp-contract=off -Wall -Wextra -Wno-unused-parameter \
    $(pkg-config --cflags liblammps) -I/usr/include/lammps -I"$here/lammps-headers" -I"$repo/include" \
    ${EXTRA_CXXFLAGS:-} -o "$out/libcantact_lammps.so" \
    "$here/pair_gran_hooke_history_cantact.cpp" "$here/cantact_register.cpp" \
    $(pkg-config --libs liblammps)
echo "build.sh: built $out/libcantact_lammps.so"
