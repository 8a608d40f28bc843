/* ----------------------------------------------------------------------
   Registers gran/hooke/history/cantact in a running LAMMPS that has no PLUGIN package (Debian
   12's lmp): the same one line as LAMMPS's plugin loader (src/PLUGIN/plugin.cpp), adding the
   style's creator to Force::pair_map, the map `pair_style` looks names up in.

   Called once per LAMMPS instance, with its pointer, before `pair_style`:
     - from an input script run by the stock lmp: the `python` command (cantact_load.py);
     - from Python (python3-lammps): ctypes.CDLL(lib).cantact_lammps_register(lmp.lmp);
     - from C/C++ that embeds liblammps: cantact_lammps_register(lmp_handle).
   Returns 0, or -1 when the name is taken by another creator (nothing changed then).
   SPDX-License-Identifier: GPL-2.0-only (derived from LAMMPS, GPL-2)
------------------------------------------------------------------------- */

#include "force.h"
#include "lammps.h"
#include "pair_gran_hooke_history_cantact.h"

using namespace LAMMPS_NS;

static Pair *cantact_pair_creator(LAMMPS *lmp)
{
  return new PairGranHookeHistoryCantact(lmp);
}

extern "C" int cantact_lammps_register(void *handle)
{
  LAMMPS *lmp = static_cast<LAMMPS *>(handle);
  if (!lmp || !lmp->force || !lmp->force->pair_map) return -1;
  Force::PairCreatorMap &map = *lmp->force->pair_map;
  const char *name = "gran/hooke/history/cantact";
  auto it = map.find(name);
  if (it != map.end() && it->second != &cantact_pair_creator) return -1;
  map[name] = &cantact_pair_creator;
  return 0;
}
