/* cantact/table.h: e(V*) tables with a checked interpolation error. Part of the library's API:
 * include <cantact.h>, which includes every part; each part includes the parts it needs.
 * SPDX-License-Identifier: GPL-3.0-or-later */
#ifndef CANTACT_PART_TABLE_H
#define CANTACT_PART_TABLE_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include "cantact/ensemble.h"
#include "cantact/sweep.h"

#ifdef __cplusplus
extern "C" {
#endif
#if defined(__GNUC__)
#pragma GCC visibility push(default)
#endif

/* ---- e(V*) tables with a checked interpolation error (src/table.c) --------------- */
/* e of the first impact on a bundle's state, as nodes in V* that a stated interpolation
 * reproduces within a tolerance everywhere it was checked: for DEM codes and notebooks that
 * need e at any speed without the model. The interpolation is in x = ln V*, linear or
 * monotone cubic (Hermite with Fritsch-Carlson-limited slopes: the Fritsch-Butland weighted
 * harmonic mean inside, three-point one-sided ends, as SLATEC PCHIM), and e = 1 exactly at and
 * below V*_c. include/cantact_table.h (dependency-free, for DEM codes) reads a written table
 * and evaluates it with the same code as ct_table_eval. */

typedef enum {
    CT_INTERP_MONOTONE_CUBIC = 0, /* = CT_TAB_MONOTONE_CUBIC of cantact_table.h */
    CT_INTERP_LINEAR = 1,         /* = CT_TAB_LINEAR */
} ct_interp;

/* Returns "monotone_cubic" or "linear", NULL for an unknown rule. */
const char *ct_interp_name(ct_interp rule);

typedef struct {
    double V_min, V_max; /* the range of V*, dimensionless, 0 < V_min < V_max */
    double tolerance;    /* largest |e_table - e| allowed, absolute, 1e-13 <= tolerance < 1 */
    ct_interp interpolation;
    size_t max_nodes;    /* the build fails (CT_ENOCONV) rather than exceed it; >= 2 */
    size_t check_points; /* points checked inside every interval, equally spaced in ln V*,
                            >= 1 (default 16) */
    ct_impact_opts opts; /* how each exact e is computed */
    ct_sweep_path path;
    ct_progress_fn progress; /* optional: exact impacts computed, of those planned so far (the
                                total grows when a round splits intervals) */
    void *progress_ctx;
    const volatile int *interrupt; /* optional: stops with CT_EINTR once *interrupt != 0 */
} ct_table_spec;

/* Fills spec with the defaults: tolerance 1e-6, monotone cubic, at most 100000 nodes, 16
 * checks per interval, ct_impact_opts_default, CT_PATH_AUTO (V_min, V_max left 0). */
void ct_table_spec_default(ct_table_spec *spec);

typedef struct ct_table ct_table;

/* What a build found. */
typedef struct {
    double V_star_crit; /* critical V* of b's state: e = 1 at and below it (a node when in range) */
    double worst_error; /* the largest |e_table - e| over every checked point, dimensionless */
    double worst_V_star; /* where it was found */
    size_t checked;      /* points checked: check_points inside each interval (nodes are exact) */
    size_t kinks;        /* nodes at kinks of e: V* where u_max reaches a breakpoint of P(u) */
    size_t rounds;       /* refinement rounds */
    size_t evaluations;  /* exact impacts computed */
} ct_table_info;

/* Builds the table of e(V*) of the first impact on b's current state (b is not changed):
 * starting from V_min, V_max, V*_c and two nodes per decade, every interval whose checks
 * exceed the tolerance is split, at the load curve's kink nearest its middle in ln V* when it
 * holds one (a rod's contact or yield point: there e has a kink), else at its middle, until
 * every check passes; the slopes are recomputed after every round and every interval checked
 * again. So the table never claims a tolerance it did not check. Returns CT_OK, CT_ENOCONV
 * (max_nodes reached, or an interval too short to split: the message says the worst error
 * and where), an exact impact's failure (e.g. CT_ERANGE: V_max crushes the layer), CT_EINVAL
 * or CT_ENOMEM. */
int ct_table_build(ct_table **out, const ct_bundle *b, const ct_table_spec *spec);
/* A table from given nodes (e.g. read back from a file): V_star strictly increasing, > 0,
 * e in [0, 1], slopes finite; the nodes are copied, info is zero but V_star_crit. */
int ct_table_from_nodes(ct_table **out, size_t n, const double *V_star, const double *e,
                        const double *slope, ct_interp rule, double V_star_crit);
void ct_table_free(ct_table *t);
size_t ct_table_size(const ct_table *t);          /* nodes */
const double *ct_table_V_star(const ct_table *t); /* nodes, dimensionless, increasing */
const double *ct_table_e(const ct_table *t);      /* e at the nodes */
const double *ct_table_slope(const ct_table *t);  /* de/d(ln V*) at the nodes */
ct_interp ct_table_interpolation(const ct_table *t);
void ct_table_get_info(const ct_table *t, ct_table_info *info);
/* Returns e at V* by the table's interpolation (cantact_table.h's rule); NaN for V* not > 0.
 * Outside the nodes and above V*_c: the nearest end's e. */
double ct_table_eval(const ct_table *t, double V_star);
/* Monotone cubic slopes d[i] = de/dx at nodes x[0..n) (strictly increasing, n >= 2) of y:
 * the Fritsch-Butland weighted harmonic mean inside, three-point one-sided ends limited to
 * three secants (Fritsch-Carlson), 0 at a local extremum. */
void ct_pchip_slopes(size_t n, const double *x, const double *y, double *d);
/* What a table file says of itself beyond its nodes. */
typedef struct {
    const char *version; /* the program's version, "" when none */
    const char *scene;   /* the scene's name (NULL: not written) */
    const char *surface; /* one line on the surface (ct_surface_table_line; NULL: none) */
    double tolerance;    /* the tolerance the build was asked for */
    size_t check_points; /* points checked inside every interval */
    double v_per_V_star; /* impact speed per V* in the scene's units (NaN: no mass given) */
    const char *samples; /* a table of samples: what they are ("landings ..."; NULL: not said) */
    size_t grid;         /* a table of samples: the speeds each was computed at */
} ct_table_meta;
/* Writes the table file include/cantact_table.h reads: "# key = value" lines, then
 * V_star,e,de_dlnV_star rows (round-trip digits). CT_EIO on a write error. */
int ct_table_write(FILE *f, const ct_table *t, const ct_table_meta *meta);
/* What a table file's header says that ct_table_read reads (NaN: the file does not say). */
typedef struct {
    double tolerance;    /* |e_table - e_model| the table was built for, dimensionless */
    double worst_error;  /* the largest |e_table - e_model| found when it was checked */
    double worst_V_star; /* where (NaN also for "none": no point above V*_c was checked) */
    double v_per_V_star; /* impact speed per unit V* in the scene's units */
} ct_table_file_info;
/* Reads a table file with include/cantact_table.h's reader (ct_tab_read: its acceptance rule,
 * one for every reader) into a table evaluated as ct_table_eval; file (may be NULL) gets the
 * header's numbers. CT_EINVAL for a file the reader refuses (the message names file:line),
 * CT_EIO when it cannot be opened or read, CT_ENOMEM. */
int ct_table_read(ct_table **out, const char *path, ct_table_file_info *file);

/* ---- tables of samples: the mean and quantiles of e over realisations or landings ---- */
/* A table of samples (an ensemble's realisations, or a curved body's landings: ct_ensemble_spec)
 * holds, per node, e as the mean over the samples and e at np probabilities p (type-7
 * quantiles of the samples, as ct_sample_stats), each column interpolated as e is. Every sample
 * is computed at `grid` speeds equally spaced in ln V* over the range (one ensemble: each
 * sample's rods built or met once), V*_c (the least of the samples': every e is 1 at and below
 * it) among them; the nodes are grid points (the ends, V*_c and every second point: the others
 * are always checked), added at the middle of every interval where a grid point of any column
 * misses the tolerance, until none does (CT_ENOCONV when an interval has no point left to add).
 * The check is at the grid points (between them it is not checked). */
#define CT_TABLE_MAX_QUANTILES 64
typedef struct {
    const double *p;  /* probabilities, strictly increasing in [0, 1], 6 significant digits */
    size_t np;        /* 1 .. CT_TABLE_MAX_QUANTILES */
    size_t grid;      /* speeds every sample is computed at, 2 .. 1e6 */
    double tolerance; /* the quantile columns' (0: the table's, spec->tolerance): e at a
                         quantile has a kink wherever two samples' e cross, the mean far fewer */
} ct_table_quantiles;
/* The table of samples (samples: count, first, the surface or rods and body; its speeds,
 * impacts, options, interrupt and progress are the table's: spec) over spec's range with
 * spec's tolerance, interpolation and max_nodes (check_points is not used: the grid is the
 * check). CT_ENOCONV when max_nodes is not enough; a sample's failed impact fails the build
 * (its message names the sample). */
int ct_table_build_samples(ct_table **out, const ct_ensemble_spec *samples,
                           const ct_table_spec *spec, const ct_table_quantiles *q);
size_t ct_table_quantile_count(const ct_table *t);              /* 0: a table of one surface */
const double *ct_table_p(const ct_table *t);                    /* the probabilities */
const double *ct_table_e_quantile(const ct_table *t, size_t j); /* e at p[j] at the nodes */
const double *ct_table_slope_quantile(const ct_table *t, size_t j);
uint64_t ct_table_samples(const ct_table *t); /* samples the statistics are over */
/* The quantile columns' tolerance and their largest error at the checked points (the mean's is
 * ct_table_info's worst_error). */
double ct_table_quantile_tolerance(const ct_table *t);
double ct_table_quantile_worst_error(const ct_table *t);
/* e at V* and probability p by cantact_table.h's rule (ct_tab_eval_quantile): NaN for a table
 * without quantiles or p outside [0, 1]. */
double ct_table_eval_quantile(const ct_table *t, double V_star, double p);

#if defined(__GNUC__)
#pragma GCC visibility pop
#endif
#ifdef __cplusplus
}
#endif
#endif
