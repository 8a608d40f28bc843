/* cantact/sweep.h: sweeps over speeds x impacts, and the Cantor plan. Part of the library's API:
 * include <cantact.h>, which includes every part; each part includes the parts it needs.
 * SPDX-License-Identifier: GPL-3.0-or-later */
#ifndef CANTACT_PART_SWEEP_H
#define CANTACT_PART_SWEEP_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include "cantact/impact.h"
#include "cantact/cantor.h"

#ifdef __cplusplus
extern "C" {
#endif
#if defined(__GNUC__)
#pragma GCC visibility push(default)
#endif

/* ---- planning and sweeps (src/sweep.c) ------------------------------------------- */

#define CT_DEPTH_AUTO (-1)
#define CT_DEPTH_FRACTAL (-2)

/* What a Cantor scene needs built. */
typedef struct {
    ct_params params;
    long depth; /* >= 0, CT_DEPTH_AUTO or CT_DEPTH_FRACTAL */
    ct_representation representation;
    double depth_tolerance; /* relative tolerance of depth auto */
    const double *V_star;   /* the speeds the bundle will see, dimensionless */
    size_t nvel;
    long impacts; /* impacts per speed */
    ct_impact_opts opts;
    int keep_all_rods; /* 1: leave out nothing (e.g. to write the whole profile) */
    int threads;       /* threads of the bundle's sums, 0: OpenMP default */
} ct_cantor_plan;

typedef struct {
    long depth;     /* the depth chosen */
    double bound;   /* its truncation bound (0 when the depth was given) */
    size_t rods;    /* rods built */
    size_t omitted; /* rods left out: no impact of the plan reaches them, and none of them
                       can be the first to yield, so no reported number changes */
    double u_reach; /* rods with tops below this were built [length] */
} ct_plan_info;

/* Chooses the depth, finds the deepest displacement any impact of the plan reaches (and the
 * first yield of the virgin surface), and builds the bundle without the rods beyond both. */
int ct_cantor_plan_build(const ct_cantor_plan *plan, ct_bundle **out, ct_plan_info *info);

/* One row of a sweep: one impact of one speed. A row holds its results or, when it failed or
 * was not run, its message, never both: message shares its bytes with r and dyn (a union), so
 * no row carries a message buffer beside its results. The message is the row's own: held
 * nowhere else and never freed, it lives as long as the row's memory, is copied with the row
 * (assignment, memcpy) and is overwritten when a sweep reuses the rows. A row that succeeded
 * has message "" (message_head, the bytes before r, starts with a NUL); a failed row's message
 * is at most 239 characters and its NUL (the bytes after that are unspecified). 272 bytes on
 * x86-64 (472 in earlier builds of 0.1.0, with the message beside r and dyn: code compiled
 * against that cantact.h must be rebuilt). */
typedef struct {
    size_t speed;  /* index of the speed in the input */
    long impact;   /* 1 for the first impact on the virgin surface */
    double V_star; /* dimensionless */
    int status;    /* CT_OK, or why this impact failed (the speed's later impacts are not run) */
    /* an anonymous struct in an anonymous union: C11; __extension__ keeps C99 and C++ quiet */
    /* clang-format off */
#ifdef __GNUC__
    __extension__
#endif
    union {
        /* clang-format on */
        char message[240]; /* why, when status != CT_OK (r and dyn are gone); "" when CT_OK */
        struct {
            char message_head[8]; /* message[0..7]: message[0] = '\0' when status == CT_OK */
            ct_impact_result r;   /* valid when status == CT_OK */
            ct_dynamics dyn;      /* with ct_sweep_spec.dynamics and status == CT_OK: the impact in
                                     time, in units where the mass is E l0 / h0, so that times are
                                     t / tau, tau = sqrt(m h0 / (E l0)) of any mass, and speeds in
                                     h0 / tau (v1 = sqrt(2) V* h0) */
        };
    };
} ct_sweep_row;

typedef void (*ct_progress_fn)(size_t done, size_t total, void *ctx);
/* Long work (a sweep, an ensemble, a table) takes an optional interrupt flag: another thread
 * (or a signal handler) sets *interrupt non-zero and the work stops at its next check, between
 * blocks of work (a speed, a block of rods of a pass over them, a realisation, a batch of a
 * table's impacts: a small fraction of a second apart), freeing what it made and returning
 * CT_EINTR; the results handed out are then incomplete. The flag is only read; NULL: never
 * stopped. Results that were not stopped do not depend on it, nor on a progress callback. */
/* Called around every impact of a speed: phase 0 before it (b in the pre-impact state, c its
 * curve), phase 1 after it (b in the post-impact state, c NULL). Return non-zero to stop. */
typedef int (*ct_observer_fn)(const ct_sweep_row *row, int phase, const ct_bundle *b,
                              const ct_curve *c, void *ctx);

/* How a sweep evaluates impacts. The curve answers each speed in O(log n) after a build that
 * costs about 170 bytes per rod event; the lean curve gives the same answers, bit for bit,
 * from its sorted events (16 bytes each, a yield's rod read from the bundle) and a checkpoint of
 * the sums every 32 breakpoints, at O(log n + 32) per query (about 48 bytes per rod while
 * built, 36 after); the rod path holds nothing but the bundle and solves all speeds together
 * by Newton's method on the closed forms summed rod by rod (a few tens of passes over the
 * rods). Auto takes the lean curve from 262144 rods when there are at most an eighth as
 * many rows (speeds x impacts) as rods or the full curve would take over a quarter of the
 * available memory, and the rod path when the curve would not fit in half the available
 * memory, or when it has over 4e6 events for at most 32 impacts. Observers, composite rules
 * and the impact in time always take the full curve. */
typedef enum {
    CT_PATH_AUTO = 0,
    CT_PATH_CURVE = 1,
    CT_PATH_RODS = 2,
    CT_PATH_LEAN = 3
} ct_sweep_path;

typedef struct {
    const double *V_star; /* speeds, dimensionless, any order */
    size_t nvel;
    long impacts; /* impacts per speed from the bundle's state, >= 1 */
    ct_impact_opts opts;
    int stop_on_error;       /* 1: return at the first failed impact */
    ct_progress_fn progress; /* optional, called after each speed */
    void *progress_ctx;
    ct_observer_fn observe; /* optional */
    void *observe_ctx;
    ct_sweep_path path; /* CT_PATH_AUTO (0) by default; observers, composite rules and
                           dynamics always use the full curve */
    ct_curve *curve;    /* optional workspace (NULL: a curve per call): the curve of b's state
                           is built here, its arrays reused from one sweep to the next (an
                           ensemble's realisations: no page faults for each new curve) */
    int dynamics;       /* 1: every row also gets its impact in time (ct_sweep_row.dyn); needs
                           the curve (the rod path is not taken) */
    const volatile int *interrupt; /* optional: stops with CT_EINTR once *interrupt != 0 (the
                                      rows are then incomplete) */
} ct_sweep_spec;

/* Runs every speed from b's state (b itself is not changed): rows[speed * impacts + i - 1]
 * gets impact i of that speed. The first impact of every speed reads one curve built once,
 * so each costs O(log n) plus the closed-form check. Returns CT_OK when the sweep ran (rows
 * carry their own statuses), a row's status under stop_on_error, or CT_ENOMEM. */
int ct_sweep(const ct_bundle *b, const ct_sweep_spec *spec, ct_sweep_row *rows);
/* The same sweep in blocks of `block` speeds, each block's rows (all impacts of its speeds,
 * row.speed the index in spec's speeds) handed to emit as soon as they are computed: memory
 * of block x impacts rows, whatever the number of speeds. The rows are those of ct_sweep, in
 * its order and bit for bit (the curve is built once, the closed-form check's sample chosen
 * over all speeds). No observer (CT_EINVAL). emit returns non-zero to stop (CT_ESKIPPED).
 * Under stop_on_error the block holding the first failure is emitted, then its status is
 * returned. */
typedef int (*ct_rows_fn)(const ct_sweep_row *rows, size_t n, void *ctx);
int ct_sweep_blocks(const ct_bundle *b, const ct_sweep_spec *spec, size_t block, ct_rows_fn emit,
                    void *ctx);

#if defined(__GNUC__)
#pragma GCC visibility pop
#endif
#ifdef __cplusplus
}
#endif
#endif
