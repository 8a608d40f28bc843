/* Internal helpers shared by the library's modules; none of these is exported. */
#ifndef CT_INTERNAL_H
#define CT_INTERNAL_H

#include "cantact.h"

#include <float.h>
#include <math.h>

#if defined(__GNUC__)
#define CT_PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define CT_PRINTF(a, b)
/* The two depth searches behind ct_cantor_choose_depth (the one public chooser): the smallest
 * depth N whose truncation changes forces and energies, relative to the smallest impact of
 * energy W_min, by less than tol (*bound: the bound reached); and the fractal limit to double
 * precision (the bound below 1e-15 and the tips within 1e-15 eps_y H* of the reference plane, so
 * that the first yield, hence V*_c, has converged too). */
int ct_auto_depth(const ct_params *p, double W_min, double tol, long *depth, double *bound);
int ct_fractal_depth(const ct_params *p, double W_min, long *depth, double *bound);

/* CT_OK when the n speeds V are finite and > 0 (V may be NULL when n = 0). */
int ct_check_speeds(const double *V, size_t n);

#endif

/* Records a detailed message for the calling thread and returns status, so that
 * "return ct_error_set(CT_EINVAL, ...)" reads naturally. Every error goes through here:
 * a breakpoint on it catches them all. */
int ct_error_set(int status, const char *fmt, ...) CT_PRINTF(2, 3);

/* NULL policy (cantact.h): functions that create, run, solve or integrate check their pointer
 * arguments with this and return CT_EINVAL naming the argument. */
