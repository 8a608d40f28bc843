/* cantact/curve.h: the load curve P(u) and quadrature. Part of the library's API: include
 * <cantact.h>, which includes every part; each part includes the parts it needs.
 * SPDX-License-Identifier: GPL-3.0-or-later */
#ifndef CANTACT_PART_CURVE_H
#define CANTACT_PART_CURVE_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include "cantact/rods.h"

#ifdef __cplusplus
extern "C" {
#endif
#if defined(__GNUC__)
#pragma GCC visibility push(default)
#endif

/* ---- the load curve P(u) (docs/model.md §4) ------------------------------------------- */
/* For a bundle's state P(u) is continuous and piecewise linear, with breakpoints at each
 * rod's contact and yield points. A curve holds it exactly: sorted breakpoints x_j, P_j, the
 * cumulative work W_j = int_{x_0}^{x_j} P du (the trapezoid rule on the breakpoints, exact for
 * P) and the dissipation D_j = sum over yielded rods of P_Y,rod (x_j - yield point): loaded
 * from the state to u, W(u) - D(u) comes back on unloading (Eq. 40). Built in one event
 * sweep: monotone runs of events are merged (O(n) for Cantor stages), arbitrary tops sorted
 * (O(n log n)); the result does not depend on the thread count. A built curve is read-only:
 * several threads may evaluate it at once. */

typedef struct ct_curve ct_curve;

/* Returns an empty curve (its arrays grow as needed and are reused by later builds). */
int ct_curve_alloc(ct_curve **out);
void ct_curve_free(ct_curve *c);
/* Builds P(u) of b's current state into c. */
int ct_curve_build(ct_curve *c, const ct_bundle *b);
size_t ct_curve_size(const ct_curve *c); /* breakpoints */
/* The sorted, distinct breakpoints [length] (x_0 is the first contact). */
const double *ct_curve_points(const ct_curve *c);
double ct_curve_first_contact(const ct_curve *c); /* [length] */
double ct_curve_first_yield(const ct_curve *c);   /* [length] */
/* Returns P(u) [force]; 0 below the first contact. */
double ct_curve_force(const ct_curve *c, double u);
/* Returns W(u) = int from the first contact to u of P [energy]. */
double ct_curve_work(const ct_curve *c, double u);
/* Returns the energy [energy] dissipated if loaded from the state to u (plastic work). */
double ct_curve_dissipation(const ct_curve *c, double u);
/* Returns the release point [length]: the first contact after being loaded to u. */
double ct_curve_release(const ct_curve *c, double u);
/* The u [length] where W(u) = W (W >= 0): the piece by binary search, then its quadratic; inf
 * where that u lies beyond the doubles, NaN for W < 0 or NaN. */
double ct_curve_inverse_work(const ct_curve *c, double W);

/* ---- quadrature ------------------------------------------------------------------ */

typedef enum {
    CT_QUAD_BREAKPOINTS = 0, /* the curve: trapezoid on the breakpoints, exact for P */
    CT_QUAD_TRAPEZOID = 1,   /* composite, K nodes, ignores breakpoints, order 2 */
    CT_QUAD_SIMPSON = 2,     /* composite, K nodes (odd), ignores breakpoints, order 4 */
    CT_QUAD_GAUSS = 3,       /* composite 3-point Gauss-Legendre, K nodes, order 6 */
    CT_QUAD_CLOSED = 4,      /* closed-form energies per rod, summed rod by rod */
} ct_quad_rule;

typedef double (*ct_function)(double x, void *ctx);

/* Integrates f over [a, b] with the given rule. For CT_QUAD_BREAKPOINTS, points holds the
 * sorted breakpoints (a and b need not be among them); otherwise nodes is K. *abserr is an
 * estimate of the absolute error (rounding for the exact rule). */
int ct_integrate(ct_function f, void *ctx, double a, double b, ct_quad_rule rule, size_t nodes,
                 const double *points, size_t npoints, double *result, double *abserr);
/* The integrand at m nodes at once: y[k] = f(x[k]). Returns CT_OK or a status. */
typedef int (*ct_batch_function)(const double *x, size_t m, double *y, void *ctx);
/* ct_integrate with an integrand that takes all nodes in one call. */
int ct_integrate_batch(ct_batch_function f, void *ctx, double a, double b, ct_quad_rule rule,
                       size_t nodes, const double *points, size_t npoints, double *result,
                       double *abserr);
/* Returns the rule's name, or NULL for an unknown rule. */
const char *ct_quad_rule_name(ct_quad_rule rule);

#if defined(__GNUC__)
#pragma GCC visibility pop
#endif
#ifdef __cplusplus
}
#endif
#endif
