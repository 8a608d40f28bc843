/* cantact/columns.h: the output columns as data. Part of the library's API: include <cantact.h>,
 * which includes every part; each part includes the parts it needs. SPDX-License-Identifier:
 * GPL-3.0-or-later */
#ifndef CANTACT_PART_COLUMNS_H
#define CANTACT_PART_COLUMNS_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include "cantact/sweep.h"

#ifdef __cplusplus
extern "C" {
#endif
#if defined(__GNUC__)
#pragma GCC visibility push(default)
#endif

/* ---- output columns as data (src/columns.c) -------------------------------------- */
/* The quantities of a sweep's rows, each a column: its name (the CSV header, Python's
 * attribute), its unit, its format and where it sits in ct_sweep_row. Groups: "e" the e
 * table, "time" the columns of what = time, "row" the library's and Python's only. */

typedef enum {
    CT_UNIT_ONE = 0,    /* dimensionless as computed */
    CT_UNIT_LENGTH = 1, /* a length: divided by h0 */
    CT_UNIT_FORCE = 2,  /* a force: divided by P_Y = sigma_y l0 */
    CT_UNIT_ENERGY = 3, /* an energy: divided by P_Y h0 */
    CT_UNIT_TIME = 4,   /* t / tau as computed (the sweep's mass is E l0 / h0) */
    CT_UNIT_COUNT = 5,  /* an integer */
    CT_UNIT_SPEED = 6,  /* a speed in h0 / tau, from V*: v1 = sqrt(2) V* h0 / tau */
} ct_unit;

typedef struct {
    const char *name;  /* "u_max_over_h0" */
    const char *group; /* "e", "time" or "row" */
    ct_unit unit;
    char type;            /* 'd' double, 'l' long, 'i' int: the field in ct_sweep_row; 'w':
                             the double at offset times the row's e (a rebound from an impact) */
    int digits;           /* 17: round trip ("%.17g"), 3: "%.3g" */
    const char *physical; /* its twin in the scene's units when a mass is given ("t_contact_s") */
    double divisor;       /* the value is divided by it last (the DEM step: period / 50) */
    size_t offset;        /* of the field in ct_sweep_row */
    const char *doc;      /* one line */
} ct_column;

/* The columns, in the order the CLI writes them within each group. */
size_t ct_sweep_columns(const ct_column **cols);
/* Column c of a row, dimensionless by the layer the rows were computed in. */
double ct_column_value(const ct_column *c, const ct_sweep_row *row, const ct_layer *layer);
/* Column c of n rows into out[0 .. n-1]: out[k] is bitwise ct_column_value(c, rows + k, layer)
 * (one call for a column of a sweep, where a front-end calling per row pays per call). */
void ct_column_values(const ct_column *c, const ct_sweep_row *rows, size_t n, const ct_layer *layer,
                      double *out);
/* Column c of a row in the physical layer's units (tau [time] for times): its twin. */
double ct_column_physical(const ct_column *c, const ct_sweep_row *row, const ct_layer *layer,
                          const ct_layer *physical, double tau);

#if defined(__GNUC__)
#pragma GCC visibility pop
#endif
#ifdef __cplusplus
}
#endif
#endif
