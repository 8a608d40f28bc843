/* cantact: coefficient of restitution of a Cantor-fractal rough surface made of
 * elastic-perfectly-plastic rods on a Winkler foundation (see docs/model.md).
 *
 * Conventions: every fallible function returns an int status (CT_OK = 0); results come
 * back through pointer arguments; ct_error_message() holds the detail of the last error
 * raised in the calling thread. Lengths are in the unit of l_0 and h_0, forces per unit
 * depth, energies per unit depth.
 *
 * NULL: pointer arguments must not be NULL unless a function says otherwise. Functions that
 * create, run, solve or integrate (the *_alloc and builders, ct_curve_build, ct_impact*,
 * ct_sweep, ct_cantor_plan_build, ct_integrate*, the depth searches, the laws) check theirs
 * and return CT_EINVAL naming the argument; the *_free functions accept NULL; accessors and
 * evaluations on a handle (ct_bundle_size, ct_bundle_force, ct_curve_work, ...) do not check,
 * as they sit in hot loops. A NaN displacement gives a NaN force or work, never a number.
 *
 * Thread safety: the library keeps no global state and changes none (not the OpenMP thread
 * count, not GSL's error handler). A function that takes a const handle (const ct_bundle *,
 * const ct_curve *) only reads it: any number of threads may call such functions on one
 * handle at once. A function that takes a non-const handle (ct_bundle_advance, ct_impact,
 * ct_curve_build, ct_bundle_set_threads, ...) needs that handle to itself. Error messages are
 * per thread. Results do not depend on the number of threads.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef CANTACT_H
#define CANTACT_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The library is built with hidden visibility: what this header declares is its API. */
#if defined(__GNUC__)
#pragma GCC visibility push(default)
#endif

/* ---- status ---------------------------------------------------------------------- */

enum {
    CT_OK = 0,
    CT_EINVAL = 1,   /* a parameter or input is outside its valid range */
    CT_ENOMEM = 2,   /* allocation failed, or the request would not fit in memory */
    CT_ERANGE = 3,   /* the physics leaves the model (e.g. crushed layer, u_max >= H*) */
    CT_ENOCONV = 4,  /* a solve did not meet its tolerance */
    CT_EIO = 5,      /* a file could not be read or written */
    CT_ESKIPPED = 6, /* not run: an earlier impact of the same speed failed */
    CT_EINTR = 7,    /* stopped: the caller's interrupt flag was set (the spec's interrupt) */
};

/* Returns a static, generic description of a status code. */
const char *ct_strerror(int status);

/* Returns the detailed message of the last error raised in this thread ("" if none). */
const char *ct_error_message(void);

/* ---- parameters (docs/model.md §1) ---------------------------------------------------- */

typedef struct {
    double fx;      /* horizontal Cantor ratio, dimensionless, > 1 */
    double fz;      /* vertical Cantor ratio, dimensionless, 1 < fz < 2 */
    double l0;      /* length of stage 0 [length], > 0 */
    double h0;      /* recess depth of stage 0 [length], > 0 */
    double Hstar;   /* Winkler layer thickness H* [length], > h0 */
    double E;       /* Young's modulus [force/length^2], > 0 */
    double sigma_y; /* yield stress [force/length^2], 0 < sigma_y < E */
} ct_params;

/* Returns CT_OK if every parameter is finite and in range, else CT_EINVAL with a
 * message naming the first offending parameter and its valid range. */
int ct_params_validate(const ct_params *p);

/* ---- Cantor geometry (Eqs. 1-3, 16-18, 28) --------------------------------------- */
/* Stage indices are doubles so that deep (millions) and continuous stages work; values
 * that underflow are 0, never NaN. Parameters must have been validated. */

double ct_stage_length(const ct_params *p, double i); /* l_i = l0 fx^-i [length], Eq. 1 */
double ct_stage_depth(const ct_params *p, double i);  /* h_i = h0 fz^-i [length], Eq. 2 */
double ct_stage_area(const ct_params *p, double i);   /* s_i = l_i - l_{i+1} [length] */
double ct_alpha(const ct_params *p);                  /* ln fx / ln fz, Eq. 28 */
double ct_beta(const ct_params *p);                   /* 1/(fx fz), Eq. 18 */
double ct_one_minus_beta(const ct_params *p);         /* 1 - beta without cancellation */
double ct_dimension(const ct_params *p);              /* fractal dimension D, Eq. 3 */
/* Returns sum_{i=n1}^{n2} s_i [length] (Eq. 16); n2 may be INFINITY. */
double ct_sum_area(const ct_params *p, double n1, double n2);
/* Returns sum_{i=n1}^{n2} h_i s_i [length^2] (Eq. 17); n2 may be INFINITY. */
double ct_sum_depth_area(const ct_params *p, double n1, double n2);
/* x-extent [length] of piece j (0 <= j < 2^stage) of a depth-N prefractal: the middle left
 * at that stage, or for stage == depth a whole tip. */
int ct_piece_extent(const ct_params *p, long depth, long stage, size_t j, double *x_left,
                    double *x_right);
/* Returns the critical speed parameter's energy scale l0 E h0 [energy]: V*^2 = W / scale. */
double ct_energy_scale(const ct_params *p);

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
/* Sets the size from which this bundle's sums use a thread team (default
 * CT_PARALLEL_MIN_RODS; for the threshold benchmark). Results do not depend on it. */
