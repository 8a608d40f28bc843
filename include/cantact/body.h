/* cantact/body.h: bodies: flat, cylinder, sphere. Part of the library's API: include <cantact.h>,
 * which includes every part; each part includes the parts it needs. SPDX-License-Identifier:
 * GPL-3.0-or-later */
#ifndef CANTACT_PART_BODY_H
#define CANTACT_PART_BODY_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include "cantact/keys.h"

#ifdef __cplusplus
extern "C" {
#endif
#if defined(__GNUC__)
#pragma GCC visibility push(default)
#endif

/* ---- bodies (docs/model.md §14) -------------------------------------------------- */
/* What strikes the rods: the paper's flat strip, a cylinder with its axis across a line
 * surface, or a sphere over an areal one. A body only shifts each rod's top by the gap of its
 * face at the rod's footprint (the first point of the footprint it reaches); everything after
 * that knows nothing of the body. The kinds of body are a registry, like the kinds of surface. */
typedef struct {
    int shape;          /* the body's index in the registry (0: flat, ct_body_name) */
    double radius;      /* R [the surface's length unit: metres for profiles and maps, the rods'
                           unit, l0's unit for Cantor surfaces], > 0 for a curved body */
    double position[2]; /* the apex: x, or x and y [length]; NaN: the middle of the surface */
    int periodic;       /* 1: the surface repeats as far as the face reaches (surface.periodic) */
    uint64_t landings;  /* [body] landings: apex positions drawn per run (0: position alone) */
    uint64_t seed;      /* [body] seed: landing k is ct_body_landing(..., seed, k, ...) */
} ct_body;
size_t ct_body_count(void);
const char *ct_body_name(size_t k);    /* "flat", "cylinder", "sphere" */
const char *ct_body_summary(size_t k); /* one line */
/* The rows of section [body] (shape, radius, position) and surface.periodic: offsets into
 * ct_body. */
const ct_key *ct_body_keys_table(size_t *n);
/* The flat body (shape 0, radius 0, position NaN). */
void ct_body_defaults(ct_body *body);
/* The gap [length] of the body's face at a horizontal distance r [length] from its apex:
 * R - sqrt(R^2 - r^2) for a curved body (computed as r^2 / (R + sqrt(R^2 - r^2))), INFINITY
 * beyond R, 0 for the flat body. */
double ct_body_gap(const ct_body *body, double r);
/* The rods of *b as the body meets them (docs/model.md §14): each top shifted by the face's
 * gap at the rod's footprint, the rods it cannot reach left out; *b is replaced (and freed).
 * scales: the units of the surface that made *b (ct_surface_scales). The flat body leaves *b
 * as it is. ct_surface_build does this for a build request's body. */
int ct_body_meet(const ct_body *body, const ct_scales *scales, ct_bundle **b);
/* Where a curved body may land on a surface (its rods as built, not met by a body; scales its
 * units): the apex positions lo[0] .. hi[0] in x and lo[1] .. hi[1] in y (NaN on a line) [the
 * surface's length unit] from which the face, however deep it goes before the layer crushes,
 * stays on the surface: the surface's extent less the reach sqrt(h (2R - h)) of a face down
 * to the deepest rod bottom h (R when h >= R) on every side; one period of a surface that
 * repeats. The region is the body's and the surface's alone (not the speeds'), so a landing is
 * the same point in every run. CT_EINVAL when no apex is left, or for the flat strip. */
int ct_body_landing_region(const ct_body *body, const ct_scales *scales, const ct_bundle *rods,
                           double lo[2], double hi[2]);
/* Landing k of seed in the region lo .. hi: lo + u (hi - lo) with u uniform in [0, 1), one
 * Philox4x64-10 block per landing (key: seed and a constant, counter: k); a pure function of
 * (seed, k), pos[1] NaN where lo[1] is. */
void ct_body_landing(const double lo[2], const double hi[2], uint64_t seed, uint64_t k,
                     double pos[2]);
/* "under a sphere of R = 0.0025, its apex at x = 1e-4, y = 2e-4" ("" for the flat body). */
void ct_body_describe(const ct_body *body, char *buf, size_t len);

#if defined(__GNUC__)
#pragma GCC visibility pop
#endif
#ifdef __cplusplus
}
#endif
#endif
