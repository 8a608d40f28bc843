/* cantact/keys.h: scene keys as data, and the run keys. Part of the library's API: include
 * <cantact.h>, which includes every part; each part includes the parts it needs.
 * SPDX-License-Identifier: GPL-3.0-or-later */
#ifndef CANTACT_PART_KEYS_H
#define CANTACT_PART_KEYS_H

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

/* ---- scene keys as data (src/scene/keys.c) --------------------------------------- */
/* A key of a scene ("[section] name = value") is one row: its type, range, default and a
 * one-line doc. Front-ends (the CLI's INI scenes, Python's keyword arguments) parse values
 * through the rows, so they accept and refuse the same values with the same words; the key
 * list of `cantact run --help` and docs/scene-keys.md are printed from them. */

typedef enum {
    CT_KEY_NUMBER = 0, /* a finite double (lo, hi: see the flags); stored as double */
    CT_KEY_INTEGER,    /* a long, lo <= v <= hi; stored as long */
    CT_KEY_COUNT,      /* an integer 0 <= n < 2^64; stored as uint64_t */
    CT_KEY_WORD,       /* one of words ("a|b|c"); stored as int, the index of the word */
    CT_KEY_WORDS,      /* a list of words (commas or blanks); stored as unsigned, bit k = word k */
    CT_KEY_TEXT,       /* non-empty text (a path); stored as a malloc'ed char * */
    CT_KEY_DEPTH,      /* an integer lo..hi or one of words; stored as long, word k as -1 - k */
    CT_KEY_SPEEDS,     /* numbers > 0: "a, b, c" or "from:to:count[:log]"; stored as ct_speeds */
    CT_KEY_RANGE,      /* "from:to", 0 < from < to; stored as double[2] */
    CT_KEY_POINT,      /* "x" or "x, y", finite; stored as double[2] (y NaN when not given) */
} ct_key_type;

enum {
    CT_KEY_LO_CLOSED = 1, /* CT_KEY_NUMBER: v >= lo (else v > lo) */
    CT_KEY_HI_CLOSED = 2, /* CT_KEY_NUMBER: v <= hi (else v < hi) */
    CT_KEY_REQUIRED = 4,  /* the scene must give it */
    CT_KEY_FILE = 8,      /* CT_KEY_TEXT: the value names a file the surface reads */
};

typedef struct {
    const char *section; /* "surface", "material", "impact", ... */
    const char *name;
    ct_key_type type;
    double lo, hi;     /* the range (CT_KEY_NUMBER, CT_KEY_INTEGER, CT_KEY_DEPTH) */
    unsigned flags;    /* CT_KEY_* above */
    const char *words; /* CT_KEY_WORD, CT_KEY_WORDS, CT_KEY_DEPTH: "stages|segments" */
    const char *range; /* what an out-of-range value is told: "must satisfy 1 < fz < 2" */
    const char *def;   /* the default as shown in docs ("" : none, or set by other keys) */
    const char *doc;   /* one line */
    size_t offset;     /* where the value is stored in the settings the row belongs to */
} ct_key;

/* A CT_KEY_SPEEDS value. */
typedef struct {
    double *v; /* malloc'ed, in the order given */
    size_t n;  /* 1 .. CT_MAX_SPEEDS */
} ct_speeds;
#define CT_MAX_SPEEDS 1000000

/* Parses text for the row and stores it at (char *)settings + row->offset (a CT_KEY_TEXT or
 * CT_KEY_SPEEDS value replaces and frees the one there). CT_EINVAL with the reason alone in
 * ct_error_message() ("must satisfy 1 < fz < 2", "not a finite number", ...); CT_ENOMEM. */
int ct_key_parse(const ct_key *row, const char *text, void *settings);
/* The row's type and range in words for docs ("number, 1 < fz < 2", "stages | segments"). */
void ct_key_describe(const ct_key *row, char *buf, size_t len);
/* Frees a row's stored value (CT_KEY_TEXT, CT_KEY_SPEEDS) and zeroes it. */
void ct_key_clear(const ct_key *row, void *settings);
/* The word's index in "a|b|c", -1 when it is none of them. */
int ct_word_index(const char *words, const char *word);
/* The name of n nearest to given ("surface.fzz": "surface.fz"), for "did you mean": by edit
 * distance (an insertion, deletion, substitution or swap of neighbours each counts 1), when it
 * is close enough to be a slip: one edit when the part after the last dot has at most 3
 * characters, two beyond; the first of equals. Its index, or n when none is that close
 * (names equal to given and NULL names are passed over). */
size_t ct_nearest_name(const char *given, const char *const *names, size_t n);

/* The keys of a run that are not the surface's (sections impact, solver, table, ensemble),
 * where their rows (ct_run_keys_table) store them. */
typedef struct {
    ct_speeds V_star, velocity;                    /* [impact] */
    double mass, drop_height, gravity, stop_speed; /* [impact], the scene's units */
    long impacts;
    int sequence;   /* 0 sweep, 1 bounce */
    int quadrature; /* [solver]: ct_quad_rule */
    long nodes;
    double tolerance, depth_tolerance;
    long threads;
    int on_error, check, path;              /* stop|skip; auto|all|closed|none; ct_sweep_path */
    double table_tolerance, table_range[2]; /* [table] */
    int interpolation;
    long max_nodes, check_points;
    long realisations; /* [ensemble] */
    int split;
    ct_speeds table_quantiles; /* [table] of samples: the probabilities (n = 0: the default) */
    long table_grid;
    double table_quantile_tolerance; /* 0: the table's tolerance */
} ct_run_keys;
/* The rows of ct_run_keys (their offsets point into it): every front-end parses the run's
 * keys through them (ct_key_parse), so ranges, words and defaults are stated once. */
const ct_key *ct_run_keys_table(size_t *n);
/* The rows' defaults (the solver's are ct_impact_opts_default's). */
void ct_run_keys_defaults(ct_run_keys *k);
/* Frees the lists ct_key_parse stored (speeds) and zeroes them. */
void ct_run_keys_clear(ct_run_keys *k);
/* What the solver keys mean: the impact options, the sweep's path, its threads, whether a
 * failed impact is a row (on_error = skip), depth auto's tolerance. */
typedef struct {
    ct_impact_opts opts;
    ct_sweep_path path;
    int threads;
    int skip_failed;
    double depth_tolerance;
} ct_run_solver;
/* CT_OK, or CT_EINVAL with the reason alone when tolerance is below what doubles can meet. */
int ct_run_keys_solver(const ct_run_keys *k, ct_run_solver *out);

#if defined(__GNUC__)
#pragma GCC visibility pop
#endif
#ifdef __cplusplus
}
#endif
#endif
