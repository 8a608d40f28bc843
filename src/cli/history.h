/* The impact in time in the CLI: the e table's time columns, histories, bounce sequences. */
#ifndef CT_CLI_HISTORY_H
#define CT_CLI_HISTORY_H

#include "cantact.h"
#include "number.h"
#include "scene.h"

#include <stdio.h>

/* The e table's time columns (what = time, from the column table's group "time"): their
 * names, after the others; with a mass also their twins in the scene's units. */
void ct_cli_time_header(FILE *f, const ct_scene *sc);
/* 1 when b's rods stand on a plane (an areal map, rods placed by x and y): l0 is an area and a
 * force is in N; on a line (l0 a length) in N per metre of depth. */
int ct_cli_bundle_areal(const ct_bundle *b);
/* Column c's name in the scene's units: the peak force in N on a plane (sc->areal). */
const char *ct_cli_physical_name(const ct_column *c, const ct_scene *sc);
/* Room for the sweep's columns (src/columns.c): places in ct_sweep_columns, chosen once per
 * block of rows rather than by name on every row. */
#define CT_CLI_COLUMNS 64
typedef struct {
    const ct_column *cols;
    size_t at[CT_CLI_COLUMNS], n;       /* the group's columns */
    size_t phys[CT_CLI_COLUMNS], nphys; /* of those, the ones with a physical twin */
} ct_cli_columns;
/* The columns of group `group` (those named impact and V_star left out) into c; -1 when the
 * table of columns outgrows CT_CLI_COLUMNS. */
int ct_cli_columns_of(ct_cli_columns *c, const char *group);
/* A row's time fields (empty for a failed row); layer: the units the rows were computed in. */
void ct_cli_time_row(ct_line *l, const ct_scene *sc, const ct_cli_columns *tc,
                     const ct_sweep_row *row);
/* The check of every run with time: e_kinematic equals the energy e to 1e-12 (beyond the
 * stated rounding); -1 with a message otherwise. */
int ct_cli_time_check(const ct_sweep_row *row, char *err, size_t errlen);
/* The history output: its header, and the rows of one impact from the pre-impact state b. */
void ct_cli_history_header(FILE *f, const ct_scene *sc);
int ct_cli_history_rows(FILE *f, const ct_scene *sc, const ct_sweep_row *row, const ct_bundle *b);
/* A bounce sequence (impact.sequence = bounce) on b, written as a table; a status and err. */
int ct_cli_bounce(FILE *f, const ct_scene *sc, const ct_bundle *b, char *err, size_t errlen);

#endif
