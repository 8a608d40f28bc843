/* cantact/random_cantor.h: random Cantor surfaces. Part of the library's API: include <cantact.h>,
 * which includes every part; each part includes the parts it needs. SPDX-License-Identifier:
 * GPL-3.0-or-later */
#ifndef CANTACT_PART_RANDOM_CANTOR_H
#define CANTACT_PART_RANDOM_CANTOR_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include "cantact/geometry.h"
#include "cantact/rods.h"

#ifdef __cplusplus
extern "C" {
#endif
#if defined(__GNUC__)
#pragma GCC visibility push(default)
#endif

/* ---- random Cantor surfaces (docs/model.md §10, src/surface/random_cantor.c) ---------- */
/* Every split draws its own ratios: child k of a piece of width w whose middle stays at
 * depth h has width w / (2 fx_k) and depth h / fz_k, with fx_k and fz_k drawn independently
 * around the centres fx and fz. Each piece is its own rod (the segments layout: piece j of
 * stage i is rod 2^i - 1 + j, its children are rods 2g + 1 and 2g + 2). A realisation is a
 * pure function of (seed, realisation): the ratios of piece g come from Philox4x64-10 with
 * key (seed, realisation) and counter (g, 0, 0, 0), so any thread or process count gives the
 * same bits. */

typedef enum {
    CT_RATIO_UNIFORM = 0,   /* f_k = f (1 + spread (2U - 1)), U uniform on (0, 1) */
    CT_RATIO_LOGNORMAL = 1, /* f_k = f exp(spread Z), Z standard normal (Box-Muller): median f */
} ct_ratio_dist;

/* Largest depth of a random Cantor surface: 2^(N+1) - 1 rods. */
#define CT_MAX_RANDOM_DEPTH 30

typedef struct {
    ct_params params;   /* fx, fz: the centres of the ratio distributions; the rest as for Cantor */
    ct_ratio_dist dist; /* the kind of both ratio distributions */
    double fx_spread;   /* >= 0, dimensionless: uniform < 1, log-normal <= 10 */
    double fz_spread;   /* >= 0, dimensionless: as fx_spread */
    long depth;         /* stages 0..depth; 0 <= depth <= CT_MAX_RANDOM_DEPTH */
    uint64_t seed;
} ct_random_cantor;

/* Returns CT_OK when the surface is valid, else CT_EINVAL with a message. */
int ct_random_cantor_validate(const ct_random_cantor *rc);
/* Ratios of the split that made piece g >= 1 (rod g) in a realisation: fx_k, fz_k after
 * clipping into the valid ranges (fx_k > 1, 1 < fz_k < 2: a draw outside is moved to the
 * nearest double inside); *clipped gets bit 0 when fx_k was clipped, bit 1 when fz_k was. */
int ct_random_cantor_ratios(const ct_random_cantor *rc, uint64_t realisation, uint64_t g,
                            double *fx_k, double *fz_k, int *clipped);
/* Builds realisation `realisation` as a virgin bundle of 2^(depth+1) - 1 rods (no rod is
 * left out), sorted by top (shallowest first, ties in piece order), filled by `threads`
 * threads (0: the OpenMP default; the rods do not depend on it). 36 bytes per rod (the rods
 * and each rod's piece), 24 more while it is built. Rod info gives each piece's stage and
 * x-extent. */
int ct_random_cantor_bundle(ct_bundle **out, const ct_random_cantor *rc, uint64_t realisation,
                            int threads);
/* The piece g (rod index in tree order: 2^stage - 1 + j) that rod k of such a bundle is. */
int ct_random_cantor_piece(const ct_bundle *b, size_t k, uint64_t *g);
/* Draws of a bundle ct_random_cantor_bundle made: clipped fx and fz ratios, and ratios drawn
 * of each kind (2^(depth+1) - 2). CT_EINVAL for another bundle. */
int ct_random_cantor_clipped(const ct_bundle *b, uint64_t *fx_clipped, uint64_t *fz_clipped,
                             uint64_t *draws);

#if defined(__GNUC__)
#pragma GCC visibility pop
#endif
#ifdef __cplusplus
}
#endif
#endif
