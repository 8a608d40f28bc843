/* cantact: coefficient of restitution of a Cantor-fractal rough surface made of
 * elastic-perfectly-plastic rods on a Winkler foundation (see MODEL.md).
 *
 * Conventions: every fallible function returns an int status (CT_OK = 0); results come
 * back through pointer arguments; ct_error_message() holds the detail of the last error
 * raised in the calling thread. Lengths are in the unit of l_0 and h_0, forces per unit
 * depth, energies per unit depth.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef CANTACT_H
#define CANTACT_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---- status ---------------------------------------------------------------------- */

enum {
    CT_OK = 0,
    CT_EINVAL = 1,  /* a parameter or input is outside its valid range */
    CT_ENOMEM = 2,  /* allocation failed, or the request would not fit in memory */
    CT_ERANGE = 3,  /* the physics leaves the model (e.g. crushed layer, u_max >= H*) */
    CT_ENOCONV = 4, /* a solve did not meet its tolerance */
    CT_EIO = 5,     /* a file could not be read or written */
};

/* Returns a static, generic description of a status code. */
const char *ct_strerror(int status);

/* Returns the detailed message of the last error raised in this thread ("" if none). */
const char *ct_error_message(void);

/* ---- parameters (MODEL.md §1) ---------------------------------------------------- */

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

/* ---- rod bundles (MODEL.md §2-4) ------------------------------------------------- */

typedef struct ct_bundle ct_bundle;

typedef enum {
    CT_REP_STAGES = 0,   /* one rod per Cantor stage (pieces merged): N + 1 rods */
    CT_REP_SEGMENTS = 1, /* one rod per Cantor piece: 2^(N+1) - 1 rods */
} ct_representation;

/* Memory per rod in bytes: top, length, area and plastic strain, 4 doubles. */
#define CT_BYTES_PER_ROD 32

/* Largest depth accepted by the builders. */
#define CT_MAX_STAGES_DEPTH 100000000
#define CT_MAX_SEGMENTS_DEPTH 40

/* Builds the depth-N prefractal (stages 0..N-1 carry s_i, the 2^N tips carry l_N) as a
 * virgin bundle. Rods whose top is deeper than u_reach (they can never be touched) are
 * left out; pass INFINITY to keep all. A segments bundle that would not fit in the
 * available memory is refused with CT_ENOMEM before anything is allocated. */
int ct_bundle_alloc(ct_bundle **out, const ct_params *p, ct_representation rep, long depth,
                    double u_reach);
void ct_bundle_free(ct_bundle *b);
/* Returns a new bundle with the same rods and state. */
int ct_bundle_clone(ct_bundle **out, const ct_bundle *b);
/* Forgets all plastic strain (back to the virgin surface). */
void ct_bundle_reset(ct_bundle *b);

size_t ct_bundle_size(const ct_bundle *b);    /* rods held */
size_t ct_bundle_omitted(const ct_bundle *b); /* rods left out as never touched */
long ct_bundle_depth(const ct_bundle *b);     /* prefractal depth N */
ct_representation ct_bundle_representation(const ct_bundle *b);
const ct_params *ct_bundle_params(const ct_bundle *b);

/* Rod k's data [length, length, length, dimensionless] and, for segments, its x-extent
 * [length] (derived from the index, not stored); stage is the Cantor stage (N = tip). */
typedef struct {
    double top, length, area, plastic_strain;
    double x_left, x_right;
    long stage;
} ct_rod_info;
int ct_bundle_rod(const ct_bundle *b, size_t k, ct_rod_info *info);

/* Returns the total force P(u) [force] at the current state, without changing it. */
double ct_bundle_force(ct_bundle *b, double u);
/* P at m displacements in one pass over the rods (the quadrature's way to assemble);
 * P[i] is bitwise ct_bundle_force(b, u[i]). Fails only with CT_ENOMEM (workspace). */
int ct_bundle_force_many(ct_bundle *b, const double *u, size_t m, double *P);
/* ct_bundle_work(b, u_a, u_b[i]) for m end points in one pass, bitwise the same. */
int ct_bundle_work_many(ct_bundle *b, double u_a, const double *u_b, size_t m, double *W);
/* Advances every rod's state along the displacement path to u (loading or unloading). */
void ct_bundle_advance(ct_bundle *b, double u);
/* Returns the work [energy] of P(u) at the current state from u_a to u_b (closed form per
 * rod; along a loading path from the current state this is the work done). */
double ct_bundle_work(ct_bundle *b, double u_a, double u_b);
/* Returns the recoverable elastic energy [energy] stored at displacement u. */
double ct_bundle_elastic_energy(ct_bundle *b, double u);
/* Returns the displacement [length] of first contact at the current state. */
double ct_bundle_first_contact(const ct_bundle *b);
/* Returns the smallest displacement [length] at which some rod yields (loading from the
 * current state). */
double ct_bundle_first_yield(const ct_bundle *b);
/* Sets the number of threads of the force assembly (0: the OpenMP default); returns the
 * number that will be used (1 without OpenMP). Results do not depend on it. */
int ct_set_threads(int threads);
/* Sets the size from which this bundle's sums use the thread team (default
 * CT_PARALLEL_MIN_RODS; for the threshold benchmark). Results do not depend on it. */
void ct_bundle_set_parallel_min(ct_bundle *b, size_t rods);
/* Bundles below this many rods are summed by one thread: bench/bench_threshold measured the
 * 2-thread team >= 10% faster from 4095 rods on the 2-core CI machine. */