void ct_bundle_set_parallel_min(ct_bundle *b, size_t rods);
/* Bundles below this many rods are summed by one thread: bench/bench_threshold measured the
 * 2-thread team >= 10% faster from 4095 rods on the 2-core CI machine. */
#define CT_PARALLEL_MIN_RODS 4096

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

/* Smallest depth N whose truncation changes forces and energies, relative to the
 * smallest impact of energy W_min, by less than tol; *bound gets the bound reached. */
int ct_auto_depth(const ct_params *p, double W_min, double tol, long *depth, double *bound);
/* The fractal limit N -> infinity to double precision: the smallest depth whose truncation
 * bound (as for ct_auto_depth) is below 1e-15 and whose tips lie within 1e-15 eps_y H* of the
 * reference plane (so that the first yield, hence V*_c, has converged too). */
int ct_fractal_depth(const ct_params *p, double W_min, long *depth, double *bound);

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
 * rods). Auto takes the lean curve from CT_LEAN_RODS rods when there are at most an eighth as
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
#define CT_LEAN_RODS 262144

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
/* ---- the paper's laws (docs/model.md §5-6) -------------------------------------------- */
/* Loads P [force] at displacement u [length] of the infinite fractal. Each function returns
 * CT_OK, CT_EINVAL (invalid parameters; u or u_max not finite or negative) or CT_ERANGE
 * (outside the law's domain); on error it leaves its output untouched. Thread-safe. */

/* Series, Eqs. 12-21 with Eq. 15 between nodes (h_i << H* in the elastic terms, exact yield
 * test of Eq. 29): P [force] at u [length]; CT_ERANGE for u > H* (crushed layer). */
int ct_series_load(const ct_params *p, double u, double *P);
/* Series unloading from u_max, Eqs. 22-24 (stages release at their own h-bar_i): P [force] at
 * u [length], a branch meant for u <= u_max; CT_ERANGE for u_max or u > H*. */
int ct_series_unload(const ct_params *p, double u_max, double u, double *P);
/* Asymptotic law, Eq. 33 (u <= eps_y H*) and Eq. 34: P [force] at u [length]; CT_ERANGE for
 * u > h0, where its continuous stage index n = -ln(u/h0)/ln fz is negative. */
int ct_asym_load(const ct_params *p, double u, double *P);
/* Asymptotic unloading, Eq. 38 as printed (consistent = 0), or with the second branch times
 * (1 - 1/fz)/(1 - beta) as derived from Eq. 23 (consistent = 1): P [force] at
 * u [length], a branch meant for u <= u_max; CT_ERANGE for u_max or u > h0. */
int ct_asym_unload(const ct_params *p, double u_max, double u, int consistent, double *P);
/* Work W [energy] of Eqs. 33-34 from 0 to u [length], closed form; CT_ERANGE for u > h0. */
int ct_asym_work_load(const ct_params *p, double u, double *W);
/* Work W [energy] of Eq. 38 from h-bar_inf = u_max - eps_y H* to u_max [length], closed form;
 * CT_ERANGE for u_max > h0. */
int ct_asym_work_unload(const ct_params *p, double u_max, int consistent, double *W);

typedef enum { CT_LAW_SERIES = 0, CT_LAW_ASYMPTOTIC = 1, CT_LAW_ASYMPTOTIC_CONSISTENT = 2 } ct_law;

/* e and u_max [length] of one impact of energy W on the virgin surface under a law: u_max
 * from Eq. 39 (to 1e-15 relative, else CT_ENOCONV), unloading energy from Eq. 40,
 * e = sqrt(W_unload / W_load); e = 1 exactly when no stage yields. CT_ERANGE where the law
 * does not apply (u_max beyond h0 or H*, W_unload > W_load). Thread-safe: no global state. */
int ct_law_impact(const ct_params *p, ct_law law, double W, double *u_max, double *e);
const char *ct_law_name(ct_law law);

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

/* ---- ensembles of realisations (src/ensemble.c) ---------------------------------- */

/* How an ensemble uses its threads: whole realisations per thread (each bundle summed by
 * one thread; memory: one realisation per thread), or one realisation at a time with its
 * rods shared by the threads. Auto: per realisation when a realisation has at most
 * CT_ENSEMBLE_SPLIT_RODS rods and there are at least two realisations. */
typedef enum {
    CT_SPLIT_AUTO = 0,
    CT_SPLIT_REALISATIONS = 1,
    CT_SPLIT_RODS = 2,
} ct_ensemble_split;
#define CT_ENSEMBLE_SPLIT_RODS ((size_t)1 << 21)

typedef struct {
    ct_random_cantor surface;
    uint64_t first;       /* realisations first .. first + count - 1 */
    uint64_t count;       /* >= 1 */
    const double *V_star; /* speeds, dimensionless */
    size_t nvel;
    long impacts; /* impacts per speed, >= 1 */
    ct_impact_opts opts;
    ct_sweep_path path;
    int stop_on_error; /* 1: stop at the first failed impact (lowest realisation, then row) */
    int threads;       /* 0: the OpenMP default */
    ct_ensemble_split split;
    ct_progress_fn progress; /* optional: realisations done (called by one thread at a time) */
    void *progress_ctx;
    const volatile int *interrupt; /* optional: stops with CT_EINTR once *interrupt != 0 */
} ct_ensemble_spec;