#define CT_NEED(ptr)                                                                               \
    do {                                                                                           \
        if (!(ptr))                                                                                \
            return ct_error_set(CT_EINVAL, "%s: %s is NULL", __func__, #ptr);                      \
    } while (0)

/* Whether the caller's interrupt flag (cantact.h: a spec's interrupt; NULL: none) is set. Another
 * thread sets it, so it is read as a relaxed atomic load: one load, checked between blocks of
 * work. */
static inline int ct_interrupted(const volatile int *flag)
{
#if defined(__GNUC__)
    return flag && __atomic_load_n(flag, __ATOMIC_RELAXED) != 0;
#else
    return flag && *flag != 0;
#endif
}

/* CT_EINTR with the one message of a stopped call. */
int ct_error_interrupted(void);

/* Sorts v ascending and drops repeated values; returns the new count. */
size_t ct_sort_unique(double *v, size_t n);
/* qsort's comparison of doubles, ascending (src/error.c). */
int ct_cmp_double(const void *a, const void *b);

/* The library's compensated sum (Neumaier's variant of Kahan's): s + c carries a sum whose
 * terms may cancel or differ widely in size. Both candidates for the rounding error are
 * computed and one is selected: branch-free, so a loop over independent sums vectorises, and
 * bitwise the same as choosing first. */
static inline void ct_add_comp(double *s, double *c, double x)
{
    const double t = *s + x;
    const double err_x = (*s - t) + x, err_s = (x - t) + *s;
    *c += fabs(*s) >= fabs(x) ? err_x : err_s;
    *s = t;
}

/* Rods per block of every sum over rods (bundle.c) and of the load curve's event passes
 * (curve.c): results are computed block by block in a fixed order and tree, so they do not
 * depend on the thread count, which only decides who computes which block. */
#define CT_BLOCK 2048

/* Bundles below this many rods are summed by one thread (docs/benchmarks.md: the threshold
 * benchmark's figure). ct_bundle_set_parallel_min changes it for one bundle: for the threshold
 * benchmark and the tests that make a small bundle use a team. Results do not depend on it. */
#define CT_PARALLEL_MIN_RODS 4096
void ct_bundle_set_parallel_min(ct_bundle *b, size_t rods);
/* The sweep's auto path takes the lean curve from this many rods (cantact/sweep.h says when). */
#define CT_LEAN_RODS 262144

/* ---- for surface builders (src/surface/) ---- */

/* What a kind of surface knows of its rods beyond top and area. */
typedef struct {
    const char *name;
    /* fills info->stage, x_left, x_right of rod k */
    void (*rod_info)(const void *meta, size_t k, ct_rod_info *info);
    void *(*clone)(const void *meta); /* NULL on failure */
    void (*free)(void *meta);
    /* optional: the largest u_max [length] at which the rods still describe what the body
     * meets (beyond it the face reaches past the surface's border), with why in words */
    double (*reach)(const void *meta, char *why, size_t len);
    /* optional: 1 and the period [length] in x and y of the surface repeated as measured, when
     * its rods' footprints may span less (a map's grid, nx dx by ny dy, its invalid edge points
     * included); 0: the footprints' extent is the period */
    int (*period)(const void *meta, double *x, double *y);
} ct_rod_meta_kind;

/* A bundle of n rods with uninitialised arrays (filled by the caller through
 * ct_bundle_arrays), or CT_ENOMEM naming the bytes and the memory available. */
int ct_bundle_create(ct_bundle **out, const ct_layer *layer, size_t n, const char *what);
void ct_bundle_arrays(ct_bundle *b, double **top, double **length, double **area,
                      double **plastic_strain);
/* Sets rods [k0, k0 + count) to one top, length and area, virgin; large ranges are filled by
 * the thread team, so that pages land where the sums will read them (first touch). */
void ct_bundle_fill(ct_bundle *b, size_t k0, size_t count, double top, double length, double area);
/* Hands the surface's metadata to the bundle (freed with it); omitted rods are counted. */
void ct_bundle_set_surface(ct_bundle *b, const ct_rod_meta_kind *kind, void *meta, size_t omitted);
/* The largest u_max [length] b's rods describe (INFINITY: no limit) and, when finite, why. */
double ct_bundle_reach(const ct_bundle *b, char *why, size_t len);
/* 1 and the period [length] of b's surface repeated as measured, when its kind knows one
 * beyond its rods' footprints (ct_rod_meta_kind.period); 0 otherwise. */
int ct_bundle_period(const ct_bundle *b, double *x, double *y);
/* CT_OK when an impact to u_max [length] stays within what b's rods describe; CT_ERANGE naming
 * u_max / h0 and the reach's reason when it passes it (a curved body's face reaching past the
 * border of a surface that does not repeat). Every impact of the library passes through it. */
int ct_reach_check(const ct_bundle *b, double u_max);
/* The metadata if b was made by this kind of surface, else NULL. */
const void *ct_bundle_surface_meta(const ct_bundle *b, const ct_rod_meta_kind *kind);
/* Events a curve of b's state would hold (two per run of identical rods): one pass. */
size_t ct_curve_events(const ct_bundle *b);
/* Bytes a curve of that many events needs while it is built. */
double ct_curve_bytes(size_t events);
/* The thread count a sum over b's rods uses (1 below the parallel threshold). */
int ct_bundle_team(const ct_bundle *b);
/* The threads b may use (its setting, else OpenMP's), whatever its size. */
int ct_bundle_threads(const ct_bundle *b);
/* The same from factor times the bundle's rod threshold: for work whose team pays only on
 * larger bundles (the curve's event sort). */
int ct_bundle_team_from(const ct_bundle *b, size_t factor);

/* Runs fn(ctx, c, i0, i1) on the chunks c = 0, 1, ... of [0, count) (chunk indices each, the
 * last one shorter), by b's thread team when count reaches b's parallel threshold. For
 * surface builders: fn must make what it writes for index i depend on i alone, so that the
 * rods do not depend on the thread count. */
typedef void (*ct_chunk_fn)(void *ctx, size_t c, size_t i0, size_t i1);
void ct_bundle_parallel(const ct_bundle *b, size_t count, size_t chunk, ct_chunk_fn fn, void *ctx);

/* Makes b (from ct_random_cantor_bundle, same depth and layer) realisation `realisation` of
 * rc in place: the same rods as a new bundle, bit for bit, without new arrays (the sort's
 * scratch is kept in b for the next refill). For ensembles. */
int ct_random_cantor_refill(ct_bundle *b, const ct_random_cantor *rc, uint64_t realisation);

/* The lean curve of b's state into c (curve_lean.c): the same answers, bit for bit, from
 * ct_curve_first_contact, _first_yield, _force, _work, _dissipation, _release, _inverse_work
 * and _size, in about 48 bytes per rod instead of 300; nothing else may be asked of it (no
 * points, view or unloading curve). b must not change while c is used. CT_ESKIPPED: this
 * bundle needs the full curve (its W rounds to a sequence that is not monotone). */
int ct_curve_build_lean(ct_curve *c, const ct_bundle *b);
/* fn(ctx, x_j, W(x_j)) at every breakpoint of c in order, full or lean (the same doubles). */
void ct_curve_each_point(const ct_curve *c, void (*fn)(void *ctx, double x, double W), void *ctx);
/* Bytes a lean curve of that many events (ct_curve_events) needs while it is built. */
double ct_curve_lean_bytes(size_t events);

/* The breakpoints of a curve as arrays (x sorted; P, cumulative W and the slope on
 * [x_j, x_{j+1}) at each), for the dynamics. */
typedef struct {
    size_t n;
    const double *x, *P, *W, *slope;
} ct_curve_view;
void ct_curve_view_of(const ct_curve *c, ct_curve_view *v);
/* Into out: the unloading curve of the state c's state reaches when loaded to u_max (its P
 * for u <= u_max: every rod in contact unloads along its elastic line from its release
 * point); its last breakpoint is u_max. */
int ct_curve_unload(const ct_curve *c, double u_max, ct_curve *out);
/* A curve's events split for the sweep's unloading curves, once per curve: contacts at cx of
 * slope ck (nc); yields at yy of rods with contact yc, eps_y L eL and slope yk (ny), each in
 * the curve's order. monotone: the yielded rods' contacts rise and their lengths fall in
 * yield order (so do their release points); nested: monotone, and every contact is paired
 * with its own yield in the same order (every virgin layer). buf and cap: the storage. */
typedef struct {
    double *buf;
    size_t cap;
    const double *cx, *ck, *yy, *yc, *eL, *yk;
    double *rel; /* room for ny release points, the builder's */
    size_t nc, ny;
    int monotone, nested;
} ct_unload_events;
int ct_unload_events_of(const ct_curve *c, ct_unload_events *e);
/* Multiplies e's positions (and eps_y L) by sx and its slopes by sk: powers of two, for the
 * units of the impact in time (exact, the order unchanged). */
void ct_unload_events_scale(ct_unload_events *e, double sx, double sk);
void ct_unload_events_free(ct_unload_events *e);
/* The unloading curve from u_max of the curve's state (e monotone), by the builder of
 * ct_curve_unload without its sort, into x, P, W and slope (room for ct_unload_split_room
 * points); returns the count of points (0: no rod in contact at u_max). Not bitwise
 * ct_curve_unload's: the events at one x are added sequence by sequence (there: in the
 * order of their slope changes); nested, the yielded rods' contacts and their taking back
 * are left out (they cancel) and the sums are plain (all terms >= 0). */
size_t ct_unload_split_room(const ct_unload_events *e, double u_max);
size_t ct_unload_split(const ct_unload_events *e, double u_max, double *x, double *P, double *W,
                       double *slope);

/* ---- the impact in time (src/dynamics.c), for the sweep ---- */

typedef struct ct_dyn_work ct_dyn_work;
int ct_dyn_work_alloc(ct_dyn_work **out);
void ct_dyn_work_free(ct_dyn_work *w);
/* A new speed: the state is c's own (no earlier maximum). */
void ct_dyn_reset(ct_dyn_work *w);
/* The impact res (solved on curve c, from c's state or, after ct_dyn_impact saw a plastic
 * impact of the same speed, from that state: c's state loaded to the earlier maximum and
 * unloaded) in time, for a body of mass m; hist (not NULL) gets its history with `grid`
 * uniform points. A plastic impact becomes the state of the next call. */
int ct_dyn_impact(ct_dyn_work *w, const ct_curve *c, const ct_impact_result *res, double m,
                  ct_dynamics *dyn, size_t grid, ct_history *hist);
/* The sweep's fast path, on the first curve c (prepared once: its moments, its events): the
 * same impacts as ct_dyn_impact on c, without histories, the first pieces of each branch by
 * their moments. ct_dyn_reset starts a speed. L: the layer of c's bundle, whose h0 and
 * E l0 h0 set the units the motion is computed in (docs/model.md §11; every workspace is
 * prepared before its impacts). Times, speeds and forces come back in the caller's units; a
 * motion beyond double precision, or whose e_kinematic differs from e, is an error. */
int ct_dyn_prepare(ct_dyn_work *w, const ct_curve *c, const ct_layer *L);
int ct_dyn_impact_fast(ct_dyn_work *w, const ct_impact_result *res, double m, ct_dynamics *dyn);
/* A workspace for another thread's speeds on parent's prepared curve, for mass m: it reads
 * the parent's prepared arrays (the parent outlives it and is not prepared again meanwhile)
 * and keeps its own state, so the speeds of a sweep can be shared among threads. */
int ct_dyn_work_fork(ct_dyn_work *parent, double m, ct_dyn_work **out);
/* Memory of the impacts in time, in bytes, beside the curve's own (ct_curve_bytes): the
 * sweep's prepared arrays on a curve of `events` events (ct_dyn_prepare: the first curve's
 * pieces and moments, its split events); and what each thread's unloading curves (the
 * state's maximum's and this impact's, built as the impacts go: from the split events when
 * they are monotone, else from ct_curve_unload's sorted copy of them as well) take for
 * impacts up to u_max [length] on w's prepared curve. */
double ct_dyn_prepared_bytes(size_t events);
double ct_dyn_work_thread_bytes(const ct_dyn_work *w, double u_max);
/* CT_ENOMEM naming the bytes when the impacts in time on b's state would not fit in the
 * memory available, else CT_OK: the sweep's fast path (its first curve and prepared arrays:
 * each thread's unloading curves are judged when the impacts are solved); one history impact
 * (ct_impact_history: its curve, split events, paths and unloading curve, not its history
 * points); the sweep's state path (its first curve held: per speed, the paths and unloading
 * curves, and for repeated impacts the state's curve and the earlier maximum's unloading). */
typedef enum { CT_DYN_SWEEP = 0, CT_DYN_ONE_SHOT = 1, CT_DYN_BY_STATE = 2 } ct_dyn_use;
int ct_dyn_memory_check(const ct_bundle *b, ct_dyn_use use, long impacts);

/* ---- measured surfaces (src/surface/profile/), shared by its files ---- */

typedef struct {
    double t, w; /* a sample's top depth [length] and area */
} ct_top_weight;
/* The valid samples' tops below the highest point with their areas, sorted by top (malloc'ed);
 * *wsum the total area. */
int ct_profile_sorted_tops(const ct_profile *p, ct_top_weight **out, double *wsum);
/* ct_profile_from_line and _from_grid without the copy: on success the profile owns x (may be
 * NULL with dx > 0) and z; on error they stay the caller's. */
int ct_profile_adopt_line(ct_profile **out, size_t n, double *x, double dx, double *z);
int ct_profile_adopt_grid(ct_profile **out, size_t nx, size_t ny, double dx, double dy, double *z);

/* ---- impacts on a curve (src/impact.c), for the sweep ---- */

/* The impact of energy W from the state c's state reaches when loaded to U (-INFINITY: c's
 * state itself), closed forms left NaN; CT_ESKIPPED when it stays below U. W_U: that state's
 * energy back to U summed rod by rod (the W_unload of the impact that reached U; with
 * U = -INFINITY its energy to its first yield, ct_critical_by_rods), or NaN to take it from
 * the curve, W(U) - D(U) (W at the first yield). W_unload NaN: the curve's W_load - D would carry e
 * to worse than CT_UNLOAD_DIFF_E relative (ct_unload_lost), and the caller sums it rod by rod (the
 * state's recoverable energy at u_max: ct_bundle_elastic_energy, or ct_bundle_closed_many's
 * W_unload); then W_U of the next impact is that sum. */
#define CT_UNLOAD_DIFF_E 1e-13
int ct_impact_on_curve(const ct_curve *c, const ct_layer *L, double U, double W_U, double W,
                       const ct_impact_opts *opts, ct_impact_result *res);
/* The critical energy of b's state (c its curve) summed rod by rod from the distances between
 * contacts, where the curve's W at its first yield carries V*_c to worse than
 * CT_UNLOAD_DIFF_E (a rod's elastic range eps_y L far below the ulps of its position); NaN
 * where the curve's is good: the W_U of a first impact. */
double ct_critical_by_rods(const ct_bundle *b, const ct_curve *c);
/* Whether W_unload as the difference of energies summing to W_sum (a few ulps of each) would
 * carry e = sqrt(W_unload / W_load), and the next impact's V*_c, to worse than
 * CT_UNLOAD_DIFF_E relative: where little comes back (e below about 0.07). */
int ct_unload_lost(double W_sum, double W_unload);
/* e, e_rounding and, when W_load_closed is set, the closed forms' check (P_max: the force at
 * u_max, for the rounding floor of the u_max solve) and e_closed. */
int ct_impact_finish(double P_max, const ct_impact_opts *opts, ct_impact_result *res);
/* CT_OK for an impact energy the solver can use: finite and a normal double (a subnormal W
 * has lost its digits, and 1/W overflows); CT_EINVAL naming V* otherwise. */
int ct_energy_check(double W, double V_star);
/* k with 2^(k-1) <= max |z| < 2^k over the heights that are not NaN (0 when none is finite and
 * non-zero): heights far from 1 are summed in units of 2^k, an exact scaling (profile.c, fit.c). */
int ct_heights_exponent(const double *z, size_t n);
/* z 2^e, with m = 2^e (ldexp(1, e)): one multiplication when m is a normal double (the same
 * correctly rounded value as ldexp(z, e), at a fraction of its cost), ldexp otherwise. */
static inline double ct_times_pow2(double z, double m, int e)
{
    return e >= DBL_MIN_EXP - 1 && e <= DBL_MAX_EXP - 1 ? z * m : ldexp(z, e);
}
/* Closed forms of m impacts in one pass over the rods: state i is b's advanced to adv[i]
 * (-INFINITY: b's own); W_load[i] its work from u0[i] to u1[i], W_unload[i] its recoverable
 * energy at u1[i] (bitwise ct_bundle_work and ct_bundle_elastic_energy of that state) and,
 * when P is not NULL, P[i] its force at u1[i]. Each impact's sums are its own: any split of
 * the m impacts into calls gives the same bits. CT_EINTR once *interrupt is set (checked
 * every block of rods; NULL: never). */
int ct_bundle_closed_many(const ct_bundle *b, const double *adv, const double *u0, const double *u1,
                          size_t m, double *W_load, double *W_unload, double *P,
                          const volatile int *interrupt);

/* ---- the paper's laws ---- */

/* e and u_max [length] of one impact of energy W on the virgin surface under the asymptotic
 * law (Eqs. 33-34, 38, 39-40); p validated, W finite and > 0. For ct_law_impact. */
int ct_asym_impact(const ct_params *p, int consistent, double W, double *u_max, double *e);
/* The same under the series (Eqs. 12-24, breakpoint quadrature of its energies). */
int ct_series_impact(const ct_params *p, double W, double *u_max, double *e);

/* The two depth searches behind ct_cantor_choose_depth (the one public chooser): the smallest
 * depth N whose truncation changes forces and energies, relative to the smallest impact of
 * energy W_min, by less than tol (*bound: the bound reached); and the fractal limit to double
 * precision (the bound below 1e-15 and the tips within 1e-15 eps_y H* of the reference plane, so
 * that the first yield, hence V*_c, has converged too). */
int ct_auto_depth(const ct_params *p, double W_min, double tol, long *depth, double *bound);
int ct_fractal_depth(const ct_params *p, double W_min, long *depth, double *bound);

/* CT_OK when the n speeds V are finite and > 0 (V may be NULL when n = 0). */
int ct_check_speeds(const double *V, size_t n);

#endif
