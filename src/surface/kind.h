/* The seam between kinds of surface and everything else: a kind is one descriptor (its name,
 * its keys as rows, how it checks, prepares and builds, and the outputs only it can give);
 * src/surface/kind.c keeps the registry and the handle. Nothing outside src/surface/ asks
 * which kind a surface is: it asks the descriptor. */
#ifndef CT_SURFACE_KIND_H
#define CT_SURFACE_KIND_H

#include "internal.h"

#include <stdio.h>

typedef struct ct_kind ct_kind;

struct ct_surface {
    const ct_kind *kind;
    size_t index; /* in the registry */
    void *config; /* the kind's settings: its rows' offsets point here */
    char **given; /* per row: the value as given (NULL: not given) */
    char **where; /* per row: where it was given, for messages */
    int checked, prepared;
    ct_scales scales; /* after prepare */
    char note[600];   /* what the front-end may print (not an error; "" when none) */
};

/* A kind of surface: what every kind states and does (required), and what only some do
 * (optional: NULL or 0 where the kind has none). The outputs a kind gives follow from its
 * operations (kind.c's table of outputs says which operation gives each and what the others
 * are told), so a kind lists no outputs and no refusals of its own.
 *
 *   required   name, summary, keys/nkeys, config_size, defaults, check, prepare, build,
 *              describe, table_line
 *   optional   release      what prepare allocated
 *              ready        what an output needs before any impact (a profile's fit)
 *              write_profile  what = profile (the rods and their state)
 *              compare, ncompare, compare_names; curve_compare...  what = compare
 *              after_sweep  what a kind redoes once the impacts are known (a refit)
 *              write_bearing  what = bearing
 *              write_geometry cantact geometry
 *              write_fit    cantact fit
 *              realisations 1: the surface is one of many random realisations (ensembles,
 *                           what = realisations, cantact merge)
 *              profile_shows_state 1: what = profile shows the state after the impacts */
struct ct_kind {
    const char *name;
    const char *summary; /* one line */
    const ct_key *keys;  /* sections surface, material, and any the kind owns */
    size_t nkeys;
    size_t config_size;
    void (*defaults)(void *config);
    /* Keys together; scene names the scene for messages about no single key. */
    int (*check)(ct_surface *s, const char *scene);
    /* Files read, levelled; s->scales set. dir: where relative paths start (NULL: cwd). */
    int (*prepare)(ct_surface *s, const char *dir);
    int (*build)(const ct_surface *s, const ct_build_request *req, ct_bundle **out,
                 ct_plan_info *info);
    /* The run's summary line ("stage rods, depth 65 (auto: ...)"), and the table file's. */
    void (*describe)(const ct_surface *s, const ct_plan_info *info, char *buf, size_t len);
    void (*table_line)(const ct_surface *s, const ct_plan_info *info, char *buf, size_t len);
    /* optional */
    void (*release)(void *config); /* text keys are freed by kind.c */
    int (*ready)(ct_surface *s, const char *output);
    int (*write_profile)(const ct_surface *s, const ct_bundle *b, FILE *f);
    size_t ncompare;
    const char *const *compare_names;
    int (*compare)(ct_surface *s, const ct_sweep_row *rows, size_t n, double *out);
    size_t ncurve_compare;
    const char *const *curve_compare_names;
    void (*curve_compare)(const ct_surface *s, int unload, double u_max, double u, double *out);
    int (*after_sweep)(ct_surface *s, const ct_sweep_row *rows, size_t n);
    int (*write_bearing)(const ct_surface *s, FILE *f);
    int (*write_geometry)(const ct_surface *s, const ct_build_request *req, FILE *f);
    int (*write_fit)(ct_surface *s, FILE *f);
    int realisations;
    int profile_shows_state;
};

/* What both Cantor kinds take: the ratios (a random surface's centres), H (H* in units of
 * h0), the scales and the material; a kind's config holds it as a member, and its rows come
 * from the macros below. */
typedef struct {
    double fx, fz, H, h0, l0; /* [surface] */
    double E, sigma_y;        /* [material] */
} ct_cantor_keys;