/* The samples of an ensemble: realisation first + r, row q = speed * impacts + impact - 1
 * at index r * nrows + q. Values in library units (u_max [length]); NaN where status != 0. */
typedef struct {
    uint64_t first, count;
    size_t nrows;
    double *e, *u_max, *V_star_crit;
    int *status;                       /* CT_OK, or why the impact failed / was not run */
    uint64_t *fx_clipped, *fz_clipped; /* per realisation */
    uint64_t draws;                    /* ratios drawn of each kind per realisation */
    double quad_error_max;             /* largest |e - e_closed| of all samples (NaN: no
                                          closed-form check) */
    uint64_t failed_realisation;       /* the first failure in (realisation, row) order */
    size_t failed_row;
    char message[240]; /* its message ("" when none failed) */
} ct_ensemble_samples;

/* Allocates the arrays for count realisations of nrows rows (all NaN, status CT_ESKIPPED). */
int ct_ensemble_samples_alloc(ct_ensemble_samples **out, uint64_t first, uint64_t count,
                              size_t nrows);
void ct_ensemble_samples_free(ct_ensemble_samples *s);
/* Runs every realisation of spec: build, sweep, drop. Samples do not depend on the thread
 * count, the split or on how realisations are shared among processes. Returns CT_OK (samples
 * carry their statuses), the first failure under stop_on_error, or CT_ENOMEM. */
int ct_ensemble(const ct_ensemble_spec *spec, ct_ensemble_samples *samples);

/* Statistics of one quantity over an ensemble. */
typedef struct {
    size_t n;             /* samples used (the NaN ones are left out) */
    double mean;          /* compensated sum in sample order, / n */
    double sd;            /* sample standard deviation (n - 1 in the denominator; NaN for n < 2) */
    double sem;           /* standard error of the mean, sd / sqrt(n) (NaN for n < 2) */
    double q05, q50, q95; /* quantiles: linear interpolation between order statistics,
                             x_(floor h) + (h - floor h)(x_(floor h + 1) - x_(floor h)),
                             h = (n - 1) p (Hyndman-Fan type 7, as R and NumPy) */
} ct_stats;

/* Statistics of x[0], x[stride], ..., x[(n - 1) stride], in that order (NaN left out):
 * the same input gives the same bits. work holds n doubles (the sort). CT_EINVAL when no
 * sample is finite. */
int ct_sample_stats(const double *x, size_t n, size_t stride, double *work, ct_stats *out);
/* Returns the p-quantile (0 <= p <= 1) of n >= 1 sorted values, type 7 as in ct_stats. */
double ct_quantile_sorted(const double *sorted, size_t n, double p);

/* ---- e(V*) tables with a checked interpolation error (src/table.c) --------------- */
/* e of the first impact on a bundle's state, as nodes in V* that a stated interpolation
 * reproduces within a tolerance everywhere it was checked: for DEM codes and notebooks that
 * need e at any speed without the model. The interpolation is in x = ln V*, linear or
 * monotone cubic (Hermite with Fritsch-Carlson-limited slopes: the Fritsch-Butland weighted
 * harmonic mean inside, three-point one-sided ends, as SLATEC PCHIM), and e = 1 exactly at and
 * below V*_c. include/cantact_table.h (dependency-free, for DEM codes) reads a written table
 * and evaluates it with the same code as ct_table_eval. */

typedef enum {
    CT_INTERP_MONOTONE_CUBIC = 0, /* = CT_TAB_MONOTONE_CUBIC of cantact_table.h */
    CT_INTERP_LINEAR = 1,         /* = CT_TAB_LINEAR */
} ct_interp;

/* Returns "monotone_cubic" or "linear", NULL for an unknown rule. */
const char *ct_interp_name(ct_interp rule);

typedef struct {
    double V_min, V_max; /* the range of V*, dimensionless, 0 < V_min < V_max */
    double tolerance;    /* largest |e_table - e| allowed, absolute, 1e-13 <= tolerance < 1 */
    ct_interp interpolation;
    size_t max_nodes;    /* the build fails (CT_ENOCONV) rather than exceed it; >= 2 */
    size_t check_points; /* points checked inside every interval, equally spaced in ln V*,
                            >= 1 (default 16) */
    ct_impact_opts opts; /* how each exact e is computed */
    ct_sweep_path path;
    ct_progress_fn progress; /* optional: exact impacts computed, of those planned so far (the
                                total grows when a round splits intervals) */
    void *progress_ctx;
    const volatile int *interrupt; /* optional: stops with CT_EINTR once *interrupt != 0 */
} ct_table_spec;

/* Fills spec with the defaults: tolerance 1e-6, monotone cubic, at most 100000 nodes, 16
 * checks per interval, ct_impact_opts_default, CT_PATH_AUTO (V_min, V_max left 0). */
void ct_table_spec_default(ct_table_spec *spec);

typedef struct ct_table ct_table;

