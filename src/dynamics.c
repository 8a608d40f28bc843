/* The impact in time (docs/model.md §11): m u'' = -P(u) while in contact, P piecewise linear, so
 * the motion is exact piece by piece.
 *
 * On a piece [x_a, x_b] with P = P_a + k (u - x_a), k >= 0, energy conservation fixes the
 * speeds v_a, v_b at its ends (v^2 = v1^2 - 2 W(u) / m). With y = u - u_eq, u_eq = x_a - P_a / k,
 * the motion is y = A sin(theta), v = omega A cos(theta), theta rising at omega = sqrt(k / m);
 * then du / (v_a + v_b) = tan(dtheta / 2) / omega, so the time across is
 *     dt = (2 / omega) atan(omega du / (v_a + v_b)) = 2 du / (v_a + v_b) * atanc(x),
 * x = omega du / (v_a + v_b), atanc(x) = atan(x) / x: exact, without cancellation, and the
 * uniform deceleration 2 du / (v_a + v_b) of a plateau (k = 0) as its limit. The piece where
 * the body turns (v = 0) takes (1 / omega) atan2(m omega v_a, P_a) -> m v_a / P_a as k -> 0,
 * from the remaining energy alone (u_max itself is not needed, so its last digits cost
 * nothing). Unloading is the time-reverse of a loading from the release point (speed v2 =
 * sqrt(2 W_unload / m)) up the unloading curve to u_max: the same two formulas.
 *
 * Where the work done is below 2^-60 of the kinetic energy, the speed is v0 to double
 * precision and x^2 < 2^-62: those first pieces (the deep Cantor stages next to the plane)
 * take du / v0 together, summed as one.
 *
 * Units: t / tau depends only on the dimensionless groups (docs/model.md §11), but the
 * layer's own units need not keep the motion within the doubles (rods 1e-160 long: speeds
 * ~1e-160, their squares underflow; tops of 1e299 m: v^2 overflows). The motion is computed
 * with lengths in units of 2^ex ~ h0, energies in 2^eW ~ E l0 h0 and times in 2^et, chosen per
 * mass so that the mass is between 1 and 4 there: then displacements, works, speeds and
 * times are of the order of the groups themselves. The scalings are powers of two, exact, so
 * wherever the layer's units kept every number a normal double the results are the same bits. */
#include "internal.h"

#include <float.h>
#include <stdio.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

/* On x86-64 a loop of divisions over a curve's pieces also gets an AVX2 clone, picked at load
 * time (as in bundle.c: no FMA, contraction being off under -std=c11, so the bits are the same). */
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) &&                             \
    !defined(__SANITIZE_ADDRESS__)
#define CT_DYN_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define CT_DYN_CLONES
#endif

/* A path through the breakpoints: u, P, the slope on [x_i, x_{i+1}) and the work from the
 * path's start. */
typedef struct {
    size_t n, cap;
    double *x, *P, *k, *W;
} path;

/* A curve as arrays, with the moments M1_j = int_{x_0}^{x_j} W du and M2_j = int W^2 du
 * (exact: W is quadratic on each piece) for the first pieces of a branch. */
typedef struct {
    size_t n, cap;
    double *x, *P, *k, *W, *M1, *M2;
} pcurve;

/* The units of the motion: lengths in 2^ex, energies in 2^eW of the layer's (sx, sW, sP, sk:
 * the factors that take a length, an energy, a force and a slope into them), h0 for
 * messages. Times in 2^et of the caller's, per mass (dyn_mass). */
typedef struct {
    int ex, eW;
    double sx, sW, sP, sk, h0;
} dyn_units;

struct ct_dyn_work {
    dyn_units s;
    path load, unload;
    ct_curve *prev, *cur; /* the unloading curves of the state's maximum U and of this impact */
    int have_prev;
    double U;
    double *t_load, *t_unload; /* per point, for histories */
    size_t tcap;
    /* the sweep's fast path (ct_dyn_prepare, ct_dyn_impact_fast) */
    const ct_curve *first;
    pcurve first_pc, pprev, pcur;
    ct_unload_events ue; /* the first curve's events, for its unloading curves */
    int one_shot;        /* ct_impact_history: one impact, prepared (no state to carry) */
    double *f_d2, *f_wd; /* the first curve's pieces' 2 du and omega du at mass f_m */
    double f_m;
    int f_sorted; /* its x finite and its W nondecreasing */
    size_t f_cap;
    /* a fork (ct_dyn_work_fork): first_pc, ue's arrays, f_d2 and f_wd are its parent's, read
     * only; ue.rel (the releases ct_unload_split writes) is its own */
    int fork;
};

static int unload_split(ct_dyn_work *w, double u_max, pcurve *out);

static void path_free(path *p)
{
    free(p->x); /* one block: x, P, k, W */
    memset(p, 0, sizeof *p);
}

/* Room for n points in all, the points kept. */
static int path_reserve(path *p, size_t n)
{
    if (n <= p->cap)
        return CT_OK;
    const size_t cap = n > 2 * p->cap ? n : 2 * p->cap;
    double *b = malloc(4 * cap * sizeof(double));
    if (!b)
        return ct_error_set(CT_ENOMEM, "impact history: out of memory");
    if (p->n) {
        memcpy(b, p->x, p->n * sizeof(double));
        memcpy(b + cap, p->P, p->n * sizeof(double));
        memcpy(b + 2 * cap, p->k, p->n * sizeof(double));
        memcpy(b + 3 * cap, p->W, p->n * sizeof(double));
    }
    free(p->x);
    p->x = b;
    p->P = b + cap;
    p->k = b + 2 * cap;
    p->W = b + 3 * cap;
    p->cap = cap;
    return CT_OK;
}

/* Appends a point (room reserved). */
static void path_put(path *p, double x, double P, double k, double W)
{
    p->x[p->n] = x;
    p->P[p->n] = P;
    p->k[p->n] = k;
    p->W[p->n] = W;
    p->n++;
}

