/* cantact/surface.h: surfaces of every kind: the one way to build rods (ct_surface_build). Part of
 * the library's API: include <cantact.h>, which includes every part; each part includes the parts
 * it needs. SPDX-License-Identifier: GPL-3.0-or-later */
#ifndef CANTACT_PART_SURFACE_H
#define CANTACT_PART_SURFACE_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include "cantact/keys.h"
#include "cantact/body.h"
#include "cantact/sweep.h"
#include "cantact/geometry.h"
#include "cantact/random_cantor.h"
#include "cantact/profile.h"

#ifdef __cplusplus
extern "C" {
#endif
#if defined(__GNUC__)
#pragma GCC visibility push(default)
#endif

/* ---- surfaces of every kind (src/surface/kind.c) --------------------------------- */
/* A surface is one kind (cantor, random_cantor, profile, rods: ct_surface_kind_name) set up
 * by its scene keys (sections surface and material, and what else the kind owns), prepared
 * (a measured profile is read and levelled; every kind fixes its scales) and built into rods
 * for the speeds asked. Everything after the rods knows nothing of the kind. The kind also
 * says which outputs it supports, and why not the others. */

typedef struct ct_surface ct_surface;

/* The kinds, in registry order: n of them; name and one-line summary of kind k. */
size_t ct_surface_kind_count(void);
const char *ct_surface_kind_name(size_t k);
const char *ct_surface_kind_summary(size_t k);
/* The key rows of kind k (its [surface] keys, [material] and any section it owns). */
const ct_key *ct_surface_kind_keys(size_t k, size_t *n);
/* Whether kind k supports an output or subcommand ("e", "time", "curve", "history",
 * "profile", "compare", "bearing", "bounce", "ensemble", "realisations", "table",
 * "geometry", "fit", "merge"): 1, or 0 with *why saying why not and what to use instead. */
int ct_surface_kind_supports(size_t k, const char *output, const char **why);
/* The outputs and subcommands every kind is asked about, space separated. */
const char *ct_surface_outputs(void);

/* A new surface of the kind named (CT_EINVAL naming the kinds for another name); every key
 * at its default. */
int ct_surface_new(ct_surface **out, const char *kind);
void ct_surface_free(ct_surface *s);
/* The kind's index and name. */
size_t ct_surface_kind_index(const ct_surface *s);
const char *ct_surface_kind(const ct_surface *s);
/* The row of section.name among the kind's keys, NULL when the kind has no such key. */
const ct_key *ct_surface_key(const ct_surface *s, const char *section, const char *name);
/* Sets a key from text; where ("file:line", "--set", "") prefixes messages: CT_EINVAL with
 * "where: section.name = value: reason". A key the kind does not have is CT_EINVAL saying
 * which kinds take it. */
int ct_surface_set(ct_surface *s, const char *section, const char *name, const char *value,
                   const char *where);
/* A key's value as parsed (its default when not given) as a number: a number, an integer, a
 * depth (auto -1, fractal -2), a count, or a word's index. CT_EINVAL for a text key. */
int ct_surface_value(const ct_surface *s, const char *section, const char *name, double *out);
/* 1 when the key was set. */
int ct_surface_is_set(const ct_surface *s, const char *section, const char *name);
/* Checks the keys together (required ones, exclusive ones, E > sigma_y ...); scene names
 * the scene in messages that concern no single key. */
int ct_surface_check(ct_surface *s, const char *scene);
/* The k-th file the surface reads (its keys flagged CT_KEY_FILE, joined to dir as
 * ct_surface_prepare joins them) into buf: 1, or 0 when it reads fewer. */
int ct_surface_input(const ct_surface *s, size_t k, const char *dir, char *buf, size_t len);
/* Reads what the surface needs (a profile's file, a rod file; relative paths from dir, NULL:
 * the working directory), levels it, fixes its scales. Idempotent. */
int ct_surface_prepare(ct_surface *s, const char *dir);

void ct_surface_scales(const ct_surface *s, ct_scales *out);
/* V* = sqrt(m / (2 l0 E h0)) v of a body of mass m at speed v on a surface of scales l0, E,
 * h0 (consistent units): the one conversion of every front-end. */
double ct_V_star_of(double m, double v, double l0, double E, double h0);
/* tau = sqrt(m h0 / (E l0)) [time] of a body of mass m in the physical units. */
double ct_time_scale(const ct_scales *sc, double m);

/* What a build is for: the speeds it will see and how. */
typedef struct {
    const double *V_star; /* dimensionless, > 0 */
    size_t nvel;
    long impacts; /* per speed, >= 1 */
    ct_impact_opts opts;
    int keep_all_rods;      /* 1: leave out nothing (the whole surface is written) */
    int threads;            /* of the bundle's sums; 0: the OpenMP default */
    double depth_tolerance; /* of depth auto (Cantor): relative truncation bound */
    const ct_body *body;    /* what strikes the rods (NULL: the flat strip of the paper) */
} ct_build_request;
/* The rods of a prepared surface for the request (a Cantor surface plans its depth and
 * leaves out what no impact reaches; a random one builds its realisation). */
int ct_surface_build(const ct_surface *s, const ct_build_request *req, ct_bundle **out,
                     ct_plan_info *info);
/* The same rods before the request's body meets them (built as for that body: a Cantor
 * surface keeps every piece a curved body may reach): what landings meet at each apex
 * (ct_ensemble_spec.rods). */
int ct_surface_build_unmet(const ct_surface *s, const ct_build_request *req, ct_bundle **out,
                           ct_plan_info *info);
/* Prepares what an output needs before any impact (a profile's fit for compare, bearing,
 * fit): CT_OK, or CT_EINVAL with the kind's reason when the kind does not give the output. */
int ct_surface_ready(ct_surface *s, const char *output);
/* 1 when what = profile shows the state after the impacts (the residual tops), so that it
 * is written at the last impact; 0 when it does not depend on the state (a profile's heights). */
int ct_surface_profile_shows_state(const ct_surface *s);
/* A note for the front-end to show (what was read, a refit), "" when none; cleared by
 * ct_surface_note_clear. Not an error. */
const char *ct_surface_note(ct_surface *s);
void ct_surface_note_clear(ct_surface *s);
/* One line about the rods built (the run's summary) and the table file's "surface" line. */
void ct_surface_describe(const ct_surface *s, const ct_plan_info *info, char *buf, size_t len);
void ct_surface_table_line(const ct_surface *s, const ct_plan_info *info, char *buf, size_t len);
/* The outputs only some kinds give; CT_EINVAL with the kind's reason where it gives none. */
/* what = profile: the surface as CSV with its header (b in the state to show). */
int ct_surface_write_profile(const ct_surface *s, const ct_bundle *b, FILE *f);
/* what = compare: the kind's columns beside e (names), and their values for nrows rows
 * (out[k * n + j]; NaN where not given: impacts after the first). */
size_t ct_surface_compare_columns(const ct_surface *s, const char *const **names);
int ct_surface_compare(ct_surface *s, const ct_sweep_row *rows, size_t nrows, double *out);
/* what = curve with compare: the kind's columns beside P (names; 0 when none), and their
 * values at u (unloading from u_max when unload), in P_Y; NaN where not given. */
size_t ct_surface_curve_compare_columns(const ct_surface *s, const char *const **names);
void ct_surface_curve_compare(const ct_surface *s, int unload, double u_max, double u, double *out);
/* After a sweep, for outputs that depend on where the impacts reached (a profile's bearing
 * fit redone on those depths); may leave a note. */
int ct_surface_after_sweep(ct_surface *s, const ct_sweep_row *rows, size_t nrows);
/* what = bearing (a profile's bearing-area curve beside its fit). */
int ct_surface_write_bearing(const ct_surface *s, FILE *f);
/* cantact geometry: the Cantor stages at the depth a run of req would use. */
int ct_surface_write_geometry(const ct_surface *s, const ct_build_request *req, FILE *f);
/* cantact fit: the Cantor surface a profile looks like, as a table. */
int ct_surface_write_fit(ct_surface *s, FILE *f);
/* A rods surface's rods from arrays, instead of surface.file or surface.rods: n tops, areas
 * and lengths (NULL: H* - top), copied; in surface.unit when given. */
int ct_surface_set_rods(ct_surface *s, size_t n, const double *top, const double *area,
                        const double *length);
/* The same with each rod's position [the unit of tops]: x (NULL: none) and y (NULL: rods on a
 * line), its footprint (a point). */
int ct_surface_set_rods_at(ct_surface *s, size_t n, const double *top, const double *area,
                           const double *length, const double *x, const double *y);
/* A random_cantor surface's generator settings (dimensionless parameters) and realisation. */
int ct_surface_random_cantor(const ct_surface *s, ct_random_cantor *rc, uint64_t *realisation);
/* A prepared profile surface's levelled profile and (fit not NULL) its fit. */
int ct_surface_profile(const ct_surface *s, const ct_profile **p, ct_profile_fit *fit);

/* The depth a Cantor surface is built at: setting (>= 0: itself; CT_DEPTH_AUTO: the
 * truncation bound below tol for the smallest speed V_min; CT_DEPTH_FRACTAL: the limit). */
int ct_cantor_choose_depth(const ct_params *p, long setting, double V_min, double tol, long *depth,
                           double *bound);

#if defined(__GNUC__)
#pragma GCC visibility pop
#endif
#ifdef __cplusplus
}
#endif
#endif