/* What a build found. */
typedef struct {
    double V_star_crit; /* critical V* of b's state: e = 1 at and below it (a node when in range) */
    double worst_error; /* the largest |e_table - e| over every checked point, dimensionless */
    double worst_V_star; /* where it was found */
    size_t checked;      /* points checked: check_points inside each interval (nodes are exact) */
    size_t kinks;        /* nodes at kinks of e: V* where u_max reaches a breakpoint of P(u) */
    size_t rounds;       /* refinement rounds */
    size_t evaluations;  /* exact impacts computed */
} ct_table_info;

/* Builds the table of e(V*) of the first impact on b's current state (b is not changed):
 * starting from V_min, V_max, V*_c and two nodes per decade, every interval whose checks
 * exceed the tolerance is split, at the load curve's kink nearest its middle in ln V* when it
 * holds one (a rod's contact or yield point: there e has a kink), else at its middle, until
 * every check passes; the slopes are recomputed after every round and every interval checked
 * again. So the table never claims a tolerance it did not check. Returns CT_OK, CT_ENOCONV
 * (max_nodes reached, or an interval too short to split: the message says the worst error
 * and where), an exact impact's failure (e.g. CT_ERANGE: V_max crushes the layer), CT_EINVAL
 * or CT_ENOMEM. */
int ct_table_build(ct_table **out, const ct_bundle *b, const ct_table_spec *spec);
/* A table from given nodes (e.g. read back from a file): V_star strictly increasing, > 0,
 * e in [0, 1], slopes finite; the nodes are copied, info is zero but V_star_crit. */
int ct_table_from_nodes(ct_table **out, size_t n, const double *V_star, const double *e,
                        const double *slope, ct_interp rule, double V_star_crit);
void ct_table_free(ct_table *t);
size_t ct_table_size(const ct_table *t);          /* nodes */
const double *ct_table_V_star(const ct_table *t); /* nodes, dimensionless, increasing */
const double *ct_table_e(const ct_table *t);      /* e at the nodes */
const double *ct_table_slope(const ct_table *t);  /* de/d(ln V*) at the nodes */
ct_interp ct_table_interpolation(const ct_table *t);
void ct_table_get_info(const ct_table *t, ct_table_info *info);
/* Returns e at V* by the table's interpolation (cantact_table.h's rule); NaN for V* not > 0.
 * Outside the nodes and above V*_c: the nearest end's e. */
double ct_table_eval(const ct_table *t, double V_star);
/* Monotone cubic slopes d[i] = de/dx at nodes x[0..n) (strictly increasing, n >= 2) of y:
 * the Fritsch-Butland weighted harmonic mean inside, three-point one-sided ends limited to
 * three secants (Fritsch-Carlson), 0 at a local extremum. */
void ct_pchip_slopes(size_t n, const double *x, const double *y, double *d);
/* What a table file says of itself beyond its nodes. */
typedef struct {
    const char *version; /* the program's version, "" when none */
    const char *scene;   /* the scene's name (NULL: not written) */
    const char *surface; /* one line on the surface (ct_surface_table_line; NULL: none) */
    double tolerance;    /* the tolerance the build was asked for */
    size_t check_points; /* points checked inside every interval */
    double v_per_V_star; /* impact speed per V* in the scene's units (NaN: no mass given) */
} ct_table_meta;
/* Writes the table file include/cantact_table.h reads: "# key = value" lines, then
 * V_star,e,de_dlnV_star rows (round-trip digits). CT_EIO on a write error. */
int ct_table_write(FILE *f, const ct_table *t, const ct_table_meta *meta);
/* What a table file's header says that ct_table_read reads (NaN: the file does not say). */
typedef struct {
    double tolerance;    /* |e_table - e_model| the table was built for, dimensionless */
    double worst_error;  /* the largest |e_table - e_model| found when it was checked */
    double worst_V_star; /* where (NaN also for "none": no point above V*_c was checked) */
    double v_per_V_star; /* impact speed per unit V* in the scene's units */
} ct_table_file_info;
/* Reads a table file with include/cantact_table.h's reader (ct_tab_read: its acceptance rule,
 * one for every reader) into a table evaluated as ct_table_eval; file (may be NULL) gets the
 * header's numbers. CT_EINVAL for a file the reader refuses (the message names file:line),
 * CT_EIO when it cannot be opened or read, CT_ENOMEM. */
int ct_table_read(ct_table **out, const char *path, ct_table_file_info *file);

/* ---- measured surfaces (docs/model.md §9, src/surface/profile.c, profile_read.c, fit.c) --- */
/* A measured line profile z(x_j) or areal topography z(x_i, y_j) is a rod set directly: after
 * levelling, the plane touches the highest point; sample j is a rod with top depth
 * t_j = max z - z_j, its share of the x-axis (a line) or the pixel area (a grid) as its area,
 * and length H* - t_j. P(u) depends only on the bearing-area curve
 * phi(d) = (area with top depth <= d) / (total area). */

typedef struct {
    size_t n;              /* valid samples */
    size_t nx, ny;         /* a line: nx samples, ny = 1; a grid: nx by ny (row-major, x fastest) */
    double *x;             /* a line: the positions [length], increasing; NULL for a grid */
    double *z;             /* heights [length], up; NaN where a grid point is invalid */
    double dx, dy;         /* a grid's spacings [length]; a uniform line's dx (0: non-uniform) */
    size_t invalid;        /* grid points left out (the X3P mask, or NaN) */
    char source[128];      /* what was read: "text", "dektak", "x3p" */
    double x_unit, z_unit; /* read: metres per file unit of x and z (1 for X3P and made ones) */
} ct_profile;

