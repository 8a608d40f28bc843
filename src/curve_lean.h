/* The lean load curve (curve_lean.c): a curve held as its sorted events, for the sweep. */
#ifndef CT_CURVE_LEAN_H
#define CT_CURVE_LEAN_H

#include "curve_event.h"

typedef struct ct_lean ct_lean;

/* The lean curve of b's state (b's arrays are read while it is used: they must not change);
 * CT_ESKIPPED when W rounds to a sequence that is not monotone (take the full curve), else
 * CT_OK or CT_ENOMEM. */
int ct_lean_build(ct_lean **out, const ct_bundle *b);
void ct_lean_free(ct_lean *L);
/* Bytes of a lean curve of that many runs of rods while it is built. */
double ct_lean_bytes(size_t runs);
size_t ct_lean_size(const ct_lean *L);
double ct_lean_first_contact(const ct_lean *L);
double ct_lean_first_yield(const ct_lean *L);
/* The breakpoint with the largest x <= u (u >= the first contact); cmin (not NULL): the
 * smallest contact of the rods yielding after it (INFINITY: none). */
void ct_lean_piece(const ct_lean *L, double u, ct_point *p, double *cmin);
/* fn at every breakpoint in order (its x, P, W, ...: the full curve's very doubles), swept
 * from the start: O(n), nothing held. */
void ct_lean_each_point(const ct_lean *L, void (*fn)(void *ctx, const ct_point *p), void *ctx);
/* The breakpoint with the largest W <= W, and the next breakpoint's x (INFINITY: none). */
void ct_lean_piece_of_work(const ct_lean *L, double W, ct_point *p, double *x_next);
/* For the tests: sorts n records of 16 bytes, {double x; uint64_t tag}, by x's total order
 * (its bits: -NaN < -inf < ... < -0 < +0 < ... < +inf < +NaN), stable, as the lean curve sorts
 * its events before putting each run of equal x in the events' order; on team threads from
 * the size where the curve's sort uses them. -1 when out of memory. */
int ct_lean_sort_records(void *rec, size_t n, int team);

#endif
