/* cantact/impact.h: one impact, and the impact in time. Part of the library's API: include
 * <cantact.h>, which includes every part; each part includes the parts it needs.
 * SPDX-License-Identifier: GPL-3.0-or-later */
#ifndef CANTACT_PART_IMPACT_H
#define CANTACT_PART_IMPACT_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include "cantact/curve.h"

#ifdef __cplusplus
extern "C" {
#endif
#if defined(__GNUC__)
#pragma GCC visibility push(default)
#endif

/* ---- impact (docs/model.md §7) -------------------------------------------------------- */

typedef struct {
    ct_quad_rule rule; /* how W_load and W_unload are computed */
    size_t nodes;      /* K for the composite rules */
    double tolerance;  /* relative tolerance of the u_max solve (1e-14 by default) */
    int check;         /* CT_CHECK_ALL (default, 1): also the closed forms rod by rod (e_closed,
                          quad_error); CT_CHECK_NONE (0); CT_CHECK_AUTO (2, ct_sweep): every
                          speed while rods x rows stays within CT_CHECK_BUDGET, else a sample */
} ct_impact_opts;

/* The closed-form check: none, every impact, or bounded (a sweep checks every impact of every
 * speed while rods x impacts x speeds <= CT_CHECK_BUDGET rod evaluations, about 1 ms; beyond
 * it every impact of a sample of max(CT_CHECK_MIN_SPEEDS, budget / (rods x impacts)) speeds:
 * the slowest and fastest, the two around V*_c, and speeds nearest to log-spaced V* between
 * them; rows outside the sample have e_closed NaN). A checked row of the breakpoints rule
 * whose e differs from the closed forms' by more than CT_CHECK_E_BOUND + 2 e_rounding fails
 * (CT_ENOCONV): a wrong e never passes a check. */
enum { CT_CHECK_NONE = 0, CT_CHECK_ALL = 1, CT_CHECK_AUTO = 2 };
#define CT_CHECK_BUDGET 524288.0
#define CT_CHECK_MIN_SPEEDS 16
#define CT_CHECK_E_BOUND 1e-12
/* An ensemble (ct_ensemble) under CT_CHECK_AUTO checks the realisations whose index is a
 * multiple of this stride (0, 8, 16, ...), each on its sweep's own sample: a function of the
 * realisation alone, so the same for any thread count, split or sharing among processes. The
 * check of one realisation costs about a tenth of its computation; a wrong curve or impact
 * is wrong in every realisation. CT_CHECK_ALL checks every realisation, every impact. */
#define CT_ENSEMBLE_CHECK_STRIDE 8
/* The realisations of [first, first + count) that ct_ensemble checks under opts->check (a
 * range past UINT64_MAX ends there). */
uint64_t ct_ensemble_checked(const ct_impact_opts *opts, uint64_t first, uint64_t count);

typedef struct {
    double kinetic_energy;  /* 1/2 m v1^2 [energy] */
    double V_star;          /* sqrt(kinetic_energy / (l0 E h0)), dimensionless */
    double u_contact;       /* first contact at impact [length] */
    double u_max;           /* maximum displacement [length], Eq. 39 */
    double u_release;       /* last contact on rebound [length] */
    double W_load;          /* loading work by the rule [energy] */
    double W_unload;        /* unloading work by the rule [energy], Eq. 40 */
    double W_load_closed;   /* the same in closed form rod by rod [energy] (NaN: check off) */
    double W_unload_closed; /* [energy] (NaN: check off) */
    double e;               /* sqrt(W_unload / W_load), dimensionless */
    double e_closed;        /* sqrt(W_unload_closed / W_load_closed) (NaN: check off) */
    double quad_error;      /* |e - e_closed| (NaN: check off) */
    double e_rounding;      /* bound on the rounding error of e from u - top cancellation
                               (stiff rods, weak impacts): 64 eps u_max / min(u_max -
                               u_contact, u_max - u_release) */
    double V_star_crit;     /* critical V* of the pre-impact state (first yield) */
    int elastic;            /* 1 when below the critical velocity: e = 1 exactly */
} ct_impact_result;

/* Fills opts with the defaults (breakpoints rule, 1e-14, check on). */
void ct_impact_opts_default(ct_impact_opts *opts);
/* The closed-form check of a result of the breakpoints rule: CT_ENOCONV (with both values in
 * the message) when e and e_closed differ by more than CT_CHECK_E_BOUND + 2 e_rounding, CT_OK
 * otherwise or when unchecked (e_closed NaN) or under another rule. Every checked impact of
 * the library passes through it. */
int ct_impact_check(const ct_impact_opts *opts, const ct_impact_result *res);
/* Returns the energy [energy] needed to make the first rod yield from the current state,
 * and that displacement [length]. */
int ct_critical_energy(const ct_bundle *b, double *energy, double *u_yield);
/* One impact of kinetic energy W [energy] on the bundle's current state: loads to u_max,
 * unloads, and leaves the plastic strain in the bundle. */
int ct_impact(ct_bundle *b, double W, const ct_impact_opts *opts, ct_impact_result *res);
/* The same impact evaluated on a curve built from b's current state, without changing b
 * (b is read for the closed-form check, the release point and the composite rules). */
int ct_impact_eval(const ct_bundle *b, const ct_curve *c, double W, const ct_impact_opts *opts,
                   ct_impact_result *res);
/* Returns the u_max [length] reached from the current state by kinetic energy W [energy],
 * without changing the state. */
int ct_solve_umax(const ct_bundle *b, double W, double tolerance, double *u_max);

/* ---- the impact in time (docs/model.md §11, src/dynamics.c) -------------------------- */
/* The body (mass m per unit depth) obeys m u'' = -P(u) while in contact. P is piecewise
 * linear, so the motion is exact piece by piece: harmonic with omega = sqrt(k/m) on a piece of
 * slope k > 0, uniform deceleration on a plateau (k = 0). The time across a piece of width du
 * entered and left at speeds v_a, v_b is 2 du / (v_a + v_b) * atan(x) / x with
 * x = omega du / (v_a + v_b) (no cancellation, the plateau's 2 du / (v_a + v_b) as k -> 0); the
 * piece holding the turning point takes (1/omega) atan2(m omega v_a, P_a). Unloading is the
 * time-reverse of a loading from the release point along the unloading curve. */

typedef struct {
    double t_contact;    /* t_load + t_unload [time] */
    double t_load;       /* from first contact to u_max, = the time of the peak force [time] */
    double t_unload;     /* from u_max to release [time] */
    double P_peak;       /* P(u_max) [force]: P rises on loading and falls on unloading */
    double v1, v2;       /* incident and rebound speed [length/time] */
    double e_kinematic;  /* v2 / v1, dimensionless: v2 from the unloading curve's own work */
    double dissipated;   /* 1/2 m (v1^2 - v2^2) [energy] */
    double k_unload_max; /* the stiffest piece of the unloading curve [force/length] */
    double period_min;   /* 2 pi sqrt(m / k_unload_max) [time]: what a DEM time step resolves */
} ct_dynamics;

typedef struct {
    double t, u, v, P; /* [time], [length], [length/time] (> 0 towards the surface), [force] */
    int unloading;     /* 0 on loading (to u_max), 1 on unloading */
    int event;         /* 1 at a breakpoint of P (a rod's contact, yield or release), 0 on the
                          uniform grid */
} ct_history_point;

typedef struct {
    size_t n;
    ct_history_point *points; /* in time order */
} ct_history;

/* One impact of a body of mass m [mass/length] at speed v1 [length/time] on b's current
 * state, in time, without changing b: res as ct_impact_eval gives it (default options), dyn
 * its times and forces, and (hist not NULL) the history: every breakpoint of both branches
 * and `grid` points uniform in time over the contact. */
int ct_impact_history(const ct_bundle *b, double m, double v1, size_t grid, ct_impact_result *res,
                      ct_dynamics *dyn, ct_history *hist);
void ct_history_free(ct_history *h);
/* A bounce sequence on a copy of b's state: impact k + 1 strikes at impact k's rebound speed,
 * the rods' state carried; res[k], dyn[k] for impact k (arrays of nmax). It ends after nmax
 * impacts or once a rebound speed is below v_stop [length/time]; *n gets the impacts run
 * (a failed impact ends it with its status, *n counting those before it). */
int ct_bounce(const ct_bundle *b, double m, double v1, size_t nmax, double v_stop,
              ct_impact_result *res, ct_dynamics *dyn, size_t *n);

#if defined(__GNUC__)
#pragma GCC visibility pop
#endif
#ifdef __cplusplus
}
#endif
#endif
