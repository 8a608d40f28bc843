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

extern const char *const ct_cli_merge_help;

#endif