/* Largest j with v.x[j] <= u (u >= v.x[0]). */
static size_t piece_of(const ct_curve_view *v, double u)
{
    size_t lo = 0, hi = v->n;
    while (hi - lo > 1) {
        size_t mid = lo + (hi - lo) / 2;
        if (v->x[mid] <= u)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

/* Appends a point given in the layer's units, in the motion's (room reserved). */
static void path_put_scaled(path *p, const dyn_units *s, double x, double P, double k, double W)
{
    path_put(p, x * s->sx, P * s->sP, k * s->sk, W * s->sW);
}

/* Appends the curve from a to b (a >= its first point; the curve, a, b and dW in the layer's
 * units), its work shifted by dW; the point a itself only when the path is empty (a junction
 * is not repeated). The path holds the motion's units. */
static int path_append(path *p, const dyn_units *s, const ct_curve *c, double a, double b,
                       double dW)
{
    ct_curve_view v;
    ct_curve_view_of(c, &v);
    if (!v.n || !(b >= a))
        return CT_OK;
    int st;
    const size_t j = piece_of(&v, a), e = piece_of(&v, b);
    if ((st = path_reserve(p, p->n + (e - j) + 2))) /* a, the points inside, b */
        return st;
    double t = a - v.x[j];
    if (!p->n)
        path_put_scaled(p, s, a, v.P[j] + v.slope[j] * t, v.slope[j],
                        v.W[j] + t * (v.P[j] + 0.5 * v.slope[j] * t) + dW);
    p->k[p->n - 1] = v.slope[j] * s->sk; /* the path goes on along this curve's piece */
    for (size_t i = j + 1; i < v.n && v.x[i] < b; i++)
        if (v.x[i] > a)
            path_put_scaled(p, s, v.x[i], v.P[i], v.slope[i], v.W[i] + dW);
    t = b - v.x[e];
    if (b * s->sx > p->x[p->n - 1])
        path_put_scaled(p, s, b, v.P[e] + v.slope[e] * t, v.slope[e],
                        v.W[e] + t * (v.P[e] + 0.5 * v.slope[e] * t) + dW);
    return CT_OK;
}

/* atan(x) / x for x^2 < 1e-8 (atanc_small), from x^2: the series, whose next term, x^6 / 7,
 * is below 2e-25. */
static int atanc_small(double x2)
{
    return x2 < 1e-8;
}

static double atanc_series(double x2)
{
    return 1.0 - x2 * (1.0 / 3.0 - x2 * 0.2);
}

static double atanc(double x)
{
    double x2 = x * x;
    if (atanc_small(x2))
        return atanc_series(x2);
    return atan(x) / x;
}

/* The harmonic frequency of a piece of slope k: sqrt(k / m). */
static double omega(double k, double m)
{
    return sqrt(k / m);
}

/* The speed squared where the work done is W: 2 (W_kin - W) / m. */
static double speed2_at(double W_kin, double W, double m)
{
    return 2.0 * (W_kin - W) / m;
}

/* The speed where the work done is W. */
static double speed_at(double W_kin, double W, double m)
{
    return sqrt(speed2_at(W_kin, W, m));
}

/* km and k, the stiffer (for the shortest period). */
static double stiffer(double km, double k)
{
    return k > km ? k : km;
}

/* Time across a piece of width du, slope k, entered and left at speeds va, vb. */
static double piece_time(double du, double k, double m, double va, double vb)
{
    double s = va + vb;
    if (!(s > 0.0))
        return 0.0;
    return 2.0 * du / s * atanc(omega(k, m) * du / s);
}

/* Pieces are timed in chunks of this many, their speeds and quotients computed in vector loops
 * before the times are added in order. */
enum { CT_PIECE_CHUNK = 64 };

/* V2[0..n) the speeds squared where the works are W[0..n). */
CT_DYN_CLONES
static void speeds2(const double *restrict W, size_t n, double W_kin, double m, double *restrict V2)
{
    for (size_t j = 0; j < n; j++)
        V2[j] = speed2_at(W_kin, W[j], m);
}

/* v[0..n) = sqrt(v): by pairs on x86-64 (a loop calling sqrt does not vectorise: it may set
 * errno); sqrt is exact, so the bits are the same. */
static void sqrt_all(double *v, size_t n)
{
    size_t j = 0;
#if defined(__SSE2__)
    for (; j + 2 <= n; j += 2)
        _mm_storeu_pd(v + j, _mm_sqrt_pd(_mm_loadu_pd(v + j)));
#endif
    for (; j < n; j++)
        v[j] = sqrt(v[j]);
}

/* For pieces 0 .. n-1 of widths and slopes given as d2 = 2 du and wd = omega du, between the
 * speeds V[0..n]: A = 2 du / (va + vb), X = omega du / (va + vb) (both 0 where va + vb is not
 * > 0: the piece takes no time) and T = A atanc(X) where the series holds (atanc_small(X^2)). */
CT_DYN_CLONES
static void piece_quotients(const double *restrict d2, const double *restrict wd,
                            const double *restrict V, size_t n, double *restrict A,
                            double *restrict X, double *restrict T)
{
    for (size_t j = 0; j < n; j++) {
        const double s = V[j] + V[j + 1], a = s > 0.0 ? d2[j] / s : 0.0,
                     x = s > 0.0 ? wd[j] / s : 0.0;
        A[j] = a;
        X[j] = x;
        T[j] = a * atanc_series(x * x);
    }
}

/* The time across pieces i .. J-1 of a path through (x, W, k), entered at speed
 * speed_at(W_kin, W[i]), added to t piece by piece in order; *v_J gets the speed at x[J].
 * d2 and wd (not NULL) hold each piece's 2 du and omega du, computed once for a curve walked
 * at many speeds (the same products, so the same bits). times (not NULL) gets the time at
 * every point i + 1 .. J. A piece of width du, slope k, entered and left at speeds va, vb
 * takes 2 du / (va + vb) atanc(omega du / (va + vb)) (0 when va + vb is not > 0). */
static double pieces_time(const double *x, const double *W, const double *k, const double *d2,
                          const double *wd, size_t i, size_t J, double t, double W_kin, double m,
                          double *v_J, double *times)
{
    double V[CT_PIECE_CHUNK + 1], A[CT_PIECE_CHUNK], X[CT_PIECE_CHUNK], T[CT_PIECE_CHUNK],
        D2[CT_PIECE_CHUNK], WD[CT_PIECE_CHUNK];
    V[0] = speed_at(W_kin, W[i], m);
    for (size_t q0 = i; q0 < J; q0 += CT_PIECE_CHUNK) {
        const size_t n = J - q0 < CT_PIECE_CHUNK ? J - q0 : CT_PIECE_CHUNK;
        speeds2(W + q0 + 1, n, W_kin, m, V + 1);
        sqrt_all(V + 1, n);
        if (!d2)
            for (size_t j = 0; j < n; j++) {
                const double du = x[q0 + j + 1] - x[q0 + j];
                D2[j] = 2.0 * du;
                WD[j] = omega(k[q0 + j], m) * du;
            }
        piece_quotients(d2 ? d2 + q0 : D2, d2 ? wd + q0 : WD, V, n, A, X, T);
        for (size_t j = 0; j < n; j++) { /* A atanc(X), in order */
            t += atanc_small(X[j] * X[j]) ? T[j] : A[j] * (atan(X[j]) / X[j]);
            if (times)
                times[q0 + j + 1] = t;
        }
        V[0] = V[n];
    }
    *v_J = V[0];
    return t;
}

/* Time from where the force is P (slope k), at speed v, to the turning point. */
static double turn_time(double P, double k, double m, double v)
{
    double w = omega(k, m);
    if (w == 0.0)
        return P > 0.0 ? m * v / P : INFINITY;
    double x = m * w * v;
    return x < P ? m * v / P * atanc(x / P) : atan2(x, P) / w;
}

/* Time from the path's start (speed sqrt(2 W_kin / m)) to the turning point where the work
 * equals W_kin; t (when not NULL, p->n entries) gets the time at every point up to the last
 * one below the turning point, whose index is *last. */
static double time_to_turn(const path *p, double W_kin, double m, double *t, size_t *last)
{
    size_t J = 0;
    while (J + 1 < p->n && p->W[J + 1] < W_kin)
        J++;
    const double v0 = sqrt(2.0 * W_kin / m);
    size_t i0 = 0;
    if (!t) /* the first pieces, while the speed is v0 to double precision */
        while (i0 < J && p->W[i0 + 1] <= 0x1p-60 * W_kin)
            i0++;
    double v, time = (p->x[i0] - p->x[0]) / v0;
    if (t)
        t[0] = 0.0;
    time = pieces_time(p->x, p->W, p->k, NULL, NULL, i0, J, time, W_kin, m, &v, t);
    *last = J;
    return time + turn_time(p->P[J], p->k[J], m, v);
}

/* The part of exponent e outside [lo, hi]: what a scaling by 2^-that takes back into it. */
static int outside(int e, int lo, int hi)
{
    return e < lo ? e - lo : e > hi ? e - hi : 0;
}

/* The motion's units for layer L: the layer's own unless h0 lies outside [2^-64, 2^64] or
 * E l0 h0 outside [1, 2^64] (exponents summed: the product itself may overflow), then lengths
 * and energies in the powers of two that bring them to the nearest end (so impact energies,
 * V*^2 E l0 h0, stay normal down to V* ~ 1e-154 and their squares finite). Shrunk towards the
 * layer's own where a factor would leave the normal doubles (a layer whose own curve is beyond
 * them anyway). NULL: the layer's own units. */
static void units_of(dyn_units *s, const ct_layer *L)
{
    double ex = 0.0, eW = 0.0;
    if (L) {
        ex = outside(ilogb(L->h0), -64, 64);
        eW = outside(ilogb(L->E) + ilogb(L->l0) + ilogb(L->h0), 0, 64);
        const double big = fmax(fmax(fabs(ex), fabs(eW)), fmax(fabs(ex - eW), fabs(2.0 * ex - eW)));
        if (big > 1000.0) {
            ex = trunc(ex * 1000.0 / big);
            eW = trunc(eW * 1000.0 / big);
        }
    }
    s->ex = (int)ex;
    s->eW = (int)eW;
    s->sx = ldexp(1.0, -s->ex);
    s->sW = ldexp(1.0, -s->eW);
    s->sP = ldexp(1.0, s->ex - s->eW);
    s->sk = ldexp(1.0, 2 * s->ex - s->eW);
    s->h0 = L ? L->h0 : 1.0;
}

/* The mass m (the caller's units) in the motion's; *et the exponent of the motion's unit of
 * time (2^et of the caller's): 0 while the mass lies within [2^-64, 2^65), else the one that
 * brings it between 1 and 4. A mass is [energy] [time]^2 / [length]^2. */
static double dyn_mass(const dyn_units *s, double m, int *et)
{
    const int e = 2 * s->ex - s->eW, q = ilogb(m) + e;
    *et = q >= -64 && q <= 64 ? 0 : q >= 0 ? q / 2 : -((1 - q) / 2); /* floor(q / 2) */
    return ldexp(m, e - 2 * *et);
}

/* dyn from the motion's units (time unit 2^et) into the caller's: exact. */
static void dyn_unscale(ct_dynamics *d, const dyn_units *s, int et)
{
    d->t_contact = ldexp(d->t_contact, et);
    d->t_load = ldexp(d->t_load, et);
    d->t_unload = ldexp(d->t_unload, et);
    d->period_min = ldexp(d->period_min, et);
    d->P_peak = ldexp(d->P_peak, s->eW - s->ex);
    d->v1 = ldexp(d->v1, s->ex - et);
    d->v2 = ldexp(d->v2, s->ex - et);
    d->dissipated = ldexp(d->dissipated, s->eW);
    d->k_unload_max = ldexp(d->k_unload_max, s->eW - 2 * s->ex);
}

/* The limit of the motion in double precision, before it is computed: a plastic impact's
 * unloading branch spans u_max - u_release, and its release points (u_max - eps_y L) round
 * to ulps of u_max. Below 2^-26 of u_max (eps_y L that thin: E / sigma_y beyond about 1e8
 * for u_max ~ h0) they keep fewer than half their digits, and e_kinematic and t_unload would
 * be wrong in their leading ones (at E / sigma_y = 1e16 e_kinematic was 0.4 % off, at 1e20
 * it was 0 and t_unload infinite). e itself does not need them (docs/model.md §7). */
#define CT_DYN_UNLOAD_MIN 0x1p-26

static int dyn_resolvable(const dyn_units *s, const ct_impact_result *res)
{
    const double span = res->u_max - res->u_release;
    if (res->elastic || span >= CT_DYN_UNLOAD_MIN * fabs(res->u_max))
        return CT_OK;
    return ct_error_set(CT_ERANGE,
                        "impact in time: the unloading interval u_max - u_release = %.3g h0 is "
                        "%.3g of u_max = %.6g h0, below 2^-26: its release points cannot be "
                        "carried in double precision (eps_y L this thin against u_max: E / "
                        "sigma_y too large for the time outputs; e alone is computed)",
                        span / s->h0, span / fabs(res->u_max), res->u_max / s->h0);
}

/* The results of an impact in time, in the caller's units: finite, and v2 / v1 from the
 * unloading curve's own work equal to the energy e to 1e-12 beyond e's rounding bound
 * (docs/model.md §11). A row failing either is an error, never a result. */
static int dyn_check(const ct_impact_result *res, const ct_dynamics *d)
{
    const struct {
        const char *name;
        double v;
    } f[] = {{"t_load", d->t_load},
             {"t_unload", d->t_unload},
             {"t_contact", d->t_contact},
             {"P_peak", d->P_peak},
             {"v1", d->v1},
             {"v2", d->v2},
             {"e_kinematic", d->e_kinematic},
             {"the unloading's stiffest slope", d->k_unload_max},
             {"the shortest unloading period", d->period_min}};
    for (size_t q = 0; q < sizeof f / sizeof f[0]; q++)
        if (!isfinite(f[q].v))
            return ct_error_set(CT_ERANGE,
                                "impact in time: %s = %g, beyond double precision in the "
                                "layer's units",
                                f[q].name, f[q].v);
    if (!(fabs(d->e_kinematic - res->e) <= 1e-12 + 4.0 * res->e_rounding))
        return ct_error_set(CT_ENOCONV,
                            "impact in time: e_kinematic = %.17g and e = %.17g differ by more "
                            "than 1e-12 (plus e's rounding bound %.3g)",
                            d->e_kinematic, res->e, res->e_rounding);
    return CT_OK;
}

int ct_dyn_work_alloc(ct_dyn_work **out)
{
    CT_NEED(out);
    ct_dyn_work *w = calloc(1, sizeof *w);
    if (!w || ct_curve_alloc(&w->prev) || ct_curve_alloc(&w->cur)) {
        ct_dyn_work_free(w);
        *out = NULL;
        return ct_error_set(CT_ENOMEM, "impact in time: out of memory");
    }
    units_of(&w->s, NULL);
    *out = w;
    return CT_OK;
}

static void pcurve_free(pcurve *c)
{
    free(c->x);
    free(c->P);
    free(c->k);
    free(c->W);
    free(c->M1);
    free(c->M2);
    memset(c, 0, sizeof *c);
}

static int pcurve_reserve(pcurve *c, size_t n)
{
    if (n <= c->cap)
        return CT_OK;
    pcurve_free(c);
    c->x = malloc(n * sizeof(double));
    c->P = malloc(n * sizeof(double));
    c->k = malloc(n * sizeof(double));
    c->W = malloc(n * sizeof(double));
    c->M1 = malloc(n * sizeof(double));
    c->M2 = malloc(n * sizeof(double));
    if (!c->x || !c->P || !c->k || !c->W || !c->M1 || !c->M2) {
        pcurve_free(c);
        return ct_error_set(CT_ENOMEM, "impact in time: out of memory");
    }
    c->cap = n;
    return CT_OK;
}

/* The moments' terms of pieces 0 .. n-2: int W du and int W^2 du across each; on a piece
 * W = a + b t + (k/2) t^2, all terms >= 0. */
CT_DYN_CLONES
static void moment_terms(const double *restrict x, const double *restrict P,
                         const double *restrict W, const double *restrict slope, size_t n,
                         double *restrict T1, double *restrict T2)
{
    for (size_t i = 0; i + 1 < n; i++) {
        const double d = x[i + 1] - x[i], a = W[i], b = P[i], k = slope[i];
        T1[i] = d * (a + d * (0.5 * b + d * k / 6.0));
        T2[i] =
            d * (a * a +
                 d * (a * b + d * ((b * b + a * k) / 3.0 + d * (0.25 * b * k + d * k * k / 20.0))));
    }
}

/* M1, M2 at every point: the terms summed in order. */
static void pcurve_moments(pcurve *c)
{
    double m1 = 0.0, m2 = 0.0;
    if (!c->n)
        return;
    c->M1[0] = c->M2[0] = 0.0;
    moment_terms(c->x, c->P, c->W, c->k, c->n, c->M1 + 1, c->M2 + 1);
    for (size_t i = 1; i < c->n; i++) {
        c->M1[i] = m1 += c->M1[i];
        c->M2[i] = m2 += c->M2[i];
    }
}

/* A curve into the motion's units, with its moments. */
static int pcurve_from_curve(pcurve *pc, const dyn_units *s, const ct_curve *c)
{
    ct_curve_view v;
    ct_curve_view_of(c, &v);
    int st = pcurve_reserve(pc, v.n ? v.n : 1);
    if (st)
        return st;
    pc->n = v.n;
    for (size_t i = 0; i < v.n; i++) {
        pc->x[i] = v.x[i] * s->sx;
        pc->P[i] = v.P[i] * s->sP;
        pc->k[i] = v.slope[i] * s->sk;
        pc->W[i] = v.W[i] * s->sW;
    }
    pcurve_moments(pc);
    return CT_OK;
}

void ct_dyn_work_free(ct_dyn_work *w)
{
    if (!w)
        return;
    if (w->fork) { /* the parent's arrays stay */
        free(w->ue.rel);
        memset(&w->first_pc, 0, sizeof w->first_pc);
        memset(&w->ue, 0, sizeof w->ue);
        w->f_d2 = w->f_wd = NULL;
    }
    pcurve_free(&w->first_pc);
    pcurve_free(&w->pprev);
    pcurve_free(&w->pcur);
    ct_unload_events_free(&w->ue);
    path_free(&w->load);
    path_free(&w->unload);
    ct_curve_free(w->prev);
    ct_curve_free(w->cur);
    free(w->t_load);
    free(w->t_unload);
    free(w->f_d2);
    free(w->f_wd);
    free(w);
}

void ct_dyn_reset(ct_dyn_work *w)
{
    w->have_prev = 0;
    w->U = -INFINITY;
}

/* u, v and P at time tau into piece i of a path (v > 0 along the path). */
static void on_piece(const path *p, size_t i, double v_i, double tau, double m, double *u,
                     double *v, double *P)
{
    const double w = sqrt(p->k[i] / m), z = w * tau, a = p->P[i] / m;
    /* sin(z) / z and (1 - cos z) / z^2, by their series where z is small */
    double S, C;
    if (z * z < 1e-8) {
        S = 1.0 - z * z / 6.0;
        C = 0.5 - z * z / 24.0;
    } else {
        S = sin(z) / z;
        C = 2.0 * pow(sin(0.5 * z) / z, 2.0);
    }
    *u = p->x[i] + v_i * tau * S - a * tau * tau * C;
    *v = v_i * cos(z) - a * tau * S;
    *P = p->P[i] + p->k[i] * (*u - p->x[i]);
}

static int grow_times(ct_dyn_work *w, size_t n)
{
    if (n <= w->tcap)
        return CT_OK;
    double *a = realloc(w->t_load, n * sizeof(double));
    if (a)
        w->t_load = a;
    double *b = a ? realloc(w->t_unload, n * sizeof(double)) : NULL;
    if (b)
        w->t_unload = b;
    if (!b)
        return ct_error_set(CT_ENOMEM, "impact history: out of memory");
    w->tcap = n;
    return CT_OK;
}

static int push_point(ct_history *h, size_t *cap, double t, double u, double v, double P,
                      int unloading, int event)
{
    if (h->n == *cap) {
        size_t nc = *cap ? 2 * *cap : 512;
        ct_history_point *q = realloc(h->points, nc * sizeof *q);
        if (!q)
            return ct_error_set(CT_ENOMEM, "impact history: out of memory");
        h->points = q;
        *cap = nc;
    }
    h->points[h->n++] = (ct_history_point){t, u, v, P, unloading, event};
    return CT_OK;
}

/* The history of one branch: its breakpoints (times t[0..J], the turning point at T) and
 * the grid times in [t0, t0 + T], in time order; an unloading branch runs backwards along
 * its path (time t0 + T - s at path time s). */
static int branch_history(ct_history *h, size_t *cap, const path *p, const double *t, size_t J,
                          double T, double W_kin, double m, double t0, int unloading,
                          const double *grid, size_t ngrid)
{
    int st;
    size_t g = 0, count = J + 2;      /* the breakpoints, and the turning point */
    size_t piece = unloading ? J : 0; /* grid times are in order: the piece only moves on */
    for (size_t q = 0; q <= count; q++) {
        if (q == count) { /* grid points at the branch's very end (the release) */
            if (g == ngrid)
                break;
        }
        /* walk the breakpoints in time order: forward on loading, backward on unloading */
        size_t i = q == count ? 0 : unloading ? count - 1 - q : q;
        double s = i <= J ? t[i] : T, time = unloading ? t0 + T - s : t0 + s;
        if (q == count)
            time = INFINITY; /* every grid point left */
        /* grid points before this breakpoint's time */
        while (g < ngrid && grid[g] < time) {
            double sg = unloading ? t0 + T - grid[g] : grid[g] - t0;
            sg = sg < 0.0 ? 0.0 : sg > T ? T : sg;
            while (!unloading && piece < J && t[piece + 1] <= sg)
                piece++;
            while (unloading && piece > 0 && t[piece] > sg)
                piece--;
            double vi = sqrt(2.0 * fmax(W_kin - p->W[piece], 0.0) / m), u, v, P;
            on_piece(p, piece, vi, sg - t[piece], m, &u, &v, &P);
            if ((st = push_point(h, cap, grid[g], u, unloading ? -v : v, P, unloading, 0)))
                return st;
            g++;
        }
        if (q == count || (unloading && q == 0))
            continue; /* the end; or u_max: the loading branch's turning point already */
        double u, P, v;
        if (i <= J) {
            u = p->x[i];
            P = p->P[i];
            v = sqrt(2.0 * fmax(W_kin - p->W[i], 0.0) / m);
        } else { /* the turning point: v = 0 */
            on_piece(p, J, sqrt(2.0 * fmax(W_kin - p->W[J], 0.0) / m), T - t[J], m, &u, &v, &P);
            v = 0.0;
        }
        if ((st = push_point(h, cap, time, u, unloading ? -v : v, P, unloading, 1)))
            return st;
    }
    return CT_OK;
}

/* The loading branch into w->load: the state's curve from the contact to u_max. After an
 * earlier maximum U (repeated impacts on the first curve) that is the unloading curve of U up
 * to U, then the first curve beyond it. */
static int load_path(ct_dyn_work *w, const ct_curve *c, const ct_impact_result *res)
{
    int st;
    const double u_max = res->u_max;
    if (!w->have_prev) {
        st = path_append(&w->load, &w->s, c, res->u_contact, u_max, 0.0);
    } else if (u_max <= w->U) {
        st = path_append(&w->load, &w->s, w->prev, ct_curve_first_contact(w->prev), u_max, 0.0);
    } else {
        st = path_append(&w->load, &w->s, w->prev, ct_curve_first_contact(w->prev), w->U, 0.0);
        if (!st)
            st = path_append(&w->load, &w->s, c, w->U, u_max,
                             ct_curve_work(w->prev, w->U) - ct_curve_work(c, w->U));
    }
    if (st)
        return st;
    if (!w->load.n)
        return ct_error_set(CT_EINVAL, "impact in time: no rod in contact");
    return CT_OK;
}

/* The unloading branch of a plastic impact into w->unload (as a loading from the release
 * point): the unloading curve of the state after u_max, c's state loaded to u_max (beyond an
 * earlier maximum that is the first state loaded to u_max as well). */
static int unload_path(ct_dyn_work *w, const ct_curve *c, double u_max)
{
    int st;
    if (w->one_shot && w->first == c && w->ue.nested) {
        /* one impact from a virgin layer (ct_impact_history): the two-run unloading */
        const double u_max_s = u_max * w->s.sx; /* w->ue holds the motion's units */
        if ((st = path_reserve(&w->unload, ct_unload_split_room(&w->ue, u_max_s))))
            return st;
        w->unload.n =
            ct_unload_split(&w->ue, u_max_s, w->unload.x, w->unload.P, w->unload.W, w->unload.k);
    } else if ((st = ct_curve_unload(c, u_max, w->cur)) ||
               (st = path_append(&w->unload, &w->s, w->cur, ct_curve_first_contact(w->cur), u_max,
                                 0.0))) {
        return st;
    }
    if (!w->unload.n)
        return ct_error_set(CT_EINVAL, "impact in time: no rod in contact at u_max");
    return CT_OK;
}

/* dyn's times, speeds and stiffness (all but P_peak) from the branches' times, the kinetic
 * energies in (W_kin) and out (W_back) and the stiffest unloading piece kmax. */
static void dyn_results(ct_dynamics *dyn, double t_load, double t_unload, double W_kin,
                        double W_back, double m, double kmax)
{
    dyn->t_load = t_load;
    dyn->t_unload = t_unload;
    dyn->t_contact = t_load + t_unload;
    dyn->v1 = sqrt(2.0 * W_kin / m);
    dyn->v2 = sqrt(2.0 * W_back / m);
    dyn->e_kinematic = dyn->v2 / dyn->v1;
    dyn->dissipated = W_kin - W_back;
    dyn->k_unload_max = kmax;
    dyn->period_min = kmax > 0.0 ? 6.283185307179586 * sqrt(m / kmax) : INFINITY;
}

/* The history of an impact whose branches are w->load (turning point J_load) and up
 * (J_unload): their breakpoints and `grid` uniform times over the contact. */
static int impact_history(ct_dyn_work *w, const path *up, size_t J_load, size_t J_unload,
                          const ct_dynamics *dyn, double W_kin, double W_back, double m,
                          size_t grid, ct_history *hist)
{
    const double t_load = dyn->t_load;
    size_t cap = 0;
    double *times = NULL;
    int st;
    hist->n = 0;
    hist->points = NULL;
    if (grid) {
        if (!(times = malloc(grid * sizeof(double))))
            return ct_error_set(CT_ENOMEM, "impact history: out of memory");
        for (size_t g = 0; g < grid; g++)
            times[g] = dyn->t_contact * (double)g / (double)(grid > 1 ? grid - 1 : 1);
    }
    size_t split = 0; /* grid points on loading: t < t_load */
    while (split < grid && times[split] < t_load)
        split++;
    st = branch_history(hist, &cap, &w->load, w->t_load, J_load, t_load, W_kin, m, 0.0, 0, times,
                        split);
    if (!st) {
        /* the turning point closes the loading branch; unloading starts there */
        st = branch_history(hist, &cap, up, w->t_unload, J_unload, dyn->t_unload, W_back, m, t_load,
                            1, times + split, grid - split);
    }
    free(times);
    if (st)
        ct_history_free(hist);
    return st;
}

/* A history from the motion's units (time unit 2^et) into the caller's: exact. */
static void history_unscale(ct_history *h, const dyn_units *s, int et)
{
    for (size_t i = 0; i < h->n; i++) {
        ct_history_point *q = &h->points[i];
        q->t = ldexp(q->t, et);
        q->u = ldexp(q->u, s->ex);
        q->v = ldexp(q->v, s->ex - et);
        q->P = ldexp(q->P, s->eW - s->ex);
    }
}

int ct_dyn_impact(ct_dyn_work *w, const ct_curve *c, const ct_impact_result *res, double m_caller,
                  ct_dynamics *dyn, size_t grid, ct_history *hist)
{
    int st, et;
    if ((st = dyn_resolvable(&w->s, res)))
        return st;
    /* the motion's units: the curves are scaled as they are read (path_append) */
    const double m = dyn_mass(&w->s, m_caller, &et), W_kin = res->kinetic_energy * w->s.sW,
                 u_max = res->u_max;
    w->load.n = w->unload.n = 0;
    if ((st = load_path(w, c, res)))
        return st;
    size_t J_load, J_unload;
    if (hist && (st = grow_times(w, w->load.n + 1)))
        return st;
    const double t_load = time_to_turn(&w->load, W_kin, m, hist ? w->t_load : NULL, &J_load);
    const path *up; /* the unloading branch, as a loading from the release point */
    double W_back;
    if (res->elastic) {
        up = &w->load; /* nothing yielded: the body comes back along the same curve */
        W_back = W_kin;
    } else {
        if ((st = unload_path(w, c, u_max)))
            return st;
        up = &w->unload;
        W_back = up->W[up->n - 1];
    }
    if (hist && (st = grow_times(w, up->n + 1)))
        return st;
    const double t_unload =
        res->elastic ? t_load : time_to_turn(up, W_back, m, hist ? w->t_unload : NULL, &J_unload);
    if (res->elastic) {
        J_unload = J_load;
        if (hist)
            memcpy(w->t_unload, w->t_load, (J_load + 1) * sizeof(double));
    }
    double kmax = 0.0;
    for (size_t i = 0; i + 1 < up->n; i++)
        kmax = up->k[i] > kmax ? up->k[i] : kmax;
    dyn_results(dyn, t_load, t_unload, W_kin, W_back, m, kmax);
    dyn->P_peak = w->load.P[w->load.n - 1];
    if (hist && (st = impact_history(w, up, J_load, J_unload, dyn, W_kin, W_back, m, grid, hist)))
        return st;
    dyn_unscale(dyn, &w->s, et);
    if (hist)
        history_unscale(hist, &w->s, et);
    if ((st = dyn_check(res, dyn))) {
        if (hist)
            ct_history_free(hist);
        return st;
    }
    if (!res->elastic &&
        !w->one_shot) { /* the new maximum: its unloading curve serves the next impact */
        ct_curve *t = w->prev;
        w->prev = w->cur;
        w->cur = t;
        w->U = u_max;
        w->have_prev = 1;
    }
    return CT_OK;
}

void ct_history_free(ct_history *h)
{
    if (!h)
        return;
    free(h->points);
    h->points = NULL;
    h->n = 0;
}

/* Doubles per event: first_pc's 6 and the pieces' products' 2 per breakpoint (at most one per
 * event), the split events' 8 (ct_unload_events_of). */
double ct_dyn_prepared_bytes(size_t events)
{
    return (double)events * (6.0 + 2.0 + 8.0) * sizeof(double);
}

/* ct_curve_unload's copy of m events: the events (6 doubles) twice (its sort), their run
 * bounds and sorted copy (2 doubles), and 8 doubles a point. */
static double unload_copy_bytes(double m)
{
    return m * (2.0 * 6.0 * sizeof(double) + sizeof(size_t) + (2.0 + 8.0) * sizeof(double));
}

double ct_dyn_work_thread_bytes(const ct_dyn_work *w, double u_max)
{
    /* an unloading curve from u_max has up to ct_unload_split_room points (the events up to
     * u_max, a yield's twice, and 2): the state's maximum's and this impact's, 6 doubles a
     * point each; a fork's releases (ny); not monotone, ct_curve_unload's copy as well */
    const double room = (double)ct_unload_split_room(&w->ue, u_max * w->s.sx);
    double bytes = 2.0 * 6.0 * sizeof(double) * room + (double)w->ue.ny * sizeof(double);
    if (!w->ue.monotone)
        bytes += unload_copy_bytes(room);
    return bytes;
}

/* The loading and unloading paths (4 doubles a point each, up to 3/2 of the events and 2) and
 * ct_curve_unload's copy (for one impact from a virgin layer, unless nested: known only once
 * split, counted); for one history impact (one_shot), the split events too (8 doubles an
 * event); for repeated impacts, the earlier maximum's unloading curve as well. */
static double impact_bytes(size_t events, int one_shot, int repeated)
{
    const double points = 1.5 * (double)events + 2.0;
    return (one_shot ? (double)events * 8.0 * sizeof(double) : 0.0) +
           2.0 * 4.0 * sizeof(double) * points + (repeated ? 2.0 : 1.0) * unload_copy_bytes(points);
}

/* The most the figures above take per event with the curve's own: below CT_MEMORY_CHECK_MIN
 * for two events a rod, no check. */
#define CT_DYN_MAX_BYTES_PER_EVENT 1000.0

int ct_dyn_memory_check(const ct_bundle *b, ct_dyn_use use, long impacts)
{
    const size_t rods = ct_bundle_size(b);
    if (2.0 * (double)rods * CT_DYN_MAX_BYTES_PER_EVENT < CT_MEMORY_CHECK_MIN)
        return CT_OK;
    const size_t events = ct_curve_events(b);
    const int repeated = impacts > 1;
    /* the sweep's state path builds its state's curve after a plastic impact (the first
     * curve is held already) */
    const double curve = use != CT_DYN_BY_STATE || repeated ? ct_curve_bytes(events) : 0.0,
                 dyn = use == CT_DYN_SWEEP ? ct_dyn_prepared_bytes(events)
                                           : impact_bytes(events, use == CT_DYN_ONE_SHOT,
                                                          use == CT_DYN_BY_STATE && repeated),
                 avail = (double)ct_available_memory();
    if (!(curve + dyn > 0.9 * avail))
        return CT_OK;
    static const char *const parts[] = {"its pieces and events", "its unloading curve and paths",
                                        "the unloading curves and paths"};
    char load[64] = "";
    if (curve > 0.0)
        snprintf(load, sizeof load, "%.3g for the %s load curve, ", curve / 1073741824.0,
                 use == CT_DYN_BY_STATE ? "state's" : "first");
    return ct_error_set(CT_ENOMEM,
                        "impact in time on %zu rods (%zu curve events): needs %.3g GiB (%s%.3g "
                        "for %s), more than 90 %% of the %.3g GiB of memory available: leave out "
                        "the time columns, or take fewer rods",
                        rods, events, (curve + dyn) / 1073741824.0, load, dyn / 1073741824.0,
                        parts[use], avail / 1073741824.0);
}

int ct_impact_history(const ct_bundle *b, double m, double v1, size_t grid, ct_impact_result *res,
                      ct_dynamics *dyn, ct_history *hist)
{
    CT_NEED(b);
    CT_NEED(res);
    CT_NEED(dyn);
    if (!isfinite(m) || !(m > 0.0) || !isfinite(v1) || !(v1 > 0.0))
        return ct_error_set(CT_EINVAL,
                            "impact in time: mass %g and speed %g must be finite and > 0", m, v1);
    if (hist) {
        hist->n = 0;
        hist->points = NULL;
    }
    ct_curve *c;
    ct_dyn_work *w;
    int st;
    if ((st = ct_dyn_memory_check(b, CT_DYN_ONE_SHOT, 1)) || (st = ct_curve_alloc(&c)))
        return st;
    if ((st = ct_dyn_work_alloc(&w))) {
        ct_curve_free(c);
        return st;
    }
    ct_dyn_reset(w);
    w->one_shot = 1;
    if (!(st = ct_curve_build(c, b)) && !(st = ct_dyn_prepare(w, c, ct_bundle_layer(b))) &&
        !(st = ct_impact_eval(b, c, 0.5 * m * v1 * v1, NULL, res)))
        st = ct_dyn_impact(w, c, res, m, dyn, grid, hist);
    ct_dyn_work_free(w);
    ct_curve_free(c);
    return st;
}

int ct_bounce(const ct_bundle *b, double m, double v1, size_t nmax, double v_stop,
              ct_impact_result *res, ct_dynamics *dyn, size_t *n)
{
    CT_NEED(b);
    CT_NEED(res);
    CT_NEED(dyn);
    CT_NEED(n);
    *n = 0;
    if (!isfinite(v_stop) || v_stop < 0.0)
        return ct_error_set(CT_EINVAL, "bounce: stop speed %g must be finite and >= 0", v_stop);
    ct_bundle *state;
    int st = ct_bundle_clone(&state, b);
    if (st)
        return st;
    double v = v1;
    for (size_t k = 0; k < nmax; k++) {
        if ((st = ct_impact_history(state, m, v, 0, &res[k], &dyn[k], NULL)))
            break;
        *n = k + 1;
        if (!res[k].elastic)
            ct_bundle_advance(state, res[k].u_max);
        v = dyn[k].v2;
        if (v < v_stop || !(v > 0.0))
            break;
    }
    ct_bundle_free(state);
    return st;
}

/* ---- the sweep's fast path: no history, the first pieces of a branch by their moments ---- */

int ct_dyn_prepare(ct_dyn_work *w, const ct_curve *c, const ct_layer *L)
{
    int st;
    w->first = c;
    w->f_m = 0.0; /* the pieces' products: for the next mass */
    units_of(&w->s, L);
    if (!w->one_shot && (st = pcurve_from_curve(&w->first_pc, &w->s, c))) /* the sweep's walks */
        return st;
    if ((st = ct_unload_events_of(c, &w->ue)))
        return st;
    ct_unload_events_scale(&w->ue, w->s.sx, w->s.sk);
    return CT_OK;
}

/* The unloading curve from u_max of the first curve's state (its events monotone), by the
 * curve's builder from the split events (ct_unload_split: no sort); u_max and the events in
 * the motion's units. */
static int unload_split(ct_dyn_work *w, double u_max, pcurve *out)
{
    int st;
    if ((st = pcurve_reserve(out, ct_unload_split_room(&w->ue, u_max))))
        return st;
    out->n = ct_unload_split(&w->ue, u_max, out->x, out->P, out->W, out->k);
    if (out->n == 0)
        return ct_error_set(CT_EINVAL, "impact in time: no rod in contact at u_max");
    return CT_OK;
}

/* The unloading curve from u_max (the layer's units) of the first curve's state
 * (ct_curve_unload) with its moments, in the motion's units: from the split events without a
 * sort when they are monotone. */
static int unload_fast(ct_dyn_work *w, double u_max, pcurve *out)
{
    int st;
    if (!w->ue.monotone) {
        if ((st = ct_curve_unload(w->first, u_max, w->cur)))
            return st;
        return pcurve_from_curve(out, &w->s, w->cur);
    }
    if ((st = unload_split(w, u_max * w->s.sx, out)))
        return st;
    pcurve_moments(out);
    return CT_OK;
}

/* Largest i with c->x[i] <= u. */
static size_t pc_piece(const pcurve *c, double u)
{
    size_t lo = 0, hi = c->n;
    while (hi - lo > 1) {
        size_t mid = lo + (hi - lo) / 2;
        if (c->x[mid] <= u)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

/* Below this kinetic energy the moments are summed in units of it: W^2 of the first pieces
 * (at most (1e-5 W_kin)^2) then stays far above the smallest double. */
#define CT_TINY_ENERGY 1e-100

/* Whether an energy W (the motion's units) is that small, there or in the layer's units
 * (where the moments were summed before the motion had units of its own: the same bits). */
static int tiny_energy(const dyn_units *s, double W)
{
    return W < CT_TINY_ENERGY || ldexp(W, s->eW) < CT_TINY_ENERGY;
}

/* Time from A's first point (work 0, speed sqrt(2 W_kin / m)) to where the work reaches
 * W_kin; beyond endA the path goes on along B with its work shifted by dW (B NULL: A goes
 * on). While the work is below 1e-5 W_kin the speed is v0 (1 - W / W_kin)^(-1/2), whose
 * series to second order integrates to (dx + M1 / (2 W_kin) + 3 M2 / (8 W_kin^2)) / v0
 * (error below 5/16 (1e-5)^3 relative); then piece by piece. *kmax (not NULL) gets the
 * stiffest piece passed. d2, wd (B NULL): A's pieces' 2 du and omega du, or NULL; sorted: A's
 * x all finite and its W nondecreasing (the turning piece by bisection). */
static double walk(const pcurve *A, double endA, const pcurve *B, double dW, double W_kin, double m,
                   double *kmax, const double *d2, const double *wd, int sorted, int tiny)
{
    const double v0 = sqrt(2.0 * W_kin / m), delta = 1e-5 * W_kin;
    size_t lo = 0, hi = A->n;
    while (hi - lo > 1) {
        size_t mid = lo + (hi - lo) / 2;
        if (A->W[mid] <= delta && A->x[mid] <= endA)
            lo = mid;
        else
            hi = mid;
    }
    size_t i = lo;
    double t;
    if (tiny) {
        /* an energy so small that W^2 underflows (M2 / W_kin^2 = 0 / 0 at V* ~ 1e-85): the
         * prefix's own pieces, in units of W_kin */
        const double s = 1.0 / W_kin;
        double M1 = 0.0, M2 = 0.0;
        for (size_t q = 0; q < i; q++) {
            const double d = A->x[q + 1] - A->x[q], a = A->W[q] * s, b = A->P[q] * s,
                         k = A->k[q] * s;
            M1 += d * (a + d * (0.5 * b + d * k / 6.0));
            M2 += d * (a * a + d * (a * b + d * ((b * b + a * k) / 3.0 +
                                                 d * (0.25 * b * k + d * k * k / 20.0))));
        }
        const double W1 = W_kin * s;
        t = (A->x[i] - A->x[0] + M1 / (2.0 * W1) + 3.0 * M2 / (8.0 * W1 * W1)) / v0;
    } else {
        t = (A->x[i] - A->x[0] + A->M1[i] / (2.0 * W_kin) +
             3.0 * A->M2[i] / (8.0 * W_kin * W_kin)) /
            v0;
    }
    if (!B) { /* A alone: the turning piece J, then the pieces up to it in order */
        size_t J = i;
        if (sorted) { /* the last point below W_kin, by bisection */
            size_t hi = A->n;
            while (hi - J > 1) {
                const size_t mid = J + (hi - J) / 2;
                if (A->W[mid] < W_kin)
                    J = mid;
                else
                    hi = mid;
            }
        } else {
            while (J + 1 < A->n && A->x[J + 1] < INFINITY && A->W[J + 1] < W_kin)
                J++;
        }
        double km = 0.0, v;
        for (size_t q = i; kmax && q <= J; q++)
            km = stiffer(km, A->k[q]);
        t = pieces_time(A->x, A->W, A->k, d2, wd, i, J, t, W_kin, m, &v, NULL);
        if (kmax)
            *kmax = km;
        return t + turn_time(A->P[J], A->k[J], m, v);
    }
    const pcurve *C = A;
    double end = endA, off = 0.0, km = 0.0;
    double x = A->x[i], P = A->P[i], k = A->k[i], W = A->W[i];
    double v = speed_at(W_kin, W, m);
    for (;;) {
        int on_point = i + 1 < C->n && C->x[i + 1] < end;
        double xn = on_point ? C->x[i + 1] : end;
        double d = xn - x;
        double Wn =
            on_point ? C->W[i + 1] + off : (isinf(xn) ? INFINITY : W + d * (P + 0.5 * k * d));
        km = stiffer(km, k);
        if (!(Wn < W_kin)) {
            t += turn_time(P, k, m, v);
            break;
        }
        double vn = speed_at(W_kin, Wn, m);
        t += piece_time(d, k, m, v, vn);
        v = vn;
        if (on_point) {
            i++;
            x = C->x[i];
            P = C->P[i];
            k = C->k[i];
            W = Wn;
        } else { /* A ends: B from here */
            size_t j = pc_piece(B, end);
            double s = end - B->x[j];
            x = end;
            P = B->P[j] + B->k[j] * s;
            k = B->k[j];
            off = dW;
            W = B->W[j] + s * (B->P[j] + 0.5 * B->k[j] * s) + off;
            C = B;
            i = j;
            end = INFINITY;
        }
    }
    if (kmax)
        *kmax = km;
    return t;
}

static double pc_force(const pcurve *c, double u)
{
    size_t j = pc_piece(c, u);
    return c->P[j] + c->k[j] * (u - c->x[j]);
}

static double pc_work(const pcurve *c, double u)
{
    size_t j = pc_piece(c, u);
    double s = u - c->x[j];
    return c->W[j] + s * (c->P[j] + 0.5 * c->k[j] * s);
}

/* The first curve's pieces' 2 du and omega du for mass m: every speed's loading walks them. */
static int first_products(ct_dyn_work *w, double m)
{
    const pcurve *F = &w->first_pc;
    if (F->n > w->f_cap) {
        double *a = realloc(w->f_d2, F->n * sizeof(double));
        if (a)
            w->f_d2 = a;
        double *b = a ? realloc(w->f_wd, F->n * sizeof(double)) : NULL;
        if (b)
            w->f_wd = b;
        if (!b)
            return ct_error_set(CT_ENOMEM, "impact in time: out of memory");
        w->f_cap = F->n;
    }
    w->f_sorted = 1;
    for (size_t q = 0; q + 1 < F->n; q++) {
        const double du = F->x[q + 1] - F->x[q];
        w->f_d2[q] = 2.0 * du;
        w->f_wd[q] = omega(F->k[q], m) * du;
        w->f_sorted &= F->x[q + 1] < INFINITY && F->W[q + 1] >= F->W[q];
    }
    w->f_m = m;
    return CT_OK;
}

int ct_dyn_work_fork(ct_dyn_work *parent, double m, ct_dyn_work **out)
{
    CT_NEED(parent);
    CT_NEED(out);
    int st;
    *out = NULL;
    if (!parent->first || parent->one_shot)
        return ct_error_set(CT_EINVAL, "impact in time: fork of an unprepared workspace");
    int et;
    const double ms = dyn_mass(&parent->s, m, &et);
    if (ms != parent->f_m && (st = first_products(parent, ms)))
        return st;
    ct_dyn_work *w;
    if ((st = ct_dyn_work_alloc(&w)))
        return st;
    w->fork = 1;
    w->s = parent->s;
    w->first = parent->first;
    w->first_pc = parent->first_pc;
    w->ue = parent->ue;
    w->ue.buf = NULL;
    w->ue.cap = 0;
    w->f_d2 = parent->f_d2;
    w->f_wd = parent->f_wd;
    w->f_m = parent->f_m;
    w->f_sorted = parent->f_sorted;
    w->f_cap = parent->f_cap;
    if (!(w->ue.rel = malloc((parent->ue.ny ? parent->ue.ny : 1) * sizeof(double)))) {
        ct_dyn_work_free(w);
        return ct_error_set(CT_ENOMEM, "impact in time: out of memory");
    }
    ct_dyn_reset(w);
    *out = w;
    return CT_OK;
}

int ct_dyn_impact_fast(ct_dyn_work *w, const ct_impact_result *res, double m_caller,
                       ct_dynamics *dyn)
{
    int st, et;
    if ((st = dyn_resolvable(&w->s, res)))
        return st;
    /* the motion's units (first_pc, pprev, pcur and the events hold them already) */
    const double m = dyn_mass(&w->s, m_caller, &et), W_kin = res->kinetic_energy * w->s.sW,
                 u_max = res->u_max * w->s.sx, U = w->U * w->s.sx;
    const int tiny = tiny_energy(&w->s, W_kin);
    double t_load, kmax;
    const pcurve *F = &w->first_pc;
    if (m != w->f_m && w->fork) /* the products are the parent's, shared: not rewritten here */
        return ct_error_set(CT_EINVAL, "impact in time: a fork's mass differs from its parent's");
    if (m != w->f_m && (st = first_products(w, m)))
        return st;
    double *k_load = res->elastic ? &kmax : NULL; /* else the unloading's stiffest piece */
    if (!w->have_prev) {
        t_load =
            walk(F, INFINITY, NULL, 0.0, W_kin, m, k_load, w->f_d2, w->f_wd, w->f_sorted, tiny);
        dyn->P_peak = pc_force(F, u_max);
    } else if (u_max <= U) {
        t_load = walk(&w->pprev, INFINITY, NULL, 0.0, W_kin, m, k_load, NULL, NULL, 0, tiny);
        dyn->P_peak = pc_force(&w->pprev, u_max);
    } else {
        const pcurve *A = &w->pprev;
        t_load =
            walk(A, U, F, A->W[A->n - 1] - pc_work(F, U), W_kin, m, &kmax, NULL, NULL, 0, tiny);
        dyn->P_peak = pc_force(F, u_max);
    }
    double W_back = W_kin, t_unload = t_load;
    if (!res->elastic) {
        if ((st = unload_fast(w, res->u_max, &w->pcur)))
            return st;
        W_back = w->pcur.W[w->pcur.n - 1];
        t_unload = walk(&w->pcur, INFINITY, NULL, 0.0, W_back, m, &kmax, NULL, NULL, 0,
                        tiny_energy(&w->s, W_back));
        pcurve t = w->pprev;
        w->pprev = w->pcur;
        w->pcur = t;
        w->U = res->u_max;
        w->have_prev = 1;
    }
    dyn_results(dyn, t_load, t_unload, W_kin, W_back, m, kmax);
    dyn_unscale(dyn, &w->s, et);
    return dyn_check(res, dyn);
}