#define CT_PARALLEL_MIN_RODS 4096

/* Breakpoints of P(u) in [lo, hi], sorted and distinct, in a malloc'ed array the caller
 * frees. The ends lo and hi are included. */
int ct_bundle_breakpoints(const ct_bundle *b, double lo, double hi, double **points, size_t *count);

/* ---- quadrature ------------------------------------------------------------------ */

typedef enum {
    CT_QUAD_BREAKPOINTS = 0, /* trapezoid on the breakpoints: exact for P */
    CT_QUAD_TRAPEZOID = 1,   /* composite, K nodes, ignores breakpoints, order 2 */
    CT_QUAD_SIMPSON = 2,     /* composite, K nodes (odd), ignores breakpoints, order 4 */
    CT_QUAD_GAUSS = 3,       /* composite 3-point Gauss-Legendre, K nodes, order 6 */
    CT_QUAD_CLOSED = 4,      /* ct_impact only: closed-form energies per rod, no quadrature */
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

/* ---- impact (MODEL.md §7) -------------------------------------------------------- */

typedef struct {
    ct_quad_rule rule; /* quadrature of the energies */
    size_t nodes;      /* K for the composite rules */
    double tolerance;  /* relative tolerance of the u_max solve (1e-14 by default) */
} ct_impact_opts;

typedef struct {
    double kinetic_energy;  /* 1/2 m v1^2 [energy] */
    double V_star;          /* sqrt(kinetic_energy / (l0 E h0)), dimensionless */
    double u_contact;       /* first contact at impact [length] */
    double u_max;           /* maximum displacement [length], Eq. 39 */
    double u_release;       /* last contact on rebound [length] */
    double W_load;          /* loading work by quadrature [energy] */
    double W_unload;        /* unloading work by quadrature [energy], Eq. 40 */
    double W_load_closed;   /* the same in closed form per rod [energy] */
    double W_unload_closed; /* [energy] */
    double e;               /* sqrt(W_unload / W_load) by quadrature, dimensionless */
    double e_closed;        /* sqrt(W_unload_closed / W_load_closed) */
    double quad_error;      /* |e - e_closed| */
    double e_rounding;      /* bound on the rounding error of e from u - top cancellation
                               (stiff rods, weak impacts): 64 eps u_max / min(u_max -
                               u_contact, u_max - u_release) */
    double V_star_crit;     /* critical V* of the pre-impact state (first yield) */
    int elastic;            /* 1 when below the critical velocity: e = 1 exactly */
} ct_impact_result;

/* Fills opts with the defaults (breakpoints rule, 1e-14). */
void ct_impact_opts_default(ct_impact_opts *opts);
/* Returns the energy [energy] needed to make the first rod yield from the current state,
 * and that displacement [length]. */
int ct_critical_energy(ct_bundle *b, double *energy, double *u_yield);
/* One impact of kinetic energy kinetic_energy on the bundle's current state: loads to
 * u_max, unloads, and leaves the plastic strain in the bundle. */
int ct_impact(ct_bundle *b, double kinetic_energy, const ct_impact_opts *opts,
              ct_impact_result *res);
/* Returns the u_max [length] reached from the current state by kinetic energy W, without
 * changing the state. */
int ct_solve_umax(ct_bundle *b, double W, double tolerance, double *u_max);

/* ---- depth selection ------------------------------------------------------------- */

/* Smallest depth N whose truncation changes forces and energies, relative to the
 * smallest impact of energy W_min, by less than tol; *bound gets the bound reached. */
int ct_auto_depth(const ct_params *p, double W_min, double tol, long *depth, double *bound);

/* The fractal limit N -> infinity to double precision: the smallest depth whose truncation
 * bound (as for ct_auto_depth) is below 1e-15 and whose tips lie within 1e-15 eps_y H* of the
 * reference plane (so that the first yield, hence V*_c, has converged too). */
int ct_fractal_depth(const ct_params *p, double W_min, long *depth, double *bound);

/* ---- the paper's laws (MODEL.md §5-6) -------------------------------------------- */
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

/* ---- scenes ---------------------------------------------------------------------- */

#define CT_MAX_VELOCITIES 1000000
#define CT_DEPTH_AUTO (-1)
#define CT_DEPTH_FRACTAL (-2)

enum { CT_OUT_E = 1, CT_OUT_CURVE = 2, CT_OUT_PROFILE = 4, CT_OUT_COMPARE = 8 };

typedef struct {
    ct_params params;
    long depth; /* >= 0, or -1 for auto */
    ct_representation representation;
    double *V_star; /* velocities, dimensionless, in input order */
    size_t nvel;
    long impacts; /* impacts per velocity, >= 1 */
    ct_impact_opts opts;
    double depth_tolerance; /* relative tolerance of depth auto */
    int threads;            /* 0: OpenMP default */
    char *output;           /* CSV path, "-" for stdout */
    unsigned what;          /* CT_OUT_* bits */
} ct_scene;

/* Reads a scene file, then applies overrides "section.key=value"; on error returns
 * CT_EINVAL (or CT_EIO) with "file:line: section.key = value: reason" as the message. */
int ct_scene_load(ct_scene *scene, const char *path, const char *const *overrides,
                  size_t noverrides);
/* Same from a string (name is used in messages). */
int ct_scene_parse(ct_scene *scene, const char *name, const char *text,
                   const char *const *overrides, size_t noverrides);
void ct_scene_free(ct_scene *scene);

#ifdef __cplusplus
}
#endif
#endif
