#!/bin/sh
# The two-sphere example of README.md (in.two_spheres) from any directory: two 2 mm steel
# spheres hit head-on in Debian's stock lmp with gran/hooke/history/cantact, their damping from a
# cantact table. The add-on, its loader and the input script are found beside this script; the
# table and the log are paths from where you run it.
#
#   dem/lammps/two_spheres.sh TABLE.csv [--speed V] [--limit-damping] [--log FILE] [--lib PATH]
#
# --speed V         relative speed [m/s] (default 1)
# --limit-damping   the force-clipped contact (pair_style ... limit_damping)
# --log FILE        lmp's log there (default: none; lmp alone writes log.lammps where it runs)
# --lib PATH        the add-on (default: dem/lammps/build/libcantact_lammps.so, from build.sh)
# Exit status: lmp's; 2 for bad usage or a missing file.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
usage() {
    sed -n '7,13s/^# \{0,1\}//p' "$0"
}
table="" v=1 limit="" log=none lib=$here/build/libcantact_lammps.so
while [ $# -gt 0 ]; do
    case $1 in
    -h | --help) usage; exit 0 ;;
    --speed | --log | --lib)
        [ $# -ge 2 ] || { echo "two_spheres.sh: $1 needs a value" >&2; exit 2; }
        case $1 in --speed) v=$2 ;; --log) log=$2 ;; --lib) lib=$2 ;; esac
        shift 2 ;;
    --limit-damping) limit=limit_damping; shift ;;
    -*) echo "two_spheres.sh: unknown option $1 (see --help)" >&2; exit 2 ;;
    *)
        [ -z "$table" ] || { echo "two_spheres.sh: one table, got $table and $1" >&2; exit 2; }
        table=$1; shift ;;
    esac
done
[ -n "$table" ] || { echo "two_spheres.sh: missing TABLE.csv (cantact table SCENE.ini -o TABLE.csv; see --help)" >&2; exit 2; }
[ -f "$table" ] || { echo "two_spheres.sh: $table: no such file" >&2; exit 2; }
[ -f "$lib" ] || { echo "two_spheres.sh: $lib not found: build it with $here/build.sh (or give --lib PATH)" >&2; exit 2; }
command -v lmp >/dev/null 2>&1 || { echo "two_spheres.sh: lmp not found (apt-get install lammps python3-lammps)" >&2; exit 2; }
exec lmp -nocite -log "$log" -in "$here/in.two_spheres" -var table "$table" -var v "$v" \
    -var limit "$limit" -var lib "$lib" -var loader "$here/cantact_load.py"