typedef enum {
    CT_DETREND_NONE = 0,
    CT_DETREND_MEAN = 1,      /* the mean height removed */
    CT_DETREND_LINEAR = 2,    /* the least-squares line (a plane for a grid) removed */
    CT_DETREND_QUADRATIC = 3, /* the least-squares parabola (quadric surface) removed */
} ct_detrend;

/* How a text file is read: two columns x z, or one column z with spacing dx. Values are
 * multiplied by x_unit, z_unit [length / file unit] (1e-6 for micrometres read in metres); a
 * unit 0 takes the one the file's column names state ("Lateral um,Raw Micrometer", "z (nm)",
 * "x [mm]": m, mm, um, micrometre, micron, nm, the micro sign in latin-1 or UTF-8), and it is
 * an error when they state none. X3P files state theirs (metres): units and dx must be 0. */
typedef struct {
    double x_unit, z_unit;
    double dx; /* > 0: one column of heights at this spacing [file units]; 0: two columns */
} ct_profile_read_opts;

/* Reads a profile: an X3P file (ISO 25178-72, a zip with main.xml), a Dektak export (a header
 * block, then "Lateral um,Raw Micrometer" rows), or text/CSV (# or ; comments, commas, tabs
 * or blanks between the columns, latin-1 or UTF-8). One pass over the file. Errors name the
 * file and its line (or the X3P entry): non-numeric rows, x not increasing, fewer than 3
 * points, a zip without main.xml, a grid whose size disagrees with its header. */
int ct_profile_read(const char *path, const ct_profile_read_opts *opts, ct_profile **out);
/* A line profile from arrays (x NULL: uniform spacing dx), copied. */
int ct_profile_from_line(ct_profile **out, size_t n, const double *x, double dx, const double *z);
/* A grid from row-major heights (NaN: invalid), copied. */
int ct_profile_from_grid(ct_profile **out, size_t nx, size_t ny, double dx, double dy,
                         const double *z);
void ct_profile_free(ct_profile *p);
/* Removes the least-squares mean, line (plane) or parabola (quadric) from the heights. */
int ct_profile_level(ct_profile *p, ct_detrend how);
/* Spikes, an explicit choice: heights more than k Rq above the mean are cut to mean + k Rq;
 * *clipped gets how many were. */
int ct_profile_trim(ct_profile *p, double k, size_t *clipped);

typedef struct {
    double mean, Ra, Rq; /* [length] about the mean height */
    double Rt;           /* peak to valley [length] */
    double length;       /* the profile's length (a line: x_n - x_1 plus one spacing) or the
                            grid's area [length or length^2]: the surface's l0 */
} ct_profile_stats;
int ct_profile_stats_of(const ct_profile *p, ct_profile_stats *s);

/* The rods of a profile in a layer of thickness Hstar (> Rt) [length] with E, sigma_y: the
 * layer's l0 is the profile's length (a line, forces per unit depth) or area (a grid, forces),
 * its h0 the peak-to-valley depth Rt, so V* = sqrt(m v^2 / (2 l0 E h0)) with that l0 and h0.
 * Rod info gives each rod's x-extent (a line) or x (a grid); no stages. */
int ct_profile_bundle(ct_bundle **out, const ct_profile *p, double E, double sigma_y, double Hstar);

/* The bearing-area curve at n depths d [length] (ascending): phi[k] = fraction of the area
 * whose top lies within d[k] of the highest point. */
int ct_profile_bearing(const ct_profile *p, size_t n, const double *d, double *phi);

/* A straight-line fit in log-log: y = slope x + intercept through n points whose abscissas
 * span [lo, hi] (in their own units: depth, lag, window width or wavenumber); r2 its
 * coefficient of determination, residual the rms of its residuals (in ln units). */
typedef struct {
    double lo, hi;
    size_t n;
    double slope, intercept, r2, residual;
} ct_fit_line;

/* The profile's fractal dimension D, three ways: the variation method (the area of the
 * graph's eps-neighbourhood ~ eps^(2 - D), its box-counting dimension: Eq. 3's D for a Cantor
 * profile), the structure function S(tau) ~ tau^(2 (2 - D)) and the power spectrum
 * C(q) ~ q^-(5 - 2D) (GSL's FFT, a Hann window). For a self-affine profile all three agree; a
 * step profile (the Cantor prefractal itself) pins the last two at 1.5 by its jumps. */
typedef enum {
    CT_DIM_VARIATION = 0, /* the default */
    CT_DIM_STRUCTURE = 1,
    CT_DIM_SPECTRUM = 2,
} ct_dimension_method;

/* The Cantor surface a profile looks like (docs/model.md §9): alpha and h0 from the bearing curve
 * (ln phi = alpha ln d - alpha ln h0), D by the method asked for (all three reported), then
 * Eq. 3 inverted: ln fz = ln 2 (2 - D) / (1 + alpha (D - 1)), ln fx = alpha ln fz; l0 the
 * profile's length (a grid: its length along x). A grid is read along x, row by row. */
