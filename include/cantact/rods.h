/* cantact/rods.h: rod sets (bundles), their layer, each rod and its footprint. Part of the
 * library's API: include <cantact.h>, which includes every part; each part includes the parts it
 * needs. SPDX-License-Identifier: GPL-3.0-or-later */
#ifndef CANTACT_PART_RODS_H
#define CANTACT_PART_RODS_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include "cantact/status.h"

#ifdef __cplusplus
extern "C" {
#endif
#if defined(__GNUC__)
#pragma GCC visibility push(default)
#endif

/* ---- rod sets (docs/model.md §3-4) ---------------------------------------------------- */
/* A bundle is a set of rods (top, length = H* - top, area, plastic strain) in one Winkler
 * layer. It knows nothing of the surface that made it: every kind of surface (Cantor below,
 * measured and random ones) only makes rods. */

typedef struct ct_bundle ct_bundle;

/* The layer all rods of a bundle share, and the units of its outputs. */
typedef struct {
    double E;       /* Young's modulus [force/length^2], > 0 */
    double sigma_y; /* yield stress [force/length^2], 0 < sigma_y < E */
    double Hstar;   /* layer thickness H*: every rod reaches from its top down to H* [length] */
    double l0;      /* reference length (the surface's extent) [length], > 0: V*, P_Y */
    double h0;      /* reference depth [length], > 0: u/h0 and V* */
} ct_layer;

/* Returns CT_OK if every field is finite and in range, else CT_EINVAL with a message. */
int ct_layer_validate(const ct_layer *layer);

/* A surface's units (ct_surface_scales, after ct_surface_prepare). The model's rods live in the
 * layer's units; a Cantor surface is computed dimensionless (l0 = h0 = sigma_y = 1, E = E/sigma_y)
 * whatever its scale, and `physical` holds its values as given. */
typedef struct {
    ct_layer layer;      /* E, sigma_y, H*, l0, h0 of the rods as built [their units] */
    ct_layer physical;   /* the same as the scene gave them (its units: SI for SI scenes) */
    double force_unit;   /* P_Y = sigma_y l0 of the layer [force]: P / force_unit is P / P_Y */
    double energy_unit;  /* sigma_y l0 h0 of the layer [energy] */
    double energy_scale; /* l0 E h0 of the layer [energy]: V*^2 = W / energy_scale */
    double physical_energy_scale; /* l0 E h0 as given: V* = sqrt(m v^2 / (2 this)) */
} ct_scales;

/* Returns the bytes of memory the kernel can give without swapping (MemAvailable): the one
 * memory check of the library and the CLI before large allocations. */
size_t ct_available_memory(void);
/* Allocations below this many bytes skip that check: it reads /proc/meminfo (about 10 us), and
 * a small run would read it a dozen times for kilobytes. */
#define CT_MEMORY_CHECK_MIN 16777216.0

/* Memory per rod in bytes: top, length, area and plastic strain, 4 doubles. */
#define CT_BYTES_PER_ROD 32

/* Builds a virgin bundle of n rods from tops [length] (depth below the reference plane,
 * 0 <= top < H*) and areas [length] (> 0), both copied. */
int ct_bundle_from_rods(ct_bundle **out, const ct_layer *layer, size_t n, const double *top,
                        const double *area);
void ct_bundle_free(ct_bundle *b);
/* Returns a new bundle with the same rods, state and surface metadata. */
int ct_bundle_clone(ct_bundle **out, const ct_bundle *b);
/* Forgets all plastic strain (back to the virgin surface). */
void ct_bundle_reset(ct_bundle *b);

size_t ct_bundle_size(const ct_bundle *b);    /* rods held */
size_t ct_bundle_omitted(const ct_bundle *b); /* rods the surface left out as never touched */
const ct_layer *ct_bundle_layer(const ct_bundle *b); /* E, sigma_y, H*, l0, h0 */
/* Returns the name of the kind of surface that made the bundle ("rods" when built from
 * arrays, "cantor" for ct_cantor_bundle). */
const char *ct_bundle_surface(const ct_bundle *b);

/* Where a rod stands on the surface, the part of the plane its top face covers: what a curved
 * body meets first (docs/model.md §14). An interval [x_lo, x_hi] of a line surface (a Cantor
 * piece, a profile sample's share of the x-axis), a rectangle of an areal one (an X3P pixel),
 * or a point (x_lo = x_hi, y_lo = y_hi; y NaN on a line) where a rod is given by its position.
 * CT_FOOTPRINT_NONE: the rod stands for pieces at several places (a merged Cantor stage) or
 * its surface gave no position; every coordinate is then NaN. [length] */
typedef enum {
    CT_FOOTPRINT_NONE = 0,
    CT_FOOTPRINT_INTERVAL = 1,
    CT_FOOTPRINT_RECTANGLE = 2,
    CT_FOOTPRINT_POINT = 3,
} ct_footprint_shape;
typedef struct {
    int shape; /* ct_footprint_shape */
    double x_lo, x_hi, y_lo, y_hi;
} ct_footprint;

/* Rod k's data [length, length, length, dimensionless] and what its surface knows of it:
 * stage (-1 when the surface has no stages), x-extent [length] (NaN when the rod stands for
 * pieces at several places, e.g. a merged Cantor stage) and footprint. */
typedef struct {
    double top, length, area, plastic_strain;
    double x_left, x_right;
    long stage;
    ct_footprint footprint;
} ct_rod_info;
int ct_bundle_rod(const ct_bundle *b, size_t k, ct_rod_info *info);

/* Threads of this bundle's sums over rods (0: the OpenMP default; at most CT_MAX_THREADS,
 * larger requests are clamped). Results do not depend on it; nothing process-wide is
 * changed. Returns the number that will be used. */
#define CT_MAX_THREADS 1024
int ct_bundle_set_threads(ct_bundle *b, int threads);
/* Returns the OpenMP default thread count (OMP_NUM_THREADS), 1 without OpenMP. */
int ct_default_threads(void);

/* Rod-by-rod assembly (the cross-check of the curve, the composite rules' integrand and the
 * deep-segments workload). Every sum is blocked and combined in a fixed order: bitwise the
 * same for any thread count. None of these changes the bundle. */

/* Returns the total force P(u) [force] at the current state. */
double ct_bundle_force(const ct_bundle *b, double u);
/* P at m displacements in one pass over the rods; P[i] is bitwise ct_bundle_force(b, u[i]).
 * Fails only with CT_ENOMEM. */
int ct_bundle_force_many(const ct_bundle *b, const double *u, size_t m, double *P);
/* P at m displacements [force] of the state the bundle would have after being taken to
 * u_adv (its unloading curve from u_adv), without changing it. */
int ct_bundle_force_after(const ct_bundle *b, double u_adv, const double *u, size_t m, double *P);
/* ct_bundle_work(b, u_a, u_b[i]) for m end points in one pass, bitwise the same. */
int ct_bundle_work_many(const ct_bundle *b, double u_a, const double *u_b, size_t m, double *W);
/* Returns the work [energy] of P(u) at the current state from u_a to u_b (closed form per
 * rod; along a loading path from the current state this is the work done). */
double ct_bundle_work(const ct_bundle *b, double u_a, double u_b);
/* Returns the recoverable elastic energy [energy] at u of the state after being taken to
 * u (Eq. 40 in closed form: the unloading work from u). */
double ct_bundle_elastic_energy(const ct_bundle *b, double u);
/* Returns the displacement [length] of first contact at the current state. */
double ct_bundle_first_contact(const ct_bundle *b);
/* Returns the first contact [length] after being taken to u_adv (the release point). */
double ct_bundle_release(const ct_bundle *b, double u_adv);
/* Returns the smallest displacement [length] at which some rod yields (loading from the
 * current state). */
double ct_bundle_first_yield(const ct_bundle *b);
/* Advances every rod's state along the displacement path to u (Eq. 10). */
void ct_bundle_advance(ct_bundle *b, double u);

#if defined(__GNUC__)
#pragma GCC visibility pop
#endif
#ifdef __cplusplus
}
#endif
#endif
