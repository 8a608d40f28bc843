/* cantact/cantor.h: the Cantor prefractal's rods and truncation depth. Part of the library's API:
 * include <cantact.h>, which includes every part; each part includes the parts it needs.
 * SPDX-License-Identifier: GPL-3.0-or-later */
#ifndef CANTACT_PART_CANTOR_H
#define CANTACT_PART_CANTOR_H

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

/* ---- the Cantor surface (docs/model.md §2, src/surface/cantor.c) ---------------------- */

typedef enum {
    CT_REP_STAGES = 0,   /* one rod per Cantor stage (pieces merged): N + 1 rods */
    CT_REP_SEGMENTS = 1, /* one rod per Cantor piece: 2^(N+1) - 1 rods */
} ct_representation;

/* Largest depth accepted by the builder. */
#define CT_MAX_STAGES_DEPTH 100000000
#define CT_MAX_SEGMENTS_DEPTH 40

/* The layer of a Cantor surface: E, sigma_y, H*, l0, h0 of p. */
void ct_cantor_layer(const ct_params *p, ct_layer *layer);
/* Builds the depth-N prefractal (stages 0..N-1 carry s_i, the 2^N tips carry l_N) as a
 * virgin bundle. Rods whose top is deeper than u_reach (they can never be touched) are left
 * out; pass INFINITY to keep all. A bundle that would not fit in the available memory is
 * refused with CT_ENOMEM (the figure in the message) before anything is allocated. */
int ct_cantor_bundle(ct_bundle **out, const ct_params *p, ct_representation rep, long depth,
                     double u_reach);
/* The Cantor depth N and representation of a bundle ct_cantor_bundle made (-1 otherwise). */
long ct_cantor_depth(const ct_bundle *b);
int ct_cantor_representation(const ct_bundle *b);

#if defined(__GNUC__)
#pragma GCC visibility pop
#endif
#ifdef __cplusplus
}
#endif
#endif
