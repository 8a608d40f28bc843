/* cantact/ensemble.h: ensembles of realisations and their statistics. Part of the library's API:
 * include <cantact.h>, which includes every part; each part includes the parts it needs.
 * SPDX-License-Identifier: GPL-3.0-or-later */
#ifndef CANTACT_PART_ENSEMBLE_H
#define CANTACT_PART_ENSEMBLE_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include "cantact/body.h"
#include "cantact/random_cantor.h"
#include "cantact/sweep.h"

#ifdef __cplusplus
extern "C" {
#endif
#if defined(__GNUC__)
#pragma GCC visibility push(default)
#endif

/* ---- ensembles of samples (src/ensemble.c) ---------------------------------------- */
/* A sample is a realisation of a random Cantor surface (the surface), or a landing of a curved
 * body on one deterministic surface (rods: that surface's rods as built; body->landings and
 * body->seed draw the apexes, ct_body_landing): either kind runs through one path, with the
 * same guarantees (samples at their own index, the same bits for any thread count or split). */

/* How an ensemble uses its threads: whole realisations per thread (each bundle summed by
 * one thread; memory: one realisation per thread), or one realisation at a time with its
 * rods shared by the threads. Auto: per realisation when a realisation has at most
 * CT_ENSEMBLE_SPLIT_RODS rods and there are at least two realisations. */
typedef enum {
    CT_SPLIT_AUTO = 0,
    CT_SPLIT_REALISATIONS = 1,
    CT_SPLIT_RODS = 2,
} ct_ensemble_split;
#define CT_ENSEMBLE_SPLIT_RODS ((size_t)1 << 21)

typedef struct {
    ct_random_cantor surface;
    uint64_t first;       /* realisations first .. first + count - 1 */
    uint64_t count;       /* >= 1 */
    const double *V_star; /* speeds, dimensionless */
    size_t nvel;
    long impacts; /* impacts per speed, >= 1 */
    ct_impact_opts opts;
    ct_sweep_path path;
    int stop_on_error; /* 1: stop at the first failed impact (lowest realisation, then row) */
    int threads;       /* 0: the OpenMP default */
    ct_ensemble_split split;
    ct_progress_fn progress; /* optional: realisations done (called by one thread at a time) */
    void *progress_ctx;
    const volatile int *interrupt; /* optional: stops with CT_EINTR once *interrupt != 0 */
    /* what strikes every realisation (NULL: the flat strip), in the units of scales, the
     * surface's (ct_surface_scales): each realisation's rods are shifted as ct_surface_build
     * shifts them, so that a sample is bit for bit the realisation's own run under the body */
    const ct_body *body;
    ct_scales scales;
    /* landings: the deterministic surface's rods as built, not met by a body (NULL: the
     * samples are realisations of surface); first and count then number the landings, and
     * the body must be curved */
    const ct_bundle *rods;
} ct_ensemble_spec;

/* The samples of an ensemble: realisation (or landing) first + r, row q = speed * impacts +
 * impact - 1 at index r * nrows + q. Values in library units (u_max [length]); NaN where
 * status != 0. */
typedef struct {
    uint64_t first, count;
    size_t nrows;
    double *e, *u_max, *V_star_crit;
    int *status;                       /* CT_OK, or why the impact failed / was not run */
    uint64_t *fx_clipped, *fz_clipped; /* per realisation (0 for landings) */
    double *x, *y;  /* per sample: a landing's apex [the surface's length unit; y NaN on a line];
                       NaN for realisations */
    uint64_t draws; /* ratios drawn of each kind per realisation */
    double quad_error_max;       /* largest |e - e_closed| of all samples (NaN: no
                                    closed-form check) */
    uint64_t failed_realisation; /* the first failure in (realisation, row) order */
    size_t failed_row;
    char message[240]; /* its message ("" when none failed) */
} ct_ensemble_samples;

/* Allocates the arrays for count realisations of nrows rows (all NaN, status CT_ESKIPPED). */
int ct_ensemble_samples_alloc(ct_ensemble_samples **out, uint64_t first, uint64_t count,
                              size_t nrows);
void ct_ensemble_samples_free(ct_ensemble_samples *s);
/* Runs every realisation of spec: build, sweep, drop. Samples do not depend on the thread
 * count, the split or on how realisations are shared among processes. Returns CT_OK (samples
 * carry their statuses), the first failure under stop_on_error, or CT_ENOMEM. */
int ct_ensemble(const ct_ensemble_spec *spec, ct_ensemble_samples *samples);

/* Statistics of one quantity over an ensemble. */
typedef struct {
    size_t n;             /* samples used (the NaN ones are left out) */
    double mean;          /* compensated sum in sample order, / n */
    double sd;            /* sample standard deviation (n - 1 in the denominator; NaN for n < 2) */
    double sem;           /* standard error of the mean, sd / sqrt(n) (NaN for n < 2) */
    double q05, q50, q95; /* quantiles: linear interpolation between order statistics,
                             x_(floor h) + (h - floor h)(x_(floor h + 1) - x_(floor h)),
                             h = (n - 1) p (Hyndman-Fan type 7, as R and NumPy) */
} ct_stats;

/* Statistics of x[0], x[stride], ..., x[(n - 1) stride], in that order (NaN left out):
 * the same input gives the same bits. work holds n doubles (the sort). CT_EINVAL when no
 * sample is finite. */
int ct_sample_stats(const double *x, size_t n, size_t stride, double *work, ct_stats *out);
/* Returns the p-quantile (0 <= p <= 1) of n >= 1 sorted values, type 7 as in ct_stats. */
double ct_quantile_sorted(const double *sorted, size_t n, double p);

#if defined(__GNUC__)
#pragma GCC visibility pop
#endif
#ifdef __cplusplus
}
#endif
#endif
