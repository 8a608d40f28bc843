/* Ensembles of random Cantor realisations in the CLI: cantact run (one process, MPI ranks, or
 * a range of realisations for a job array). cantact merge is merge.h; the outputs both write,
 * ensemble_out.h. */
#ifndef CT_CLI_ENSEMBLE_H
#define CT_CLI_ENSEMBLE_H

#include "scene.h"

/* A scene's samples as the library runs them: realisations of its random surface, or landings
 * of its body on its surface's rods (built once, not met). */
typedef struct {
    int landings;
    uint64_t count;           /* ensemble.realisations or body.landings */
    ct_random_cantor surface; /* realisations */
    ct_bundle *rods;          /* landings: owned */
    ct_plan_info info;        /* landings: the rods as built */
    char line[1024];          /* what runs, for the summary */
} ct_cli_samples;
/* Prepares them (landings: the rods built, the region checked): CT_OK, or a status with the
 * message in err. */
int ct_cli_samples_prepare(const ct_scene *sc, ct_cli_samples *s, char *err, size_t errlen);
/* The library's spec of samples first .. first + count - 1 under the scene's speeds and solver. */
void ct_cli_samples_spec(const ct_scene *sc, const ct_cli_samples *s, uint64_t first,
                         uint64_t count, ct_ensemble_spec *spec);
void ct_cli_samples_free(ct_cli_samples *s);

/* `cantact run` of a scene with [ensemble]; range is the --realisations value ("a:b") or
 * NULL. Returns the exit status (the same on every MPI rank). */
int ct_cli_ensemble_run(const ct_scene *sc, int quiet, const char *range);

#endif