typedef struct {
    ct_dimension_method dimension; /* in: the D that enters Eq. 3 */
    ct_fit_line bearing;           /* ln phi against ln d, d [length] */
    double alpha, h0;              /* dimensionless, [length] */
    ct_fit_line variation;         /* ln V against ln eps, eps [length] (window width) */
    ct_fit_line structure;         /* ln S against ln tau, tau [length] */
    ct_fit_line spectrum;          /* ln C against ln q, q [1/length] */
    double D_variation, D_structure, D_spectrum;
    double D;          /* the one used */
    double fx, fz, l0; /* Eq. 3 with alpha and D; l0 [length] */
    ct_profile_stats stats;
} ct_profile_fit;

/* Bands (0 for the default): depths [d_lo, d_hi] for the bearing fit (default: from the depth
 * of the 20th highest sample to where phi reaches 0.1, the top of the bearing area an impact
 * touches); lags [tau_lo, tau_hi] for the three dimensions (default 2 spacings to a tenth
 * of the length). fit->dimension is read (the method for Eq. 3), everything else written.
 * CT_EINVAL when the heights are all equal or a band holds fewer than 3 points. */
int ct_profile_fit_of(const ct_profile *p, double d_lo, double d_hi, double tau_lo, double tau_hi,
                      ct_profile_fit *fit);
/* The bearing fit of a whole fit (ct_profile_fit_of) redone on depths [d_lo, d_hi] (0: the
 * default), alpha, h0, fx and fz with it; the dimensions are kept. On error fit is unchanged. */
int ct_profile_fit_bearing(const ct_profile *p, double d_lo, double d_hi, ct_profile_fit *fit);
/* The bearing fit redone on the depths n impacts reached (u_max [length], NaN ones left out):
 * from the shallowest (not above the fit's default band's start) to the deepest (not below
 * Rt), as `cantact run` does for compare and bearing. CT_EINVAL when that band holds no fit. */
int ct_profile_fit_on_reach(const ct_profile *p, const ct_profile_fit *fit, const double *u_max,
                            size_t n, ct_profile_fit *out);
/* The fitted Cantor surface beside a profile's rods (layer: its E, sigma_y, H*): for n impact
 * energies W [energy per unit depth; a grid: energy] (NaN ones skipped), e of the fitted
 * surface's exact rods at its fractal depth, e of the asymptotic law with the fitted
 * parameters, and the fitted surface's V*. CT_ERANGE when the fit leaves the model's ranges. */
int ct_profile_fitted_e(const ct_profile *p, const ct_profile_fit *fit, const ct_layer *layer,
                        const double *W, size_t n, int threads, double *e_fit, double *e_asym,
                        double *V_fit);
/* The fit as CSV: quantity,value,band_lo,band_hi,points,r2,rms_residual_ln (lengths in m), after
 * a '#' line on the source and, when a dimension is outside (1, 2), a '# warning: ' line with
 * ct_profile_fit_warning's text. */
int ct_profile_fit_write(FILE *f, const ct_profile_fit *fit, const char *source, size_t n);
/* How many of the fit's three dimensions lie outside (1, 2), the range of a profile's fractal
 * dimension (0: none, buf ""); buf gets one line naming them and, when the one Eq. 3 took is
 * among them, that fx and fz describe no Cantor surface. */
size_t ct_profile_fit_warning(const ct_profile_fit *fit, char *buf, size_t len);

/* ---- output columns as data (src/columns.c) -------------------------------------- */
/* The quantities of a sweep's rows, each a column: its name (the CSV header, Python's
 * attribute), its unit, its format and where it sits in ct_sweep_row. Groups: "e" the e
 * table, "time" the columns of what = time, "row" the library's and Python's only. */

typedef enum {
    CT_UNIT_ONE = 0,    /* dimensionless as computed */
    CT_UNIT_LENGTH = 1, /* a length: divided by h0 */
    CT_UNIT_FORCE = 2,  /* a force: divided by P_Y = sigma_y l0 */
    CT_UNIT_ENERGY = 3, /* an energy: divided by P_Y h0 */
    CT_UNIT_TIME = 4,   /* t / tau as computed (the sweep's mass is E l0 / h0) */
    CT_UNIT_COUNT = 5,  /* an integer */
    CT_UNIT_SPEED = 6,  /* a speed in h0 / tau, from V*: v1 = sqrt(2) V* h0 / tau */
} ct_unit;

typedef struct {
    const char *name;  /* "u_max_over_h0" */
    const char *group; /* "e", "time" or "row" */
    ct_unit unit;
    char type;            /* 'd' double, 'l' long, 'i' int: the field in ct_sweep_row; 'w':
                             the double at offset times the row's e (a rebound from an impact) */
    int digits;           /* 17: round trip ("%.17g"), 3: "%.3g" */
    const char *physical; /* its twin in the scene's units when a mass is given ("t_contact_s") */
    double divisor;       /* the value is divided by it last (the DEM step: period / 50) */
    size_t offset;        /* of the field in ct_sweep_row */
    const char *doc;      /* one line */
} ct_column;