/* clang-format off */
#define CT_CANTOR_SURFACE_ROWS(type, m, fx_doc, fz_doc)                                            \
    {"surface", "fx", CT_KEY_NUMBER, 1.0, INFINITY, CT_KEY_REQUIRED, NULL,                         \
     "must satisfy fx > 1", "", fx_doc, offsetof(type, m.fx)},                                     \
    {"surface", "fz", CT_KEY_NUMBER, 1.0, 2.0, CT_KEY_REQUIRED, NULL,                              \
     "must satisfy 1 < fz < 2", "", fz_doc, offsetof(type, m.fz)},                                 \
    {"surface", "H", CT_KEY_NUMBER, 1.0, INFINITY, CT_KEY_REQUIRED, NULL,                          \
     "H = H*/h0 must satisfy H > 1 (the stage-0 rod needs a length)", "",                          \
     "Winkler layer thickness H* in units of h0", offsetof(type, m.H)},                            \
    {"surface", "h0", CT_KEY_NUMBER, 0.0, INFINITY, 0, NULL, "must be > 0", "1",                   \
     "recess depth of stage 0 [length] (a scale: results are per h0)", offsetof(type, m.h0)},      \
    {"surface", "l0", CT_KEY_NUMBER, 0.0, INFINITY, 0, NULL, "must be > 0", "1",                   \
     "length of stage 0 [length] (a scale: results are per l0)", offsetof(type, m.l0)}
#define CT_CANTOR_MATERIAL_ROWS(type, m)                                                           \
    {"material", "E", CT_KEY_NUMBER, 0.0, INFINITY, CT_KEY_REQUIRED, NULL, "must be > 0", "",      \
     "Young's modulus (only E/sigma_y matters)", offsetof(type, m.E)},                             \
    {"material", "sigma_y", CT_KEY_NUMBER, 0.0, INFINITY, 0, NULL, "must be > 0", "1",             \
     "yield stress", offsetof(type, m.sigma_y)}
/* clang-format on */

/* h0 = l0 = sigma_y = 1 (the keys' defaults). */
void ct_cantor_keys_defaults(ct_cantor_keys *k);
/* E > sigma_y; the parameters as given (physical) and in the dimensionless form the model is
 * computed in (params: l0 = h0 = sigma_y = 1, H* = H, E = E/sigma_y), both validated; scene
 * names the scene in messages. */
int ct_cantor_keys_check(ct_surface *s, const ct_cantor_keys *k, const char *scene,
                         ct_params *physical, ct_params *params);

extern const ct_kind ct_kind_cantor, ct_kind_random_cantor, ct_kind_profile, ct_kind_rods;

/* The row of section.name among the kind's keys, its index in *k. */
const ct_key *ct_kind_key(const ct_kind *kind, const char *section, const char *name, size_t *k);
/* "where: section.name = value: reason" for row k of s (where and value as given). */
int ct_surface_key_error(const ct_surface *s, const char *section, const char *name, int status,
                         const char *fmt, ...) CT_PRINTF(5, 6);
/* 1 when row section.name was given. */
int ct_surface_given(const ct_surface *s, const char *section, const char *name);
/* Sets the front-end's note (appends with "; " when one is there). */
void ct_surface_note_set(ct_surface *s, const char *fmt, ...) CT_PRINTF(2, 3);
/* value as a message shows it: at most 80 characters, longer ones cut with "...". */
void ct_value_shown(const char *value, char *buf, size_t len);
/* A relative path joined to dir (malloc'ed; NULL on failure). */
char *ct_path_join(const char *dir, const char *path);
/* Fills scales from a layer as built and the layer as given. */
void ct_scales_of(ct_scales *sc, const ct_layer *built, const ct_layer *physical);

/* The units a kind that takes lengths, areas and stresses as given builds its rods in: each a
 * power of two of the given one (exact), 1 where the scale (h0, l0, sigma_y) lies within
 * [2^-64, 2^64] (ordinary scenes: the same bits), else the one that brings it into [1, 2),
 * so that a rod's stiffness E s / L and energy E s L stay within the doubles at any scale
 * (rods 1e-160 long at E = 1e200 were refused as crushed; 1e20 long of area 1e-300 failed).
 * Areas on a plane take an even power, whose square root (exact) is the unit of
 * the positions: positions are in the unit of l0 (a line) or of its square root (a plane), as
 * a curved body reads them (physical l0 over built l0). */
typedef struct {
    double length, area, stress; /* built per given */
    double position;             /* a footprint's coordinates, built per given */
} ct_build_units;
void ct_build_units_of(const ct_layer *given, int plane, ct_build_units *u);
/* The layer as built from the layer as given, in units u; CT_EINVAL naming the figure when the
 * given one has a field that is no finite positive normal double, or the built one leaves the
 * doubles (ct_layer_validate's checks on it: E/sigma_y times H* / h0 beyond 1.8e308). */
int ct_layer_built(const ct_layer *given, const ct_build_units *u, ct_layer *built);
/* CT_EINVAL naming rod k (its top, length and area as built, and what) when its stiffness
 * E s / L or its energy scale E s L is not a finite normal double in the built units, else
 * CT_OK: such a rod's force or work cannot be represented (what: the rod's name). */
int ct_rod_representable(const ct_layer *built, double top, double length, double area,
                         const char *what);

#endif
