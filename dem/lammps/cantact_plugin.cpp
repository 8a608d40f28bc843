/* ----------------------------------------------------------------------
   The plugin form, for a LAMMPS built with the PLUGIN package (not Debian's): compile this file
   and pair_gran_hooke_history_cantact.cpp against that LAMMPS's src/ (see README.md) and load
   the shared library with `plugin load cantactplugin.so`.
   SPDX-License-Identifier: GPL-2.0-only (derived from LAMMPS, GPL-2)
------------------------------------------------------------------------- */

#include "lammpsplugin.h"
#include "version.h"

#include "pair_gran_hooke_history_cantact.h"

using namespace LAMMPS_NS;

static Pair *cantact_pair_creator(LAMMPS *lmp)
{
  return new PairGranHookeHistoryCantact(lmp);
}

extern "C" void lammpsplugin_init(void *lmp, void *handle, void *regfunc)
{
  lammpsplugin_t plugin;
  lammpsplugin_regfunc register_plugin = (lammpsplugin_regfunc) regfunc;
  plugin.version = LAMMPS_VERSION;
  plugin.style = "pair";
  plugin.name = "gran/hooke/history/cantact";
  plugin.info = "gran/hooke/history with e(v) per contact from a cantact table";
  plugin.author = "cantact";
  plugin.creator.v1 = (lammpsplugin_factory1 *) &cantact_pair_creator;
  plugin.handle = handle;
  (*register_plugin)(&plugin, lmp);
}