/* The columns, in the order the CLI writes them within each group. */
size_t ct_sweep_columns(const ct_column **cols);
/* Column c of a row, dimensionless by the layer the rows were computed in. */
double ct_column_value(const ct_column *c, const ct_sweep_row *row, const ct_layer *layer);
/* Column c of n rows into out[0 .. n-1]: out[k] is bitwise ct_column_value(c, rows + k, layer)
 * (one call for a column of a sweep, where a front-end calling per row pays per call). */
void ct_column_values(const ct_column *c, const ct_sweep_row *rows, size_t n, const ct_layer *layer,
                      double *out);
/* Column c of a row in the physical layer's units (tau [time] for times): its twin. */
double ct_column_physical(const ct_column *c, const ct_sweep_row *row, const ct_layer *layer,
                          const ct_layer *physical, double tau);

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

/* ---- surfaces of every kind (src/surface/kind.c) --------------------------------- */
/* A surface is one kind (cantor, random_cantor, profile, rods: ct_surface_kind_name) set up
 * by its scene keys (sections surface and material, and what else the kind owns), prepared
 * (a measured profile is read and levelled; every kind fixes its scales) and built into rods
 * for the speeds asked. Everything after the rods knows nothing of the kind. The kind also
 * says which outputs it supports, and why not the others. */

typedef struct ct_surface ct_surface;

/* The kinds, in registry order: n of them; name and one-line summary of kind k. */
size_t ct_surface_kind_count(void);
const char *ct_surface_kind_name(size_t k);
const char *ct_surface_kind_summary(size_t k);
/* The key rows of kind k (its [surface] keys, [material] and any section it owns). */
const ct_key *ct_surface_kind_keys(size_t k, size_t *n);
/* Whether kind k supports an output or subcommand ("e", "time", "curve", "history",
 * "profile", "compare", "bearing", "bounce", "ensemble", "realisations", "table",
 * "geometry", "fit", "merge"): 1, or 0 with *why saying why not and what to use instead. */
int ct_surface_kind_supports(size_t k, const char *output, const char **why);
/* The outputs and subcommands every kind is asked about, space separated. */
const char *ct_surface_outputs(void);

/* A new surface of the kind named (CT_EINVAL naming the kinds for another name); every key
 * at its default. */
int ct_surface_new(ct_surface **out, const char *kind);
void ct_surface_free(ct_surface *s);
/* The kind's index and name. */
size_t ct_surface_kind_index(const ct_surface *s);
const char *ct_surface_kind(const ct_surface *s);
/* The row of section.name among the kind's keys, NULL when the kind has no such key. */
const ct_key *ct_surface_key(const ct_surface *s, const char *section, const char *name);
/* Sets a key from text; where ("file:line", "--set", "") prefixes messages: CT_EINVAL with
 * "where: section.name = value: reason". A key the kind does not have is CT_EINVAL saying
 * which kinds take it. */
int ct_surface_set(ct_surface *s, const char *section, const char *name, const char *value,
                   const char *where);
/* A key's value as parsed (its default when not given) as a number: a number, an integer, a
 * depth (auto -1, fractal -2), a count, or a word's index. CT_EINVAL for a text key. */
int ct_surface_value(const ct_surface *s, const char *section, const char *name, double *out);
/* 1 when the key was set. */
int ct_surface_is_set(const ct_surface *s, const char *section, const char *name);
/* Checks the keys together (required ones, exclusive ones, E > sigma_y ...); scene names
 * the scene in messages that concern no single key. */
int ct_surface_check(ct_surface *s, const char *scene);
/* The k-th file the surface reads (its keys flagged CT_KEY_FILE, joined to dir as
 * ct_surface_prepare joins them) into buf: 1, or 0 when it reads fewer. */
int ct_surface_input(const ct_surface *s, size_t k, const char *dir, char *buf, size_t len);
/* Reads what the surface needs (a profile's file, a rod file; relative paths from dir, NULL:
 * the working directory), levels it, fixes its scales. Idempotent. */
int ct_surface_prepare(ct_surface *s, const char *dir);

/* A surface's units (after ct_surface_prepare). The model's rods live in the layer's units;
 * a Cantor surface is computed dimensionless (l0 = h0 = sigma_y = 1, E = E/sigma_y) whatever
 * its scale, and `physical` holds its values as given. */
typedef struct {
    ct_layer layer;      /* E, sigma_y, H*, l0, h0 of the rods as built [their units] */
    ct_layer physical;   /* the same as the scene gave them (its units: SI for SI scenes) */
    double force_unit;   /* P_Y = sigma_y l0 of the layer [force]: P / force_unit is P / P_Y */
    double energy_unit;  /* sigma_y l0 h0 of the layer [energy] */
    double energy_scale; /* l0 E h0 of the layer [energy]: V*^2 = W / energy_scale */
    double physical_energy_scale; /* l0 E h0 as given: V* = sqrt(m v^2 / (2 this)) */
} ct_scales;
void ct_surface_scales(const ct_surface *s, ct_scales *out);
/* V* of a body of mass m [mass/length; a grid: mass] at speed v [length/time], in the
 * surface's physical units: sqrt(m / (2 l0 E h0)) v. */
double ct_speed_to_V_star(const ct_scales *sc, double m, double v);
/* V* = sqrt(m / (2 l0 E h0)) v of a body of mass m at speed v on a surface of scales l0, E,
 * h0 (consistent units): the one conversion of every front-end. */
