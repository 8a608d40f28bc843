/* What cantact run (src/cli/ensemble.c) and cantact merge (src/cli/merge.c) share: an
 * ensemble's samples in the output's units, and the outputs written from them, the statistics
 * per speed and the realisations CSV (whose identity line and header merge reads back). */
#ifndef CT_CLI_ENSEMBLE_OUT_H
#define CT_CLI_ENSEMBLE_OUT_H

#include "output.h"
#include "scene.h"

#include <stddef.h>
#include <stdint.h>

/* The samples of realisations first .. first + count - 1, nrows rows each (speeds x impacts). */
typedef struct {
    uint64_t first, count;
    size_t nrows;
    double *e, *u, *vc; /* e, u_max / h0, V*_c: [r * nrows + q], NaN where failed */
    char **err;         /* a failed row's error text (NULL: computed) */
    int owns_err;       /* merge: the texts were read and are freed */
    uint64_t *cx, *cz;  /* clipped ratios per realisation */
    double *x, *y;      /* landings: the apex per landing (y NaN on a line) */
    int landings;       /* 1: the samples are landings, 0: realisations */
    ct_plan_info info;  /* landings: the surface's rods as built (the identity line says them) */
} ct_ens_table;

/* Allocates the arrays (err and the clip counts zeroed): 0, or -1 out of memory (t emptied). */
int ct_ens_table_alloc(ct_ens_table *t, uint64_t first, uint64_t count, size_t nrows, int landings);
void ct_ens_table_free(ct_ens_table *t);

/* 1 when the scene's landings have a y as well as an x (a sphere over a plane). */
int ct_ens_landings_plane(const ct_scene *sc);
/* The header row of a samples CSV, realisations or landings (skip: solver.on_error = skip, with
 * its error column; plane: landings with y). */
const char *ct_ens_samples_header(const ct_scene *sc);
/* What identifies a part's scene: the first line of a samples CSV, checked by merge; it begins
 * with CT_ENS_ID_HEAD (realisations) or CT_ENS_LANDINGS_HEAD. info: landings: the surface's
 * rods as built (their count and depth); realisations: unused. */
void ct_ens_identity(const ct_scene *sc, const ct_plan_info *info, char *buf, size_t len);
#define CT_ENS_ID_HEAD "# realisations of surface = "
#define CT_ENS_LANDINGS_HEAD "# landings on surface = "

/* The outputs of an ensemble: the statistics (FILE) and the samples (FILE, or
 * FILE_realisations / FILE_landings when both are written). */
typedef struct {
    ct_out ens, real;
    int opened_ens, opened_real;
    char *real_path;
} ct_ens_outputs;

/* Opens the outputs that what asks for (CT_OUT_ENSEMBLE, CT_OUT_REALISATIONS or
 * CT_OUT_LANDINGS): 0, -1 with the
 * message in err, -2 when it was said already (an output that is an input: the scene, or one
 * of parts, nparts of them). */
int ct_ens_open_outputs(ct_ens_outputs *o, const ct_scene *sc, unsigned what,
                        const char *const *parts, size_t nparts, char *err, size_t errlen);
/* Drops what was not committed and frees o. */
void ct_ens_close_outputs(ct_ens_outputs *o);
/* Writes what was asked from the samples and commits, then (unless quiet) the summary on
 * stderr. Returns an exit status. */
int ct_ens_write_outputs(ct_ens_outputs *o, const ct_scene *sc, const ct_ens_table *t, int quiet);

#endif
