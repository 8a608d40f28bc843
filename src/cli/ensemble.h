/* Ensembles of random Cantor realisations in the CLI: cantact run (one process, MPI ranks, or
 * a range of realisations for a job array). cantact merge is merge.h; the outputs both write,
 * ensemble_out.h. */
#ifndef CT_CLI_ENSEMBLE_H
#define CT_CLI_ENSEMBLE_H

#include "scene.h"

/* `cantact run` of a scene with [ensemble]; range is the --realisations value ("a:b") or
 * NULL. Returns the exit status (the same on every MPI rank). */
int ct_cli_ensemble_run(const ct_scene *sc, int quiet, const char *range);

#endif