double ct_V_star_of(double m, double v, double l0, double E, double h0);
/* tau = sqrt(m h0 / (E l0)) [time] of a body of mass m in the physical units. */
double ct_time_scale(const ct_scales *sc, double m);

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
/* "under a sphere of R = 0.0025, its apex at x = 1e-4, y = 2e-4" ("" for the flat body). */
void ct_body_describe(const ct_body *body, char *buf, size_t len);

/* What a build is for: the speeds it will see and how. */
typedef struct {
    const double *V_star; /* dimensionless, > 0 */
    size_t nvel;
    long impacts; /* per speed, >= 1 */
    ct_impact_opts opts;
    int keep_all_rods;      /* 1: leave out nothing (the whole surface is written) */
    int threads;            /* of the bundle's sums; 0: the OpenMP default */
    double depth_tolerance; /* of depth auto (Cantor): relative truncation bound */
    const ct_body *body;    /* what strikes the rods (NULL: the flat strip of the paper) */
} ct_build_request;
/* The rods of a prepared surface for the request (a Cantor surface plans its depth and
 * leaves out what no impact reaches; a random one builds its realisation). */
int ct_surface_build(const ct_surface *s, const ct_build_request *req, ct_bundle **out,
                     ct_plan_info *info);
/* Prepares what an output needs before any impact (a profile's fit for compare, bearing,
 * fit): CT_OK, or CT_EINVAL with the kind's reason when the kind does not give the output. */
int ct_surface_ready(ct_surface *s, const char *output);
/* 1 when what = profile shows the state after the impacts (the residual tops), so that it
 * is written at the last impact; 0 when it does not depend on the state (a profile's heights). */
int ct_surface_profile_shows_state(const ct_surface *s);
/* A note for the front-end to show (what was read, a refit), "" when none; cleared by
 * ct_surface_note_clear. Not an error. */
const char *ct_surface_note(ct_surface *s);
void ct_surface_note_clear(ct_surface *s);
/* One line about the rods built (the run's summary) and the table file's "surface" line. */
void ct_surface_describe(const ct_surface *s, const ct_plan_info *info, char *buf, size_t len);
void ct_surface_table_line(const ct_surface *s, const ct_plan_info *info, char *buf, size_t len);
/* The outputs only some kinds give; CT_EINVAL with the kind's reason where it gives none. */
/* what = profile: the surface as CSV with its header (b in the state to show). */
int ct_surface_write_profile(const ct_surface *s, const ct_bundle *b, FILE *f);
/* what = compare: the kind's columns beside e (names), and their values for nrows rows
 * (out[k * n + j]; NaN where not given: impacts after the first). */
size_t ct_surface_compare_columns(const ct_surface *s, const char *const **names);
int ct_surface_compare(ct_surface *s, const ct_sweep_row *rows, size_t nrows, double *out);
/* what = curve with compare: the kind's columns beside P (names; 0 when none), and their
 * values at u (unloading from u_max when unload), in P_Y; NaN where not given. */
size_t ct_surface_curve_compare_columns(const ct_surface *s, const char *const **names);
void ct_surface_curve_compare(const ct_surface *s, int unload, double u_max, double u, double *out);
/* After a sweep, for outputs that depend on where the impacts reached (a profile's bearing
 * fit redone on those depths); may leave a note. */
int ct_surface_after_sweep(ct_surface *s, const ct_sweep_row *rows, size_t nrows);
/* what = bearing (a profile's bearing-area curve beside its fit). */
int ct_surface_write_bearing(const ct_surface *s, FILE *f);
/* cantact geometry: the Cantor stages at the depth a run of req would use. */
int ct_surface_write_geometry(const ct_surface *s, const ct_build_request *req, FILE *f);
/* cantact fit: the Cantor surface a profile looks like, as a table. */
int ct_surface_write_fit(ct_surface *s, FILE *f);
/* A rods surface's rods from arrays, instead of surface.file or surface.rods: n tops, areas
 * and lengths (NULL: H* - top), copied; in surface.unit when given. */
int ct_surface_set_rods(ct_surface *s, size_t n, const double *top, const double *area,
                        const double *length);
/* The same with each rod's position [the unit of tops]: x (NULL: none) and y (NULL: rods on a
 * line), its footprint (a point). */
int ct_surface_set_rods_at(ct_surface *s, size_t n, const double *top, const double *area,
                           const double *length, const double *x, const double *y);
/* A random_cantor surface's generator settings (dimensionless parameters) and realisation. */
int ct_surface_random_cantor(const ct_surface *s, ct_random_cantor *rc, uint64_t *realisation);
/* A prepared profile surface's levelled profile and (fit not NULL) its fit. */
int ct_surface_profile(const ct_surface *s, const ct_profile **p, ct_profile_fit *fit);

/* The depth a Cantor surface is built at: setting (>= 0: itself; CT_DEPTH_AUTO: the
 * truncation bound below tol for the smallest speed V_min; CT_DEPTH_FRACTAL: the limit). */
int ct_cantor_choose_depth(const ct_params *p, long setting, double V_min, double tol, long *depth,
                           double *bound);

#if defined(__GNUC__)
#pragma GCC visibility pop
#endif

#ifdef __cplusplus
}
#endif
#endif
