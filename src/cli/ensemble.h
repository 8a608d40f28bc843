/* Ensembles of random Cantor realisations in the CLI: run (one process, MPI ranks, or a range
 * of realisations for a job array), merge, and their CSV outputs. */
#ifndef CT_CLI_ENSEMBLE_H
#define CT_CLI_ENSEMBLE_H

#include "scene.h"

#include <stdio.h>

/* `cantact run` of a scene with [ensemble]; range is the --realisations value ("a:b") or
 * NULL. Returns the exit status (the same on every MPI rank). */
int ct_cli_ensemble_run(const ct_scene *sc, int quiet, const char *range);
/* `cantact merge SCENE PART.csv...`: returns the exit status. */
int ct_cli_merge(int argc, char **argv);
/* The profile of a bundle whose rods know their stage and x-extent (a random Cantor
 * realisation): one row per piece, in piece order (stage, then x). */
int ct_cli_write_rod_profile(FILE *f, const ct_bundle *b);
/* The one realisation of a random_cantor scene without [ensemble], as a run's surface. */
int ct_cli_random_surface(const ct_scene *sc, ct_bundle **b, ct_plan_info *info);

extern const char *const ct_cli_merge_help;

#endif
